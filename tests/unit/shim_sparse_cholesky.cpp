// shim_sparse_cholesky.cpp - the shim's sparse Cholesky factorisations on their own,
// rodnet's supernodal one (shim_cxx/factor/sparse_cholesky.hpp) and CHOLMOD's
// (shim_cxx/factor/cholmod_factor.hpp), against dense LAPACK and against each other:
//  - random sparse symmetric patterns (with and without a dense "joint" block coupled
//    to everything, disconnected components, n = 1, 2, 3, a diagonal matrix): for
//    A - s I with s below the lowest eigenvalue (dsyev) by 1e-6 of the spectral
//    scale, factor() succeeds; with s above it by as much, factor() returns false;
//    solve() has a backward error below 1e-13;
//  - the factorisation is reusable: a further factor() with a well-conditioning shift
//    on the same analysis, after the failed one, gives dposv's solution to 1e-10
//    relative;
//  - a non-finite entry makes factor() return false;
//  - both implementations give the same solutions to 1e-12 relative.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <set>
#include <vector>

#include "factor/cholmod_factor.hpp"
#include "factor/sparse_cholesky.hpp"

extern "C" {
#include "testutil.h"
void dsyev_(const char *jobz, const char *uplo, const int *n, double *a, const int *lda,
            double *w, double *work, const int *lwork, int *info, size_t, size_t);
void dposv_(const char *uplo, const int *n, const int *nrhs, double *a, const int *lda,
            double *b, const int *ldb, int *info, size_t);
}

namespace {

struct Csr {
  size_t n = 0;
  std::vector<int64_t> rowptr;
  std::vector<int32_t> col;
  std::vector<double> val, ident; // values, identity on the pattern
};

// Symmetric pattern: a chain (banded, like rods), random extra pairs, optionally a
// last block of `dense` rows coupled to a random half of the others (like joints);
// `components` > 1 leaves that many uncoupled chains.
Csr random_matrix(size_t n, int extra, size_t dense, int components, uint64_t *seed) {
  std::vector<std::set<size_t>> rows(n);
  const size_t chain = n - dense, per = std::max<size_t>(1, chain / components);
  for (size_t i = 0; i < n; ++i) rows[i].insert(i);
  for (size_t i = 0; i + 1 < chain; ++i)
    if ((i + 1) % per != 0 || components == 1) {
      rows[i].insert(i + 1);
      rows[i + 1].insert(i);
    }
  for (int k = 0; k < extra && components == 1; ++k) {
    const size_t a =
        static_cast<size_t>((rn_test_rand(seed) + 1.0) * 0.5 * static_cast<double>(n)) %
        n;
    const size_t b =
        static_cast<size_t>((rn_test_rand(seed) + 1.0) * 0.5 * static_cast<double>(n)) %
        n;
    rows[a].insert(b);
    rows[b].insert(a);
  }
  for (size_t j = chain; j < n; ++j)
    for (size_t i = 0; i < n; ++i)
      if (i >= chain || rn_test_rand(seed) > 0.0) {
        rows[i].insert(j);
        rows[j].insert(i);
      }
  Csr A;
  A.n = n;
  A.rowptr.push_back(0);
  for (size_t i = 0; i < n; ++i) {
    for (size_t j : rows[i]) A.col.push_back(static_cast<int32_t>(j));
    A.rowptr.push_back(static_cast<int64_t>(A.col.size()));
  }
  A.val.assign(A.col.size(), 0.0);
  A.ident.assign(A.col.size(), 0.0);
  for (size_t i = 0; i < n; ++i) // symmetric values: from the (min, max) pair
    for (int64_t k = A.rowptr[i]; k < A.rowptr[i + 1]; ++k) {
      const size_t j = static_cast<size_t>(A.col[static_cast<size_t>(k)]);
      const double u = std::sin(1.3 * static_cast<double>(std::min(i, j)) +
                                0.7 * static_cast<double>(std::max(i, j)) + 0.1);
      A.val[static_cast<size_t>(k)] = i == j ? 2.0 + u : u;
      A.ident[static_cast<size_t>(k)] = i == j ? 1.0 : 0.0;
    }
  return A;
}

std::vector<double> dense(const Csr &A) {
  std::vector<double> D(A.n * A.n, 0.0);
  for (size_t i = 0; i < A.n; ++i)
    for (int64_t k = A.rowptr[i]; k < A.rowptr[i + 1]; ++k)
      D[i + A.n * static_cast<size_t>(A.col[static_cast<size_t>(k)])] =
          A.val[static_cast<size_t>(k)];
  return D;
}

// Eigenvalues (ascending) of the dense matrix.
std::vector<double> eigenvalues(const Csr &A) {
  std::vector<double> D = dense(A), w(A.n);
  const int n = static_cast<int>(A.n);
  int lwork = 8 * n + 8, info = 0;
  std::vector<double> work(static_cast<size_t>(lwork));
  dsyev_("N", "L", &n, D.data(), &n, w.data(), work.data(), &lwork, &info, 1, 1);
  CHECK(info == 0);
  return w;
}

// Factor A - s I sparse; if ok, check the solution of (A - s I) x = b: backward error
// ||(A - s I) x - b|| <= 1e-13 (||A - s I||_F ||x|| + ||b||), and, when compare is
// set (a well-conditioned shift), agreement with dposv to 1e-10 relative.  Returns
// factor()'s result.
template <class Chol>
bool factor_and_check(Chol &chol, const Csr &A, double s, bool compare) {
  const bool ok = chol.factor(A.val.data(), -s, A.ident.data());
  if (!ok) return false;
  std::vector<double> D = dense(A), b(A.n), x(A.n), r(A.n, 0.0);
  for (size_t i = 0; i < A.n; ++i) {
    D[i + A.n * i] -= s;
    b[i] = x[i] = std::cos(0.3 * static_cast<double>(i));
  }
  chol.solve(x.data());
  double rn = 0.0, an = 0.0, xn = 0.0, bn = 0.0;
  for (size_t j = 0; j < A.n; ++j)
    for (size_t i = 0; i < A.n; ++i) {
      r[i] += D[i + A.n * j] * x[j];
      an += D[i + A.n * j] * D[i + A.n * j];
    }
  for (size_t i = 0; i < A.n; ++i) {
    rn += (r[i] - b[i]) * (r[i] - b[i]);
    xn += x[i] * x[i];
    bn += b[i] * b[i];
  }
  CHECK(std::sqrt(rn) <= 1e-13 * (std::sqrt(an) * std::sqrt(xn) + std::sqrt(bn)));
  if (!compare) return true;
  const int n = static_cast<int>(A.n), one = 1;
  int info = 0;
  dposv_("L", &n, &one, D.data(), &n, b.data(), &n, &info, 1);
  CHECK(info == 0);
  double num = 0.0, den = 0.0;
  for (size_t i = 0; i < A.n; ++i) {
    num += (x[i] - b[i]) * (x[i] - b[i]);
    den += b[i] * b[i];
  }
  CHECK(std::sqrt(num / den) <= 1e-10);
  return true;
}

// Solution of (A - s I) x = b, b_i = cos(0.3 i), for the comparison.
template <class Chol>
std::vector<double> solution(Chol &chol, const Csr &A, double s) {
  std::vector<double> x(A.n);
  for (size_t i = 0; i < A.n; ++i) x[i] = std::cos(0.3 * static_cast<double>(i));
  CHECK(chol.factor(A.val.data(), -s, A.ident.data()));
  if (chol.factored()) chol.solve(x.data());
  return x;
}

template <class Analysis, class Chol>
void check_case(const char *impl, const char *label, const Csr &A) {
  auto an = std::make_shared<const Analysis>(A.n, A.rowptr.data(), A.col.data());
  Chol chol(an);
  const std::vector<double> w = eigenvalues(A);
  const double scale = std::max(std::fabs(w.front()), std::fabs(w.back())),
               gap = 1e-6 * scale;
  const bool below = factor_and_check(chol, A, w.front() - gap, false);
  const bool above = factor_and_check(chol, A, w.front() + gap, false);
  const bool again = factor_and_check(chol, A, w.front() - 0.5 * scale, true);
  std::printf("%-7s %-34s n %4zu, nnz %6zu, supernodes %4zu, nnz(L) %7zu, lowest "
              "eigenvalue %+.4e: below %s, above %s\n",
              impl, label, A.n, A.col.size(), an->num_supernodes(), an->factor_entries(),
              w.front(), below ? "factors" : "FAILS", above ? "FACTORS" : "fails");
  CHECK(below);
  CHECK(!above);
  CHECK(again);
  // A non-finite entry (both triangles: each implementation reads one of them).
  std::vector<double> bad = A.val;
  const size_t kbad = bad.size() / 2;
  size_t ibad = 0;
  while (static_cast<size_t>(A.rowptr[ibad + 1]) <= kbad) ++ibad;
  const int32_t jbad = A.col[kbad];
  for (int64_t k = A.rowptr[static_cast<size_t>(jbad)];
       k < A.rowptr[static_cast<size_t>(jbad) + 1]; ++k)
    if (static_cast<size_t>(A.col[static_cast<size_t>(k)]) == ibad)
      bad[static_cast<size_t>(k)] = std::nan("");
  bad[kbad] = std::nan("");
  CHECK(!chol.factor(bad.data(), 0.0, nullptr));
  CHECK(!chol.factored());
}

void check_case(const char *label, const Csr &A) {
  check_case<rodnet::SparseAnalysis, rodnet::SparseCholesky>("rodnet", label, A);
  check_case<rodnet::CholmodAnalysis, rodnet::CholmodCholesky>("cholmod", label, A);
  // The two factorisations agree on a well-conditioned shift.
  const std::vector<double> w = eigenvalues(A);
  const double s = w.front() - 0.5 * std::max(std::fabs(w.front()), std::fabs(w.back()));
  auto a1 =
      std::make_shared<const rodnet::SparseAnalysis>(A.n, A.rowptr.data(), A.col.data());
  auto a2 =
      std::make_shared<const rodnet::CholmodAnalysis>(A.n, A.rowptr.data(), A.col.data());
  rodnet::SparseCholesky c1(a1);
  rodnet::CholmodCholesky c2(a2);
  const std::vector<double> x1 = solution(c1, A, s), x2 = solution(c2, A, s);
  double num = 0.0, den = 0.0;
  for (size_t i = 0; i < A.n; ++i) {
    num += (x1[i] - x2[i]) * (x1[i] - x2[i]);
    den += x1[i] * x1[i];
  }
  CHECK(std::sqrt(num) <= 1e-12 * std::sqrt(den));
}

} // namespace

int main() {
  uint64_t seed = 5;
  check_case("n = 1", random_matrix(1, 0, 0, 1, &seed));
  check_case("n = 2", random_matrix(2, 0, 0, 1, &seed));
  check_case("n = 3, one dense row", random_matrix(3, 0, 1, 1, &seed));
  {
    Csr diag = random_matrix(40, 0, 0, 40, &seed); // 40 components of one row
    check_case("diagonal, n = 40", diag);
  }
  check_case("chain, n = 300", random_matrix(300, 0, 0, 1, &seed));
  check_case("chain + random pairs, n = 300", random_matrix(300, 60, 0, 1, &seed));
  check_case("chain + 12 dense rows, n = 400", random_matrix(400, 20, 12, 1, &seed));
  check_case("4 components, n = 200", random_matrix(200, 0, 0, 4, &seed));
  check_case("4 components + dense rows, n = 210", random_matrix(210, 0, 10, 4, &seed));
  return rn_test_finish("shim_sparse_cholesky");
}
