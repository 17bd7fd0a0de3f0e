// examples/geodesics/main.cpp — heat-method geodesic distances (paper section 5.5) from several
// sources: geodesics MESH OUT.ply SOURCE [SOURCE ...]. The solver factors once; each distance()
// call is two back-substitutions. Writes the distance to the nearest source as a PLY vertex
// property and prints the farthest vertex.
#include <polydec/apps/applications/geodesics.h>
#include <polydec/dec/io/mesh_io.h>

#include <cstdio>
#include <exception>
#include <string>
#include <vector>

using namespace polydec;

int main(int argc, char** argv) try {
  if (argc < 4) {
    std::fprintf(stderr, "usage: geodesics MESH OUT.ply SOURCE [SOURCE ...]\n");
    return 2;
  }
  const Mesh mesh = read_mesh(argv[1]);
  std::vector<int> sources;
  for (int a = 3; a < argc; ++a) sources.push_back(std::stoi(argv[a]));
  const HeatGeodesics heat(mesh);  // factors M - t S and -S once
  const Eigen::VectorXd d = heat.distance(sources);
  Eigen::Index far = 0;
  d.maxCoeff(&far);
  write_mesh(argv[2], mesh, {{"distance", d}});
  std::printf("%d vertices, %zu sources, farthest vertex %ld at distance %.6g; wrote %s\n", mesh.n_vertices(),
              sources.size(), long(far), d[far], argv[2]);
  return 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "geodesics: %s\n", e.what());
  return 1;
}
