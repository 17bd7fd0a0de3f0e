#!/usr/bin/env python3
# fuzz/make_volume_seeds.py — writes the seed corpora fuzz/corpus/{ovm,vtk,medit,meshb}/: small
# generated volume meshes (a tetrahedron, a Kuhn-split cube, two hexahedra, two wedges, a
# pyramid on a hexahedron, a polyhedron cell) in each format, and VTK BINARY variants (classic
# int32 cells with float or double points, the 5.1 int64 layout, polyhedra, a METADATA block),
# and ParaView-style dataset FIELD data before POINTS (ASCII and BINARY); MEDIT files with vertex,
# cell and triangle references, ASCII (medit/) and binary GMF version 2 (meshb/).
# Rerun only to change them.
import os
import struct

HERE = os.path.dirname(os.path.abspath(__file__))

# VTK's outward faces of its linear cells (local vertex numbers), as dec/mesh/polyhedron_builder.cpp.
FACES = {
    10: [[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]],
    12: [[0, 3, 2, 1], [4, 5, 6, 7], [0, 1, 5, 4], [1, 2, 6, 5], [2, 3, 7, 6], [3, 0, 4, 7]],
    13: [[0, 1, 2], [3, 5, 4], [0, 3, 4, 1], [1, 4, 5, 2], [2, 5, 3, 0]],
    14: [[0, 3, 2, 1], [0, 1, 4], [1, 2, 4], [2, 3, 4], [3, 0, 4]],
}

CUBE = [(x, y, z) for z in (0, 1) for y in (0, 1) for x in (0, 1)]
CUBE = [CUBE[i] for i in (0, 1, 3, 2, 4, 5, 7, 6)]  # VTK hexahedron order


def kuhn():
    cells = []
    for a, b in ((0, 1), (0, 2), (1, 0), (1, 2), (2, 0), (2, 1)):
        p = [0, 0, 0]
        path = [tuple(p)]
        for axis in (a, b):
            p[axis] = 1
            path.append(tuple(p))
        path.append((1, 1, 1))
        idx = [CUBE.index(q) for q in path]
        A, B, C, D = (CUBE[i] for i in idx)
        det = sum((B[i] - A[i]) * ((C[(i + 1) % 3] - A[(i + 1) % 3]) * (D[(i + 2) % 3] - A[(i + 2) % 3]) -
                                   (C[(i + 2) % 3] - A[(i + 2) % 3]) * (D[(i + 1) % 3] - A[(i + 1) % 3])) for i in range(3))
        if det < 0:
            idx[1], idx[2] = idx[2], idx[1]
        cells.append((10, idx))
    return CUBE, cells


MESHES = {
    "tet": ([(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)], [(10, [0, 1, 2, 3])]),
    "kuhn": kuhn(),
    "two_hexes": (CUBE + [(2, 0, 0), (2, 1, 0), (2, 0, 1), (2, 1, 1)],
                  [(12, list(range(8))), (12, [1, 8, 9, 2, 5, 10, 11, 6])]),
    "wedges": (CUBE, [(13, [0, 3, 1, 4, 7, 5]), (13, [1, 3, 2, 5, 7, 6])]),
    "pyramid_hex": (CUBE + [(0.5, 0.5, 2.0)], [(12, list(range(8))), (14, [4, 5, 6, 7, 8])]),
}


def polygons(cells):
    out = []
    for t, v in cells:
        out.append([[v[i] for i in f] for f in FACES[t]])
    return out


def ovm(points, cells):
    faces, halffaces = [], []
    for polys in polygons(cells):
        hf = []
        for p in polys:
            key = sorted(p)
            for k, f in enumerate(faces):
                if sorted(f) == key:
                    hf.append(2 * k + 1)
                    break
            else:
                faces.append(p)
                hf.append(2 * (len(faces) - 1))
        halffaces.append(hf)
    edges = []
    def he(a, b):
        e = (min(a, b), max(a, b))
        if e not in edges:
            edges.append(e)
        return 2 * edges.index(e) + (0 if a < b else 1)
    face_he = [[he(f[i], f[(i + 1) % len(f)]) for i in range(len(f))] for f in faces]
    s = "OVM ASCII\nVertices\n%d\n" % len(points) + "".join("%r %r %r\n" % p for p in points)
    s += "Edges\n%d\n" % len(edges) + "".join("%d %d\n" % e for e in edges)
    s += "Faces\n%d\n" % len(faces) + "".join("%d %s\n" % (len(h), " ".join(map(str, h))) for h in face_he)
    s += "Polyhedra\n%d\n" % len(halffaces) + "".join("%d %s\n" % (len(h), " ".join(map(str, h))) for h in halffaces)
    return s


def face_streams(cells):
    # Each cell's polyhedron face stream: n_faces, then per face its size and vertices.
    out = []
    for polys in polygons(cells):
        e = [len(polys)]
        for p in polys:
            e += [len(p)] + p
        out.append(e)
    return out


def field_block(binary):
    # Dataset FIELD data as ParaView writes it before POINTS (TimeValue), with an int array, a
    # string array and a NULL_ARRAY; binary payloads big-endian, strings behind their length byte.
    if not binary:
        return ("FIELD FieldData 4\nTimeValue 1 1 double\n0.5\nCYCLE 1 2 int\n3 4\nNULL_ARRAY\n"
                "Names 1 1 string\nseed%20mesh\n")
    s = b"FIELD FieldData 4\nTimeValue 1 1 double\n" + struct.pack(">d", 0.5) + b"\n"
    s += b"CYCLE 1 2 int\n" + struct.pack(">2i", 3, 4) + b"\nNULL_ARRAY\n"
    return s + b"Names 1 1 string\n" + bytes([0xC0 | 9]) + b"seed mesh\n"


def vtk(points, cells, version="3.0", polyhedron=False, field=False):
    s = "# vtk DataFile Version %s\nseed\nASCII\nDATASET UNSTRUCTURED_GRID\n" % version
    s += (field_block(False) if field else "") + "POINTS %d double\n" % len(points)
    s += "".join("%r %r %r\n" % p for p in points)
    if polyhedron:
        entries = [[len(e)] + e for e in face_streams(cells)]
        s += "CELLS %d %d\n" % (len(entries), sum(len(e) for e in entries))
        s += "".join(" ".join(map(str, e)) + "\n" for e in entries)
        s += "CELL_TYPES %d\n" % len(cells) + "42\n" * len(cells)
        return s
    if version.startswith("5"):
        offs = [0]
        for _, v in cells:
            offs.append(offs[-1] + len(v))
        s += "CELLS %d %d\nOFFSETS vtktypeint64\n%s\nCONNECTIVITY vtktypeint64\n%s\n" % (
            len(offs), offs[-1], " ".join(map(str, offs)), " ".join(str(i) for _, v in cells for i in v))
    else:
        s += "CELLS %d %d\n" % (len(cells), sum(1 + len(v) for _, v in cells))
        s += "".join("%d %s\n" % (len(v), " ".join(map(str, v))) for _, v in cells)
    s += "CELL_TYPES %d\n" % len(cells) + "".join("%d\n" % t for t, _ in cells)
    return s


def vtk_binary(points, cells, version="4.2", polyhedron=False, point_type="double", metadata=False, field=False):
    # Big-endian payloads, each after its header line's newline, as VTK's legacy writer does.
    pack = {"double": ">3d", "float": ">3f"}[point_type]
    s = b"# vtk DataFile Version %s\nseed\nBINARY\nDATASET UNSTRUCTURED_GRID\n" % version.encode()
    s += (field_block(True) if field else b"") + b"POINTS %d %s\n" % (len(points), point_type.encode())
    s += b"".join(struct.pack(pack, *p) for p in points) + b"\n"
    if metadata:
        s += b"METADATA\nINFORMATION 1\nNAME L2_NORM_RANGE LOCATION vtkDataArray\nDATA 2 0 1.7 \n\n"
    if polyhedron:
        cells_out = [(42, e) for e in face_streams(cells)]
    else:
        cells_out = cells
    if version.startswith("5"):
        offs = [0]
        for _, v in cells_out:
            offs.append(offs[-1] + len(v))
        s += b"CELLS %d %d\nOFFSETS vtktypeint64\n" % (len(offs), offs[-1])
        s += struct.pack(">%dq" % len(offs), *offs) + b"\nCONNECTIVITY vtktypeint64\n"
        flat = [i for _, v in cells_out for i in v]
        s += struct.pack(">%dq" % len(flat), *flat) + b"\n"
    else:
        flat = [i for _, v in cells_out for i in [len(v)] + list(v)]
        s += b"CELLS %d %d\n" % (len(cells_out), len(flat)) + struct.pack(">%di" % len(flat), *flat) + b"\n"
    s += b"CELL_TYPES %d\n" % len(cells_out) + struct.pack(">%di" % len(cells_out), *[t for t, _ in cells_out]) + b"\n"
    return s


def medit(points, cells):
    s = "MeshVersionFormatted 2\nDimension 3\nVertices\n%d\n" % len(points)
    s += "".join("%r %r %r 0\n" % p for p in points)
    for t, key in ((10, "Tetrahedra"), (12, "Hexahedra")):
        sel = [v for tt, v in cells if tt == t]
        if sel:
            s += "%s\n%d\n" % (key, len(sel)) + "".join(" ".join(str(i + 1) for i in v) + " 1\n" for v in sel)
    return s + "End\n"


def medit_refs(points, cells, binary=False):
    """MEDIT with references: vertex v carries v % 3, cell c the reference c % 2 + 1, and each
    cell's first three vertices make a triangle (skipped) with reference 7; ASCII or binary GMF
    version 2 (32-bit integers and positions, float64 coordinates)."""
    keys = {10: ("Tetrahedra", 8), 12: ("Hexahedra", 10)}
    triangles = [v[:3] for _, v in cells]
    if not binary:
        s = "MeshVersionFormatted 2\nDimension 3\nVertices\n%d\n" % len(points)
        s += "".join("%r %r %r %d\n" % (*p, i % 3) for i, p in enumerate(points))
        s += "Triangles\n%d\n" % len(triangles) + "".join("%d %d %d 7\n" % tuple(i + 1 for i in t) for t in triangles)
        for t, (key, _) in keys.items():
            sel = [(c, v) for c, (tt, v) in enumerate(cells) if tt == t]
            if sel:
                s += "%s\n%d\n" % (key, len(sel)) + "".join(
                    " ".join(str(i + 1) for i in v) + " %d\n" % (c % 2 + 1) for c, v in sel)
        return s + "End\n"
    out = bytearray(struct.pack("<2i", 1, 2))

    def keyword(code, payload):
        out.extend(struct.pack("<2i", code, len(out) + 8 + len(payload)) + payload)

    keyword(3, struct.pack("<i", 3))
    keyword(4, struct.pack("<i", len(points)) + b"".join(struct.pack("<3di", *p, i % 3) for i, p in enumerate(points)))
    keyword(6, struct.pack("<i", len(triangles)) + b"".join(struct.pack("<4i", *(i + 1 for i in t), 7) for t in triangles))
    for t, (_, code) in keys.items():
        sel = [(c, v) for c, (tt, v) in enumerate(cells) if tt == t]
        if sel:
            keyword(code, struct.pack("<i", len(sel)) + b"".join(
                struct.pack("<%di" % (len(v) + 1), *(i + 1 for i in v), c % 2 + 1) for c, v in sel))
    out.extend(struct.pack("<2i", 54, 0))
    return bytes(out)


def put(target, name, text):
    d = os.path.join(HERE, "corpus", target)
    os.makedirs(d, exist_ok=True)
    with open(os.path.join(d, name), "wb" if isinstance(text, bytes) else "w") as f:
        f.write(text)


for name, (points, cells) in MESHES.items():
    put("ovm", name + ".ovm", ovm(points, cells))
    put("vtk", name + ".vtk", vtk(points, cells))
    if all(t in (10, 12) for t, _ in cells):
        put("medit", name + ".mesh", medit(points, cells))
put("vtk", "kuhn_v5.vtk", vtk(*MESHES["kuhn"], version="5.1"))
put("vtk", "two_hexes_polyhedra.vtk", vtk(*MESHES["two_hexes"], polyhedron=True))
put("vtk", "tet_binary.vtk", vtk_binary(*MESHES["tet"]))
put("vtk", "pyramid_hex_binary_float.vtk", vtk_binary(*MESHES["pyramid_hex"], point_type="float", metadata=True))
put("vtk", "wedges_binary.vtk", vtk_binary(*MESHES["wedges"]))
put("vtk", "kuhn_v5_binary.vtk", vtk_binary(*MESHES["kuhn"], version="5.1", metadata=True))
put("vtk", "two_hexes_polyhedra_binary.vtk", vtk_binary(*MESHES["two_hexes"], polyhedron=True))
put("vtk", "two_hexes_polyhedra_v5_binary.vtk", vtk_binary(*MESHES["two_hexes"], version="5.1", polyhedron=True))
put("vtk", "kuhn_v5_field.vtk", vtk(*MESHES["kuhn"], version="5.1", field=True))
put("vtk", "pyramid_hex_field_binary.vtk", vtk_binary(*MESHES["pyramid_hex"], version="5.1", field=True))
put("medit", "kuhn_refs.mesh", medit_refs(*MESHES["kuhn"]))
put("meshb", "kuhn_refs_v2.meshb", medit_refs(*MESHES["kuhn"], binary=True))
put("meshb", "two_hexes_refs_v2.meshb", medit_refs(*MESHES["two_hexes"], binary=True))
