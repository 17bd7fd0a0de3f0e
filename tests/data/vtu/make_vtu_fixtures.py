#!/usr/bin/env python3
"""tests/data/vtu/make_vtu_fixtures.py — writes the .vtu fixtures of tests/dec/io/test_vtu.cpp with
Debian's python3-vtk9 (VTK 9.1) and python3-meshio, in every encoding their writers offer:
ASCII, inline base64 (UInt32 and UInt64 headers), appended raw and base64, zlib-, LZ4- and
LZMA-compressed in blocks of 64 bytes (several blocks per array), big-endian, Float32 points,
Int32 and Int64 ids. Two layouts VTK 9.1 cannot write are assembled from its output: files of
several pieces (the Piece elements of separately written files, ASCII and inline binary, put into
one file as ParaView writes partitioned data), and VTK 9.4's polyhedron arrays (face_connectivity,
face_offsets, polyhedron_to_faces, polyhedron_offsets in place of faces and faceoffsets).

The volume mesh: a row of five cubes of edge 0.5 sharing faces (a hexahedron, a voxel, two
wedges, a 7-faced polyhedron whose top is split into two triangles, six pyramids around the
cube's centre) and, apart, a cube of six Kuhn tetrahedra: 33 points, 17 volume cells, total
volume 6 * 0.125 = 0.75; beside them a vertex, a line, two triangles, a quad and a polygon
(boundary cells, skipped by the reader). Point data (a scalar and a 3-vector) and cell data
ride along. The surface: a quad, two triangles and a pentagon (8 points, 4 faces) and a line.
The two pieces of the volume: the row of cubes with the vertex, line, quad and polygon cells, then
the tetrahedra's cube with its two triangles (the points in the one-piece files' order, the volume
cells in their order). The two pieces of the surface: the surface and a copy moved by 3 in x.

It also writes the seeds of the .vtu fuzz target, fuzz/corpus/vtu/: the six tetrahedra and the
polyhedron alone, in five encodings.

Run from anywhere: /usr/bin/python3 tests/data/vtu/make_vtu_fixtures.py
"""
import base64
import os
import re

import meshio
import numpy as np
import vtk

HERE = os.path.dirname(os.path.abspath(__file__))
H = 0.5  # cube edge


def volume_cells():
    """Points and (VTK type, ids or face stream) cells of the volume fixture."""
    pts = [(i * H, j * H, k * H) for k in (0, 1) for j in (0, 1) for i in range(6)]

    def p(i, j, k):  # grid point index: x fastest
        return k * 12 + j * 6 + i

    cells = []
    # hexahedron [0, 1]
    cells.append((12, [p(0, 0, 0), p(1, 0, 0), p(1, 1, 0), p(0, 1, 0), p(0, 0, 1), p(1, 0, 1), p(1, 1, 1), p(0, 1, 1)]))
    # voxel [1, 2]: x fastest, then y, then z
    cells.append((11, [p(1, 0, 0), p(2, 0, 0), p(1, 1, 0), p(2, 1, 0), p(1, 0, 1), p(2, 0, 1), p(1, 1, 1), p(2, 1, 1)]))
    # two wedges [2, 3], split by the vertical plane through (2,0)-(3,1): triangles in z = 0 and z = 1,
    # the first one's right-hand normal pointing away from the second (VTK's orientation)
    cells.append((13, [p(2, 0, 0), p(3, 1, 0), p(3, 0, 0), p(2, 0, 1), p(3, 1, 1), p(3, 0, 1)]))
    cells.append((13, [p(2, 0, 0), p(2, 1, 0), p(3, 1, 0), p(2, 0, 1), p(2, 1, 1), p(3, 1, 1)]))
    # polyhedron [3, 4]: outward faces, the top split into two triangles
    a, b, c, d = p(3, 0, 0), p(4, 0, 0), p(4, 1, 0), p(3, 1, 0)
    e, f, g, h = p(3, 0, 1), p(4, 0, 1), p(4, 1, 1), p(3, 1, 1)
    faces = [[a, d, c, b], [e, f, g], [e, g, h], [a, b, f, e], [b, c, g, f], [c, d, h, g], [d, a, e, h]]
    stream = [len(faces)]
    for fc in faces:
        stream += [len(fc)] + fc
    cells.append((42, stream))
    # six pyramids [4, 5] around the centre
    centre = len(pts)
    pts.append((4.5 * H, 0.5 * H, 0.5 * H))
    a, b, c, d = p(4, 0, 0), p(5, 0, 0), p(5, 1, 0), p(4, 1, 0)
    e, f, g, h = p(4, 0, 1), p(5, 0, 1), p(5, 1, 1), p(4, 1, 1)
    for quad in ([a, b, c, d], [e, h, g, f], [a, e, f, b], [b, f, g, c], [c, g, h, d], [d, h, e, a]):
        cells.append((14, quad + [centre]))
    # apart: a cube [6, 7] of six Kuhn tetrahedra (all along the diagonal 0-6)
    base = len(pts)
    for k in (0, 1):
        for j in (0, 1):
            for i in (0, 1):
                pts.append(((6 + i) * H, j * H, k * H))
    q = lambda i, j, k: base + k * 4 + j * 2 + i
    v0, v7 = q(0, 0, 0), q(1, 1, 1)
    for path in ([(1, 0, 0), (1, 1, 0)], [(1, 0, 0), (1, 0, 1)], [(0, 1, 0), (1, 1, 0)],
                 [(0, 1, 0), (0, 1, 1)], [(0, 0, 1), (1, 0, 1)], [(0, 0, 1), (0, 1, 1)]):
        t = [v0, q(*path[0]), q(*path[1]), v7]
        P = np.array([pts[i] for i in t])
        if np.linalg.det(P[1:] - P[0]) < 0:
            t[1], t[2] = t[2], t[1]
        cells.append((10, t))
    # lower-dimensional cells beside them
    cells += [(1, [p(0, 0, 0)]), (3, [p(0, 0, 0), p(1, 0, 0)]), (5, [q(0, 0, 0), q(1, 1, 0), q(1, 0, 0)]),
              (5, [q(0, 0, 0), q(0, 1, 0), q(1, 1, 0)]), (9, [p(0, 0, 0), p(0, 1, 0), p(1, 1, 0), p(1, 0, 0)]),
              (7, [p(5, 0, 0), p(5, 1, 0), p(5, 1, 1), p(5, 0, 1)])]
    return np.array(pts), cells


def surface_cells():
    pts = [(0, 0, 0), (1, 0, 0), (2, 0, 0), (0, 1, 0), (1, 1.25, 0), (2, 1, 0), (2, 2, 0), (0, 2, 0)]
    cells = [(9, [0, 1, 4, 3]), (5, [1, 2, 5]), (5, [1, 5, 4]), (7, [3, 4, 5, 6, 7]), (3, [0, 2])]
    return np.array(pts, dtype=float) * H, cells


def vtk_grid(pts, cells, float32=False):
    g = vtk.vtkUnstructuredGrid()
    points = vtk.vtkPoints()
    points.SetDataTypeToFloat() if float32 else points.SetDataTypeToDouble()
    for x in pts:
        points.InsertNextPoint(*x)
    g.SetPoints(points)
    for t, ids in cells:
        lst = vtk.vtkIdList()
        for i in ids:
            lst.InsertNextId(i)
        g.InsertNextCell(t, lst)
    f = vtk.vtkDoubleArray()
    f.SetName("f")
    v = vtk.vtkDoubleArray()
    v.SetName("v")
    v.SetNumberOfComponents(3)
    for x in pts:
        f.InsertNextValue(x[0] + 2 * x[1] + 3 * x[2])
        v.InsertNextTuple3(x[2], -x[1], x[0])
    g.GetPointData().AddArray(f)
    g.GetPointData().AddArray(v)
    cid = vtk.vtkIntArray()
    cid.SetName("cell_id")
    for c in range(len(cells)):
        cid.InsertNextValue(c)
    g.GetCellData().AddArray(cid)
    return g


def write_vtk(name, grid, mode, encode=True, zlib=False, header64=False, ids64=True, big=False, compressor=None,
              to_string=False):
    """Writes grid to name (or, with to_string, returns the file's text)."""
    w = vtk.vtkXMLUnstructuredGridWriter()
    if to_string:
        w.WriteToOutputStringOn()
    else:
        w.SetFileName(os.path.join(HERE, name))
    w.SetInputData(grid)
    {"ascii": w.SetDataModeToAscii, "binary": w.SetDataModeToBinary, "appended": w.SetDataModeToAppended}[mode]()
    w.SetEncodeAppendedData(encode)
    compressor = "zlib" if zlib else compressor
    if compressor:
        {"zlib": w.SetCompressorTypeToZLib, "lz4": w.SetCompressorTypeToLZ4, "lzma": w.SetCompressorTypeToLZMA}[compressor]()
        w.SetBlockSize(64)
    else:
        w.SetCompressorTypeToNone()
    w.SetHeaderTypeToUInt64() if header64 else w.SetHeaderTypeToUInt32()
    w.SetIdTypeToInt64() if ids64 else w.SetIdTypeToInt32()
    w.SetByteOrderToBigEndian() if big else w.SetByteOrderToLittleEndian()
    assert w.Write() == 1, name
    return w.GetOutputString() if to_string else None


def subgrid(pts, cells, keep):
    """The points used by the cells keep(i) selects (in their order) and those cells, renumbered."""
    chosen = [(t, ids) for i, (t, ids) in enumerate(cells) if keep(i)]
    used = sorted({i for t, ids in chosen for i in (ids if t != 42 else stream_ids(ids))})
    renumber = {old: new for new, old in enumerate(used)}
    return pts[used], [(t, [renumber[i] for i in ids] if t != 42 else restream(ids, renumber)) for t, ids in chosen]


def write_pieces(name, grids, mode, **kw):
    """One file of several pieces: the Piece elements of each grid's file (ASCII or inline binary, so
    that each piece is self-contained) in the envelope of the first."""
    texts = [write_vtk(None, g, mode, to_string=True, **kw) for g in grids]
    pieces = [t[t.index("    <Piece"):t.index("</Piece>") + len("</Piece>\n")] for t in texts]
    head = texts[0][:texts[0].index("    <Piece")]
    tail = texts[0][texts[0].index("</Piece>\n") + len("</Piece>\n"):]
    with open(os.path.join(HERE, name), "w") as f:
        f.write(head + "".join(pieces) + tail)


def b64_array(values, dtype):
    """Inline base64 of a UInt64 byte count and the little-endian values (as VTK encodes them)."""
    data = np.asarray(values, dtype=dtype).tobytes()
    return (base64.b64encode(np.uint64(len(data)).tobytes()) + base64.b64encode(data)).decode()


def vtk94_layout(text, binary):
    """The ASCII file text (one piece, UInt64 headers) with its faces and faceoffsets replaced by VTK 9.4's
    four polyhedron arrays: face_connectivity and face_offsets (the end of each face), polyhedron_to_faces
    and polyhedron_offsets (the end of each cell's face list, equal to the previous one for other cells);
    with `binary` these four are inline base64 (Int64)."""
    def array(name):
        m = re.search(r'<DataArray[^>]*Name="%s"[^>]*>(.*?)</DataArray>\s*' % name, text, re.S)
        return m, [int(x) for x in m.group(1).split()]
    (mf, faces), (mo, ends) = array("faces"), array("faceoffsets")
    conn, face_ends, to_faces, cell_ends, start = [], [], [], [], 0
    for end in ends:
        if end >= 0:
            p = start + 1
            for _ in range(faces[start]):
                k = faces[p]
                conn += faces[p + 1:p + 1 + k]
                face_ends.append(len(conn))
                to_faces.append(len(face_ends) - 1)
                p += 1 + k
            start = end
        cell_ends.append(len(to_faces))
    out = ""
    for name, values in (("face_connectivity", conn), ("face_offsets", face_ends),
                         ("polyhedron_to_faces", to_faces), ("polyhedron_offsets", cell_ends)):
        fmt = "binary" if binary else "ascii"
        data = b64_array(values, "<i8") if binary else " ".join(map(str, values))
        out += f'<DataArray type="Int64" Name="{name}" format="{fmt}">\n          {data}\n        </DataArray>\n        '
    text = text[:mf.start()] + out + text[mo.end():]
    return text.replace('version="0.1"', 'version="2.3"').replace('version="1.0"', 'version="2.3"')


def seeds():
    """Small fuzz seeds: one polyhedron, or six tetrahedra and a boundary triangle."""
    pts, cells = volume_cells()
    for tag, keep in (("tets", lambda t: t in (10, 5)), ("poly", lambda t: t == 42)):
        chosen = [(t, ids) for t, ids in cells if keep(t)]
        used = sorted({i for t, ids in chosen for i in (ids if t != 42 else [])} |
                      {i for t, ids in chosen if t == 42 for i in stream_ids(ids)})
        renumber = {old: new for new, old in enumerate(used)}
        small = [(t, [renumber[i] for i in ids] if t != 42 else restream(ids, renumber)) for t, ids in chosen]
        g = vtk_grid(pts[used], small)
        g_pts, g_cells = pts[used], small
        folder = os.path.join(HERE, "..", "..", "..", "fuzz", "corpus", "vtu")
        os.makedirs(folder, exist_ok=True)
        for name, kw in (("ascii", dict(mode="ascii")), ("binary", dict(mode="binary", ids64=False)),
                         ("raw", dict(mode="appended", encode=False)),
                         ("zlib_base64", dict(mode="appended", encode=True, zlib=True, header64=True)),
                         ("big_zlib_raw", dict(mode="appended", encode=False, zlib=True, big=True)),
                         ("lz4_raw", dict(mode="appended", encode=False, compressor="lz4")),
                         ("lzma_base64", dict(mode="appended", encode=True, compressor="lzma", header64=True))):
            write_vtk(os.path.join(folder, f"{tag}_{name}.vtu"), g, **kw)
        if tag == "poly":
            text = write_vtk(None, g, "ascii", header64=True, to_string=True)
            for binary in (False, True):
                with open(os.path.join(folder, f"poly_vtk94_{'binary' if binary else 'ascii'}.vtu"), "w") as f:
                    f.write(vtk94_layout(text, binary))
        else:
            write_pieces(os.path.join(folder, "tets_pieces_binary.vtu"),
                         [vtk_grid(*subgrid(g_pts, g_cells, lambda i: i < 3)),
                          vtk_grid(*subgrid(g_pts, g_cells, lambda i: i >= 3))], "binary")


def stream_ids(stream):
    """The point ids of a face stream."""
    out, p = [], 1
    for _ in range(stream[0]):
        out += stream[p + 1:p + 1 + stream[p]]
        p += 1 + stream[p]
    return out


def restream(stream, renumber):
    out, p = [stream[0]], 1
    for _ in range(stream[0]):
        out += [stream[p]] + [renumber[i] for i in stream[p + 1:p + 1 + stream[p]]]
        p += 1 + stream[p]
    return out


def main():
    seeds()
    pts, cells = volume_cells()
    g = vtk_grid(pts, cells)
    write_vtk("vtk_ascii.vtu", g, "ascii")
    write_vtk("vtk_binary_u32_int32.vtu", g, "binary", ids64=False)
    write_vtk("vtk_binary_u64.vtu", g, "binary", header64=True)
    write_vtk("vtk_appended_raw.vtu", g, "appended", encode=False)
    write_vtk("vtk_appended_base64.vtu", g, "appended", encode=True, header64=True)
    write_vtk("vtk_zlib_appended_raw.vtu", g, "appended", encode=False, zlib=True)
    write_vtk("vtk_zlib_binary_u64.vtu", g, "binary", zlib=True, header64=True)
    write_vtk("vtk_bigendian_binary.vtu", g, "binary", big=True, ids64=False)
    write_vtk("vtk_bigendian_zlib_appended.vtu", g, "appended", encode=False, zlib=True, header64=True, big=True)
    write_vtk("vtk_float32_appended_base64.vtu", vtk_grid(pts, cells, float32=True), "appended", encode=True)
    write_vtk("vtk_lz4_appended_raw.vtu", g, "appended", encode=False, compressor="lz4")
    write_vtk("vtk_lz4_bigendian_binary.vtu", g, "binary", compressor="lz4", big=True, ids64=False)
    write_vtk("vtk_lzma_binary_u64.vtu", g, "binary", compressor="lzma", header64=True)
    write_vtk("vtk_lzma_appended_base64.vtu", g, "appended", encode=True, compressor="lzma")
    text = write_vtk(None, g, "ascii", header64=True, to_string=True)
    for binary in (False, True):
        with open(os.path.join(HERE, f"vtk94_polyhedra_{'binary' if binary else 'ascii'}.vtu"), "w") as f:
            f.write(vtk94_layout(text, binary))
    # Two pieces: the row of cubes (points 0-24) with its lower cells, the tetrahedra's cube (25-32).
    row = lambda i: i < 11 or i in (17, 18, 21, 22)
    parts = [vtk_grid(*subgrid(pts, cells, row)), vtk_grid(*subgrid(pts, cells, lambda i: not row(i)))]
    write_pieces("vtk_pieces_ascii.vtu", parts, "ascii")
    write_pieces("vtk_pieces_binary_zlib.vtu", parts, "binary", zlib=True, header64=True)
    spts, scells = surface_cells()
    write_vtk("vtk_surface_ascii.vtu", vtk_grid(spts, scells), "ascii")
    write_vtk("vtk_surface_zlib_binary.vtu", vtk_grid(spts, scells), "binary", zlib=True)
    write_vtk("vtk_surface_lzma_appended_raw.vtu", vtk_grid(spts, scells), "appended", encode=False,
              compressor="lzma")
    write_pieces("vtk_surface_pieces_binary.vtu", [vtk_grid(spts, scells), vtk_grid(spts + [3.0, 0, 0], scells)],
                 "binary")

    # meshio: the standard cells (no voxel, no polyhedron) in blocks by type, Int32 ids. meshio's own
    # wedge numbers its triangles the other way round and reorders them for VTK (0 2 1 3 5 4).
    names = {10: "tetra", 12: "hexahedron", 13: "wedge", 14: "pyramid", 1: "vertex", 3: "line", 5: "triangle", 9: "quad"}
    blocks = {}
    for t, ids in cells:
        if t in names:
            blocks.setdefault(names[t], []).append([ids[i] for i in (0, 2, 1, 3, 5, 4)] if t == 13 else ids)
    m = meshio.Mesh(pts, [(k, np.array(v, dtype=np.int32)) for k, v in blocks.items()],
                    point_data={"f": pts[:, 0] + 2 * pts[:, 1], "v": pts[:, ::-1].copy()})
    m.write(os.path.join(HERE, "meshio_ascii.vtu"), binary=False)
    m.write(os.path.join(HERE, "meshio_binary.vtu"), binary=True, compression=None)
    m.write(os.path.join(HERE, "meshio_zlib.vtu"), binary=True, compression="zlib")
    sm = meshio.Mesh(spts, [("quad", np.array([[0, 1, 4, 3]], dtype=np.int32)),
                            ("triangle", np.array([[1, 2, 5], [1, 5, 4]], dtype=np.int32))])
    sm.write(os.path.join(HERE, "meshio_surface_zlib.vtu"), binary=True, compression="zlib")


if __name__ == "__main__":
    main()
