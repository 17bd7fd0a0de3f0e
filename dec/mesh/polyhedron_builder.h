// dec/mesh/polyhedron_builder.h — builds a PolyhedronSoup from cells given as polygon lists (as VTK,
// MEDIT and the generators describe them): a polygon with the vertex set of an earlier face is
// that face, as half-face 2f when it has the face's cyclic order and 2f+1 when reversed.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "polydec/dec/mesh/volume_mesh.h"

namespace polydec {

// VTK cell type numbers of the linear cells polydec reads and writes.
enum VtkCellType : int {
  kVtkTetra = 10,
  kVtkVoxel = 11,
  kVtkHexahedron = 12,
  kVtkWedge = 13,
  kVtkPyramid = 14,
  kVtkPolyhedron = 42
};

// The faces of a VTK linear cell (10, 12, 13, 14) as local vertex numbers in VTK's vertex order,
// each with its right-hand normal pointing out of the cell when the cell is positively oriented
// in VTK's convention; empty for other types. MEDIT's tetrahedra and hexahedra use the same
// orders.
const std::vector<std::vector<int>>& vtk_cell_faces(int vtk_type);
// Number of vertices of a VTK linear cell type (0 for other types).
int vtk_cell_size(int vtk_type);

class PolyhedronSoupBuilder {
 public:
  explicit PolyhedronSoupBuilder(Eigen::MatrixX3d positions);

  // Adds a polygon to the current cell and returns its half-face; -1 (nothing added) when an
  // earlier face has the same vertex set in a cyclic order that is neither the same nor reversed.
  int add_polygon(std::span<const int> polygon);
  // Adds the faces of a VTK linear cell (vtk_cell_faces) with the given vertices and closes the
  // cell; false (the cell left open, nothing closed) when a face does not match an earlier one.
  bool add_vtk_cell(int vtk_type, std::span<const int> vertices);
  // Closes the current cell (its half-faces are the polygons added since the last end_cell).
  void end_cell();
  // Room for `faces` faces with `face_indices` vertices in all and `cells` cells with
  // `cell_halffaces` half-faces in all, when the caller knows them (no regrowth while adding).
  void reserve(long faces, long face_indices, long cells, long cell_halffaces);
  // Index of the face that add_polygon last matched or created.
  int last_face() const { return last_face_; }

  int n_faces() const { return soup_.n_faces(); }
  PolyhedronSoup take() { return std::move(soup_); }

 private:
  // Open-addressing table of the faces by the hash of their sorted vertices (linear probing, at most
  // half full): a slot holds a face and its hash's high 32 bits, or face -1; face_hash_low_ keeps
  // each face's low 32 bits, which pick its slot. No allocation per face.
  struct Slot {
    std::uint32_t tag = 0;
    int face = -1;
  };
  void grow();

  PolyhedronSoup soup_;
  std::vector<Slot> table_ = std::vector<Slot>(1024);
  std::vector<std::uint32_t> face_hash_low_;
  std::vector<int> cell_, key_, other_, ordered_;
  int last_face_ = -1;
};

}  // namespace polydec
