#!/usr/bin/env python3
# tests/data/bad/make_corpus.py — writes the hostile-file corpus next to this script (committed;
# rerun only to change it). Each file is one case of tests/dec/test_io_bad.cpp; docs/io.md
# tabulates them.
import os
import random
import struct

HERE = os.path.dirname(os.path.abspath(__file__))


def put(rel, data):
    path = os.path.join(HERE, rel)
    os.makedirs(os.path.dirname(path), exist_ok=True)
    if isinstance(data, str):
        data = data.encode()
    with open(path, "wb") as f:
        f.write(data)


PNG = b"\x89PNG\r\n\x1a\n\x00\x00\x00\rIHDR\x00\x00\x00\x10\x00\x00\x00\x10\x08\x06\x00\x00\x00\x1f\xf3\xffa"
rng = random.Random(20201)
RANDOM = bytes(rng.randrange(256) for _ in range(512))

# A unit square split in two triangles plus one more vertex: the valid base of many cases.
QUAD = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)]

# ---------------------------------------------------------------- OBJ
V = "".join(f"v {x} {y} {z}\n" for x, y, z in QUAD)
put("obj/empty.obj", "")
put("obj/header_only.obj", "# exported by a modeler\nmtllib scene.mtl\no Square\n")
put("obj/nan.obj", V + "v nan 0 0\nf 1 2 3 4\n")
put("obj/inf.obj", "v 0 0 0\nv inf 0 0\nv 1 1 0\nf 1 2 3\n")
# Found by fuzz_assemble: a finite coordinate so large that fourth powers of lengths overflow.
put("obj/huge_coordinate.obj", "v 0 0 1e308\nv 1 0 0\nv 1 1 0\nf 1 2 3\n")
put("obj/overflow.obj", "v 0 0 0\nv 1e999 0 0\nv 1 1 0\nf 1 2 3\n")
put("obj/face_1.obj", V + "f 1 2 3 4\nf 2\n")
put("obj/face_2.obj", V + "f 1 2 3 4\nf 2 3\n")
put("obj/index_out_of_range.obj", V + "f 1 2 5\n")
put("obj/index_negative_out_of_range.obj", V + "f -1 -2 -5\n")
put("obj/index_zero.obj", V + "f 0 1 2\n")
put("obj/index_llong_min.obj", V + "f 1 2 -9223372036854775808\n")
put("obj/index_overflow.obj", V + "f 1 2 99999999999999999999\n")
put("obj/index_huge.obj", V + "f 1 2 3000000000\n")
put("obj/repeated_vertex.obj", V + "f 1 2 2 3\n")
put("obj/bad_number.obj", "v 0 0 0\nv 1 0 zero\n")
put("obj/short_vertex.obj", "v 0 0 0\nv 1 0\n")
put("obj/bad_face_entry.obj", V + "f 1/1/1/1 2 3\n")
put("obj/png.obj", PNG)
put("obj/random.obj", RANDOM)
# Accepted: BOM, CRLF, tabs and mixed whitespace, i/t/n entries, negative indices, other statements.
put("obj/bom_crlf_tabs.obj",
    "\ufeff# square\r\nmtllib a.mtl\r\no sq\r\n"
    "v\t0 0\t 0\r\nv  1 0 0 1.0\r\nv 1\t\t1 0\r\nv 0 1 0 0.5 0.5 0.5\r\n"
    "vt 0 0\r\nvt 1 0\r\nvn 0 0 1\r\ng group\r\nusemtl m\r\ns off\r\n"
    "f 1/1/1 2/2/1 -2//1\t-1/1\r\nl 1 2\r\n")

# ---------------------------------------------------------------- OFF ascii
VO = "".join(f"{x} {y} {z}\n" for x, y, z in QUAD)
put("off/empty.off", "")
put("off/header_only.off", "OFF\n")
put("off/counts_too_large.off",
    "OFF\n8 1 0\n" + "".join(f"{x}.000000000000 {y}.000000000000 {z}.000000000000\n" for x, y, z in QUAD))
put("off/negative_counts.off", "OFF\n-4 1 0\n" + VO + "4 0 1 2 3\n")
put("off/claims_1e12.off", "OFF\n1000000000000 1 0\n" + VO + "4 0 1 2 3\n")
put("off/claims_1e9.off", "OFF\n1000000000 1 0\n" + VO + "4 0 1 2 3\n")
put("off/nan.off", "OFF\n4 1 0\n0 0 0\n1 0 0\n1 NaN 0\n0 1 0\n4 0 1 2 3\n")
put("off/inf.off", "OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 -inf 0\n4 0 1 2 3\n")
put("off/face_2.off", "OFF\n4 2 0\n" + VO + "4 0 1 2 3\n2 0 1\n")
put("off/index_out_of_range.off", "OFF\n4 1 0\n" + VO + "4 0 1 2 4\n")
put("off/index_negative.off", "OFF\n4 1 0\n" + VO + "4 0 1 2 -1\n")
put("off/repeated_vertex.off", "OFF\n4 1 0\n" + VO + "4 0 1 1 2\n")
put("off/valence_too_large.off", "OFF\n4 1 0\n" + VO + "5 0 1 2 3\n")
put("off/four_d.off", "4OFF\n4 1 0\n" + VO + "4 0 1 2 3\n")
put("off/png.off", PNG)
put("off/random.off", RANDOM)
put("off/bad_number.off", "OFF\n4 1 0\n" + VO.replace("1 1 0", "1 1,5 0") + "4 0 1 2 3\n")
# Accepted.
put("off/bom.off", "\ufeffOFF\n4 1 0\n" + VO + "4 0 1 2 3\n")
put("off/crlf_tabs_comments.off",
    "# comment before the header\r\n\r\nOFF\t4  1\t0 # counts on the header line\r\n"
    "0\t0 0\r\n\r\n# a comment between vertices\r\n1 0  0\r\n 1\t1\t0\r\n0 1 0\r\n4 0 1 2 3 # the face\r\n")
put("off/coff.off", "COFF\n4 1 0\n" + "".join(f"{x} {y} {z} 255 0 0 255\n" for x, y, z in QUAD)
    + "4 0 1 2 3 0.5 0.5 0.5\n")
put("off/noff.off", "NOFF\n4 1 0\n" + "".join(f"{x} {y} {z} 0 0 1\n" for x, y, z in QUAD) + "4 0 1 2 3\n")


# ---------------------------------------------------------------- OFF binary (pmp layout)
def off_binary(nv, nf, verts, faces, endian="<"):
    b = b"OFF BINARY\n" + struct.pack(endian + "iii", nv, nf, 0)
    for p in verts:
        b += struct.pack(endian + "fff", *p)
    for f in faces:
        b += struct.pack(endian + "i", len(f)) + struct.pack(endian + "%di" % len(f), *f)
    return b


SQ = [[0, 1, 2, 3]]
put("offb/header_only.off", b"OFF BINARY\n")
put("offb/counts_too_large.off", off_binary(8, 1, QUAD, SQ))
put("offb/negative_counts.off", off_binary(-4, 1, QUAD, SQ))
put("offb/claims_2e9.off", off_binary(2000000000, 1, QUAD, SQ))
put("offb/truncated_face.off", off_binary(4, 1, QUAD, SQ)[:-4])
put("offb/nan.off", off_binary(4, 1, [(0, 0, 0), (1, 0, 0), (float("nan"), 1, 0), (0, 1, 0)], SQ))
put("offb/inf.off", off_binary(4, 1, [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, float("inf"), 0)], SQ))
put("offb/face_2.off", off_binary(4, 2, QUAD, [[0, 1, 2, 3], [0, 1]]))
put("offb/index_out_of_range.off", off_binary(4, 1, QUAD, [[0, 1, 2, 7]]))
put("offb/index_negative.off", off_binary(4, 1, QUAD, [[0, 1, 2, -1]]))
put("offb/repeated_vertex.off", off_binary(4, 1, QUAD, [[0, 1, 2, 2]]))
put("offb/negative_valence.off", off_binary(4, 1, QUAD, [[0, 1, 2, 3]])[:-20] + struct.pack("<5i", -4, 0, 1, 2, 3))
put("offb/big_endian.off", off_binary(4, 1, QUAD, SQ, ">"))
put("offb/png_after_header.off", b"OFF BINARY\n" + PNG)


# ---------------------------------------------------------------- PLY
def ply_header(fmt, nv, nf, vprops="property float x\nproperty float y\nproperty float z\n",
               flist="property list uchar int vertex_indices\n", extra=""):
    return (f"ply\nformat {fmt} 1.0\ncomment hostile case\nelement vertex {nv}\n{vprops}"
            f"element face {nf}\n{flist}{extra}end_header\n").encode()


def ply_binary(nv, nf, verts, faces, endian="<", fmt="binary_little_endian"):
    b = ply_header(fmt, nv, nf)
    for p in verts:
        b += struct.pack(endian + "fff", *p)
    for f in faces:
        b += struct.pack(endian + "B", len(f)) + struct.pack(endian + "%di" % len(f), *f)
    return b


VA = VO.encode()
put("ply/empty.ply", "")
put("ply/header_only.ply", ply_header("ascii", 4, 1))
put("ply/no_end_header.ply", b"ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\n")
put("ply/no_format.ply", b"ply\nelement vertex 0\nproperty float x\nproperty float y\nproperty float z\nend_header\n")
put("ply/counts_too_large.ply", ply_header("ascii", 8, 1) + "".join(
    f"{x}.000000000000 {y}.000000000000 {z}.000000000000\n" for x, y, z in QUAD).encode())
put("ply/negative_count.ply", ply_header("ascii", -4, 1) + VA + b"4 0 1 2 3\n")
put("ply/claims_1e12.ply", ply_binary(10**12, 1, QUAD, SQ))
put("ply/nan.ply", ply_header("ascii", 4, 1) + b"0 0 0\n1 0 0\n1 1 0\n0 nan 0\n4 0 1 2 3\n")
put("ply/inf_binary.ply", ply_binary(4, 1, [(0, 0, 0), (float("-inf"), 0, 0), (1, 1, 0), (0, 1, 0)], SQ))
put("ply/face_1.ply", ply_header("ascii", 4, 2) + VA + b"4 0 1 2 3\n1 0\n")
put("ply/index_out_of_range.ply", ply_header("ascii", 4, 1) + VA + b"4 0 1 2 4\n")
put("ply/index_negative.ply", ply_binary(4, 1, QUAD, [[0, 1, -2, 3]]))
put("ply/repeated_vertex.ply", ply_header("ascii", 4, 1) + VA + b"4 0 1 1 2\n")
put("ply/truncated_binary.ply", ply_binary(4, 1, QUAD, SQ)[:-6])
put("ply/truncated_big_endian.ply", ply_binary(4, 1, QUAD, SQ, ">", "binary_big_endian")[:-50])
put("ply/wrong_endianness.ply", ply_binary(4, 1, QUAD, SQ, "<", "binary_big_endian"))
put("ply/list_count_huge.ply",
    ply_header("binary_little_endian", 4, 1, flist="property list uint int vertex_indices\n")
    + b"".join(struct.pack("<fff", *p) for p in QUAD) + struct.pack("<I", 0xFFFFFFFF) + struct.pack("<4i", 0, 1, 2, 3))
put("ply/float_indices.ply", ply_header("ascii", 4, 1, flist="property list uchar float vertex_indices\n")
    + VA + b"4 0 1 2 3\n")
put("ply/unknown_format.ply", ply_header("binary_middle_endian", 4, 1) + VA + b"4 0 1 2 3\n")
put("ply/no_xyz.ply", ply_header("ascii", 4, 1, vprops="property float x\nproperty float y\n") + VA)
put("ply/png.ply", PNG)
put("ply/random.ply", RANDOM)
put("ply/bad_number.ply", ply_header("ascii", 4, 1) + VA.replace(b"1 1 0", b"1 1 0x3") + b"4 0 1 2 3\n")
# Accepted.
put("ply/bom_crlf_tabs.ply", b"\xef\xbb\xbf" + ply_header("ascii", 4, 1).replace(b"\n", b"\r\n")
    + b"0\t0 0\r\n1  0\t0\r\n\t1 1 0\r\n0 1 0\r\n4\t0 1 2 3\r\n")
# Mixed types, big-endian, extra elements and list properties to skip, vertex_index spelling.
mixed = ("ply\nformat binary_big_endian 1.0\nobj_info mixed types\n"
         "element material 2\nproperty list uchar float rgba\nproperty int id\n"
         "element vertex 4\nproperty uchar red\nproperty float x\nproperty double y\nproperty short z\n"
         "property list ushort int neighbours\n"
         "element face 1\nproperty uchar flags\nproperty list uint ushort vertex_index\nproperty float quality\n"
         "element edge 1\nproperty int vertex1\nproperty int vertex2\nend_header\n").encode()
mixed += struct.pack(">B4fi", 4, 1, 0, 0, 1, 7) + struct.pack(">B0fi", 0, 8)
for i, (x, y, z) in enumerate(QUAD):
    mixed += struct.pack(">Bfdh", 200, x, y, z) + struct.pack(">H2i", 2, i, i)
mixed += struct.pack(">BI4Hf", 1, 4, 0, 1, 2, 3, 0.5) + struct.pack(">2i", 0, 1)
put("ply/mixed_types_big_endian.ply", mixed)
put("ply/truncated_mid_record.ply", mixed[:-10])

# ---------------------------------------------------------------- Matrix Market
put("mtx/claims_1e12.mtx", "%%MatrixMarket matrix coordinate real general\n3 3 1000000000000\n1 1 1\n")
put("mtx/out_of_range.mtx", "%%MatrixMarket matrix coordinate real general\n3 3 2\n1 1 1\n4 1 2\n")
put("mtx/truncated.mtx", "%%MatrixMarket matrix coordinate real general\n% a comment\n3 3 3\n1 1 1\n2 2 2\n")
put("mtx/vector_format.mtx", "%%MatrixMarket matrix vector real general\n3 3\n1\n2\n")
put("mtx/array_two_per_line.mtx", "%%MatrixMarket matrix array real general\n2 2\n1 2\n3 4\n")
put("mtx/array_truncated.mtx", "%%MatrixMarket matrix array real general\n3 3\n1\n2\n")
put("mtx/png.mtx", PNG)
# Found by fuzz_mtx: a symmetric matrix that is not square (the mirrored entry fell outside).
# Found by fuzz_mtx: 3 entries claiming 723221734 columns (a 2.9 GB column index).
put("mtx/huge_columns.mtx", "%%MatrixMarket matrix coordinate real general\n3 723221734 1\n1 1 1.5\n")
put("mtx/symmetric_not_square.mtx", "%%MatrixMarket matrix coordinate integer symmetric\n4 1 2\n1 1 4\n2 1 -1\n")
