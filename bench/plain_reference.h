// bench/plain_reference.h — calls into ../shared/bench/plain_reference.cpp, the plain baseline
// in the style of the authors' code, compiled unchanged into the benchmark (its main renamed).
#pragma once

#include <Eigen/Core>
#include <Eigen/Sparse>
#include <memory>
#include <vector>

namespace plain_reference {

struct Input;  // the baseline's own mesh type, built once outside the timed region

std::shared_ptr<const Input> make_input(const Eigen::MatrixX3d& positions, const std::vector<int>& face_offsets,
                                        const std::vector<int>& face_indices);

// The baseline's build(): S and unlumped M through triplets.
void build(const Input& input, Eigen::SparseMatrix<double>& S, Eigen::SparseMatrix<double>& M);

}  // namespace plain_reference
