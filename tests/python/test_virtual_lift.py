"""tests/python/test_virtual_lift.py — polydec.lifted_laplacian: without a lift, or with the affine
points given as positions, the paper's operator exactly; the sphere lift's virtual points on the
sphere with S symmetric and S @ 1 = 0; bad lifts refused with ValueError."""

import numpy as np
import pytest

import polydec


def test_affine_placements_give_the_papers_operator():
    V, F = polydec.hex_sphere(1)
    S0, M0 = polydec.laplacian(V, F)
    S1, M1, X = polydec.lifted_laplacian(V, F)
    # S bit for bit; the lumped mass to rounding (without the Galerkin mass it is summed face by
    # face, here from the Galerkin mass's columns).
    assert (S1 != S0).nnz == 0 and abs(M1 - M0).max() <= 1e-14 * abs(M0).max()
    S2, M2, X2 = polydec.lifted_laplacian(V, F, positions=X, mass="galerkin")
    assert (S2 != S0).nnz == 0 and (M2 != polydec.mass(V, F)).nnz == 0
    assert np.array_equal(X2, X)


def test_sphere_lift():
    V, F = polydec.cube_sphere(4)
    S, M, X = polydec.lifted_laplacian(V, F, lift="sphere:0,0,0,1")
    assert X.shape == (len(F[1]) - 1, 3)  # F: the flat (indices, offsets)
    assert np.max(np.abs(np.linalg.norm(X, axis=1) - 1)) < 1e-14
    s = abs(S).max()
    assert abs(S - S.T).max() <= 1e-14 * s
    assert np.max(np.abs(S @ np.ones(S.shape[0]))) <= 1e-12 * s
    assert M.diagonal().min() > 0
    _, _, Xa = polydec.lifted_laplacian(V, F)
    assert np.all(np.linalg.norm(Xa, axis=1) < 1)  # the affine points lie inside the sphere


def test_bad_lifts_are_refused():
    V, F = polydec.quad_grid(3, 3)
    with pytest.raises(ValueError, match="coplanar"):
        polydec.lifted_laplacian(V, F, lift="sphere")
    with pytest.raises(ValueError, match="unknown virtual lift"):
        polydec.lifted_laplacian(V, F, lift="ball")
    with pytest.raises(ValueError):
        polydec.lifted_laplacian(V, F, positions=np.zeros((2, 3)))
    with pytest.raises(ValueError, match="no virtual vertices"):
        polydec.lifted_laplacian(V, F, lift="quadric", laplacian="diamond")


def test_cli_positions_file_equals_the_lift(cli, tmp_path):
    """`polydec operators --virtual-positions FILE` with the quadric lift's points written to FILE
    gives the same matrices, byte for byte, as `--virtual-lift quadric`; a malformed file is a bad
    input (exit 3) naming file and line, both options at once a usage error (exit 2)."""
    import os
    import subprocess

    V, F = polydec.hex_sphere(1)
    mesh = tmp_path / "m.ply"
    polydec.write_mesh(str(mesh), V, F)
    _, _, X = polydec.lifted_laplacian(V, F, lift="quadric")
    points = tmp_path / "x.txt"
    points.write_text("".join("%.17g %.17g %.17g\n" % tuple(p) for p in X))
    cli("operators", mesh, "--virtual-positions", points, "--out", tmp_path / "given")
    cli("operators", mesh, "--virtual-lift", "quadric", "--out", tmp_path / "lifted")
    for name in ("S.mtx", "M.mtx", "M_lumped.mtx", "G.mtx", "P.mtx"):
        assert (tmp_path / "given" / name).read_bytes() == (tmp_path / "lifted" / name).read_bytes(), name
    exe = os.environ.get("POLYDEC_CLI")
    if not exe:
        pytest.skip("exit codes need POLYDEC_CLI")
    bad = tmp_path / "bad.txt"
    lines = points.read_text().splitlines(keepends=True)
    bad.write_text(lines[0] + "1 2\n" + "".join(lines[2:]))
    r = subprocess.run([exe, "operators", str(mesh), "--virtual-positions", str(bad), "--out", str(tmp_path / "o")],
                       capture_output=True, text=True)
    assert r.returncode == 3 and f"{bad}:2: expected 'x y z', found 2 values" in r.stderr
    r = subprocess.run([exe, "curvature", str(mesh), "--virtual-positions", str(points), "--virtual-lift", "sphere"],
                       capture_output=True, text=True)
    assert r.returncode == 2 and "exclude each other" in r.stderr
