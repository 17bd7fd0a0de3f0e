"""tests/python/test_groups.py — polydec.read_mesh_groups on the gmsh fixtures of tests/data/msh
(written by gmsh 4.8.4, tests/data/msh/make_fixtures.sh): group vertex sets against the geometry,
element sets and skipped counts, the docstring example, files without groups; MEDIT references."""

import doctest

import numpy as np

import polydec
from polydec import _groups
from conftest import TEST_DATA

MSH = TEST_DATA / "msh"


def test_volume_groups_match_the_geometry():
    for name in ("tet_41_ascii.msh", "tet_22_binary.msh"):
        m = polydec.read_volume_mesh(str(MSH / name))
        X = m.positions
        groups = polydec.read_mesh_groups(MSH / name)
        assert sorted(groups) == ["corner", "edge", "left", "solid"]
        assert groups["left"].dtype == np.int32
        assert groups["left"].tolist() == np.flatnonzero(X[:, 0] == 0).tolist()
        assert groups["edge"].tolist() == np.flatnonzero((X[:, 0] == 0) & (X[:, 1] == 0)).tolist()
        assert groups["solid"].tolist() == list(range(44))
        vertices, elements, skipped = polydec.read_mesh_groups(MSH / name, with_elements=True)
        assert elements["solid"].tolist() == list(range(90))
        assert skipped == {"lines": 2, "points": 1, "triangles": 14}


def test_medit_references_are_groups(tmp_path):
    """Element references r as "ref r", vertex references as "vertex ref r", 0 as none."""
    path = tmp_path / "t.mesh"
    path.write_text("MeshVersionFormatted 2\nDimension 3\nVertices\n5\n0 0 0 1\n1 0 0 0\n0 1 0 0\n0 0 1 0\n"
                    "1 1 1 7\nTriangles\n1\n1 2 3 5\nTetrahedra\n2\n1 2 3 4 0\n2 3 4 5 3\nEnd\n")
    vertices, elements, skipped = polydec.read_mesh_groups(path, with_elements=True)
    assert {k: v.tolist() for k, v in vertices.items()} == {
        "ref 3": [1, 2, 3, 4], "ref 5": [0, 1, 2], "vertex ref 1": [0], "vertex ref 7": [4]}
    assert {k: v.tolist() for k, v in elements.items()} == {"ref 3": [1]}
    assert skipped == {"triangles": 1}
    # polydec writes references 0: its .meshb has no groups.
    polydec.write_volume_mesh(tmp_path / "t.meshb", polydec.read_volume_mesh(path))
    assert polydec.read_mesh_groups(tmp_path / "t.meshb") == {}


def test_surface_groups_and_other_formats(tmp_path):
    V, F = polydec.read_mesh(MSH / "quad_41_binary.msh")
    groups = polydec.read_mesh_groups(MSH / "quad_41_binary.msh")
    assert groups["left"].tolist() == np.flatnonzero(V[:, 0] == 0).tolist()
    assert groups["origin"].tolist() == np.flatnonzero(np.all(V == 0, axis=1)).tolist()
    assert len(groups["plate"]) == len(V)
    path = tmp_path / "q.obj"
    polydec.write_mesh(path, V, F)
    assert polydec.read_mesh_groups(path) == {}


def test_docstring_example():
    assert doctest.testmod(_groups).failed == 0
