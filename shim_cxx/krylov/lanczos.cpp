// lanczos.cpp - shift-and-invert Lanczos for the largest eigenpair of A^{-1} M (see
// lanczos.hpp).
#include "krylov/lanczos.hpp"

#include <algorithm>
#include <cmath>

#include "base/lapack.hpp"
#include "base/shim_error.hpp"

namespace rodnet {

namespace {

double mdot(const std::vector<double> &d, const double *a, const double *b) {
  double s = 0.0;
  for (size_t i = 0; i < d.size(); ++i) s += d[i] * a[i] * b[i];
  return s;
}

// Largest eigenvalue of the k x k tridiagonal (alpha, beta) and its eigenvector y.
double tridiagonal_largest(const std::vector<double> &alpha,
                           const std::vector<double> &beta, int k,
                           std::vector<double> &y) {
  std::vector<double> dd(alpha.begin(), alpha.begin() + k),
      e(beta.begin(), beta.begin() + k);
  std::vector<double> z(static_cast<size_t>(k) * static_cast<size_t>(k)),
      work(static_cast<size_t>(std::max(1, 2 * k - 2)));
  int info = 0;
  dstev_("V", &k, dd.data(), e.data(), z.data(), &k, work.data(), &info, 1);
  if (info != 0) throw Error(RN_ERR_LAPACK, "rn_solve: Lanczos: dstev failed");
  const size_t last = static_cast<size_t>(k - 1); // eigenvalues ascending
  y.assign(z.begin() + static_cast<std::ptrdiff_t>(last * static_cast<size_t>(k)),
           z.begin() + static_cast<std::ptrdiff_t>((last + 1) * static_cast<size_t>(k)));
  return dd[last];
}

} // namespace

LanczosResult lanczos_largest(const std::function<void(double *)> &solve_A,
                              const std::vector<double> &d, int max_steps, double rel_tol,
                              std::vector<double> &v,
                              const std::vector<std::vector<double>> *locked) {
  const size_t n = d.size();
  auto deflate = [&](std::vector<double> &w) {
    if (!locked) return;
    for (const std::vector<double> &u : *locked) {
      const double c = mdot(d, u.data(), w.data());
      for (size_t i = 0; i < n; ++i) w[i] -= c * u[i];
    }
  };
  const int m =
      static_cast<int>(std::min<size_t>(n, static_cast<size_t>(std::max(1, max_steps))));
  std::vector<std::vector<double>> Q;
  std::vector<double> alpha, beta, y, w(n);
  LanczosResult res;
  deflate(v);
  deflate(v);
  double nv = std::sqrt(mdot(d, v.data(), v.data()));
  if (!(nv > 0.0)) return res; // the start vector lies in the locked span
  Q.emplace_back(v);
  for (double &e : Q[0]) e /= nv;
  for (int j = 0; j < m; ++j) {
    const std::vector<double> &q = Q[static_cast<size_t>(j)];
    for (size_t i = 0; i < n; ++i) w[i] = d[i] * q[i];
    solve_A(w.data());
    alpha.push_back(mdot(d, q.data(), w.data()));
    for (int pass = 0; pass < 2; ++pass) { // full reorthogonalisation, twice
      deflate(w);
      for (const std::vector<double> &qi : Q) {
        const double c = mdot(d, qi.data(), w.data());
        for (size_t i = 0; i < n; ++i) w[i] -= c * qi[i];
      }
    }
    beta.push_back(std::sqrt(mdot(d, w.data(), w.data())));
    res.steps = j + 1;
    res.theta = tridiagonal_largest(alpha, beta, j + 1, y);
    const double resid = std::fabs(beta.back() * y.back());
    if (resid <= rel_tol * res.theta || beta.back() <= 1e-14 * res.theta) {
      res.converged = true;
      break;
    }
    if (j + 1 < m) {
      Q.emplace_back(w);
      for (double &e : Q.back()) e /= beta.back();
    }
  }
  v.assign(n, 0.0);
  for (size_t k = 0; k < y.size(); ++k)
    for (size_t i = 0; i < n; ++i) v[i] += y[k] * Q[k][i];
  nv = std::sqrt(mdot(d, v.data(), v.data()));
  for (double &e : v) e /= nv;
  return res;
}

} // namespace rodnet
