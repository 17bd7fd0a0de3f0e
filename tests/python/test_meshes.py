"""tests/python/test_meshes.py — meshes in and out of Python: the three face forms and any
integer dtype give the same operator, positions of other dtypes are converted exactly or refused,
read_mesh / write_mesh round trips, the generators and transformations, and the error cases
(ValueError naming the face or vertex; FileError with file and line)."""

import numpy as np
import pytest

import polydec
from conftest import TEST_DATA, shared_mesh

# Two quads and a triangle, consistently oriented, in the plane.
V0 = np.array([[0, 0, 0], [1, 0, 0], [2, 0, 0], [0, 1, 0], [1, 1, 0], [2, 1, 0], [1, 2, 0]], dtype=np.float64)
F_MIXED = [[0, 1, 4, 3], [1, 2, 5, 4], [3, 4, 6]]


def test_face_forms_agree():
    S = polydec.stiffness(V0, F_MIXED)
    idx = np.array([0, 1, 4, 3, 1, 2, 5, 4, 3, 4, 6])
    off = np.array([0, 4, 8, 11])
    for dtype in [np.int8, np.uint8, np.int16, np.uint16, np.int32, np.uint32, np.int64, np.uint64]:
        flat = (idx.astype(dtype), off.astype(dtype))
        assert (polydec.stiffness(V0, flat) != S).nnz == 0, dtype
    assert (polydec.stiffness(V0, tuple(tuple(f) for f in F_MIXED)) != S).nnz == 0
    assert (polydec.stiffness(V0, [np.array(f, dtype=np.int16) for f in F_MIXED]) != S).nnz == 0
    # (F, k) arrays of any integer dtype.
    grid = polydec.quad_grid(3, 2)
    Vq, Fq = grid.positions, grid.face_array()
    assert isinstance(Fq, np.ndarray) and Fq.shape == (6, 4) and Fq.dtype == np.int64
    Sq = polydec.stiffness(Vq, Fq)
    for dtype in [np.int8, np.uint16, np.int32, np.uint64]:
        assert (polydec.stiffness(Vq, Fq.astype(dtype)) != Sq).nnz == 0, dtype
    assert (polydec.stiffness(Vq, Fq.tolist()) != Sq).nnz == 0
    assert (polydec.stiffness(Vq, (Fq.reshape(-1), np.arange(7) * 4)) != Sq).nnz == 0
    # Non-contiguous and Fortran-ordered inputs.
    assert (polydec.stiffness(np.asfortranarray(Vq), np.asfortranarray(Fq)) != Sq).nnz == 0
    assert (polydec.stiffness(np.hstack([Vq, Vq])[:, :3], Fq[:, :]) != Sq).nnz == 0


def test_position_dtypes_are_converted_exactly_or_refused():
    Vq, Fq = polydec.quad_grid(2, 2).positions, polydec.quad_grid(2, 2).face_array()
    Vi = np.round(Vq * 2).astype(np.int32)      # integer grid coordinates
    S = polydec.stiffness(Vi.astype(np.float64), Fq)
    for dtype in [np.int8, np.int16, np.int64, np.uint32, np.float16, np.float32]:
        assert (polydec.stiffness(Vi.astype(dtype), Fq) != S).nnz == 0, dtype
    assert (polydec.stiffness(Vi.tolist(), Fq) != S).nnz == 0
    # (|V|, 2) positions are the plane z = 0.
    assert (polydec.stiffness(Vi[:, :2].astype(np.float64), Fq) != S).nnz == 0
    big = Vi.astype(np.int64)
    big[4, 0] = 2**53 + 1                        # not representable in float64
    with pytest.raises(ValueError, match="vertex 4"):
        polydec.stiffness(big, Fq)
    if np.finfo(np.longdouble).eps < np.finfo(np.float64).eps:
        ld = Vq.astype(np.longdouble)
        ld[3, 1] += np.longdouble(2) ** -60       # needs more than 53 bits
        with pytest.raises(ValueError, match="vertex 3"):
            polydec.stiffness(ld, Fq)
    with pytest.raises(TypeError):
        polydec.stiffness(Vq.astype(np.complex128), Fq)
    with pytest.raises(TypeError):
        polydec.stiffness(Vq, Fq.astype(np.float64))
    with pytest.raises(ValueError, match="shape"):
        polydec.stiffness(Vq[:, :1], Fq)


def test_errors_name_the_face_or_vertex():
    Vq, Fq = polydec.quad_grid(2, 2).positions, polydec.quad_grid(2, 2).face_array()
    bad = Fq.copy()
    bad[2, 1] = 99
    with pytest.raises(ValueError, match="face 2") as e:
        polydec.stiffness(Vq, bad)
    assert isinstance(e.value, polydec.InvalidMeshError) and e.value.element == "face" and e.value.index == 2
    bad[2, 1] = -1
    with pytest.raises(ValueError, match="face 2"):
        polydec.laplacian(Vq, bad)
    with pytest.raises(ValueError, match="face 1"):
        polydec.stiffness(V0, [[0, 1, 4, 3], [1, 2, 2**40, 4]])
    nan = Vq.copy()
    nan[5, 2] = np.nan
    with pytest.raises(ValueError, match="vertex 5") as e:
        polydec.stiffness(nan, Fq)
    assert e.value.element == "vertex" and e.value.index == 5
    inf = Vq.copy()
    inf[1, 0] = np.inf
    with pytest.raises(polydec.InvalidMeshError, match="vertex 1"):
        polydec.HeatGeodesics(inf, Fq)
    # A non-manifold edge: three faces on edge (0, 1).
    Vn = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1]], dtype=float)
    with pytest.raises(ValueError, match="edge") as e:
        polydec.stiffness(Vn, [[0, 1, 2], [1, 0, 3], [0, 1, 4]])
    assert isinstance(e.value, polydec.InvalidMeshError)
    with pytest.raises(ValueError, match="face 0"):
        polydec.stiffness(Vq, [[0, 1]])                 # fewer than 3 vertices
    with pytest.raises(ValueError, match="face 1"):
        polydec.stiffness(V0, [[0, 1, 4, 3], [1, 2, 2, 4]])   # a repeated vertex
    with pytest.raises(ValueError, match="offsets"):
        polydec.stiffness(V0, (np.array([0, 1, 4]), np.array([0, 4])))


def test_read_write_round_trip(tmp_path):
    V, F = polydec.hex_sphere(1)
    for ext in ["obj", "off", "ply"]:
        path = tmp_path / f"m.{ext}"
        polydec.write_mesh(path, V, F)
        V2, F2 = polydec.read_mesh(path)
        assert np.array_equal(V, V2), ext                         # 17 digits: bit-exact
        assert np.array_equal(F[0], F2[0]) and np.array_equal(F[1], F2[1]), ext
    polydec.write_mesh(tmp_path / "b.ply", V, F, binary=True, scalars={"u": V[:, 0]})
    b = polydec.read_mesh(tmp_path / "b.ply")
    F3 = b.face_list()
    assert np.array_equal(V, b.positions) and isinstance(F3, list) and len(F3) == len(F[1]) - 1
    assert F3[0] == F[0][F[1][0]:F[1][1]].tolist()
    with pytest.raises(ValueError, match="one size"):
        b.face_array()


def test_read_paper_meshes_in_file_order():
    Vb, Fb = polydec.read_mesh(shared_mesh("bunny-hexa.off"))          # binary OFF
    info = polydec.mesh_info(Vb, Fb)
    assert info["vertices"] == Vb.shape[0] and info["euler_characteristic"] == 2
    V, F = polydec.read_mesh(shared_mesh("quad-plane.obj"))
    assert F[0].shape == (256,) and np.array_equal(F[1], 4 * np.arange(65))
    assert V[0].tolist() == [float(x) for x in first_vertex(shared_mesh("quad-plane.obj"))]


def first_vertex(path):
    for line in open(path):
        if line.startswith("v "):
            return line.split()[1:4]
    raise AssertionError("no vertex")


def test_bad_files_raise_oserror_and_valueerror_with_file_and_line(tmp_path):
    missing = tmp_path / "missing.obj"
    with pytest.raises(OSError) as e:
        polydec.read_mesh(missing)
    assert isinstance(e.value, polydec.FileError) and e.value.filename == str(missing)
    bad = tmp_path / "bad.obj"
    bad.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n")
    with pytest.raises(ValueError, match=r"bad\.obj:4") as e:
        polydec.read_mesh(bad)
    assert isinstance(e.value, OSError) and e.value.line == 4
    nm = tmp_path / "nonmanifold.off"
    nm.write_text("OFF\n5 3 0\n0 0 0\n1 0 0\n0 1 0\n0 -1 0\n0 0 1\n3 0 1 2\n3 1 0 3\n3 0 1 4\n")
    with pytest.raises(polydec.FileError, match="nonmanifold.off"):
        polydec.read_mesh(nm)
    # Files of the C++ hostile-file corpus (tests/dec/io/test_mesh_io_bad.cpp gives the same lines).
    for name, line, reason in [("obj/nan.obj", 5, "vertex 4 has a non-finite coordinate"),
                               ("obj/face_2.obj", 6, "face 1 has 2 vertices"),
                               ("obj/repeated_vertex.obj", 5, "face 0 repeats vertex 1"),
                               ("off/index_out_of_range.off", 7, "face vertex index 4 out of range")]:
        with pytest.raises(ValueError, match=reason) as e:
            polydec.read_mesh(TEST_DATA / "bad" / name)
        assert e.value.line == line and e.value.filename.endswith(name), name
    with pytest.raises(polydec.FileError):
        polydec.write_mesh(tmp_path / "no" / "dir" / "m.obj", V0, F_MIXED)
    with pytest.raises(polydec.FileError, match="unknown mesh format"):
        polydec.write_mesh(tmp_path / "m.xyz", V0, F_MIXED)


def test_generators_and_transformations():
    for (V, F), chi in [(polydec.quad_grid(3, 4), 1), (polydec.triangle_grid(3, 3), 1), (polydec.hex_grid(4, 3), 1),
                        (polydec.uv_sphere(6, 8), 2), (polydec.cube_sphere(3), 2), (polydec.hex_sphere(1), 2),
                        (polydec.torus(8, 6), 0), (polydec.genus2(0), -2)]:
        info = polydec.mesh_info(V, F)
        assert info["euler_characteristic"] == chi
    V, F = polydec.cube_sphere(2)
    Vc, Fc = polydec.catmull_clark(V, F)
    assert Vc.shape == (26 + 48 + 24, 3) and np.array_equal(Fc[1], 4 * np.arange(97))
    Vd, Fd = polydec.dual(V, F)
    assert Vd.shape[0] == 24 and polydec.mesh_info(Vd, Fd)["faces"] == V.shape[0]
    Vp, _ = polydec.project_to_unit_sphere(2 * V, F)
    assert np.allclose(np.linalg.norm(Vp, axis=1), 1, rtol=0, atol=1e-15)
    Vn1, _ = polydec.add_noise(V, F, 0.1, seed=5)
    Vn2, _ = polydec.add_noise(V, F, 0.1, seed=5)
    assert np.array_equal(Vn1, Vn2) and not np.array_equal(Vn1, V)
    with pytest.raises(ValueError):
        polydec.quad_grid(0, 3)
    with pytest.raises(ValueError, match="origin"):
        polydec.project_to_unit_sphere(np.vstack([V, [0, 0, 0]]), F)   # an unreferenced vertex at 0
