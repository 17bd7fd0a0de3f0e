// bench/cholmod_bset_probe.cpp — what CHOLMOD's sparse right-hand side (cholmod_solve2 with Bset)
// gives for a point source: on a supernodal factor of a 5-point grid Laplacian plus a small shift
// (the shape of the heat step's M - t S), it compares the solution on Xset with the dense solve,
// counts the solution's non-zeros outside Xset, reports whether the factor is still supernodal, and
// times both solves. Not part of the build (it checks the library CHOLMOD, not polydec):
//   g++ -O2 -std=c++17 bench/cholmod_bset_probe.cpp -o /tmp/bset_probe -lcholmod
//   OPENBLAS_NUM_THREADS=1 /tmp/bset_probe 310
#include <suitesparse/cholmod.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

namespace {

// Milliseconds per call of f over `repeat` calls.
template <class F>
double ms_per_call(int repeat, F f) {
  const auto t0 = std::chrono::steady_clock::now();
  for (int r = 0; r < repeat; ++r) f();
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count() / repeat;
}

}  // namespace

int main(int argc, char** argv) {
  const int m = argc > 1 ? std::atoi(argv[1]) : 310;  // m x m grid
  const int n = m * m;
  cholmod_common c;
  cholmod_start(&c);
  c.supernodal = CHOLMOD_SUPERNODAL;
  std::vector<int> Ap(n + 1), Ai;  // lower triangle, column by column
  std::vector<double> Ax;
  for (int j = 0; j < n; ++j) {
    Ap[j] = int(Ai.size());
    const int x = j % m, y = j / m;
    Ai.push_back(j), Ax.push_back(4.01);
    if (x + 1 < m) Ai.push_back(j + 1), Ax.push_back(-1);
    if (y + 1 < m) Ai.push_back(j + m), Ax.push_back(-1);
  }
  Ap[n] = int(Ai.size());
  cholmod_sparse A{};
  A.nrow = A.ncol = size_t(n);
  A.nzmax = Ai.size();
  A.p = Ap.data();
  A.i = Ai.data();
  A.x = Ax.data();
  A.stype = -1;
  A.itype = CHOLMOD_INT;
  A.xtype = CHOLMOD_REAL;
  A.dtype = CHOLMOD_DOUBLE;
  A.sorted = 1;
  A.packed = 1;
  cholmod_factor* L = cholmod_analyze(&A, &c);
  cholmod_factorize(&A, L, &c);
  std::printf("n %d, supernodal %d, nnz(L) %.0f\n", n, L->is_super, c.lnz);

  const int source = n / 3 + m / 5;
  cholmod_dense* B = cholmod_zeros(size_t(n), 1, CHOLMOD_REAL, &c);
  static_cast<double*>(B->x)[source] = 1.0;
  cholmod_dense *X = nullptr, *Y = nullptr, *E = nullptr;
  const double dense_ms = ms_per_call(20, [&] { cholmod_solve2(CHOLMOD_A, L, B, nullptr, &X, nullptr, &Y, &E, &c); });
  const std::vector<double> x(static_cast<double*>(X->x), static_cast<double*>(X->x) + n);

  cholmod_sparse* Bset = cholmod_allocate_sparse(size_t(n), 1, 1, 1, 1, 0, CHOLMOD_PATTERN, &c);
  static_cast<int*>(Bset->p)[0] = 0;
  static_cast<int*>(Bset->p)[1] = 1;
  static_cast<int*>(Bset->i)[0] = source;
  cholmod_dense *Xs = nullptr, *Ys = nullptr, *Es = nullptr;
  cholmod_sparse* Xset = nullptr;
  cholmod_solve2(CHOLMOD_A, L, B, Bset, &Xs, &Xset, &Ys, &Es, &c);
  std::printf("after the solve with Bset the factor is supernodal: %d\n", L->is_super);
  const double sparse_ms = ms_per_call(20, [&] { cholmod_solve2(CHOLMOD_A, L, B, Bset, &Xs, &Xset, &Ys, &Es, &c); });
  const double simplicial_ms =
      ms_per_call(20, [&] { cholmod_solve2(CHOLMOD_A, L, B, nullptr, &X, nullptr, &Y, &E, &c); });

  const int n_set = static_cast<int*>(Xset->p)[1];
  std::vector<char> in_set(size_t(n), 0);
  double diff_in = 0, largest = 0, largest_out = 0;
  for (int p = 0; p < n_set; ++p) {
    const int i = static_cast<int*>(Xset->i)[p];
    in_set[size_t(i)] = 1;
    diff_in = std::max(diff_in, std::abs(static_cast<double*>(Xs->x)[i] - x[size_t(i)]));
  }
  int nonzero_out = 0;
  for (int i = 0; i < n; ++i) {
    largest = std::max(largest, std::abs(x[size_t(i)]));
    if (!in_set[size_t(i)] && x[size_t(i)] != 0) ++nonzero_out, largest_out = std::max(largest_out, std::abs(x[size_t(i)]));
  }
  std::printf("Xset: %d of %d entries, max |X - x| there %.3g (max |x| %.3g); x has %d non-zeros outside Xset "
              "(largest %.3g)\n",
              n_set, n, diff_in, largest, nonzero_out, largest_out);
  std::printf("per solve: supernodal %.3f ms; with Bset (simplicial, on Xset only) %.3f ms; the converted "
              "simplicial factor, dense %.3f ms\n",
              dense_ms, sparse_ms, simplicial_ms);
  cholmod_free_sparse(&Bset, &c);
  cholmod_free_sparse(&Xset, &c);
  for (cholmod_dense** d : {&B, &X, &Y, &E, &Xs, &Ys, &Es}) cholmod_free_dense(d, &c);
  cholmod_free_factor(&L, &c);
  cholmod_finish(&c);
}
