// examples/eigenpairs/main.cpp — the K smallest eigenpairs of -S x = lambda M x (lumped M) with the
// paper's Laplacian: eigenpairs MESH K OUT.txt. OUT.txt holds one line per eigenpair: the
// eigenvalue, then the eigenvector's |V| values (M-orthonormal). Without a mesh file ("-") a
// generated hexagon sphere of radius 1 is used, whose eigenvalues approach l(l+1).
#include <polydec/apps/applications/spectrum.h>
#include <polydec/dec/mesh/generators.h>
#include <polydec/dec/io/mesh_io.h>

#include <cstdio>
#include <exception>
#include <fstream>
#include <string>

using namespace polydec;

int main(int argc, char** argv) try {
  if (argc < 4) {
    std::fprintf(stderr, "usage: eigenpairs MESH|- K OUT.txt\n");
    return 2;
  }
  const Mesh mesh = std::string(argv[1]) == "-" ? project_to_unit_sphere(hex_sphere(3)) : read_mesh(argv[1]);
  SpectrumOptions options;
  options.k = std::stoi(argv[2]);
  const Spectrum s = laplacian_spectrum(mesh, options);
  std::ofstream out(argv[3]);
  out.precision(17);
  for (int j = 0; j < s.eigenvalues.size(); ++j) {
    out << s.eigenvalues[j];
    for (int i = 0; i < s.eigenvectors.rows(); ++i) out << ' ' << s.eigenvectors(i, j);
    out << '\n';
  }
  if (!out) throw std::runtime_error(std::string("cannot write ") + argv[3]);
  std::printf("%d eigenpairs (%s), lambda_1..%d =", int(s.eigenvalues.size()), s.method.c_str(),
              int(s.eigenvalues.size()));
  for (int j = 0; j < s.eigenvalues.size(); ++j) std::printf(" %.6g", s.eigenvalues[j]);
  std::printf("\nwrote %s\n", argv[3]);
  return 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "eigenpairs: %s\n", e.what());
  return 1;
}
