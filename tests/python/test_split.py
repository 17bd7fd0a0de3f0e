"""tests/python/test_split.py — laplacian="split" (several virtual vertices in non-convex faces): the
paper's operators exactly on convex meshes; on a saw-tooth grid (faces without a valid single fan)
S symmetric, S @ 1 = 0, linear precision at the interior vertices and exact gradients of linear
functions."""

import numpy as np

import polydec


def sawtooth_grid(n, teeth=2, dent=0.7):
    """The n x n saw-tooth tiling of the unit square, as dec/mesh/sawtooth_grid.h builds it."""
    per_cell = 2 * teeth
    per_line = n * per_cell + 1
    V = [(k / (n * per_cell), (j + (dent if k % 2 == 1 and 0 < j < n else 0.0)) / n, 0.0)
         for j in range(n + 1) for k in range(per_line)]
    F = []
    for j in range(n):
        for i in range(n):
            bottom = [j * per_line + i * per_cell + k for k in range(per_cell + 1)]
            top = [(j + 1) * per_line + i * per_cell + k for k in range(per_cell, -1, -1)]
            F.append(bottom + top)
    return np.array(V), F


def test_split_is_the_papers_operator_on_convex_meshes():
    V, F = polydec.hex_grid(4, 4)
    for part in (polydec.stiffness, polydec.mass, polydec.gradient):
        assert (part(V, F, laplacian="split") != part(V, F)).nnz == 0


def test_split_on_sawtooth_grid():
    V, F = sawtooth_grid(3)
    S, M = polydec.laplacian(V, F, laplacian="split", mass="galerkin")
    s = abs(S).max()
    assert abs(S - S.T).max() == 0
    assert np.max(np.abs(S @ np.ones(len(V)))) <= 1e-13 * s
    assert abs(M.sum() - 1) < 1e-12
    interior = (V[:, 0] > 1e-12) & (V[:, 0] < 1 - 1e-12) & (V[:, 1] > 1e-12) & (V[:, 1] < 1 - 1e-12)
    assert interior.sum() > 0
    for g in ([1, 0, 0], [0, 1, 0], [0.3, -1.7, 0]):
        u = V @ np.array(g)
        assert np.max(np.abs((S @ u)[interior])) <= 1e-12 * s
        Gu = polydec.gradient(V, F, laplacian="split") @ u
        assert np.max(np.abs(Gu.reshape(-1, 3) - g)) <= 1e-10
    # The paper's single virtual vertex gives these faces inverted fan triangles: another operator.
    assert abs(S - polydec.stiffness(V, F)).max() > 1e-3 * s
