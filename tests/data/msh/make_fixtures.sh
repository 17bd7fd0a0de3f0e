#!/usr/bin/env bash
# tests/data/msh/make_fixtures.sh — writes the gmsh and MEDIT fixtures of tests/dec/io/test_msh.cpp
# with Debian's gmsh (4.8.4; `apt-get install gmsh`) and meshio (5.0; `apt-get install
# python3-meshio`). Run once from anywhere; the outputs are committed beside this script:
#   <kind>_<version>_<ascii|binary>.msh  for kind tri, quad (surfaces of the 2 x 1 rectangle) and
#     tet, hex, prism, pyramid (volumes of the 2 x 1 x 1 box), version 22 and 41;
#   <kind>.mesh and <kind>.meshb (meshio's ASCII and binary MEDIT of the 4.1 file; GMF version 4 for
#     tet and hex, 3 for prism and pyramid) for the volume kinds (gmsh 4.8's MEDIT writer drops prisms
#     and pyramids).
# Every mesh holds physical groups ("solid"/"plate" and boundary groups of lower dimension, whose
# elements the readers skip and count).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# The 2 x 1 rectangle: triangles (tri) or quadrangles (quad).
for kind in tri quad; do
  cat >"$tmp/$kind.geo" <<EOF
Point(1) = {0, 0, 0, 0.7}; Point(2) = {2, 0, 0, 0.7}; Point(3) = {2, 1, 0, 0.7}; Point(4) = {0, 1, 0, 0.7};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
$([[ $kind == quad ]] && echo 'Recombine Surface{1};')
Physical Surface("plate") = {1};
Physical Curve("left") = {4};
Physical Point("origin") = {1};
EOF
done

# The 2 x 1 x 1 box: tetrahedra; hexahedra (transfinite); prisms (an extruded triangle mesh);
# hexahedra, tetrahedra and the pyramid gmsh puts between them.
cat >"$tmp/tet.geo" <<'EOF'
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 2, 1, 1};
Mesh.MeshSizeMin = 0.7; Mesh.MeshSizeMax = 0.7;
Physical Volume("solid") = {1};
Physical Surface("left") = {1};
Physical Curve("edge") = {1};
Physical Point("corner") = {1};
EOF
cat >"$tmp/hex.geo" <<'EOF'
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 2, 1, 1};
Transfinite Curve{:} = 3;
Transfinite Surface{:};
Recombine Surface{:};
Transfinite Volume{1};
Physical Volume("solid") = {1};
Physical Surface("left") = {1};
EOF
cat >"$tmp/prism.geo" <<'EOF'
Point(1) = {0, 0, 0, 0.7}; Point(2) = {2, 0, 0, 0.7}; Point(3) = {2, 1, 0, 0.7}; Point(4) = {0, 1, 0, 0.7};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
out[] = Extrude {0, 0, 1} { Surface{1}; Layers{2}; Recombine; };
Physical Volume("solid") = {out[1]};
Physical Surface("bottom") = {1};
EOF
cat >"$tmp/pyramid.geo" <<'EOF'
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 1, 1};
Box(2) = {1, 0, 0, 1, 1, 1};
BooleanFragments{ Volume{1}; Delete; }{ Volume{2}; Delete; }
Transfinite Curve{:} = 2;
Transfinite Surface{:};
s() = Surface In BoundingBox{-0.1, -0.1, -0.1, 1.1, 1.1, 1.1};
Recombine Surface{s()};
Transfinite Volume{1};
Physical Volume("hexes") = {1};
Physical Volume("tets") = {2};
EOF

for kind in tri quad tet hex prism pyramid; do
  dim=3
  [[ $kind == tri || $kind == quad ]] && dim=2
  for version in 22 41; do
    gmsh "$tmp/$kind.geo" -$dim -format msh$version -o "${kind}_${version}_ascii.msh" >/dev/null
    gmsh "$tmp/$kind.geo" -$dim -format msh$version -bin -o "${kind}_${version}_binary.msh" >/dev/null
  done
  if ((dim == 3)); then
    # Points and cells only (meshio would write a 2-column point array as the references); 64-bit
    # cell arrays make GMF version 4, 32-bit ones version 3.
    /usr/bin/python3 - "${kind}_41_ascii.msh" "$kind" "$([[ $kind == tet || $kind == hex ]] && echo 64 || echo 32)" <<'EOF'
import sys, meshio
m = meshio.read(sys.argv[1])
cells = [(c.type, c.data.astype("int" + sys.argv[3])) for c in m.cells]
for ext in ("mesh", "meshb"):
    meshio.write(sys.argv[2] + "." + ext, meshio.Mesh(m.points, cells))
EOF
  fi
done
ls -l
