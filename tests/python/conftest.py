"""tests/python/conftest.py — shared fixtures of the Python tests: the paper's meshes in
../shared/data (skipped with a message when absent, mandatory with POLYDEC_REQUIRE_SHARED_DATA=1),
the polydec command-line program (POLYDEC_CLI, set by CTest) that writes the C++ library's
matrices, and small generated meshes."""

import os
import pathlib
import shutil
import subprocess

import numpy as np
import pytest

import polydec

ROOT = pathlib.Path(__file__).resolve().parents[2]
SHARED = pathlib.Path(os.environ.get("POLYDEC_SHARED_DATA", ROOT.parent / "shared" / "data"))
TEST_DATA = pathlib.Path(os.environ.get("POLYDEC_TEST_DATA", ROOT / "tests" / "data"))


def shared_mesh(name):
    """Path of ../shared/data/NAME, or skip (fail when POLYDEC_REQUIRE_SHARED_DATA=1)."""
    p = SHARED / name
    if not p.exists():
        if os.environ.get("POLYDEC_REQUIRE_SHARED_DATA") == "1":
            pytest.fail(f"required test mesh missing: {p}")
        pytest.skip(f"{p} not found (clone without shared data)")
    return p


@pytest.fixture(scope="session")
def cli():
    """Runs `polydec ARGS...` and returns its stdout; fails on a non-zero exit."""
    exe = os.environ.get("POLYDEC_CLI") or shutil.which("polydec")
    if not exe:
        for cand in (ROOT / "build" / "polydec",):
            if cand.exists():
                exe = str(cand)
    if not exe:
        pytest.skip("the polydec command-line program is needed (set POLYDEC_CLI)")

    def run(*args):
        r = subprocess.run([exe, *map(str, args)], capture_output=True, text=True)
        assert r.returncode == 0, r.stderr
        return r.stdout

    return run


def relative_difference(A, B):
    """|A - B|_F / max(|A|_F, |B|_F) for sparse or dense arrays."""
    import scipy.sparse

    def fro(X):
        return scipy.sparse.linalg.norm(X) if scipy.sparse.issparse(X) else np.linalg.norm(X)

    import scipy.sparse.linalg  # noqa: F401

    scale = max(fro(A), fro(B), 1e-300)
    return fro(A - B) / scale


@pytest.fixture
def hexgrid():
    return polydec.hex_grid(6, 5)
