"""polydec._quadratic — the quadratic polygon Laplacian (order 2 elements on the vertices and edge
midpoints, docs/extensions.md). Imported into polydec."""

import numpy as np
import scipy.sparse

from . import _polydec
from ._mesh import handle as _handle


def quadratic_operators(V, F=None, mass="galerkin"):
    """(S, M, dof_positions) of the quadratic elements: S (n, n) csc_matrix negative
    semi-definite, n = |V| + |E| (the vertices in order, then one dof per edge, edges (i, j) i < j
    in lexicographic order); M the Galerkin mass (csc_matrix), or with mass="lumped" its diagonal
    (HRZ) lumping as a dia_matrix; dof_positions (n, 3): the vertices, then the edge midpoints.
    V, F may be a polydec.Mesh (F omitted).

    >>> S, M, X = polydec.quadratic_operators(polydec.quad_grid(2, 2))
    >>> S.shape, X.shape, bool(abs(S @ np.ones(S.shape[0])).max() < 1e-12), round(M.sum(), 12)
    ((21, 21), (21, 3), True, 1.0)
    """
    if mass not in ("galerkin", "lumped"):
        raise ValueError("mass must be 'galerkin' or 'lumped'")
    S, M, M_lumped, dofs = _polydec.quadratic_operators(_handle(V, F))
    if mass == "lumped":
        M = scipy.sparse.diags(np.asarray(M_lumped))
    return S, M, np.ascontiguousarray(dofs)
