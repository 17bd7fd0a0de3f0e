// dec/io/matrix_market.cpp — Matrix Market files: written as coordinate "real general", 1-based
// (sparse matrices) or array "real general" (dense ones), 17 significant digits; read in either
// format, real or integer, general, symmetric or skew-symmetric.
#include <climits>
#include <filesystem>
#include <fstream>

#include "polydec/dec/detail/io_common.h"

namespace polydec {

using namespace io_detail;

namespace {

// The values of an array-format file after its size line: column by column, all r x c of them
// (general) or the lower triangle with the diagonal (symmetric; skew-symmetric: strictly lower).
// Zeros are not stored in the sparse result.
Eigen::SparseMatrix<double> read_array_values(LineReader& lines, const std::string& name, long long r,
                                              long long c, double mirror) {
  const bool strict = mirror < 0;
  // In 128 bits: r and c may each be near their limit in a hostile file.
  const __int128 wide = mirror == 0.0 ? (__int128)r * c
                        : strict      ? (__int128)c * (c - 1) / 2
                                      : (__int128)c * (c + 1) / 2;
  if (wide > (__int128)(lines.remaining() + 1) / 2)
    throw FileError(name, lines.line(), -1,
                    fmt::format("claims a {} x {} array but only {} bytes follow", r, c, lines.remaining()));
  const long long count = (long long)wide;
  std::vector<Eigen::Triplet<double>> t;
  std::string_view line;
  std::vector<std::string_view> tok;
  long long read = 0;
  for (long long j = 0; j < c; ++j) {
    for (long long i = mirror == 0.0 ? 0 : strict ? j + 1 : j; i < r; ++i, ++read) {
      do {
        if (!lines.next(line))
          throw FileError(name, lines.line(), -1,
                          fmt::format("unexpected end of file after {} of {} values", read, count));
        split(line, tok);
      } while (tok.empty() || tok[0][0] == '%');
      double v;
      if (tok.size() != 1 || !parse_double(tok[0], v))
        throw FileError(name, lines.line(), -1, "expected one VALUE per line");
      if (v == 0.0) continue;
      t.emplace_back(int(i), int(j), v);
      if (mirror != 0.0 && i != j) t.emplace_back(int(j), int(i), mirror * v);
    }
  }
  Eigen::SparseMatrix<double> A(r, c);
  A.setFromTriplets(t.begin(), t.end());
  return A;
}

}  // namespace

void write_matrix_market(const std::string& path, const Eigen::SparseMatrix<double>& A) {
  fmt::memory_buffer b;
  auto out = std::back_inserter(b);
  fmt::format_to(out, "%%MatrixMarket matrix coordinate real general\n{} {} {}\n", A.rows(), A.cols(),
                 A.nonZeros());
  for (int j = 0; j < A.outerSize(); ++j)
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, j); it; ++it)
      fmt::format_to(out, "{} {} {:.17g}\n", it.row() + 1, it.col() + 1, it.value());
  std::ofstream f(path, std::ios::binary);
  if (!f) throw FileError(path, 0, -1, "cannot open file for writing");
  f.write(b.data(), std::streamsize(b.size()));
  f.close();
  if (!f) throw FileError(path, 0, -1, "write failed");
}

void write_dense_matrix_market(const std::string& path, const Eigen::MatrixXd& A) {
  fmt::memory_buffer b;
  auto out = std::back_inserter(b);
  fmt::format_to(out, "%%MatrixMarket matrix array real general\n{} {}\n", A.rows(), A.cols());
  for (Eigen::Index j = 0; j < A.cols(); ++j)
    for (Eigen::Index i = 0; i < A.rows(); ++i) fmt::format_to(out, "{:.17g}\n", A(i, j));
  std::ofstream f(path, std::ios::binary);
  if (!f) throw FileError(path, 0, -1, "cannot open file for writing");
  f.write(b.data(), std::streamsize(b.size()));
  f.close();
  if (!f) throw FileError(path, 0, -1, "write failed");
}

Eigen::SparseMatrix<double> read_matrix_market_from_memory(std::string_view bytes, const std::string& name) {
  LineReader lines(strip_bom(bytes));
  std::string_view line;
  std::vector<std::string_view> tok;
  if (!lines.next(line)) throw FileError(name, 0, -1, "empty file (no %%MatrixMarket header)");
  split(line, tok);
  if (tok.size() != 5 || tok[0] != "%%MatrixMarket" || lower(tok[1]) != "matrix")
    throw FileError(name, 1, -1, "expected '%%MatrixMarket matrix coordinate|array FIELD SYMMETRY'");
  const std::string format = lower(tok[2]);
  if (format != "coordinate" && format != "array")
    throw FileError(name, 1, -1, "format " + quote(tok[2]) + " not supported (coordinate or array)");
  const std::string field = lower(tok[3]), symmetry = lower(tok[4]);
  if (field != "real" && field != "integer" && field != "double")
    throw FileError(name, 1, -1, "field " + quote(tok[3]) + " not supported (real or integer)");
  if (symmetry != "general" && symmetry != "symmetric" && symmetry != "skew-symmetric")
    throw FileError(name, 1, -1,
                    "symmetry " + quote(tok[4]) + " not supported (general, symmetric, skew-symmetric)");
  const double mirror = symmetry == "general" ? 0.0 : symmetry == "symmetric" ? 1.0 : -1.0;

  auto next_data = [&]() {
    while (lines.next(line)) {
      split(line, tok);
      if (!tok.empty() && tok[0][0] != '%') return true;
    }
    return false;
  };
  if (!next_data()) throw FileError(name, lines.line(), -1, "no size line");
  const bool array = format == "array";
  long long r, c, nnz = 0;
  if (array) {
    if (tok.size() != 2 || !parse_int(tok[0], r) || !parse_int(tok[1], c) || r < 0 || c < 0)
      throw FileError(name, lines.line(), -1, "expected 'ROWS COLS', two non-negative integers");
  } else if (tok.size() != 3 || !parse_int(tok[0], r) || !parse_int(tok[1], c) || !parse_int(tok[2], nnz) ||
             r < 0 || c < 0 || nnz < 0) {
    throw FileError(name, lines.line(), -1, "expected 'ROWS COLS ENTRIES', three non-negative integers");
  }
  if (r > INT_MAX || c > INT_MAX) throw FileError(name, lines.line(), -1, "matrix too large");
  // Assembly stores one index per row and per column (setFromTriplets goes through the transposed
  // storage): a few bytes must not claim gigabytes.
  const long long max_dimension = (long long)bytes.size() * 64 + (1 << 20);
  if (r > max_dimension || c > max_dimension)
    throw FileError(
        name, lines.line(), -1,
        fmt::format("claims a {} x {} matrix in a file of {} bytes (at most 64 rows or columns per "
                    "byte plus 2^20)",
                    r, c, bytes.size()));
  if (mirror != 0.0 && r != c)
    throw FileError(name, lines.line(), -1,
                    fmt::format("{} matrix must be square, is {} x {}", symmetry, r, c));
  if (array) return read_array_values(lines, name, r, c, mirror);
  if (nnz > (long long)(lines.remaining() + 1) / 6)
    throw FileError(name, lines.line(), -1,
                    fmt::format("claims {} entries but only {} bytes follow", nnz, lines.remaining()));
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(size_t(nnz) * (mirror != 0.0 ? 2 : 1));
  for (long long k = 0; k < nnz; ++k) {
    if (!next_data())
      throw FileError(name, lines.line(), -1,
                      fmt::format("unexpected end of file after {} of {} entries", k, nnz));
    long long i, j;
    double v;
    if (tok.size() != 3 || !parse_int(tok[0], i) || !parse_int(tok[1], j) || !parse_double(tok[2], v))
      throw FileError(name, lines.line(), -1, "expected 'ROW COL VALUE'");
    if (i < 1 || i > r || j < 1 || j > c)
      throw FileError(name, lines.line(), -1,
                      fmt::format("entry ({}, {}) outside the {} x {} matrix", i, j, r, c));
    t.emplace_back(int(i - 1), int(j - 1), v);
    if (mirror != 0.0 && i != j) t.emplace_back(int(j - 1), int(i - 1), mirror * v);
  }
  Eigen::SparseMatrix<double> A(r, c);
  A.setFromTriplets(t.begin(), t.end());
  return A;
}

Eigen::SparseMatrix<double> read_matrix_market(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw FileError(path, 0, -1, "is a directory, not a file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw FileError(path, 0, -1, "cannot open file");
  std::string data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return read_matrix_market_from_memory(data, path);
}

}  // namespace polydec
