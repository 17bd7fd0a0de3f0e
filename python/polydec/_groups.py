"""Named vertex sets of mesh files: gmsh physical groups and MEDIT references (docs/io.md, "Groups")."""

from . import _polydec


def read_mesh_groups(path, with_elements=False):
    """The physical groups of a gmsh .msh file (surface or volume) as a dict name -> sorted int32
    array of vertex indices (the vertices of read_mesh / read_volume_mesh of the same file). An
    unnamed group is named by its number ("7"). The references of a MEDIT .mesh or .meshb file
    make the groups "ref r" (the vertices of the elements with reference r, cells among them) and
    "vertex ref r" (the vertices carrying r); reference 0 makes none. With with_elements=True, returns
    (vertices, elements, skipped): elements maps the groups of the mesh's own faces (surface) or
    cells (volume) to their indices, skipped counts the lower-dimensional elements the reader
    skipped ({"triangles": 14, ...}). Files of other formats have no groups ({}).

    >>> import polydec, tempfile, os
    >>> path = os.path.join(tempfile.mkdtemp(), "t.msh")
    >>> _ = open(path, "w").write('''$MeshFormat
    ... 2.2 0 8
    ... $EndMeshFormat
    ... $PhysicalNames
    ... 1
    ... 1 7 "edge"
    ... $EndPhysicalNames
    ... $Nodes
    ... 3
    ... 1 0 0 0
    ... 2 1 0 0
    ... 3 0 1 0
    ... $EndNodes
    ... $Elements
    ... 2
    ... 1 1 2 7 1 2 3
    ... 2 2 2 0 1 1 2 3
    ... $EndElements
    ... ''')
    >>> polydec.read_mesh_groups(path)["edge"].tolist()
    [1, 2]
    """
    vertices, elements, skipped = _polydec.read_mesh_groups(str(path))
    return (vertices, elements, skipped) if with_elements else vertices
