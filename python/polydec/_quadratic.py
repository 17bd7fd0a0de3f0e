"""polydec._quadratic — the quadratic polygon Laplacian (order 2 elements on the vertices and edge
midpoints, docs/extensions.md). Imported into polydec."""

import numpy as np
import scipy.sparse

from . import _convert, _polydec


def quadratic_operators(V, F, mass="galerkin"):
    """(S, M, dof_positions) of the quadratic elements: S (n, n) csc_matrix negative
    semi-definite, n = |V| + |E| (the vertices in order, then one dof per edge, edges (i, j) i < j
    in lexicographic order); M the Galerkin mass (csc_matrix), or with mass="lumped" its diagonal
    (HRZ) lumping as a dia_matrix; dof_positions (n, 3): the vertices, then the edge midpoints."""
    if mass not in ("galerkin", "lumped"):
        raise ValueError("mass must be 'galerkin' or 'lumped'")
    S, M, M_lumped, dofs = _polydec.quadratic_operators(*_convert.mesh(V, F))
    if mass == "lumped":
        M = scipy.sparse.diags(np.asarray(M_lumped))
    return S, M, np.ascontiguousarray(dofs)
