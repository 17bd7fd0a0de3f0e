#!/usr/bin/env bash
# scripts/test_pip_install.sh — the documented install of the Python module, tested from scratch:
# a fresh `python3 -m venv --system-site-packages` (Debian's numpy and scipy visible), then
# `pip install --no-build-isolation --no-index ./python` (no network: Debian's setuptools and wheel
# build it, python/setup.py drives CMake), then, from outside the source tree, an import and a small
# computation, and the whole pytest suite (tests/python) against the installed package.
# Usage: scripts/test_pip_install.sh [PYTHON] (default /usr/bin/python3).
# POLYDEC_PREFIX=PREFIX: build the module against an installed shared polydec there (what
# scripts/test_install.sh does, compiling the module's sources only); without it pip builds the
# library too. POLYDEC_CLI: the polydec program the tests compare with (default PREFIX/bin/polydec).
set -euo pipefail

root=$(cd "$(dirname "$0")/.." && pwd)
python=${1:-/usr/bin/python3}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp" "$root/python/build" "$root/python/polydec.egg-info"' EXIT

"$python" -m venv --system-site-packages "$tmp/venv"
# pip builds in the source tree (python/build/, removed on exit), then installs the wheel.
t0=$(date +%s)
PIP_DISABLE_PIP_VERSION_CHECK=1 "$tmp/venv/bin/pip" install --no-build-isolation --no-index -q "$root/python"
echo "test_pip_install.sh: pip install took $(( $(date +%s) - t0 )) s${POLYDEC_PREFIX:+ (against the installation in $POLYDEC_PREFIX)}"
cd "$tmp"
"$tmp/venv/bin/python" - <<'PY'
import sys

import numpy as np
import polydec

assert polydec.__file__.startswith(sys.prefix), f"imported {polydec.__file__}, not the venv's"
V, F = polydec.hex_sphere(2)
S, M = polydec.laplacian(V, F)
assert abs(S @ np.ones(V.shape[0])).max() <= 1e-12 * abs(S).max()
evals, _ = polydec.spectrum(V, F, 4)
assert abs(evals[1] - 2) < 0.1, evals
print(f"test_pip_install.sh: polydec {polydec.__version__} from {polydec.__file__}: S {S.shape}, evals {np.round(evals, 3)}")
PY
cli=${POLYDEC_CLI:-${POLYDEC_PREFIX:+$POLYDEC_PREFIX/bin/polydec}}
POLYDEC_CLI=$cli PYTHONDONTWRITEBYTECODE=1 "$tmp/venv/bin/python" -m pytest -q -p no:cacheprovider \
  --rootdir "$tmp" "$root/tests/python"
echo "test_pip_install.sh: pip install into a --system-site-packages venv, import and the pytest suite ok"
