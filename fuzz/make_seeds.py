#!/usr/bin/env python3
# fuzz/make_seeds.py — writes the committed seed corpus fuzz/corpus/<target>/ (small valid
# files of each format and flavour; the mutator starts from these). Rerun only to change it.
import math
import os
import struct

HERE = os.path.dirname(os.path.abspath(__file__))


def put(rel, data):
    path = os.path.join(HERE, "corpus", rel)
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "wb") as f:
        f.write(data.encode() if isinstance(data, str) else data)


# Small meshes: (positions, faces).
square = ([(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)], [[0, 1, 2, 3]])
hexagon = ([(math.cos(k * math.pi / 3), math.sin(k * math.pi / 3), 0.1 * (k % 2)) for k in range(6)] + [(0, 0, 0)],
           [[0, 1, 2, 3, 4, 5]])
lshape = ([(0, 0, 0), (2, 0, 0), (2, 1, 0), (1, 1, 0), (1, 2, 0), (0, 2, 0), (3, 0, 0), (3, 2, 0)],
          [[0, 1, 2, 3, 4, 5], [1, 6, 7, 4, 3, 2]])
pyramid = ([(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0.5, 0.5, 1)],
           [[3, 2, 1, 0], [0, 1, 4], [1, 2, 4], [2, 3, 4], [3, 0, 4]])
collinear = ([(0, 0, 0), (1, 0, 0), (2, 0, 0), (2, 1, 0), (0, 1, 0)], [[0, 1, 2, 3, 4]])
tiny = ([(x * 1e-9 + 1e3, y * 1e-9, 0) for x, y, _ in square[0]], square[1])
grid = ([(i, j, 0.05 * ((i * j) % 3)) for j in range(3) for i in range(3)],
        [[j * 3 + i, j * 3 + i + 1, j * 3 + i + 4, j * 3 + i + 3] for j in range(2) for i in range(2)])
MESHES = {"square": square, "hexagon": hexagon, "lshape": lshape, "pyramid": pyramid, "collinear": collinear,
          "tiny": tiny, "grid": grid}


def obj(m, style=0):
    V, F = m
    s = "# seed\n" + "".join(f"v {x!r} {y!r} {z!r}\n" for x, y, z in V)
    if style == 1:
        s += "vt 0 0\nvn 0 0 1\n"
    for f in F:
        if style == 0:
            s += "f " + " ".join(str(i + 1) for i in f) + "\n"
        elif style == 1:
            s += "f " + " ".join(f"{i + 1}/1/1" for i in f) + "\n"
        else:
            s += "f " + " ".join(str(i - len(V)) for i in f) + "\r\n"
    return s


def off(m):
    V, F = m
    return (f"OFF\n{len(V)} {len(F)} 0\n" + "".join(f"{x!r} {y!r} {z!r}\n" for x, y, z in V)
            + "".join(f"{len(f)} " + " ".join(map(str, f)) + "\n" for f in F))


def off_binary(m):
    V, F = m
    b = b"OFF BINARY\n" + struct.pack("<iii", len(V), len(F), 0)
    b += b"".join(struct.pack("<fff", *p) for p in V)
    return b + b"".join(struct.pack("<i", len(f)) + struct.pack("<%di" % len(f), *f) for f in F)


def ply(m, fmt):
    V, F = m
    h = (f"ply\nformat {fmt} 1.0\nelement vertex {len(V)}\nproperty double x\nproperty double y\n"
         f"property float z\nproperty uchar red\nelement face {len(F)}\nproperty list uchar int vertex_indices\n"
         "end_header\n").encode()
    if fmt == "ascii":
        return h + "".join(f"{x!r} {y!r} {z!r} 7\n" for x, y, z in V).encode() + "".join(
            f"{len(f)} " + " ".join(map(str, f)) + "\n" for f in F).encode()
    e = "<" if fmt == "binary_little_endian" else ">"
    return h + b"".join(struct.pack(e + "ddfB", x, y, z, 7) for x, y, z in V) + b"".join(
        struct.pack(e + "B", len(f)) + struct.pack(e + "%di" % len(f), *f) for f in F)


for name, m in MESHES.items():
    put(f"obj/{name}.obj", obj(m, 0))
    put(f"assemble/{name}.obj", obj(m, 0))
for name in ("square", "pyramid"):
    put(f"obj/{name}_vtn.obj", obj(MESHES[name], 1))
    put(f"obj/{name}_relative.obj", "\ufeff" + obj(MESHES[name], 2))
for name in ("square", "hexagon", "pyramid"):
    put(f"off/{name}.off", off(MESHES[name]))
    put(f"off/{name}_binary.off", off_binary(MESHES[name]))
    for fmt in ("ascii", "binary_little_endian", "binary_big_endian"):
        put(f"ply/{name}_{fmt}.ply", ply(MESHES[name], fmt))
put("off/coff.off", "COFF\n# colors\n3 1 0\n0 0 0 1 0 0 1\n1 0 0 0 1 0 1\n0 1 0 0 0 1 1\n3 0 1 2 0.5 0.5 0.5\n")
put("mtx/general.mtx", "%%MatrixMarket matrix coordinate real general\n% c\n3 4 3\n1 1 1.5\n3 4 -2e-300\n2 2 7\n")
put("mtx/symmetric.mtx", "%%MatrixMarket matrix coordinate integer symmetric\n2 2 2\n1 1 4\n2 1 -1\n")
