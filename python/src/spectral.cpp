// python/src/spectral.cpp — bindings of the spectral tools: eigenpairs of the Hodge Laplacian on
// Whitney 1- and 2-forms (apps/applications/form_spectrum.h) and on volume 1-, 2- and 3-forms
// (apps/applications/volume/spectrum.h), and the kernel signatures, spectral
// distances and low-pass filter computed from 0-form eigenpairs (apps/applications/spectral_tools.h),
// which take (eigenvalues, eigenvectors) as `spectrum` or `volume_spectrum` return them.
#include "bindings.h"
#include "polydec/apps/applications/form_spectrum.h"
#include "polydec/apps/applications/spectral_tools.h"
#include "polydec/apps/applications/volume/spectrum.h"

namespace polydec::python {
namespace {

// A Spectrum of the given eigenpairs (copied with the GIL held): k eigenvalues, |V| x k eigenvectors.
Spectrum spectrum_of(const Eigen::VectorXd& evals, const Eigen::MatrixXd& evecs) {
  if (evals.size() < 1 || evecs.cols() != evals.size())
    throw std::invalid_argument("eigenvectors must have one column per eigenvalue (at least one)");
  if (!evals.allFinite() || !evecs.allFinite()) throw std::invalid_argument("eigenpairs must be finite");
  for (Eigen::Index i = 1; i < evals.size(); ++i)
    if (evals[i] < evals[i - 1]) throw std::invalid_argument("eigenvalues must be in ascending order");
  if (!(evals[evals.size() - 1] > 0)) throw std::invalid_argument("the largest eigenvalue must be positive");
  Spectrum s;
  s.eigenvalues = evals;
  s.eigenvectors = evecs;
  return s;
}

// The dict form_spectrum returns (with the GIL held).
py::dict form_spectrum_dict(const FormSpectrum& s, bool decompose) {
  py::dict d;
  d["eigenvalues"] = s.eigenvalues;
  d["eigenvectors"] = s.eigenvectors;
  if (decompose) {
    d["exact"] = s.exact;
    d["coexact"] = s.coexact;
    d["harmonic"] = s.harmonic;
    d["norm_exact"] = s.norm_exact;
    d["norm_coexact"] = s.norm_coexact;
    d["norm_harmonic"] = s.norm_harmonic;
    py::list kinds;
    for (FormKind kind : s.kinds) kinds.append(form_kind_name(kind));
    d["kinds"] = kinds;
  }
  d["rank"] = s.rank;
  d["shift"] = s.shift;
  d["n_converged"] = s.n_converged;
  d["n_solves"] = s.n_solves;
  d["method"] = s.method;
  d["degenerate_fan_triangles"] = s.quality.n_degenerate;
  return d;
}

// The options of form_spectrum and volume_form_spectrum from the Python arguments (with the GIL held:
// parse_dec_complex may throw).
FormSpectrumOptions form_spectrum_options(int degree, int k, bool lumped_mass, double tolerance, int max_iterations,
                                          bool decompose, const std::string& complex) {
  FormSpectrumOptions options;
  options.complex = parse_dec_complex(complex);
  options.degree = degree;
  options.k = k;
  options.lumped_mass = lumped_mass;
  options.tolerance = tolerance;
  options.max_iterations = max_iterations;
  options.decompose = decompose;
  return options;
}

}  // namespace

void register_spectral(py::module_& m) {
  m.def("form_spectrum", [](const MeshHandle& h, int degree,
                            int k, bool lumped_mass, double tolerance, int max_iterations, bool decompose,
                            const std::string& complex, double planarity) {
    const Mesh mesh = h.with_planarity(planarity);
    const FormSpectrumOptions options =
        form_spectrum_options(degree, k, lumped_mass, tolerance, max_iterations, decompose, complex);
    FormSpectrum s;
    {
      py::gil_scoped_release release;
      s = form_spectrum(mesh, options);
    }
    return form_spectrum_dict(s, decompose);
  });
  m.def("volume_form_spectrum", [](const VolumeMesh& mesh, int degree, int k, bool lumped_mass, double tolerance,
                                   int max_iterations, bool decompose, const std::string& complex) {
    const FormSpectrumOptions options =
        form_spectrum_options(degree, k, lumped_mass, tolerance, max_iterations, decompose, complex);
    FormSpectrum s;
    {
      py::gil_scoped_release release;
      s = volume_form_spectrum(mesh, options);
    }
    return form_spectrum_dict(s, decompose);
  });

  m.def("hks_times", [](const Eigen::VectorXd& evals, const Eigen::MatrixXd& evecs, int n) {
    return hks_times(spectrum_of(evals, evecs), n);
  });
  m.def("heat_kernel_signature",
        [](const Eigen::VectorXd& evals, const Eigen::MatrixXd& evecs, const Eigen::VectorXd& times) {
          const Spectrum s = spectrum_of(evals, evecs);
          if (!times.allFinite() || (times.array() < 0).any())
            throw std::invalid_argument("times must be finite and non-negative");
          py::gil_scoped_release release;
          return heat_kernel_signature(s, times);
        });
  m.def("wks_samples", [](const Eigen::VectorXd& evals, const Eigen::MatrixXd& evecs, int n) {
    const WksSamples w = wks_samples(spectrum_of(evals, evecs), n);
    return py::make_tuple(w.energies, w.sigma);
  });
  m.def("wave_kernel_signature", [](const Eigen::VectorXd& evals, const Eigen::MatrixXd& evecs,
                                    const Eigen::VectorXd& energies, double sigma) {
    const Spectrum s = spectrum_of(evals, evecs);
    if (!energies.allFinite() || !(sigma > 0) || !std::isfinite(sigma))
      throw std::invalid_argument("energies must be finite and sigma positive");
    py::gil_scoped_release release;
    return wave_kernel_signature(s, energies, sigma);
  });
  m.def("biharmonic_distance",
        [](const Eigen::VectorXd& evals, const Eigen::MatrixXd& evecs, int source, int k) {
          const Spectrum s = spectrum_of(evals, evecs);
          py::gil_scoped_release release;
          return biharmonic_distance(s, source, k);
        });
  m.def("diffusion_distance",
        [](const Eigen::VectorXd& evals, const Eigen::MatrixXd& evecs, double t, int source, int k) {
          const Spectrum s = spectrum_of(evals, evecs);
          py::gil_scoped_release release;
          return diffusion_distance(s, t, source, k);
        });
  m.def("lowpass_filter", [](const Eigen::VectorXd& evals, const Eigen::MatrixXd& evecs,
                             const Eigen::VectorXd& lumped_mass, const Eigen::MatrixX3d& X, int k) {
    const Spectrum s = spectrum_of(evals, evecs);
    py::gil_scoped_release release;
    return Eigen::MatrixX3d(lowpass_filter(s, lumped_mass, X, k));
  });
}

}  // namespace polydec::python
