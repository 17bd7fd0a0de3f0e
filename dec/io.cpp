// dec/io.cpp — mesh and matrix file formats (first version: OBJ and ASCII OFF readers,
// OBJ/OFF/PLY-ascii writers, Matrix Market).
#include "dec/io.h"

#include <algorithm>
#include <cstdio>
#include <fmt/format.h>
#include <fstream>
#include <sstream>

namespace polydec {

FileError::FileError(std::string file_, long line_, long byte_offset_, std::string reason_)
    : std::runtime_error(line_ > 0 ? fmt::format("{}:{}: {}", file_, line_, reason_)
                         : byte_offset_ >= 0 ? fmt::format("{}: byte {}: {}", file_, byte_offset_, reason_)
                                             : fmt::format("{}: {}", file_, reason_)),
      file(std::move(file_)),
      line(line_),
      byte_offset(byte_offset_),
      reason(std::move(reason_)) {}

namespace {

std::string extension(const std::string& path) {
  const auto dot = path.find_last_of('.');
  if (dot == std::string::npos) return "";
  std::string e = path.substr(dot + 1);
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return e;
}

PolygonSoup read_obj(const std::string& path, std::istream& in) {
  PolygonSoup soup;
  std::vector<Eigen::RowVector3d> pos;
  std::string line;
  long lineno = 0;
  std::vector<int> face;
  while (std::getline(in, line)) {
    ++lineno;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::istringstream ss(line);
    std::string tag;
    ss >> tag;
    if (tag == "v") {
      Eigen::RowVector3d p;
      if (!(ss >> p[0] >> p[1] >> p[2])) throw FileError(path, lineno, 0, "vertex needs three coordinates");
      pos.push_back(p);
    } else if (tag == "f") {
      face.clear();
      std::string c;
      while (ss >> c) {
        long i = 0;
        try {
          i = std::stol(c.substr(0, c.find('/')));
        } catch (...) {
          throw FileError(path, lineno, -1, "bad face index '" + c + "'");
        }
        if (i == 0) throw FileError(path, lineno, -1, "face index 0 (OBJ indices start at 1)");
        const long idx = i > 0 ? i - 1 : long(pos.size()) + i;
        if (idx < 0 || idx >= long(pos.size()))
          throw FileError(path, lineno, -1, fmt::format("face index {} out of range", i));
        face.push_back(int(idx));
      }
      soup.add_face(face);
    }
  }
  soup.positions.resize(pos.size(), 3);
  for (size_t i = 0; i < pos.size(); ++i) soup.positions.row(i) = pos[i];
  return soup;
}

PolygonSoup read_off(const std::string& path, std::istream& in) {
  std::vector<std::pair<std::string, long>> toks;
  std::string line;
  long lineno = 0;
  while (std::getline(in, line)) {
    ++lineno;
    const auto h = line.find('#');
    if (h != std::string::npos) line.resize(h);
    std::istringstream ss(line);
    std::string t;
    while (ss >> t) toks.emplace_back(t, lineno);
  }
  size_t p = 0;
  auto next = [&]() -> const std::pair<std::string, long>& {
    if (p >= toks.size()) throw FileError(path, lineno, -1, "unexpected end of file");
    return toks[p++];
  };
  const auto& head = next();
  if (head.first != "OFF") throw FileError(path, head.second, -1, "expected 'OFF' header");
  const long nv = std::stol(next().first), nf = std::stol(next().first);
  next();
  if (nv < 0 || nf < 0) throw FileError(path, head.second, -1, "negative counts");
  PolygonSoup soup;
  soup.positions.resize(std::min<long>(nv, long(toks.size())), 3);
  for (long i = 0; i < nv; ++i)
    for (int c = 0; c < 3; ++c) soup.positions(i, c) = std::stod(next().first);
  std::vector<int> face;
  for (long i = 0; i < nf; ++i) {
    const long n = std::stol(next().first);
    face.clear();
    for (long k = 0; k < n; ++k) face.push_back(std::stoi(next().first));
    soup.add_face(face);
  }
  return soup;
}

std::string num(double x) { return fmt::format("{:.17g}", x); }

}  // namespace

PolygonSoup read_polygon_soup(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw FileError(path, 0, -1, "cannot open file");
  const std::string ext = extension(path);
  if (ext == "obj") return read_obj(path, in);
  if (ext == "off") return read_off(path, in);
  throw FileError(path, 0, -1, "unknown mesh format '." + ext + "' (obj, off, ply)");
}

Mesh read_mesh(const std::string& path) {
  PolygonSoup soup = read_polygon_soup(path);
  try {
    return Mesh(std::move(soup));
  } catch (const InvalidMeshError& e) {
    throw FileError(path, 0, -1, e.what());
  }
}

void write_mesh(const std::string& path, const Mesh& mesh, const VertexScalars& scalars) {
  std::ofstream out(path);
  if (!out) throw FileError(path, 0, -1, "cannot open file for writing");
  const std::string ext = extension(path);
  const auto& X = mesh.positions();
  if (ext == "obj") {
    for (int v = 0; v < mesh.n_vertices(); ++v) out << "v " << num(X(v, 0)) << ' ' << num(X(v, 1)) << ' ' << num(X(v, 2)) << '\n';
    for (int f = 0; f < mesh.n_faces(); ++f) {
      out << 'f';
      for (int v : mesh.face(f)) out << ' ' << v + 1;
      out << '\n';
    }
  } else if (ext == "off") {
    out << "OFF\n" << mesh.n_vertices() << ' ' << mesh.n_faces() << " 0\n";
    for (int v = 0; v < mesh.n_vertices(); ++v) out << num(X(v, 0)) << ' ' << num(X(v, 1)) << ' ' << num(X(v, 2)) << '\n';
    for (int f = 0; f < mesh.n_faces(); ++f) {
      out << mesh.face_size(f);
      for (int v : mesh.face(f)) out << ' ' << v;
      out << '\n';
    }
  } else if (ext == "ply") {
    out << "ply\nformat ascii 1.0\nelement vertex " << mesh.n_vertices() << "\nproperty double x\nproperty double y\nproperty double z\n";
    for (const auto& [name, values] : scalars) out << "property double " << name << '\n';
    out << "element face " << mesh.n_faces() << "\nproperty list uchar int vertex_indices\nend_header\n";
    for (int v = 0; v < mesh.n_vertices(); ++v) {
      out << num(X(v, 0)) << ' ' << num(X(v, 1)) << ' ' << num(X(v, 2));
      for (const auto& [name, values] : scalars) out << ' ' << num(values[v]);
      out << '\n';
    }
    for (int f = 0; f < mesh.n_faces(); ++f) {
      out << mesh.face_size(f);
      for (int v : mesh.face(f)) out << ' ' << v;
      out << '\n';
    }
  } else {
    throw FileError(path, 0, -1, "unknown mesh format '." + ext + "' (obj, off, ply)");
  }
  if (!out) throw FileError(path, 0, -1, "write failed");
}

void write_matrix_market(const std::string& path, const Eigen::SparseMatrix<double>& A) {
  std::ofstream out(path);
  if (!out) throw FileError(path, 0, -1, "cannot open file for writing");
  out << "%%MatrixMarket matrix coordinate real general\n" << A.rows() << ' ' << A.cols() << ' ' << A.nonZeros() << '\n';
  for (int j = 0; j < A.outerSize(); ++j)
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, j); it; ++it)
      out << it.row() + 1 << ' ' << it.col() + 1 << ' ' << num(it.value()) << '\n';
  if (!out) throw FileError(path, 0, -1, "write failed");
}

Eigen::SparseMatrix<double> read_matrix_market(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw FileError(path, 0, -1, "cannot open file");
  std::string line;
  long lineno = 0;
  bool symmetric = false;
  while (std::getline(in, line)) {
    ++lineno;
    if (lineno == 1) symmetric = line.find("symmetric") != std::string::npos;
    if (!line.empty() && line[0] != '%') break;
  }
  std::istringstream hs(line);
  long r = 0, c = 0, nnz = 0;
  if (!(hs >> r >> c >> nnz) || r < 0 || c < 0 || nnz < 0) throw FileError(path, lineno, -1, "bad size line");
  std::vector<Eigen::Triplet<double>> t;
  for (long k = 0; k < nnz; ++k) {
    long i, j;
    double v;
    if (!(in >> i >> j >> v)) throw FileError(path, lineno + k + 1, -1, "bad or missing entry");
    if (i < 1 || i > r || j < 1 || j > c) throw FileError(path, lineno + k + 1, -1, "entry out of range");
    t.emplace_back(int(i - 1), int(j - 1), v);
    if (symmetric && i != j) t.emplace_back(int(j - 1), int(i - 1), v);
  }
  Eigen::SparseMatrix<double> A(r, c);
  A.setFromTriplets(t.begin(), t.end());
  return A;
}

}  // namespace polydec
