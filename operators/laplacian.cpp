// operators/laplacian.cpp — face-by-face assembly of S, M and lumped M into a precomputed pattern.
#include "operators/laplacian.h"

#include <algorithm>

#include "operators/local_matrices.h"

namespace polydec {

FacePattern face_pattern(const Mesh& mesh) {
  const int nv = mesh.n_vertices(), nf = mesh.n_faces();
  FacePattern fp;
  // Column j holds the rows of all vertices sharing a face with j: gather, sort, unique.
  std::vector<int> col_start(nv + 1, 0);
  for (int v = 0; v < nv; ++v)
    for (int f : mesh.vertex_faces(v)) col_start[v + 1] += mesh.face_size(f);
  for (int v = 0; v < nv; ++v) col_start[v + 1] += col_start[v];
  std::vector<int> rows(col_start[nv]);
  std::vector<int> outer(nv + 1, 0);
  long nnz = 0;
  for (int v = 0; v < nv; ++v) {
    int* b = rows.data() + col_start[v];
    int* e = b;
    for (int f : mesh.vertex_faces(v))
      for (int u : mesh.face(f)) *e++ = u;
    std::sort(b, e);
    e = std::unique(b, e);
    std::copy(b, e, rows.data() + nnz);
    nnz += e - b;
    outer[v + 1] = int(nnz);
  }
  fp.pattern.resize(nv, nv);
  fp.pattern.resizeNonZeros(nnz);
  std::copy(outer.begin(), outer.end(), fp.pattern.outerIndexPtr());
  std::copy(rows.begin(), rows.begin() + nnz, fp.pattern.innerIndexPtr());
  std::fill(fp.pattern.valuePtr(), fp.pattern.valuePtr() + nnz, 0.0);

  fp.local_offsets.resize(nf + 1, 0);
  for (int f = 0; f < nf; ++f)
    fp.local_offsets[f + 1] = fp.local_offsets[f] + long(mesh.face_size(f)) * mesh.face_size(f);
  fp.slots.resize(fp.local_offsets[nf]);
  const int* inner = fp.pattern.innerIndexPtr();
  for (int f = 0; f < nf; ++f) {
    const auto face = mesh.face(f);
    const int n = int(face.size());
    for (int b = 0; b < n; ++b) {
      const int col = face[b];
      const int* cb = inner + outer[col];
      const int* ce = inner + outer[col + 1];
      for (int a = 0; a < n; ++a)
        fp.slots[fp.local_offsets[f] + a * n + b] = int(std::lower_bound(cb, ce, face[a]) - inner);
    }
  }
  return fp;
}

Laplacian assemble_laplacian(const Mesh& mesh, const Refinement& refinement, LaplacianParts parts,
                             const FacePattern* pattern) {
  FacePattern own;
  if (!pattern) {
    own = face_pattern(mesh);
    pattern = &own;
  }
  Laplacian L;
  L.quality = refinement.quality;
  const bool want_mass = parts.mass || parts.lumped_mass;
  if (parts.stiffness) L.S = pattern->pattern;
  SparseMatrix M = pattern->pattern;
  double* sv = parts.stiffness ? L.S.valuePtr() : nullptr;
  double* mv = M.valuePtr();
  Eigen::MatrixXd Sl, Ml;
  for (int f = 0; f < mesh.n_faces(); ++f) {
    const PolygonPositions X = face_positions(mesh, f);
    const int n = int(X.rows()), h0 = mesh.face_offsets()[f];
    const Eigen::Map<const Eigen::VectorXd> w(refinement.weights.data() + h0, n);
    const Eigen::Vector3d xf = refinement.virtual_points.row(f).transpose();
    polygon_matrices(X, w, xf, refinement.fan.data() + h0, sv ? &Sl : nullptr, want_mass ? &Ml : nullptr);
    const int* slot = pattern->slots.data() + pattern->local_offsets[f];
    for (int a = 0; a < n; ++a)
      for (int b = 0; b < n; ++b) {
        if (sv) sv[slot[a * n + b]] += Sl(a, b);
        if (want_mass) mv[slot[a * n + b]] += Ml(a, b);
      }
  }
  if (parts.lumped_mass) {
    L.M_lumped = Eigen::VectorXd::Zero(mesh.n_vertices());
    for (int j = 0; j < M.outerSize(); ++j)
      for (SparseMatrix::InnerIterator it(M, j); it; ++it) L.M_lumped[it.row()] += it.value();
  }
  if (parts.mass) L.M = std::move(M);
  return L;
}

SparseMatrix stiffness(const Mesh& mesh, const Refinement& refinement) {
  return assemble_laplacian(mesh, refinement, {true, false, false}).S;
}

SparseMatrix mass(const Mesh& mesh, const Refinement& refinement) {
  return assemble_laplacian(mesh, refinement, {false, true, false}).M;
}

Eigen::VectorXd lumped_mass(const Mesh& mesh, const Refinement& refinement) {
  return assemble_laplacian(mesh, refinement, {false, false, true}).M_lumped;
}

}  // namespace polydec
