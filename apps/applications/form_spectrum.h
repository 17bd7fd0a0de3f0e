// apps/applications/form_spectrum.h — eigenpairs of the Hodge Laplacian on Whitney 1-forms and
// 2-forms of a polygon mesh (FEEC mixed form; docs/spectral.md), by Spectra's shift-invert
// Lanczos.
//
// 1-forms: K1 w = lambda star1 w with K1 = d1^T star2 d1 + star1 d0 M0^-1 d0^T star1, M0 the
//   0-form mass: the lumped star0 by default, or the Galerkin star0 (lumped_mass = false).
// 2-forms: K2 u = lambda star2 u with K2 = star2 d1 star1^+ d1^T star2 (star1^+ on the span of
//   the Whitney 1-forms, operators/solvers/span_solver.h).
// Both are posed on the reduced basis of dec/surface/form_span.h (w = R y), so that the mass R^T star R
// is positive definite. The shift-inverted operator (K - sigma B)^-1 is applied without forming
// K (M0^-1 and star1^-1 make it dense-ish): the symmetric quasi-definite system
//   1-forms: [R1^T d1^T star2 d1 R1 - sigma B1,  R1^T star1 d0;  d0^T star1 R1,  -M0]
//   2-forms: [-sigma B2,  R2^T star2 d1 R1;  R1^T d1^T star2 R2,  -R1^T star1 R1]
// (sigma < 0) is factored once by sparse LDL^T (Eigen's SimplicialLDLT with AMD: a quasi-definite
// matrix has an LDL^T factorization in every symmetric ordering, Vanderbei 1995; CHOLMOD's
// supernodal LL^T does not apply). Its Schur complement on the first block is K - sigma B.
//
// Conventions: eigenvalues ascending, lambda >= 0; eigenvectors are coarse k-cochains (values on
// CoarseComplex::pairs() or triples()) supported on the span cells, star-orthonormal
// (W^T star W = I). On the mesh complex (options.complex, dec/surface/mesh_complex.h) the stars are
// positive definite, R is the identity and the cochains live on the mesh's edges or faces. Scaling the mesh by s scales lambda by 1/s^2.
// Each eigenform is split by the Hodge decomposition: 1-forms by HodgeDecomposer
// (exact d0 alpha, co-exact, harmonic; star1 norms); 2-forms into exact d1 (delta u / lambda)
// and the rest, harmonic (for lambda = 0 the whole form is harmonic).
#pragma once

#include <Eigen/Dense>
#include <string>
#include <vector>

#include "polydec/dec/mesh/mesh.h"
#include "polydec/dec/surface/mesh_complex.h"
#include "polydec/dec/surface/refinement.h"

namespace polydec {

struct FormSpectrumOptions {
  int degree = 1;             // 1 or 2
  int k = 10;                 // eigenpairs, 1 <= k < rank of the Whitney forms
  bool lumped_mass = true;    // M0 in K1: lumped star0 (default) or Galerkin star0
  double shift_factor = 0.1;  // sigma = -shift_factor / (surface area)
  double tolerance = 1e-10;   // Spectra's relative convergence tolerance
  int max_iterations = 1000;  // restarts
  int krylov_size = 0;        // 0: spectrum_krylov_size(k, rank) (apps/applications/spectrum.h)
  bool decompose = true;      // compute the Hodge parts of every eigenform
  DecComplex complex = DecComplex::Complete;  // the paper's cells, or the mesh's edges and faces
  RefinementOptions refinement;
};

enum class FormKind { Exact, Coexact, Harmonic };
// "exact", "co-exact", "harmonic".
const char* form_kind_name(FormKind kind);

struct FormSpectrum {
  int degree = 1;
  Eigen::VectorXd eigenvalues;   // k, ascending
  Eigen::MatrixXd eigenvectors;  // |C_degree| x k, star-orthonormal coarse cochains
  // Hodge parts (|C_degree| x k each, summing to the eigenvectors; 2-forms: coexact is zero) and
  // their star norms, k each. Empty unless options.decompose.
  Eigen::MatrixXd exact, coexact, harmonic;
  Eigen::VectorXd norm_exact, norm_coexact, norm_harmonic;
  std::vector<FormKind> kinds;  // the part of largest norm
  int rank = 0;                 // dimension of the Whitney forms (reduced basis)
  double shift = 0;
  int n_converged = 0;
  int n_solves = 0;
  std::string method;
  // Fan triangles of the refinement: a degenerate one (zero area) carries no Whitney form, so each
  // can add a zero eigenvalue that is no harmonic form (callers should warn).
  FanQuality quality;
};

// The k smallest eigenpairs of the Hodge Laplacian on Whitney `degree`-forms. Throws
// std::invalid_argument (degree, k), SolverError when the factorization fails or Spectra does
// not converge, InvalidMeshError for an empty mesh.
FormSpectrum form_spectrum(const Mesh& mesh, const FormSpectrumOptions& options = {});

// The tangent vector of Whitney 1-form `cochain` (values on pairs()) at each face's virtual
// vertex: the mean over the face's fan triangles of the Whitney form of the prolonged cochain
// P1 w there (eq. 25), |F| x 3. A Whitney form at the vertex it is opposite to: on fan triangle
// (a, b, v), the vector u in its plane with u . (x_a - x_v) = -(P1 w)_(a v) and likewise for b.
// On the mesh complex the cochain holds values on Mesh::edges() and P1 is mesh_prolongation1.
Eigen::MatrixX3d whitney_vectors_at_virtual_vertices(const Mesh& mesh, const Refinement& refinement,
                                                     const Eigen::VectorXd& cochain,
                                                     DecComplex complex = DecComplex::Complete);

// The density of Whitney 2-form `cochain` (values on triples()) per face: its integral over the
// face's fan triangles (P2 cochain, eq. 26, oriented as the face) divided by their total area, |F|.
// The area cochain of a plane (signed areas of the triples) has density 1 on every face of it.
// On the mesh complex the cochain holds one value per face and P2 is mesh_prolongation2.
Eigen::VectorXd whitney2_face_densities(const Mesh& mesh, const Refinement& refinement,
                                        const Eigen::VectorXd& cochain, DecComplex complex = DecComplex::Complete);

}  // namespace polydec
