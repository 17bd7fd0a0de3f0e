"""polydec — discrete exterior calculus on polygon meshes ("Polygon Laplacian Made Simple",
Bunge, Herholz, Kazhdan, Botsch, EG 2020), from Python.

Conventions (docs/python.md):
  * A surface is a polydec.Mesh (validated once; its refinement built on first use and kept), or
    positions V, a (|V|, 3) float64 array, with faces F, a list of lists, an (|F|, k) integer
    array, or the flat tuple (indices, offsets) of two 1-D integer numpy arrays. Any integer
    dtype; positions of other real dtypes are converted exactly (never silently rounded). Every
    function taking (V, F) takes a Mesh instead: stiffness(mesh), laplacian(mesh, mass=...).
  * Meshes returned (read_mesh, generators, transformations) are Mesh objects; `V, F = mesh`
    unpacks them. Faces are returned in one form everywhere: the flat tuple (indices, offsets) of
    two int64 arrays.
  * planarity=None | "exact" | T wherever the refinement is built (docs/python.md): None the
    mesh's coordinate precision (a read file's digits, as the command line), "exact" the doubles
    as exact, T a tolerance (the command line's --planarity-tolerance T).
  * The stiffness S is symmetric NEGATIVE semi-definite (S @ 1 = 0, x^T S x <= 0), as libigl's
    cotmatrix; the Laplacian is L = M^-1 S. The mass M is the Galerkin (consistent) mass; the
    lumped mass is its row sums (a diagonal matrix). Sparse results are
    scipy.sparse.csc_matrix of float64, rows and columns in the given vertex order.
  * Laplacian variants by name, as on the command line: "ours" (default), "centroid",
    "abs-area", "convex", "trace-min", "triangulated-minarea", "triangulated-maxminangle",
    "refined", "intrinsic-delaunay", "aw11:LAMBDA", "degoes20:LAMBDA", "diamond" (laplacian_names()).
  * The GIL is released during validation, assembly, factorization and solves.
  * Errors: InvalidMeshError (a ValueError naming the face, vertex or edge), FileError (an
    OSError and a ValueError with the file and line; MeshFileNotFoundError, also a
    FileNotFoundError, for a missing file), SolverError (a RuntimeError), ValueError for bad
    arguments (sizes that are not integers, threads < 0, non-positive time step factors, ...).
  * meshio: from_meshio(m) / to_meshio(mesh) (polydec._meshio; meshio is optional).
  * Volume meshes: VolumeMesh and the volume_* functions (polydec._volume); spectra of forms and
    spectral shape tools: polydec._spectral.
"""

import os

import numpy as np

from . import _convert, _polydec
from ._convert import MeshFileNotFoundError
from ._mesh import Mesh
from ._mesh import handle as _handle
from ._mesh import shift as _shift
from ._polydec import FileError, InvalidMeshError, SolverError

__version__ = "0.3.0"

__all__ = [
    "FileError", "MeshFileNotFoundError", "InvalidMeshError", "SolverError", "Mesh", "from_meshio", "to_meshio",
    "read_mesh", "write_mesh", "mesh_info",
    "quad_grid", "triangle_grid", "hex_grid", "uv_sphere", "cube_sphere", "hex_sphere", "torus", "genus2",
    "catmull_clark", "dual", "project_to_unit_sphere", "add_noise",
    "laplacian_names", "stiffness", "mass", "lumped_mass", "laplacian", "gradient", "divergence",
    "prolongation", "d0", "d1", "star0", "star1", "star2", "P0", "P1", "P2", "cells", "dec_operators",
    "HeatGeodesics", "suggested_time_factor", "spectrum", "HodgeDecomposer", "HodgeParts", "hodge_decomposition",
    "mean_curvature", "vertex_normals", "CurvatureFlow", "curvature_flow",
    "conformal_parametrization", "conformal_distortion",
    "form_spectrum", "surface_dec", "hks_times", "heat_kernel_signature", "wave_kernel_signature", "biharmonic_distance",
    "diffusion_distance", "lowpass_filter",
    "VolumeMesh", "read_volume_mesh", "write_volume_mesh", "jitter_interior", "hex_grid_volume", "tet_grid_volume",
    "pyramid_grid_volume", "truncated_octahedra_volume", "cuboctahedra_volume", "hex_torus_volume",
    "hex_ball_volume", "volume_laplacian_names", "volume_operators", "volume_stiffness", "volume_mass",
    "volume_lumped_mass", "volume_laplacian", "volume_gradient", "volume_divergence", "volume_dec_max_degree",
    "volume_dec", "VolumeHeatGeodesics", "volume_spectrum", "ball_eigenvalues", "volume_poisson",
    "volume_franke_poisson", "VolumeHodgeDecomposer", "lifted_laplacian", "quadratic_operators",
    "read_mesh_groups", "keep_freed_memory",
]


# ----------------------------------------------------------------------------------------- meshes

def read_mesh(path):
    """Reads an OBJ, OFF, PLY, gmsh .msh or VTK XML .vtu file (by extension) -> Mesh, in the file's vertex order, keeping
    what the file's digits resolve (so its matrices equal the command line's on the same file).
    `V, F = read_mesh(path)` unpacks positions and flat faces. Raises MeshFileNotFoundError (a
    FileError and a FileNotFoundError) for a missing file, FileError (OSError and ValueError)
    naming the file and line (or byte offset) for an unreadable or malformed file or an invalid
    mesh in it.

    >>> import tempfile, os
    >>> path = os.path.join(tempfile.mkdtemp(), "grid.obj")
    >>> polydec.write_mesh(path, polydec.quad_grid(2, 1))
    >>> polydec.read_mesh(path)
    Mesh(6 vertices, 2 faces, 7 edges)
    """
    return Mesh._wrap(_polydec.read_mesh(_convert.existing_file(path)))


def write_mesh(path, V, F=None, scalars=None, binary=False):
    """Writes a Mesh (or (V, F)) as OBJ, OFF, PLY or VTK XML .vtu (by extension), positions with 17
    significant digits.

    scalars: optional {name: (|V|,) array}, written as PLY vertex properties or .vtu point data
    (OBJ and OFF hold none: FileError). binary: binary PLY or base64 .vtu (bit-exact) or OFF BINARY
    (float32, lossy). Raises FileError.

    >>> import tempfile, os
    >>> path = os.path.join(tempfile.mkdtemp(), "t.ply")
    >>> polydec.write_mesh(path, polydec.triangle_grid(1, 1), scalars={"u": [0, 1, 2, 3]})
    >>> polydec.read_mesh(path).n_faces
    2
    """
    h = _handle(V, F)
    s = {str(k): np.asarray(v, dtype=np.float64).reshape(-1) for k, v in (scalars or {}).items()}
    _polydec.write_mesh(os.fspath(path), h, s, bool(binary))


def mesh_info(V, F=None):
    """Validates a Mesh or (V, F) and returns counts: vertices, faces, edges, halfedges,
    boundary_loops, components, unreferenced_vertices, euler_characteristic, and edge_list
    (|E|, 2) int32 with rows (i, j), i < j, in lexicographic order (the numbering of the edges
    everywhere). Raises InvalidMeshError (ValueError) for an invalid mesh.

    >>> polydec.mesh_info(polydec.torus(8, 4))["euler_characteristic"]
    0
    """
    return _polydec.validate(_handle(V, F))


def quad_grid(nx, ny):
    """Planar nx x ny quad grid on [0,1]^2 (z = 0) -> Mesh. Sizes must be integers; meshes of
    more than 1e8 vertices are refused (ValueError) before anything is built.

    >>> polydec.quad_grid(4, 2)
    Mesh(15 vertices, 8 faces, 22 edges)
    """
    return Mesh._wrap(_polydec.quad_grid(_convert.size(nx, "nx", 1), _convert.size(ny, "ny", 1)))


def triangle_grid(nx, ny):
    """Planar nx x ny grid on [0,1]^2, each cell split into two triangles -> Mesh.

    >>> polydec.triangle_grid(2, 2).face_array().shape
    (8, 3)
    """
    return Mesh._wrap(_polydec.triangle_grid(_convert.size(nx, "nx", 1), _convert.size(ny, "ny", 1)))


def hex_grid(nx, ny):
    """Hexagon-dominant tiling of [0,1]^2 (dual of triangle_grid, boundary faces cut) -> Mesh.

    >>> int(np.diff(polydec.hex_grid(4, 4).faces[1]).max())
    6
    """
    return Mesh._wrap(_polydec.hex_grid(_convert.size(nx, "nx", 1), _convert.size(ny, "ny", 1)))


def uv_sphere(n_lat, n_lon):
    """Unit UV sphere, polar axis z: quads, triangles at the poles -> Mesh.

    >>> polydec.uv_sphere(4, 8).euler_characteristic
    2
    """
    return Mesh._wrap(_polydec.uv_sphere(_convert.size(n_lat, "n_lat", 2), _convert.size(n_lon, "n_lon", 3)))


def cube_sphere(n):
    """Unit quad sphere: a cube with n x n quads per side projected to the sphere -> Mesh.

    >>> polydec.cube_sphere(3).n_faces
    54
    """
    return Mesh._wrap(_polydec.cube_sphere(_convert.size(n, "n", 1)))


def hex_sphere(level):
    """Hexagon-dominant unit sphere (12 pentagons): dual of an icosahedron subdivided `level`
    times -> Mesh (20 4^level vertices; ValueError above 1e8, at once).

    >>> polydec.hex_sphere(1).n_vertices
    80
    """
    return Mesh._wrap(_polydec.hex_sphere(_convert.size(level, "level", 0)))


def torus(n_major, n_minor, R=1.0, r=0.4):
    """Quad torus around the z axis, radii R > r > 0 -> Mesh.

    >>> polydec.torus(6, 4).n_faces
    24
    """
    return Mesh._wrap(_polydec.torus(_convert.size(n_major, "n_major", 3), _convert.size(n_minor, "n_minor", 3),
                                     float(R), float(r)))


def genus2(subdivisions=1):
    """Closed genus-2 quad surface, smoothed by `subdivisions` Catmull-Clark steps -> Mesh.

    >>> polydec.genus2(0).euler_characteristic
    -2
    """
    return Mesh._wrap(_polydec.genus2(_convert.size(subdivisions, "subdivisions", 0)))


def catmull_clark(V, F=None):
    """One Catmull-Clark step of a Mesh (or (V, F)) -> Mesh: old vertices first (same indices),
    then edge points, then face points.

    >>> polydec.catmull_clark(polydec.quad_grid(1, 1)).n_faces
    4
    """
    return Mesh._wrap(_polydec.catmull_clark(_handle(V, F)))


def dual(V, F=None):
    """Dual mesh -> Mesh: one vertex per face (centroid), one face per vertex (with boundary:
    boundary edge midpoints and boundary vertices added).

    >>> polydec.dual(polydec.cube_sphere(1)).n_faces
    8
    """
    return Mesh._wrap(_polydec.dual(_handle(V, F)))


def project_to_unit_sphere(V, F=None):
    """Every vertex moved to p / |p| -> Mesh. InvalidMeshError for a vertex at the origin.

    >>> m = polydec.project_to_unit_sphere(polydec.dual(polydec.cube_sphere(2)))
    >>> bool(np.allclose(np.linalg.norm(m.positions, axis=1), 1))
    True
    """
    return Mesh._wrap(_polydec.project_to_unit_sphere(_handle(V, F)))


def add_noise(V, F=None, amplitude=None, seed=1):
    """Every vertex moved by a uniform random vector of length up to amplitude * mean edge length
    (deterministic for a seed) -> Mesh. add_noise(mesh, amplitude) or add_noise(V, F, amplitude).

    >>> g = polydec.quad_grid(2, 2)
    >>> bool(np.abs(polydec.add_noise(g, 0.1).positions - g.positions).max() <= 0.1 * g.mean_edge_length)
    True
    """
    V, F, amplitude = _shift(V, F, amplitude)
    if amplitude is None:
        raise TypeError("add_noise needs an amplitude")
    return Mesh._wrap(_polydec.add_noise(_handle(V, F), float(amplitude), int(seed)))


# -------------------------------------------------------------------------------------- operators

def laplacian_names():
    """The Laplacian methods accepted by laplacian=... (parameters follow a colon: "aw11:0.5").

    >>> "ours" in polydec.laplacian_names()
    True
    """
    return list(_polydec.laplacian_names())


def _operators(V, F, laplacian, parts, threads=1, planarity=None):
    d = _polydec.operators(_handle(V, F), str(laplacian), set(parts), _convert.threads(threads),
                           _convert.planarity(planarity))
    if "M" in parts and not d["has_M"]:
        raise ValueError(f"the Laplacian {d['name']!r} defines no Galerkin mass; use lumped_mass")
    if ("G" in parts or "D" in parts) and not d["has_G"]:
        raise ValueError(f"the Laplacian {d['name']!r} defines no gradient")
    return d


def _diagonal(v):
    import scipy.sparse

    n = v.shape[0]
    return scipy.sparse.csc_matrix((np.asarray(v, dtype=np.float64), np.arange(n, dtype=np.int32),
                                    np.arange(n + 1, dtype=np.int32)), shape=(n, n))


def stiffness(V, F=None, laplacian="ours", threads=1, planarity=None):
    """Stiffness matrix S (paper eq. 12) of a Mesh (or (V, F)), (|V|, |V|)
    scipy.sparse.csc_matrix, float64.

    Symmetric NEGATIVE semi-definite: S @ ones = 0 and x @ S @ x <= 0 (libigl's cotmatrix sign;
    robust_laplacian and potpourri3d return -S). Rows and columns in the given vertex order;
    unreferenced vertices get empty rows. laplacian: the method's name ("ours", "aw11:0.5", ...);
    for "refined" the matrix is on the refined mesh, |V| + |F| square, input vertices first.
    threads: assembly threads for "ours" (an integer >= 0, 0: all; the result does not depend on
    it). planarity: None (the mesh's coordinate precision: a read file's digits, exact doubles
    for arrays), "exact", or a tolerance T in (0, 1) (the command line's --planarity-tolerance).

    >>> S = polydec.stiffness(polydec.quad_grid(3, 3))
    >>> S.shape, bool(abs(S @ np.ones(16)).max() < 1e-14)
    ((16, 16), True)
    """
    return _operators(V, F, laplacian, {"S"}, threads, planarity)["S"]


def mass(V, F=None, laplacian="ours", threads=1, planarity=None):
    """Galerkin (consistent, unlumped) mass matrix M (paper eq. 13), (|V|, |V|) csc_matrix,
    symmetric positive semi-definite, summing to the surface area. ValueError for a method
    without one ("aw11" and "degoes20" define only lumped masses).

    >>> round(polydec.mass(polydec.quad_grid(3, 3)).sum(), 12)
    1.0
    """
    return _operators(V, F, laplacian, {"M"}, threads, planarity)["M"]


def lumped_mass(V, F=None, laplacian="ours", threads=1, planarity=None):
    """Lumped mass (paper eq. 14): the row sums of the Galerkin mass, as a diagonal (|V|, |V|)
    csc_matrix (its .diagonal() is the vector of vertex areas), positive at referenced vertices.

    >>> round(polydec.lumped_mass(polydec.quad_grid(2, 2)).diagonal()[4], 12)
    0.25
    """
    return _diagonal(_operators(V, F, laplacian, {"M_lumped"}, threads, planarity)["M_lumped"])


def laplacian(V, F=None, laplacian="ours", mass="lumped", threads=1, planarity=None):
    """(S, M): the stiffness S (NEGATIVE semi-definite, S @ 1 = 0) and the mass M, both
    (|V|, |V|) csc_matrix; the Laplace-Beltrami operator is L = M^-1 S (so L x = lambda x has
    lambda <= 0). mass="lumped" (default, diagonal) or "galerkin". One assembly for both.

    >>> S, M = polydec.laplacian(polydec.hex_sphere(2))
    >>> bool(abs(S - S.T).max() < 1e-14), round(M.sum(), 1)
    (True, 12.4)
    """
    lumped = _convert.lumped_flag(mass)
    d = _operators(V, F, laplacian, {"S", "M_lumped" if lumped else "M"}, threads, planarity)
    return d["S"], _diagonal(d["M_lumped"]) if lumped else d["M"]


def gradient(V, F=None, laplacian="ours", planarity=None):
    """Gradient G (paper eq. 17), (3 |H|, |V|) csc_matrix, |H| = number of face corners: rows
    3h, 3h+1, 3h+2 are the x, y, z components of the constant gradient on fan triangle h
    (corner h, the next corner of its face and the face's virtual vertex). S = D @ G.

    >>> g = polydec.quad_grid(2, 2)
    >>> G = polydec.gradient(g)
    >>> G.shape, bool(np.allclose(G @ g.positions[:, 0], np.tile([1, 0, 0], 16)))
    ((48, 9), True)
    """
    return _operators(V, F, laplacian, {"G"}, 1, planarity)["G"]


def divergence(V, F=None, laplacian="ours", planarity=None):
    """Divergence D = -G^T W (paper eq. 18), (|V|, 3 |H|) csc_matrix, W the fan-triangle areas
    (each repeated three times); S = D @ G, so D is the negative adjoint of G.

    >>> g = polydec.hex_grid(3, 3)
    >>> bool(abs(polydec.divergence(g) @ polydec.gradient(g) - polydec.stiffness(g)).max() < 1e-12)
    True
    """
    return _operators(V, F, laplacian, {"D"}, 1, planarity)["D"]


def _dec(V, F, parts, virtual_vertex="squared-area", planarity=None):
    return _polydec.dec(_handle(V, F), set(parts), str(virtual_vertex), _convert.planarity(planarity))


def prolongation(V, F=None, virtual_vertex="squared-area", planarity=None):
    """Prolongation P = P0 (paper eq. 11), (|V| + |F|, |V|) csc_matrix: the identity on the
    vertices, row |V| + f the virtual-vertex weights of face f (summing to 1). S = P^T S^f P.

    >>> P = polydec.prolongation(polydec.quad_grid(1, 1))
    >>> P.toarray()[4].tolist()
    [0.25, 0.25, 0.25, 0.25]
    """
    return _dec(V, F, {"P0"}, virtual_vertex, planarity)["P0"]


def P0(V, F=None, virtual_vertex="squared-area", planarity=None):
    """P0 (paper eq. 24), the prolongation of 0-forms: same as prolongation().

    >>> polydec.P0(polydec.quad_grid(2, 1)).shape
    (8, 6)
    """
    return prolongation(V, F, virtual_vertex, planarity)


def P1(V, F=None, virtual_vertex="squared-area", planarity=None):
    """P1 (paper eq. 25), (|E| + |H|, |C1|) csc_matrix from the coarse 1-cells (cells()[0]) to
    the refined edges (mesh edges, then one spoke per face corner).

    >>> polydec.P1(polydec.quad_grid(1, 1)).shape
    (8, 6)
    """
    return _dec(V, F, {"P1"}, virtual_vertex, planarity)["P1"]


def P2(V, F=None, virtual_vertex="squared-area", planarity=None):
    """P2 (paper eq. 26), (|H|, |C2|) csc_matrix from the coarse 2-cells (cells()[1]) to the fan
    triangles.

    >>> polydec.P2(polydec.quad_grid(1, 1)).shape
    (4, 4)
    """
    return _dec(V, F, {"P2"}, virtual_vertex, planarity)["P2"]


def d0(V, F=None):
    """Coboundary d0 (paper eq. 19), (|C1|, |V|) csc_matrix with entries -1 (row's i) and +1
    (row's j) for coarse 1-cell (i, j), i < j (cells()[0]: edges and diagonals).

    >>> polydec.d0(polydec.quad_grid(1, 1)).toarray()[0].tolist()
    [-1.0, 1.0, 0.0, 0.0]
    """
    return _dec(V, F, {"d0"})["d0"]


def d1(V, F=None):
    """Coboundary d1 (paper eq. 19), (|C2|, |C1|) csc_matrix: (d1 c)_ijk = c_ij + c_jk - c_ik.
    d1 @ d0 = 0 exactly.

    >>> g = polydec.hex_grid(2, 2)
    >>> (polydec.d1(g) @ polydec.d0(g)).count_nonzero()
    0
    """
    return _dec(V, F, {"d1"})["d1"]


def star0(V, F=None, lumped=False, virtual_vertex="squared-area", planarity=None):
    """Hodge star of 0-forms (paper eq. 20, 27), (|V|, |V|) csc_matrix, positive semi-definite:
    the Galerkin mass (lumped=True: its row sums, diagonal).

    >>> round(polydec.star0(polydec.quad_grid(2, 2), lumped=True).sum(), 12)
    1.0
    """
    if lumped:
        return _diagonal(_dec(V, F, {"star0_lumped"}, virtual_vertex, planarity)["star0_lumped"])
    return _dec(V, F, {"star0"}, virtual_vertex, planarity)["star0"]


def star1(V, F=None, virtual_vertex="squared-area", planarity=None):
    """Hodge star of 1-forms (paper eq. 21, 27), (|C1|, |C1|) csc_matrix, symmetric positive
    SEMI-definite (singular on faces with 5 or more corners). S = -d0^T star1 d0.

    >>> g = polydec.hex_grid(2, 2)
    >>> D0 = polydec.d0(g)
    >>> bool(abs(-D0.T @ polydec.star1(g) @ D0 - polydec.stiffness(g)).max() < 1e-12)
    True
    """
    return _dec(V, F, {"star1"}, virtual_vertex, planarity)["star1"]


def star2(V, F=None, virtual_vertex="squared-area", planarity=None):
    """Hodge star of 2-forms (paper eq. 22, 27), (|C2|, |C2|) csc_matrix, positive semi-definite.

    >>> polydec.star2(polydec.quad_grid(1, 1)).shape
    (4, 4)
    """
    return _dec(V, F, {"star2"}, virtual_vertex, planarity)["star2"]


def cells(V, F=None):
    """The coarse cell lists (paper section 4.6): (pairs (|C1|, 2), triples (|C2|, 3)) int32,
    vertex indices increasing in each row, rows in lexicographic order — all vertex pairs and
    triples sharing a face (polygon edges and diagonals). The numbering of d0, d1, star1, star2.

    >>> pairs, triples = polydec.cells(polydec.quad_grid(1, 1))
    >>> len(pairs), len(triples)
    (6, 4)
    """
    d = _dec(V, F, {"pairs", "triples"})
    return d["pairs"], d["triples"]


def surface_dec(V, F=None, complex="mesh", max_degree=2, spoke_rule="area", virtual_vertex="squared-area",
                planarity=None):
    """DEC on a polygon mesh in one bundle (dec/surface/hodge_star.h, SurfaceDec) -> dict with the
    lists d [d0, d1], P [P0, P1, P2], star [star0, star1, star2] (csc_matrix; d_k for k < max_degree,
    P_k and star_k for k <= max_degree), so that d[k], P[k], star[k] read like PyDEC's and like
    volume_dec's; complex, max_degree, and the cells: complex="mesh" (default) the mesh's edges
    (|E|, 2) int32 (i < j, oriented i -> j) and faces (a list of vertex arrays, each in its
    orientation), with star1, star2 positive definite (star2 diagonal, 1/area with
    spoke_rule="area"; "minimum-norm" the alternative of docs/feec.md); complex="complete" the
    paper's pairs (|C1|, 2) and triples (|C2|, 3). S = -d[0].T @ star[1] @ d[0] on both.

    >>> D = polydec.surface_dec(polydec.quad_grid(2, 2))
    >>> [m.shape for m in D["d"]]
    [(12, 9), (4, 12)]
    """
    d = _polydec.surface_dec(_handle(V, F), str(complex), int(max_degree), str(spoke_rule), str(virtual_vertex),
                             _convert.planarity(planarity))
    if "faces" in d:
        o, i = d.pop("face_offsets"), d.pop("face_indices")
        d["faces"] = [i[o[f]:o[f + 1]] for f in range(len(o) - 1)]
    return d


def dec_operators(V, F=None, virtual_vertex="squared-area", planarity=None):
    """All DEC pieces from one refinement: a dict with d0, d1, star0, star0_lumped (vector),
    star1, star2, P0, P1, P2 (csc_matrix), pairs, triples (int32 cell lists) and is_edge (bool
    per pair: a mesh edge rather than a diagonal).

    >>> int(polydec.dec_operators(polydec.quad_grid(1, 1))["is_edge"].sum())
    4
    """
    return _dec(V, F, {"d0", "d1", "star0", "star0_lumped", "star1", "star2", "P0", "P1", "P2", "pairs",
                       "triples", "is_edge"}, virtual_vertex, planarity)


# ---------------------------------------------------------------------------------------- solvers

class HeatGeodesics:
    """Geodesic distance by the heat method (paper section 5.5, eq. 31-33), factored once.

    HeatGeodesics(mesh, laplacian="ours", time_step_factor=1.0, mass="lumped") (a Mesh, or V, F)
    factors M - t S and the Poisson matrix -S (t = factor * mean edge length^2, factor > 0); each
    distance(sources) then costs two back-substitutions. Distances: (|V|,) float64, >= 0, 0 at
    the nearest source, +inf at vertices no source reaches (other components, unreferenced).

    >>> h = polydec.HeatGeodesics(polydec.quad_grid(8, 8))
    >>> d = h.distance(0)
    >>> float(d[0]), bool(abs(d[80] - 2 ** 0.5) < 0.1)
    (0.0, True)
    """

    def __init__(self, V, F=None, laplacian="ours", time_step_factor=1.0, mass="lumped", mass_weighted_source=True,
                 planarity=None):
        h = _handle(V, F)
        self._n = h.n_vertices
        factor = _convert.positive(time_step_factor, "time_step_factor")
        self._solver = _polydec.HeatGeodesics(h, str(laplacian), factor, _convert.lumped_flag(mass),
                                              bool(mass_weighted_source), _convert.planarity(planarity))

    def distance(self, sources, return_diagnostics=False):
        """Distances from a vertex index or a sequence of them -> (|V|,) float64.
        ValueError for a source outside [0, |V|).

        return_diagnostics=True returns (distances, diagnostics), diagnostics a dict saying how far
        the heat step (eq. 31) carried: "unresolved_vertices" (int), the reached vertices whose
        heat value fell below what the solve resolves (1e-280 of its maximum, about 650 sqrt(t)
        from the sources: meshes more than ~650 edges across at the default factor), where the
        distance is wrong (too small, flat); "resolved_radius" (float), the largest distance
        among the resolved vertices. When vertices are unresolved, rebuild with
        time_step_factor=suggested_time_factor(time_step_factor, diagnostics, extent).
        """
        return _convert.heat_distance(self._solver, self._n, sources, return_diagnostics)

    def distances(self, sources, block=64, out=None):
        """One distance field per source -> (|V|, k) float64, column c the distances from
        sources[c] (distance(sources) is the distance to the whole set): equal to k calls of
        distance() up to round-off, solved as blocks of up to `block` right-hand sides, several
        times cheaper per source. An all-pairs matrix: D = distances(range(|V|)), then
        0.5 * (D + D.T) (the heat method is not exactly symmetric). The object keeps the call's two
        blocks (2 |V| min(block, k) doubles) for the next call; release_blocks() frees them.

        out: a writeable float64 (|V|, k) array with contiguous columns (Fortran order, e.g.
        D[:, c0:c1] of D = numpy.empty((n, m), order="F")) to write the distances into instead of
        a new array; it is returned. ValueError for any other.

        >>> polydec.HeatGeodesics(polydec.quad_grid(4, 4)).distances([0, 24]).shape
        (25, 2)
        """
        return _convert.heat_distances(self._solver, self._n, sources, block, out)

    def release_blocks(self):
        """Frees the blocks distances() keeps between calls."""
        self._solver.release_blocks()

    @property
    def time_step(self):
        """The heat time step t."""
        return self._solver.time_step


def suggested_time_factor(time_step_factor, diagnostics, extent):
    """The heat time step factor whose heat step reaches `extent` (e.g. the bounding-box diagonal,
    np.linalg.norm(V.max(0) - V.min(0))), from a run at `time_step_factor` and its diagnostics
    (the dict of HeatGeodesics/VolumeHeatGeodesics .distance(..., return_diagnostics=True)):
    the factor f' whose implicit heat step decays per mean edge length by
    kappa(f') = kappa(time_step_factor) resolved_radius / (1.25 extent), with
    kappa(f) = 2 asinh(1 / (2 sqrt(f))) (for large factors time_step_factor * (1.25 extent /
    resolved_radius)^2, the reach growing as sqrt(t)); time_step_factor itself when no vertex was
    unresolved, never less. ValueError unless time_step_factor and extent are positive and
    finite.

    >>> polydec.suggested_time_factor(1.0, {"unresolved_vertices": 0, "resolved_radius": 1.0}, 2.0)
    1.0
    """
    factor, extent = float(time_step_factor), float(extent)
    if not (np.isfinite(factor) and factor > 0 and np.isfinite(extent) and extent > 0):
        raise ValueError(f"time_step_factor and extent must be positive and finite, got {factor} and {extent}")
    return _polydec.suggested_time_factor(factor, int(diagnostics["unresolved_vertices"]),
                                          float(diagnostics["resolved_radius"]), extent)


def spectrum(V, F=None, k=None, laplacian="ours", mass="lumped", tolerance=1e-10, max_iterations=1000,
             return_info=False, planarity=None):
    """The k smallest eigenpairs of -S x = lambda M x (manifold harmonics, paper section 5.4).

    Returns (evals, evecs): evals (k,) ascending, >= 0 (one 0 per connected component, since S
    is negative semi-definite); evecs (|V|, k), M-orthonormal (evecs.T @ M @ evecs = I), with
    S @ evecs + M @ evecs @ diag(evals) = 0. mass="lumped" (default) or "galerkin".
    return_info=True adds a dict (shift, n_converged, n_solves, method). SolverError when the
    solver does not converge. spectrum(mesh, k) or spectrum(V, F, k).

    >>> evals, evecs = polydec.spectrum(polydec.hex_sphere(3), 4)
    >>> np.round(np.abs(evals), 1).tolist()
    [0.0, 2.0, 2.0, 2.0]
    """
    V, F, k = _shift(V, F, k)
    evals, evecs, info = _polydec.spectrum(_handle(V, F), _convert.size(k, "k", 1), str(laplacian),
                                           _convert.lumped_flag(mass), _convert.positive(tolerance, "tolerance"),
                                           _convert.size(max_iterations, "max_iterations", 1),
                                           _convert.planarity(planarity))
    return (evals, evecs, info) if return_info else (evals, evecs)


class HodgeParts:
    """Result of a Hodge decomposition: exact, coexact, harmonic (|C1|,) with
    exact + coexact + harmonic = omega, potential (|V|,) with exact = d0 @ potential, and the
    star1 norms norm, norm_exact, norm_coexact, norm_harmonic.

    >>> g = polydec.quad_grid(2, 2)
    >>> parts = polydec.hodge_decomposition(g, polydec.d0(g) @ g.positions[:, 0])
    >>> round(parts.norm_coexact, 9), round(parts.norm_harmonic, 9)
    (0.0, 0.0)
    """

    def __init__(self, d):
        self.__dict__.update(d)

    def __repr__(self):
        return (f"HodgeParts(norm={self.norm:.6g}, exact={self.norm_exact:.6g}, coexact={self.norm_coexact:.6g}, "
                f"harmonic={self.norm_harmonic:.6g})")


class HodgeDecomposer:
    """Hodge decomposition of coarse 1-cochains, omega = d0 alpha + delta beta + h, orthogonal in
    the star1 inner product (paper section 4.6), factored once.

    HodgeDecomposer(V, F) builds the coarse complex, d0, star1, factors d0^T star1 d0 and the
    harmonic basis; decompose(omega) with omega (|C1|,), one value per pair of cells()[0] (the
    integral of the 1-form from i to j), returns HodgeParts. Attributes: pairs (|C1|, 2), d0,
    star1 (csc_matrix), harmonic_basis (|C1|, 2 genus + ...), star1-orthonormal.
    complex="mesh": on the mesh's own edges (pairs = the mesh edges (i, j), i < j; star1 positive
    definite, so every step is an ordinary solve and the parts are unique).

    >>> polydec.HodgeDecomposer(polydec.torus(8, 6), complex="mesh").harmonic_basis.shape
    (96, 2)
    """

    def __init__(self, V, F=None, virtual_vertex="squared-area", complex="complete", planarity=None):
        self._h = _polydec.HodgeDecomposer(_handle(V, F), str(virtual_vertex), str(complex),
                                           _convert.planarity(planarity))
        self.pairs = self._h.pairs
        self.d0 = self._h.d0
        self.star1 = self._h.star1
        self.harmonic_basis = self._h.harmonic_basis

    def decompose(self, omega):
        """HodgeParts of omega ((|C1|,) float64; ValueError for a wrong size or non-finite values).

        >>> g = polydec.quad_grid(1, 1)
        >>> round(polydec.HodgeDecomposer(g).decompose(np.ones(6)).norm_exact, 6) > 0
        True
        """
        w = np.asarray(omega, dtype=np.float64).reshape(-1)
        return HodgeParts(self._h.decompose(w))


def hodge_decomposition(V, F=None, omega=None):
    """One-shot HodgeDecomposer(mesh).decompose(omega) -> HodgeParts; hodge_decomposition(mesh,
    omega) or hodge_decomposition(V, F, omega).

    >>> g = polydec.quad_grid(1, 1)
    >>> round(polydec.hodge_decomposition(g, np.zeros(6)).norm, 12)
    0.0
    """
    V, F, omega = _shift(V, F, omega)
    return HodgeDecomposer(V, F).decompose(omega)


def mean_curvature(V, F=None, laplacian="ours", mass="lumped", planarity=None):
    """Mean curvature per vertex (paper section 5.2, eq. 29), (|V|,) float64:
    H_i = 1/2 |(L X)_i| sign<-(L X)_i, n_i>, L = M^-1 S, n the outward normal, so a sphere of
    radius r has H = 1/r > 0. 0 at vertices without mass.

    >>> H = polydec.mean_curvature(polydec.hex_sphere(3))
    >>> bool(abs(H - 1).max() < 0.05)
    True
    """
    return _polydec.mean_curvature(_handle(V, F), str(laplacian), _convert.lumped_flag(mass),
                                   _convert.planarity(planarity))


def vertex_normals(V, F=None):
    """Angle-weighted unit vertex normals, (|V|, 3) float64, oriented by the faces.

    >>> polydec.vertex_normals(polydec.quad_grid(1, 1))[0].tolist()
    [0.0, 0.0, 1.0]
    """
    return _polydec.vertex_normals(_handle(V, F))


class CurvatureFlow:
    """Conformalized mean curvature flow (paper section 5.1, eq. 28): S^0 of the input kept, M^t
    re-assembled on the current positions, each step solves (M^t - eps S^0) X' = M^t X, then
    re-centres (area centroid at the origin) and re-scales to the input's area.

    CurvatureFlow(mesh, time_step=0 (eps = 1e-3 * area), mass="lumped", laplacian="ours");
    step() -> the new positions (|V|, 3); attributes positions, time_step, area.

    >>> flow = polydec.CurvatureFlow(polydec.genus2(1))
    >>> flow.step().shape
    (198, 3)
    """

    def __init__(self, V, F=None, time_step=0.0, mass="lumped", laplacian="ours", planarity=None):
        t = float(time_step)
        if not (np.isfinite(t) and t >= 0):
            raise ValueError(f"time_step must be >= 0 (0: 1e-3 of the area), got {time_step!r}")
        self._flow = _polydec.CurvatureFlow(_handle(V, F), t, _convert.lumped_flag(mass), str(laplacian),
                                            _convert.planarity(planarity))

    def step(self):
        """One step -> positions (|V|, 3) float64."""
        return self._flow.step()

    @property
    def positions(self):
        return self._flow.positions

    @property
    def time_step(self):
        return self._flow.time_step

    @property
    def area(self):
        return self._flow.area


def curvature_flow(V, F=None, steps=None, time_step=0.0, mass="lumped", laplacian="ours"):
    """`steps` steps of CurvatureFlow -> list of steps + 1 position arrays (the input first);
    curvature_flow(mesh, steps) or curvature_flow(V, F, steps).

    >>> len(polydec.curvature_flow(polydec.genus2(1), 2))
    3
    """
    V, F, steps = _shift(V, F, steps)
    flow = CurvatureFlow(V, F, time_step, mass, laplacian)
    return [flow.positions] + [flow.step() for _ in range(_convert.size(steps, "steps"))]


def conformal_parametrization(V, F=None, laplacian="ours", return_eigenvalue=False, planarity=None):
    """Spectral free-boundary conformal parametrization (paper section 5.3) -> uv (|V|, 2)
    float64 scaled into [0,1]^2; with return_eigenvalue=True also the eigenvalue (the conformal
    energy up to scale). ValueError when a connected component has no boundary.

    >>> uv = polydec.conformal_parametrization(polydec.quad_grid(4, 4))
    >>> uv.shape, bool(uv.min() >= 0 and uv.max() <= 1)
    ((25, 2), True)
    """
    uv, ev = _polydec.conformal_parametrization(_handle(V, F), str(laplacian), _convert.planarity(planarity))
    return (uv, ev) if return_eigenvalue else uv


def conformal_distortion(V, F=None, uv=None):
    """Area-weighted RMS difference (radians) between the corner angles in 3D and in uv (|V|, 2);
    conformal_distortion(mesh, uv) or conformal_distortion(V, F, uv).

    >>> g = polydec.quad_grid(2, 2)
    >>> round(polydec.conformal_distortion(g, g.positions[:, :2]), 12)
    0.0
    """
    V, F, uv = _shift(V, F, uv)
    return _polydec.conformal_distortion(_handle(V, F), np.asarray(uv, dtype=np.float64))


def keep_freed_memory(max_bytes=1 << 30):
    """Opt-in, process-wide: asks the C library's allocator (glibc, mallopt) to keep up to max_bytes of
    freed memory for reuse instead of returning it to the system, and to serve blocks of up to 32 MB
    from that reserve (M_TRIM_THRESHOLD = max_bytes, M_MMAP_THRESHOLD = 32 MB). Without it glibc hands
    the matrices and work arrays of a call on a large mesh back to the system once they are freed,
    and the next call faults every page in afresh (~13 us per 4 KB page measured here:
    docs/benchmarks.md, "Python call overhead"). It applies to every library in the process, holds
    up to max_bytes that other processes cannot use, and cannot be undone (glibc's adaptive default
    is then off); polydec never calls it by itself. -> True when applied (glibc), False elsewhere.

    >>> polydec.keep_freed_memory(256 << 20) in (True, False)
    True
    """
    return bool(_polydec.keep_freed_memory(_convert.size(max_bytes, "max_bytes", 0)))


from ._meshio import from_meshio, to_meshio  # noqa: E402
from ._quadratic import quadratic_operators  # noqa: E402
from ._spectral import (  # noqa: E402
    biharmonic_distance, diffusion_distance, form_spectrum, heat_kernel_signature, hks_times, lowpass_filter,
    wave_kernel_signature)
from ._virtual_lift import lifted_laplacian  # noqa: E402
from ._volume import (  # noqa: E402
    VolumeHeatGeodesics, VolumeHodgeDecomposer, VolumeMesh, ball_eigenvalues, cuboctahedra_volume, hex_ball_volume,
    hex_grid_volume, hex_torus_volume, jitter_interior, pyramid_grid_volume, read_volume_mesh, tet_grid_volume,
    truncated_octahedra_volume, volume_dec, volume_dec_max_degree, volume_divergence, volume_franke_poisson,
    volume_gradient, volume_laplacian, volume_laplacian_names, volume_lumped_mass, volume_mass, volume_operators,
    volume_poisson, volume_spectrum, volume_stiffness, write_volume_mesh)
from ._groups import read_mesh_groups  # noqa: E402
