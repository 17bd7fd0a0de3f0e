"""polydec._virtual_lift — the paper's operator with its virtual vertices off their affine points
(beyond the paper; docs/extensions.md): the weights keep defining the prolongation P, the fan
triangles meet at given or lifted positions. Imported into polydec."""

import numpy as np

from . import _convert, _polydec
from ._mesh import handle as _handle


def lifted_laplacian(V, F=None, lift="none", positions=None, mass="lumped", laplacian="ours"):
    """(S, M, virtual_points) of `laplacian` ("ours" or another virtual-vertex rule: "centroid",
    "abs-area", "convex", "trace-min") with the virtual vertices placed by lift: "none" (the affine
    points, the paper's operator; default), "sphere" (closest point on the vertices' best-fit sphere),
    "sphere:cx,cy,cz,r", "quadric" (local quadric fit); or at positions, an (|F|, 3) array (then
    lift must stay "none"). S is symmetric NEGATIVE semi-definite with S @ 1 = 0; M the lumped
    (diagonal, mass="lumped") or Galerkin mass ("galerkin"); virtual_points (|F|, 3) where the fans
    meet. V, F may be a polydec.Mesh (F omitted). ValueError for a lift that does not fit the mesh
    (e.g. "sphere" on a planar mesh).

    >>> S, M, X = polydec.lifted_laplacian(polydec.hex_sphere(2), lift="sphere")
    >>> bool(abs(S @ np.ones(S.shape[0])).max() < 1e-12), X.shape[1]
    (True, 3)
    """
    lumped = _convert.lumped_flag(mass)
    if positions is not None:
        positions = np.ascontiguousarray(positions, dtype=np.float64)
    d = _polydec.lifted_operators(_handle(V, F), str(laplacian), str(lift), positions)
    if lumped:
        import scipy.sparse

        n = d["M_lumped"].shape[0]
        M = scipy.sparse.csc_matrix((d["M_lumped"], np.arange(n, dtype=np.int32), np.arange(n + 1, dtype=np.int32)),
                                    shape=(n, n))
    else:
        M = d["M"]
    return d["S"], M, d["virtual_points"]
