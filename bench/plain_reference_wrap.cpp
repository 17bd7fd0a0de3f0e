// bench/plain_reference_wrap.cpp — the only translation unit that sees plain_reference.cpp
// (compiled with -Dmain=plain_reference_main); exposes its build() to the benchmark.
#include "plain_reference.cpp"

#include "bench/plain_reference.h"

namespace plain_reference {

struct Input {
  ::Mesh mesh;
};

std::shared_ptr<const Input> make_input(const Eigen::MatrixX3d& positions, const std::vector<int>& face_offsets,
                                        const std::vector<int>& face_indices) {
  auto in = std::make_shared<Input>();
  for (Eigen::Index v = 0; v < positions.rows(); ++v) in->mesh.V.push_back(positions.row(v).transpose());
  for (size_t f = 0; f + 1 < face_offsets.size(); ++f)
    in->mesh.F.emplace_back(face_indices.begin() + face_offsets[f], face_indices.begin() + face_offsets[f + 1]);
  return in;
}

void build(const Input& input, Eigen::SparseMatrix<double>& S, Eigen::SparseMatrix<double>& M) {
  Ops o = ::build(input.mesh);
  S.swap(o.S);  // Eigen 3.4's SparseMatrix has no move assignment: swap, not copy
  M.swap(o.M);
}

}  // namespace plain_reference
