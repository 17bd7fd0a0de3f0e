"""polydec._volume — polyhedral volume meshes (docs/volumes.md, docs/python.md): the
VolumeMesh class, its readers, writer and generators, the volume Laplacians ("ours",
"polylaplace", "diamond"), volume DEC and the volume applications. Imported into polydec.

Conventions as on surfaces: S symmetric NEGATIVE semi-definite (S @ 1 = 0), M the Galerkin mass,
the lumped mass its row sums; sparse results are scipy.sparse.csc_matrix of float64 in the
mesh's vertex order; the GIL is released during validation, assembly and solves.
"""

import os

import numpy as np

from . import _convert, _polydec


def _flat_cells(cells, n_vertices):
    """(polygon indices, polygon offsets, cell offsets) int32 of cells given as lists of polygons,
    every polygon checked (3 or more vertices, indices in [0, n_vertices))."""
    if isinstance(cells, np.ndarray):
        if cells.ndim != 3:
            raise ValueError(f"a cell array must have shape (|C|, faces per cell, vertices per face), got {cells.shape}")
        c, f, k = cells.shape
        polygons = cells.reshape(c * f, k)
        cell_sizes = np.full(c, f, dtype=np.int64)
    else:
        try:
            cells = [list(c) for c in cells]
        except TypeError:
            raise TypeError("cells must be a list of cells, each a list of faces (vertex index lists)") from None
        polygons = [p for c in cells for p in c]
        cell_sizes = np.array([len(c) for c in cells], dtype=np.int64)
    cell_offsets = np.concatenate([[0], np.cumsum(cell_sizes)]).astype(np.int64)
    try:
        idx, off = _convert.lists(polygons, n_vertices, "face", "vertex")
    except _polydec.InvalidMeshError as e:  # "face P refers to ...", P counted over all cells
        c = int(np.searchsorted(cell_offsets, e.index, side="right") - 1)
        detail = str(e).split(" ", 2)[2]
        raise _convert._mesh_error("cell", c, f"cell {c}, face {e.index - int(cell_offsets[c])} {detail}") from None
    sizes = np.diff(off)
    if np.any(sizes < 3):
        p = int(np.argmax(sizes < 3))
        c = int(np.searchsorted(cell_offsets, p, side="right") - 1)
        raise _convert._mesh_error("cell", c, f"cell {c}, face {p - int(cell_offsets[c])} has {int(sizes[p])} "
                                   "vertices (at least 3 needed)")
    return idx, off, np.ascontiguousarray(cell_offsets, dtype=np.int32)


class VolumeMesh:
    """A validated polyhedral volume mesh (dec/mesh/volume_mesh.h): positions, polygonal faces (each
    stored once) and cells as cycles of oriented faces; immutable.

    Build one with VolumeMesh(V, cells) (= VolumeMesh.from_cells), VolumeMesh.from_soup(V, faces,
    cells), read_volume_mesh(path) or a generator (hex_grid_volume, ...). Validation raises
    InvalidMeshError (a ValueError) naming the vertex, face, cell or edge. After validation every
    cell's half-faces have right-hand normals pointing out of the cell (a mesh given consistently
    inward, as polyLaplace's OVM files, is flipped once).

    Attributes: n_vertices, n_edges, n_faces, n_cells, positions (|V|, 3), faces (flat (indices,
    offsets)), cells (flat (half-faces, offsets): half-face 2f is face f as listed, 2f+1 reversed),
    face_cells (|F|, 2) (-1 where none), edges (|E|, 2) (i < j, lexicographic), boundary_vertices
    (bool |V|), cell_volumes (|C|,), volume, mean_edge_length, bounding_box_diagonal.

    The mesh is validated once, when built. Its refinement (dec/volume/refinement.h: face points,
    cell points, sub-tetrahedra) is built on the first operator call that needs it, one per
    cell-point rule ("squared-volume" for the Laplacians "ours" and "diamond", "polylaplace"), and
    kept for the next calls: volume_operators and the functions built on it (volume_stiffness, ...),
    volume_dec, VolumeHeatGeodesics, volume_spectrum, volume_poisson, volume_franke_poisson and
    VolumeHodgeDecomposer. The results are bitwise
    those of a fresh refinement. n_cached_refinements tells how many are held, clear_refinements()
    drops them; a pickled mesh leaves them out (rebuilt after unpickling on first use).

    >>> m = polydec.VolumeMesh([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]],
    ...                        [[[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]]])
    >>> m.n_cells, m.n_faces, round(m.volume, 12)
    (1, 4, 0.166666666667)
    """

    def __init__(self, V, cells):
        """From positions V (|V|, 3) and cells, each a list of faces, each a list of vertex indices
        (a shared face is recognized by its vertex set; its two cells must list it in opposite
        cyclic orders), or a (|C|, faces per cell, vertices per face) integer array."""
        X = _convert.positions(V)
        self._m = _polydec.VolumeMesh.from_cells(X, *_flat_cells(cells, X.shape[0]))

    @classmethod
    def from_cells(cls, V, cells, kind=None):
        """VolumeMesh(V, cells) (cells as lists of faces), or with `kind` one block of cells of one
        linear type as an (n, k) integer array in VTK's (and meshio's) vertex order: "tetra" (k = 4),
        "hexahedron" (8), "wedge" (6, also "prism") or "pyramid" (5); polydec takes each cell's
        faces from VTK's tables (dec/mesh/polyhedron_builder.h), so a cell numbered as VTK wants it
        (positively oriented) gets outward faces.

        >>> V = [[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]]
        >>> round(polydec.VolumeMesh.from_cells(V, [[0, 1, 2, 3]], "tetra").volume, 12)
        0.166666666667
        """
        if kind is None:
            return cls(V, cells)
        return cls.from_blocks(V, [(kind, cells)])

    @classmethod
    def from_blocks(cls, V, blocks):
        """Cells from a list of blocks (kind, cells), concatenated in block order: kind one of
        from_cells' linear kinds with an (n, k) array, or "polyhedron" with a list of cells, each a
        list of faces (vertex lists).

        >>> V = [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0.5, 0.5, 1], [0.5, 0.5, -1]]
        >>> m = polydec.VolumeMesh.from_blocks(V, [("pyramid", [[0, 1, 2, 3, 4]]), ("pyramid", [[0, 3, 2, 1, 5]])])
        >>> m.n_cells, round(m.volume, 12)
        (2, 0.666666666667)
        """
        X = _convert.positions(V)
        types, items, sizes = [], [], []
        for kind, cells in blocks:
            t = _cell_type(kind)
            if t == 42:
                for c in cells:
                    stream = [len(c)]
                    for f in c:
                        f = list(f)
                        stream += [len(f)] + f
                    types.append(42)
                    items.append(np.asarray(stream, dtype=np.int64))
                    sizes.append(len(stream))
                continue
            a = _convert._integers(cells, f"{kind} cells")
            if a.size == 0:
                continue
            if a.ndim != 2 or a.shape[1] != _CELL_SIZES[t]:
                raise ValueError(f"{kind} cells must be an (n, {_CELL_SIZES[t]}) integer array, got shape {a.shape}")
            types += [t] * a.shape[0]
            items.append(a.reshape(-1).astype(np.int64))
            sizes += [a.shape[1]] * a.shape[0]
        flat = np.concatenate(items) if items else np.zeros(0, dtype=np.int64)
        offsets = np.concatenate([[0], np.cumsum(sizes, dtype=np.int64)])
        _check_cell_vertices(types, flat, offsets, X.shape[0])
        return cls._wrap(_polydec.VolumeMesh.from_typed_cells(X, np.asarray(types, dtype=np.int32),
                                                              flat.astype(np.int32), offsets.astype(np.int32)))

    @classmethod
    def _wrap(cls, m):
        mesh = cls.__new__(cls)
        mesh._m = m
        return mesh

    @classmethod
    def from_soup(cls, V, faces, cells):
        """The library's soup form (dec/mesh/volume_mesh.h, PolyhedronSoup): faces as vertex lists (each
        face once; any form polydec accepts for surface faces), cells as lists of half-faces
        (2f: face f as listed, 2f+1: reversed), lists of lists, an (n, k) array or the flat tuple
        (indices, offsets)."""
        X = _convert.positions(V)
        fi, fo = _convert.faces(faces, X.shape[0])
        ci, co = _convert.lists(cells, 2 * (fo.size - 1), "cell", "half-face")
        return cls._wrap(_polydec.VolumeMesh.from_soup(X, fi, fo, ci, co))

    @classmethod
    def read(cls, path):
        """read_volume_mesh(path)."""
        return read_volume_mesh(path)

    def write(self, path, scalars=None):
        """write_volume_mesh(path, self, scalars)."""
        write_volume_mesh(path, self, scalars)

    def with_positions(self, V):
        """The same connectivity with new positions (|V|, 3)."""
        return VolumeMesh._wrap(self._m.with_positions(_convert.positions(V)))

    def boundary_surface(self):
        """The boundary faces, oriented outward, as a surface Mesh on all |V| vertices (interior
        vertices unreferenced), for every surface tool of polydec.

        >>> polydec.hex_grid_volume(2, 2, 2).boundary_surface()
        Mesh(27 vertices, 24 faces, 48 edges)
        """
        from ._mesh import Mesh

        X, idx, off = self._m.boundary_surface()
        return Mesh(X, (idx, off))

    @property
    def faces(self):
        """The faces as the flat tuple (indices, offsets) of two int64 arrays (as surface faces)."""
        idx, off = self._m.faces
        return np.asarray(idx, dtype=np.int64), np.asarray(off, dtype=np.int64)

    def cell_faces(self, c):
        """Cell c as a list of faces (vertex lists), each oriented with its normal out of the cell."""
        hf, off = self.cells
        fi, fo = self.faces
        if not 0 <= c < self.n_cells:
            raise IndexError(f"cell {c} outside [0, {self.n_cells})")
        out = []
        for h in hf[off[c]:off[c + 1]]:
            f = fi[fo[h // 2]:fo[h // 2 + 1]].tolist()
            out.append(f if h % 2 == 0 else f[::-1])
        return out

    def _refinements(self):
        """The extension's refinement cache of this mesh (created on first use)."""
        r = self.__dict__.get("_r")
        if r is None:
            r = self._r = _polydec.VolumeRefinements(self._m)
        return r

    @property
    def n_cached_refinements(self):
        """How many refinements the mesh holds (one per cell-point rule used).

        >>> m = polydec.hex_grid_volume(2, 2, 2)
        >>> S = polydec.volume_stiffness(m); M = polydec.volume_mass(m)
        >>> m.n_cached_refinements
        1
        """
        r = self.__dict__.get("_r")
        return 0 if r is None else r.n_cached

    def clear_refinements(self):
        """Drops the cached refinements (the next operator call builds its refinement again)."""
        r = self.__dict__.get("_r")
        if r is not None:
            r.clear()

    def __getattr__(self, name):
        if name in ("n_vertices", "n_edges", "n_faces", "n_cells", "n_unreferenced_vertices", "positions",
                    "cells", "face_cells", "edges", "boundary_vertices", "cell_volumes", "volume",
                    "mean_edge_length", "bounding_box_diagonal"):
            m = self.__dict__.get("_m")
            if m is not None:
                return getattr(m, name)
        raise AttributeError(name)

    def __repr__(self):
        return (f"VolumeMesh({self.n_vertices} vertices, {self.n_faces} faces, {self.n_cells} cells, "
                f"volume {self.volume:.6g})")

    def __reduce__(self):
        fi, fo = self.faces
        hf, co = self.cells
        return _unpickle, (self.positions, fi, fo, hf, co, self._m.coordinate_noise, self._m.planarity_tolerance)


def _unpickle(X, fi, fo, hf, co, noise, planarity_tolerance):
    m = _polydec.VolumeMesh.from_soup(*(np.ascontiguousarray(a, dtype=t) for a, t in
                                        ((X, np.float64), (fi, np.int32), (fo, np.int32), (hf, np.int32),
                                         (co, np.int32))))
    if noise or planarity_tolerance:
        m = m.with_precision(float(noise), float(planarity_tolerance))
    return VolumeMesh._wrap(m)


_CELL_TYPES = {"tetra": 10, "tetrahedron": 10, "hexahedron": 12, "hex": 12, "wedge": 13, "prism": 13,
               "pyramid": 14, "polyhedron": 42}
_CELL_SIZES = {10: 4, 12: 8, 13: 6, 14: 5}


def _cell_type(kind):
    t = _CELL_TYPES.get(str(kind))
    if t is None:
        raise ValueError(f"unknown cell kind {kind!r} (known: {', '.join(_CELL_TYPES)})")
    return t


def _check_cell_vertices(types, flat, offsets, n_vertices):
    """InvalidMeshError naming the cell for a vertex index outside [0, n_vertices) (polyhedron face
    streams: only their vertex entries)."""
    bad = (flat < 0) | (flat >= n_vertices)
    if 42 in types:  # sizes in the face streams are not vertex indices
        for c, t in enumerate(types):
            if t == 42:
                s, k, n = int(offsets[c]), 1, int(offsets[c + 1] - offsets[c])
                bad[s] = n == 0
                while k < n:
                    bad[s + k] = False
                    if flat[s + k] < 1:
                        break
                    k += int(flat[s + k]) + 1
    if np.any(bad):
        pos = int(np.argmax(bad))
        c = int(np.searchsorted(offsets, pos, side="right") - 1)
        raise _convert._mesh_error("cell", c, f"cell {c} refers to vertex {int(flat[pos])}, outside [0, {n_vertices})")


def _mesh(mesh):
    if not isinstance(mesh, VolumeMesh):
        raise TypeError(f"a polydec.VolumeMesh is needed, got {type(mesh).__name__}")
    return mesh._m


def _cached(mesh):
    """(the extension's mesh, its refinement cache)."""
    return _mesh(mesh), mesh._refinements()


def read_volume_mesh(path):
    """Reads an OVM (OpenVolumeMesh ASCII), VTK legacy or XML (.vtu) unstructured grid or MEDIT .mesh file (by
    extension; others by their first word) -> VolumeMesh, in the file's vertex order. Raises
    MeshFileNotFoundError (a FileError and a FileNotFoundError) for a missing file, FileError
    (OSError and ValueError) naming the file and line for an unreadable or malformed file or an
    invalid mesh in it.

    >>> import tempfile, os
    >>> path = os.path.join(tempfile.mkdtemp(), "cube.vtk")
    >>> polydec.write_volume_mesh(path, polydec.hex_grid_volume(2, 2, 2))
    >>> polydec.read_volume_mesh(path).n_cells
    8
    """
    return VolumeMesh._wrap(_polydec.VolumeMesh.read(_convert.existing_file(path)))


def write_volume_mesh(path, mesh, scalars=None):
    """Writes by extension (.ovm, .vtk, .vtu, .mesh; MEDIT holds tetrahedra, prisms, hexahedra and pyramids),
    positions with 17 significant digits. scalars: optional {name: (|V|,) array}, written as VTK
    point data (.vtk POINT_DATA or .vtu Float64 arrays only). Raises FileError.

    >>> import tempfile, os
    >>> path = os.path.join(tempfile.mkdtemp(), "grid.vtk")
    >>> polydec.write_volume_mesh(path, polydec.tet_grid_volume(1, 1, 1), scalars={"u": np.arange(8.0)})
    >>> polydec.read_volume_mesh(path).n_cells
    6
    """
    s = {str(k): np.asarray(v, dtype=np.float64).reshape(-1) for k, v in (scalars or {}).items()}
    _mesh(mesh).write(os.fspath(path), s)


def _sizes(nx, ny, nz):
    return _convert.size(nx, "nx", 1), _convert.size(ny, "ny", 1), _convert.size(nz, "nz", 1)


def jitter_interior(mesh, amplitude, seed=1):
    """Every interior vertex moved by a uniform random vector in the ball of radius amplitude times
    its shortest incident edge (0 <= amplitude < 0.5 keeps the generators' cells valid); boundary
    vertices stay. Deterministic for a seed -> VolumeMesh.

    >>> m = polydec.hex_grid_volume(3, 3, 3)
    >>> b = m.boundary_vertices
    >>> j = polydec.jitter_interior(m, 0.2)
    >>> bool(np.array_equal(j.positions[b], m.positions[b])), bool((j.positions[~b] != m.positions[~b]).any())
    (True, True)
    """
    return VolumeMesh._wrap(_polydec.jitter_interior(_mesh(mesh), float(amplitude), int(seed)))


def hex_grid_volume(nx, ny, nz, jitter=0.0, seed=1):
    """nx x ny x nz hexahedra filling [0, 1]^3; vertex (i, j, k) is i + (nx+1)(j + (ny+1) k);
    jitter: amplitude of jitter_interior.

    >>> polydec.hex_grid_volume(2, 3, 4).n_cells
    24
    """
    return VolumeMesh._wrap(_polydec.hex_grid_volume(*_sizes(nx, ny, nz), float(jitter), int(seed)))


def tet_grid_volume(nx, ny, nz, jitter=0.0, seed=1):
    """The hex grid with every cube split into 6 tetrahedra (Kuhn subdivision).

    >>> polydec.tet_grid_volume(1, 1, 1).n_cells
    6
    """
    return VolumeMesh._wrap(_polydec.tet_grid_volume(*_sizes(nx, ny, nz), float(jitter), int(seed)))


def pyramid_grid_volume(nx, ny, nz, jitter=0.0, seed=1):
    """The hex grid with every cube split into 6 pyramids around its centre (centres numbered
    after the grid vertices).

    >>> polydec.pyramid_grid_volume(1, 1, 1).n_cells
    6
    """
    return VolumeMesh._wrap(_polydec.pyramid_grid_volume(*_sizes(nx, ny, nz), float(jitter), int(seed)))


def truncated_octahedra_volume(n, jitter=0.0, seed=1):
    """The bitruncated cubic honeycomb clipped to [0, 1]^3 (n cubes per side): truncated octahedra
    inside, convex clipped cells at the boundary; n^3 + (n+1)^3 cells.

    >>> polydec.truncated_octahedra_volume(2).n_cells
    35
    """
    return VolumeMesh._wrap(_polydec.truncated_octahedra_volume(_convert.size(n, "n", 1), float(jitter), int(seed)))


def cuboctahedra_volume(n, jitter=0.0, seed=1):
    """Each of n^3 cubes of [0, 1]^3 split into a cuboctahedron and 8 corner tetrahedra (polyLaplace's
    cube_truncated family; n = 2^(L-1) is level L); 9 n^3 cells.

    >>> m = polydec.cuboctahedra_volume(1)
    >>> m.n_cells, round(m.volume, 12)
    (9, 1.0)
    """
    return VolumeMesh._wrap(_polydec.cuboctahedra_volume(_convert.size(n, "n", 1), float(jitter), int(seed)))


def hex_torus_volume(n_around, n_cross, R=1.0, r=0.4, jitter=0.0, seed=1):
    """A hexahedral solid torus around the z axis (first Betti number 1), 0 < r < R.

    >>> polydec.VolumeHodgeDecomposer(polydec.hex_torus_volume(8, 2), complex="mesh").harmonic_basis.shape[1]
    1
    """
    n_around, n_cross = _convert.size(n_around, "n_around", 1), _convert.size(n_cross, "n_cross", 1)
    return VolumeMesh._wrap(_polydec.hex_torus_volume(n_around, n_cross, float(R), float(r), float(jitter), int(seed)))


def hex_ball_volume(n, jitter=0.0, seed=1):
    """A hexahedral unit ball from the n x n x n grid of [-1, 1]^3 (boundary vertices on the unit sphere).

    >>> m = polydec.hex_ball_volume(4)
    >>> bool(np.allclose(np.linalg.norm(m.positions[m.boundary_vertices], axis=1), 1))
    True
    """
    return VolumeMesh._wrap(_polydec.hex_ball_volume(_convert.size(n, "n", 1), float(jitter), int(seed)))


# -------------------------------------------------------------------------------------- operators

def volume_laplacian_names():
    """The volume Laplacians: "ours" (least-norm cell-point weights), "polylaplace" (polyLaplace's
    cell-point weights, the same cell point), "diamond" (Bunge, Botsch & Alexa 2021).

    >>> "polylaplace" in polydec.volume_laplacian_names()
    True
    """
    return list(_polydec.volume_laplacian_names())


def volume_operators(mesh, laplacian="ours", parts=("S", "M", "M_lumped", "G", "D"), threads=1):
    """The parts asked for ("S", "M", "M_lumped", "G", "D") from one assembly -> dict with those
    (S, M, G, D csc_matrix; M_lumped a (|V|,) vector), "G_blocks" with G (row blocks the heat method
    normalizes as one vector; empty: blocks of 3), "name", and the refinement's sub-tetrahedron
    counts "subtet_degenerate", "subtet_inverted", "cells_affected". threads: refinement and
    assembly threads for "ours" and "polylaplace" (0: all; the result does not depend on it).

    >>> d = polydec.volume_operators(polydec.hex_grid_volume(2, 2, 2), parts={"S", "M_lumped"})
    >>> d["S"].shape, round(d["M_lumped"].sum(), 12)
    ((27, 27), 1.0)
    """
    m, cache = _cached(mesh)
    return _polydec.volume_operators(m, str(laplacian), set(parts), _convert.threads(threads), cache)


def volume_stiffness(mesh, laplacian="ours", threads=1):
    """Stiffness S = P^T S^tet P (|V|, |V|) csc_matrix, symmetric NEGATIVE semi-definite, S @ 1 = 0,
    exact on linear functions at interior vertices.

    >>> S = polydec.volume_stiffness(polydec.hex_grid_volume(2, 2, 2))
    >>> bool(abs(S @ np.ones(27)).max() < 1e-14)
    True
    """
    return volume_operators(mesh, laplacian, {"S"}, threads)["S"]


def volume_mass(mesh, laplacian="ours", threads=1):
    """Galerkin mass M = P^T M^tet P (|V|, |V|) csc_matrix, positive semi-definite, summing to the volume.

    >>> round(polydec.volume_mass(polydec.tet_grid_volume(2, 2, 2)).sum(), 12)
    1.0
    """
    return volume_operators(mesh, laplacian, {"M"}, threads)["M"]


def volume_lumped_mass(mesh, laplacian="ours", threads=1):
    """Lumped mass (row sums of M) as a diagonal (|V|, |V|) csc_matrix.

    >>> round(polydec.volume_lumped_mass(polydec.pyramid_grid_volume(2, 2, 2)).sum(), 12)
    1.0
    """
    from . import _diagonal

    return _diagonal(volume_operators(mesh, laplacian, {"M_lumped"}, threads)["M_lumped"])


def volume_laplacian(mesh, laplacian="ours", mass="lumped", threads=1):
    """(S, M) from one assembly; mass="lumped" (diagonal, default) or "galerkin"; L = M^-1 S.

    >>> S, M = polydec.volume_laplacian(polydec.hex_grid_volume(2, 2, 2), mass="galerkin")
    >>> bool(abs(S - S.T).max() < 1e-15), round(M.sum(), 12)
    (True, 1.0)
    """
    from . import _diagonal

    lumped = _convert.lumped_flag(mass)
    d = volume_operators(mesh, laplacian, {"S", "M_lumped" if lumped else "M"}, threads)
    return d["S"], _diagonal(d["M_lumped"]) if lumped else d["M"]


def volume_gradient(mesh, laplacian="ours"):
    """Gradient G, (3T, |V|) csc_matrix: rows 3t..3t+2 the constant gradient on sub-tetrahedron t
    of the refinement ("diamond": per sub-diamond). S = D @ G.

    >>> m = polydec.hex_grid_volume(2, 2, 2)
    >>> G = polydec.volume_gradient(m)
    >>> bool(np.allclose(G @ m.positions[:, 0], np.tile([1.0, 0, 0], G.shape[0] // 3)))
    True
    """
    return volume_operators(mesh, laplacian, {"G"})["G"]


def volume_divergence(mesh, laplacian="ours"):
    """Divergence D = -G^T W (W the sub-tetrahedron volumes, each three times), (|V|, 3T) csc_matrix.

    >>> m = polydec.jitter_interior(polydec.hex_grid_volume(2, 2, 2), 0.2)
    >>> DG = polydec.volume_divergence(m) @ polydec.volume_gradient(m)
    >>> bool(abs(DG - polydec.volume_stiffness(m)).max() < 1e-12)
    True
    """
    return volume_operators(mesh, laplacian, {"D"})["D"]


def volume_dec_max_degree(mesh):
    """The largest form degree (0..3) whose Hodge star every cell's size allows (dec/volume/complex.h).

    >>> polydec.volume_dec_max_degree(polydec.tet_grid_volume(1, 1, 1))
    3
    """
    return _polydec.volume_dec_max_degree(_mesh(mesh))


def volume_dec(mesh, max_degree=None, cell_point="squared-volume", complex="complete", spoke_rule="area"):
    """DEC on a volume mesh from one refinement (dec/volume/hodge_star.h) -> dict with d0, d1, d2
    (d_k for k < max_degree; integer-valued, d_{k+1} @ d_k = 0 exactly), P0..P3 and star0..star3
    (for k <= max_degree; star0 is the Galerkin mass, S = -d0.T @ star1 @ d0), all csc_matrix,
    the coarse cell lists pairs, triples, quads ((n, k+1) int32, increasing indices,
    lexicographic: the numbering of d and star) and max_degree. max_degree=None: the largest the
    cells allow (volume_dec_max_degree); a larger one raises ValueError naming the cell.
    cell_point: "squared-volume" (default, method "ours") or "polylaplace".
    complex="mesh": on the mesh's own edges, faces and cells (dec/volume/mesh_complex.h), every
    degree for every cell size (max_degree=None: 3), positive definite stars, star3 diagonal; the
    dict then also holds the lists d, P, star (d[k], P[k], star[k]), edges ((|E|, 2) int32, i < j),
    faces (vertex lists, each in its orientation) and cells (half-face lists: h // 2 is the face,
    even h as listed (d2 = +1), odd reversed (d2 = -1)).

    >>> D = polydec.volume_dec(polydec.hex_grid_volume(2, 2, 2), complex="mesh")
    >>> (D["d1"] @ D["d0"]).count_nonzero(), (D["d2"] @ D["d1"]).count_nonzero()
    (0, 0)
    """
    k = -1 if max_degree is None else int(max_degree)
    if max_degree is not None and not 0 <= k <= 3:
        raise ValueError(f"max_degree must be 0..3, got {max_degree}")
    m, cache = _cached(mesh)
    return _polydec.volume_dec(m, k, str(cell_point), str(complex), str(spoke_rule), cache)


# ---------------------------------------------------------------------------------------- solvers

class VolumeHeatGeodesics:
    """Geodesic distances in a volume by the heat method, the surface HeatGeodesics on a volume
    operator set (factored once; t = time_step_factor * mean edge length^2).

    VolumeHeatGeodesics(mesh, laplacian="ours", time_step_factor=1.0, mass="lumped",
    mass_weighted_source=True); distance(sources) -> (|V|,) float64, 0 at the nearest source,
    +inf where no source reaches. Equal to `polydec geodesics MESH --source ...` on a volume mesh.

    >>> d = polydec.VolumeHeatGeodesics(polydec.hex_grid_volume(4, 4, 4)).distance(0)
    >>> d.shape, float(d[0])
    ((125,), 0.0)
    """

    def __init__(self, mesh, laplacian="ours", time_step_factor=1.0, mass="lumped", mass_weighted_source=True):
        m, cache = _cached(mesh)
        self._n = m.n_vertices
        self._solver = _polydec.volume_heat_geodesics(m, str(laplacian),
                                                      _convert.positive(time_step_factor, "time_step_factor"),
                                                      _convert.lumped_flag(mass), bool(mass_weighted_source), cache)

    def distance(self, sources, return_diagnostics=False):
        """Distances from a vertex index or a sequence of them -> (|V|,) float64; with
        return_diagnostics=True (distances, diagnostics) as HeatGeodesics.distance (the heat
        step's unresolved vertices and resolved radius; see suggested_time_factor)."""
        return _convert.heat_distance(self._solver, self._n, sources, return_diagnostics)

    def distances(self, sources, block=64, out=None):
        """One distance field per source -> (|V|, k), as HeatGeodesics.distances (out= too)."""
        return _convert.heat_distances(self._solver, self._n, sources, block, out)

    def release_blocks(self):
        """Frees the blocks distances() keeps between calls."""
        self._solver.release_blocks()

    @property
    def time_step(self):
        return self._solver.time_step


def volume_spectrum(mesh, k, laplacian="ours", boundary="neumann", mass="lumped", tolerance=1e-10,
                    max_iterations=1000, return_info=False):
    """The k smallest eigenpairs of -S x = lambda M x on the volume -> (evals (k,) ascending,
    evecs (|V|, k) M-orthonormal). boundary="neumann" (every vertex free; lambda_0 = 0 with a
    constant vector per connected component) or "dirichlet" (boundary vertices removed, their rows
    0). return_info=True adds a dict (shift, n_converged, n_solves, method).

    >>> evals, evecs = polydec.volume_spectrum(polydec.hex_grid_volume(4, 4, 4), 2)
    >>> bool(abs(evals[0]) < 1e-8), bool(abs(evals[1] - np.pi ** 2) < 1)
    (True, True)
    """
    if boundary not in ("neumann", "dirichlet"):
        raise ValueError(f"boundary must be 'neumann' or 'dirichlet', got {boundary!r}")
    m, cache = _cached(mesh)
    evals, evecs, info = _polydec.volume_spectrum(m, int(k), str(laplacian), boundary == "dirichlet",
                                                  _convert.lumped_flag(mass), float(tolerance), int(max_iterations),
                                                  cache)
    return (evals, evecs, info) if return_info else (evals, evecs)


def ball_eigenvalues(count, boundary="neumann"):
    """The `count` smallest eigenvalues of -Delta on the unit ball, each repeated 2l + 1 times ->
    (lambda (count,), l, n): squared zeros of the spherical Bessel j_l (Dirichlet) or of j_l'
    (Neumann, with the 0 of the constants).

    >>> lam, l, n = polydec.ball_eigenvalues(4, "dirichlet")
    >>> round(float(lam[0]), 4), l.tolist()
    (9.8696, [0, 1, 1, 1])
    """
    if boundary not in ("neumann", "dirichlet"):
        raise ValueError(f"boundary must be 'neumann' or 'dirichlet', got {boundary!r}")
    return _polydec.ball_eigenvalues(int(count), boundary == "dirichlet")


def _vertex_values(f, X, what):
    v = f(X) if callable(f) else f
    v = np.asarray(v, dtype=np.float64).reshape(-1)
    if v.shape[0] != X.shape[0]:
        raise ValueError(f"{what}: one value per vertex expected ({X.shape[0]}), got {v.shape[0]}")
    if not np.all(np.isfinite(v)):
        raise ValueError(f"{what}: values must be finite (vertex {int(np.argmax(~np.isfinite(v)))})")
    return v


def volume_poisson(mesh, exact, laplacian_of_exact, laplacian="ours", mass="galerkin"):
    """Solves Delta f = b with f = exact on the boundary vertices (S f = M b at the interior ones)
    and measures the error -> dict: solution, exact (|V|,), l2_error sqrt(e^T M e), rms_error (over
    all vertices), h (mean edge length), n_vertices, n_cells, n_boundary. exact and
    laplacian_of_exact: (|V|,) arrays or functions of the (|V|, 3) positions. ValueError on a mesh
    without boundary.

    >>> r = polydec.volume_poisson(polydec.hex_grid_volume(3, 3, 3), lambda X: X[:, 0] + 2 * X[:, 1],
    ...                            lambda X: np.zeros(len(X)))
    >>> bool(r["rms_error"] < 1e-12)
    True
    """
    m, cache = _cached(mesh)
    X = m.positions
    return _polydec.volume_poisson(m, _vertex_values(exact, X, "exact"),
                                   _vertex_values(laplacian_of_exact, X, "laplacian_of_exact"), str(laplacian),
                                   _convert.lumped_flag(mass), cache)


def volume_franke_poisson(mesh, laplacian="ours", mass="galerkin"):
    """The 3D Franke Poisson problem on a mesh of the unit cube (apps/applications/volume/poisson.h,
    as `polydec poisson` on a volume) -> the dict of volume_poisson.

    >>> r = polydec.volume_franke_poisson(polydec.hex_grid_volume(4, 4, 4))
    >>> r["n_cells"], bool(r["l2_error"] > 0)
    (64, True)
    """
    m, cache = _cached(mesh)
    return _polydec.volume_franke_poisson(m, str(laplacian), _convert.lumped_flag(mass), cache)


class VolumeHodgeDecomposer:
    """Hodge decomposition of coarse 1-cochains on a volume mesh, omega = d0 alpha + co-exact +
    harmonic, orthogonal in star1 (apps/applications/volume/hodge_decomposition.h; dense harmonic
    part: meshes of up to a few thousand coarse pairs, cells of at most 16 vertices).

    decompose(omega) with omega (|C1|,) on the pairs -> HodgeParts. Attributes pairs, d0, star1,
    harmonic_basis (|C1|, first Betti number), star1-orthonormal. complex="mesh": on the mesh's own
    edges (pairs = the mesh edges), positive definite star1, cells of any size.

    >>> h = polydec.VolumeHodgeDecomposer(polydec.hex_grid_volume(2, 2, 2), complex="mesh")
    >>> h.harmonic_basis.shape[1]
    0
    """

    def __init__(self, mesh, cell_point="squared-volume", complex="complete"):
        m, cache = _cached(mesh)
        self._h = _polydec.VolumeHodgeDecomposer(m, str(cell_point), str(complex), cache)
        self.pairs = self._h.pairs
        self.d0 = self._h.d0
        self.star1 = self._h.star1
        self.harmonic_basis = self._h.harmonic_basis

    def decompose(self, omega):
        from . import HodgeParts

        return HodgeParts(self._h.decompose(np.asarray(omega, dtype=np.float64).reshape(-1)))
