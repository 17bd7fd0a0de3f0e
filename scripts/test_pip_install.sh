#!/usr/bin/env bash
# scripts/test_pip_install.sh — the documented install of the Python module, tested from scratch:
# a fresh `python3 -m venv --system-site-packages` (Debian's numpy and scipy visible), then
# `pip install --no-build-isolation ./python` (no network: Debian's setuptools and wheel build it,
# python/setup.py drives CMake), then an import and a small computation from outside the tree.
# Usage: scripts/test_pip_install.sh [PYTHON] (default /usr/bin/python3). Leaves nothing behind
# except python/build/ (the CMake build of the wheel, reused by the next run; ccache when installed).
set -euo pipefail

root=$(cd "$(dirname "$0")/.." && pwd)
python=${1:-/usr/bin/python3}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

"$python" -m venv --system-site-packages "$tmp/venv"
# pip copies nothing: it builds in the source tree (python/build/), then installs the wheel.
PIP_DISABLE_PIP_VERSION_CHECK=1 "$tmp/venv/bin/pip" install --no-build-isolation --no-index -q "$root/python"
cd "$tmp"
"$tmp/venv/bin/python" - <<'PY'
import numpy as np
import polydec

assert polydec.__file__.startswith(__import__("sys").prefix), polydec.__file__
V, F = polydec.hex_sphere(2)
S, M = polydec.laplacian(V, F)
assert abs(S @ np.ones(V.shape[0])).max() <= 1e-12 * abs(S).max()
evals, _ = polydec.spectrum(V, F, 4)
assert abs(evals[1] - 2) < 0.1, evals
print(f"polydec {polydec.__version__} from {polydec.__file__}: S {S.shape}, evals {np.round(evals, 3)}")
PY
