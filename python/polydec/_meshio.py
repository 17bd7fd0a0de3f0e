"""polydec._meshio — polydec meshes to and from meshio (https://github.com/nschloe/meshio; optional:
Debian's python3-meshio, pip's meshio). Imported into polydec as from_meshio and to_meshio.

Surfaces: triangle, quad and polygon blocks (polygonN too) concatenated in block order into one
Mesh. Volumes: tetra, hexahedron, wedge and pyramid blocks (VTK's vertex order, which meshio
uses) and polyhedron blocks (polyhedronN: lists of faces), concatenated in block order into one
VolumeMesh. Blocks of a lower dimension than the mesh's (vertices, lines, boundary triangles
beside tetrahedra) are skipped and counted."""

import numpy as np

from . import _convert

_SURFACE = ("triangle", "quad")
_VOLUME = {"tetra": "tetra", "hexahedron": "hexahedron", "wedge": "wedge", "pyramid": "pyramid"}
_LOWER = {"vertex": 0, "line": 1}


def _kind(block):
    """(dimension, polydec kind) of a meshio cell block; ValueError for cells polydec does not take
    (higher-order elements, a type it does not know)."""
    t = str(block.type)
    if t in _SURFACE or t.startswith("polygon"):
        return 2, "polygon"
    if t in _VOLUME:
        return 3, _VOLUME[t]
    if t.startswith("polyhedron"):
        return 3, "polyhedron"
    if t in _LOWER:
        return _LOWER[t], None
    dim = getattr(block, "dim", None)
    raise ValueError(f"meshio cell type {t!r} (dimension {dim}) is not supported: polydec takes linear cells "
                     "(triangle, quad, polygon; tetra, hexahedron, wedge, pyramid, polyhedron)")


def from_meshio(m, return_skipped=False):
    """A meshio.Mesh -> polydec.Mesh (surface cells only or highest) or polydec.VolumeMesh (when
    any volume cell is present), cells concatenated in block order; point positions as given
    ((n, 2) gets z = 0). Blocks of a lower dimension are skipped; return_skipped=True returns
    (mesh, skipped) with skipped = {meshio type: number of cells skipped}. ValueError for a mesh
    without surface or volume cells or with cells polydec does not take (higher-order elements).

    >>> import meshio
    >>> m = meshio.Mesh([[0, 0], [1, 0], [1, 1], [0, 1], [2, 0]],
    ...                 [("quad", [[0, 1, 2, 3]]), ("triangle", [[1, 4, 2]]), ("line", [[0, 1]])])
    >>> polydec.from_meshio(m, return_skipped=True)
    (Mesh(5 vertices, 2 faces, 6 edges), {'line': 1})
    """
    from ._mesh import Mesh
    from ._volume import VolumeMesh

    kinds = [_kind(b) for b in m.cells]
    if not kinds or max(d for d, _ in kinds) < 2:
        raise ValueError("the meshio mesh has no surface or volume cells")
    top = max(d for d, _ in kinds)
    skipped = {}
    for b, (d, _) in zip(m.cells, kinds):
        if d < top:
            skipped[str(b.type)] = skipped.get(str(b.type), 0) + len(b.data)
    if top == 3:
        blocks = [(k, b.data) for b, (d, k) in zip(m.cells, kinds) if d == 3]
        mesh = VolumeMesh.from_blocks(m.points, blocks)
    else:
        rows = []
        for b, (d, _) in zip(m.cells, kinds):
            if d != 2:
                continue
            data = b.data
            if isinstance(data, np.ndarray) and data.ndim == 2:
                rows.append(_convert._integers(data, f"{b.type} cells"))
            else:  # a list of polygons of different sizes
                rows.extend(_convert._integers(np.asarray(f), f"{b.type} cells").reshape(1, -1) for f in data)
        sizes = np.concatenate([np.full(r.shape[0], r.shape[1], dtype=np.int64) for r in rows])
        idx = np.concatenate([r.reshape(-1).astype(np.int64) for r in rows])
        mesh = Mesh(m.points, (idx, np.concatenate([[0], np.cumsum(sizes)])))
    return (mesh, skipped) if return_skipped else mesh


def to_meshio(mesh, point_data=None, cell_data=None):
    """A polydec.Mesh or VolumeMesh -> meshio.Mesh with the same vertex and face/cell order:
    surfaces as consecutive triangle, quad and polygon blocks (a new block wherever the face size
    changes), volumes as polyhedronN blocks (N vertices; lists of faces oriented out of the cell,
    which meshio writes to VTU for ParaView). point_data: {name: (|V|,) or (|V|, k) array};
    cell_data: {name: one value (or row) per face or cell, in mesh order} (split per block).

    >>> [b.type for b in polydec.to_meshio(polydec.quad_grid(2, 1)).cells]
    ['quad']
    >>> hexagons = polydec.hex_grid(2, 2)
    >>> polydec.from_meshio(polydec.to_meshio(hexagons)).face_list() == hexagons.face_list()
    True
    """
    import meshio

    from ._volume import VolumeMesh

    if isinstance(mesh, VolumeMesh):
        runs = []
        for c in range(mesh.n_cells):
            faces = [np.asarray(f, dtype=np.int64) for f in mesh.cell_faces(c)]
            key = f"polyhedron{np.unique(np.concatenate(faces)).size}"
            if not runs or runs[-1][0] != key:
                runs.append((key, []))
            runs[-1][1].append(faces)
        blocks = [(k, cells) for k, cells in runs]
        sizes = [len(cells) for _, cells in runs]
        X = np.array(mesh.positions)
    else:
        from ._mesh import Mesh

        if not isinstance(mesh, Mesh):
            raise TypeError(f"a polydec.Mesh or VolumeMesh is needed, got {type(mesh).__name__}")
        idx, off = mesh.faces
        n = np.diff(off)
        cut = np.flatnonzero(np.diff(n)) + 1
        starts = np.concatenate([[0], cut])
        ends = np.concatenate([cut, [n.size]])
        blocks = []
        for s, e in zip(starts, ends):
            k = int(n[s])
            name = {3: "triangle", 4: "quad"}.get(k, "polygon")
            blocks.append((name, idx[off[s]:off[e]].reshape(-1, k)))
        sizes = [int(e - s) for s, e in zip(starts, ends)]
        X = np.array(mesh.positions)
    split = None
    if cell_data:
        bounds = np.cumsum([0] + sizes)
        split = {name: [np.asarray(v)[bounds[i]:bounds[i + 1]] for i in range(len(sizes))]
                 for name, v in cell_data.items()}
    return meshio.Mesh(X, blocks, point_data=dict(point_data or {}), cell_data=split or {})
