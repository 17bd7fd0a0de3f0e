"""tests/python/test_quadratic.py — polydec.quadratic_operators: the dof layout (vertices, then edge
midpoints in lexicographic edge order), S symmetric with constants in its null space, M and the
HRZ lumping summing to the area, the patch test for a quadratic function on hexagons, and equality
with the matrices `polydec operators --order 2` writes."""

import numpy as np
import pytest
import scipy.io

import polydec
from conftest import relative_difference


def edges(F):
    return sorted({(min(a, b), max(a, b)) for f in F for a, b in zip(f, list(f[1:]) + [f[0]])})


def test_layout_symmetry_and_mass():
    mesh = polydec.hex_grid(4, 3)
    V, F = mesh.positions, mesh.face_list()
    S, M, dofs = polydec.quadratic_operators(V, F)
    E = edges(F)
    n = len(V) + len(E)
    assert S.shape == (n, n) and M.shape == (n, n) and dofs.shape == (n, 3)
    assert np.array_equal(dofs[: len(V)], V)
    assert np.allclose(dofs[len(V):], [(V[i] + V[j]) / 2 for i, j in E], rtol=0, atol=1e-15)
    assert relative_difference(S, S.T) < 1e-14
    assert np.abs(S @ np.ones(n)).max() < 1e-12 * np.abs(S.diagonal()).max()
    assert abs(M.sum() - 1.0) < 1e-12  # the unit square
    _, L, _ = polydec.quadratic_operators(V, F, mass="lumped")
    assert L.diagonal().min() > 0 and abs(L.diagonal().sum() - 1.0) < 1e-12
    with pytest.raises(ValueError):
        polydec.quadratic_operators(V, F, mass="row-sum")


def test_patch_test_on_hexagons():
    mesh = polydec.hex_grid(5, 5)
    V, F = mesh.positions, mesh.face_list()
    S, M, dofs = polydec.quadratic_operators(V, F)
    x, y = dofs[:, 0], dofs[:, 1]
    u = 2 * x * x - x * y + 0.5 * y * y + x
    Su, rhs = S @ u, (2 * 2 + 2 * 0.5) * (M @ np.ones(len(u)))
    interior = (x > 1e-12) & (x < 1 - 1e-12) & (y > 1e-12) & (y < 1 - 1e-12)
    assert interior.sum() > 0
    assert np.abs(Su - rhs)[interior].max() < 1e-10 * np.abs(rhs).max()


def test_equals_the_command_line(cli, tmp_path):
    mesh = polydec.hex_grid(3, 3)
    V, F = mesh.positions, mesh.face_list()
    path = tmp_path / "hex.obj"
    polydec.write_mesh(path, V, F)
    cli("operators", path, "--order", "2", "--out", tmp_path / "q")
    S, M, dofs = polydec.quadratic_operators(*polydec.read_mesh(path))
    assert relative_difference(S, scipy.io.mmread(str(tmp_path / "q" / "S.mtx"))) < 1e-14
    assert relative_difference(M, scipy.io.mmread(str(tmp_path / "q" / "M.mtx"))) < 1e-14
    assert np.abs(dofs - np.loadtxt(tmp_path / "q" / "dofs.txt")).max() < 1e-15
