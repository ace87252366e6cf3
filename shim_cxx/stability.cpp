// stability.cpp - lowest eigenvalues and zero modes of the reduced Hessian (see
// stability.hpp).
#include "stability.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <vector>

#include "lanczos.hpp"
#include "shim_error.hpp"
#include "spd_factor.hpp"

extern "C" {
void dsyev_(const char *jobz, const char *uplo, const int *n, double *a, const int *lda,
            double *w, double *work, const int *lwork, int *info, size_t jobz_len,
            size_t uplo_len);
}

namespace rodnet {

namespace {

constexpr int kMaxSweeps = 200;        // subspace iterations
constexpr int kLanczosSteps = 20;      // certified case: Lanczos steps (memory 20 n)
constexpr double kResidualRel = 1e-8;  // Ritz pair converged: ||H x - mu x|| below
constexpr double kResidualAbs = 1e-13; // max(kResidualRel |mu|, kResidualAbs scale)
constexpr double kMetricFloor = 1e-20; // D_i >= kMetricFloor max_j D_j

// ||D^{-1/2} H D^{-1/2}||_inf of the assembled Hessian.
double row_sum_norm(const Problem &p, const std::vector<double> &d) {
  double s = 0.0;
  for (size_t i = 0; i < p.size(); ++i) {
    double r = 0.0;
    for (int64_t k = p.rowptr()[i]; k < p.rowptr()[i + 1]; ++k)
      r +=
          std::fabs(p.values()[k]) / std::sqrt(d[i] * d[static_cast<size_t>(p.col()[k])]);
    s = std::max(s, r);
  }
  return s;
}

// <a, b>_D
double ddot(const std::vector<double> &d, const double *a, const double *b) {
  double s = 0.0;
  for (size_t i = 0; i < d.size(); ++i) s += d[i] * a[i] * b[i];
  return s;
}

// A deterministic pseudo-random vector (entries in [-1, 1]).
void fill_start(size_t n, uint64_t seed, double *x) {
  uint64_t s = seed * 0x9E3779B97F4A7C15ULL + 1;
  for (size_t i = 0; i < n; ++i) {
    s = s * 6364136223846793005ULL + 1442695040888963407ULL;
    x[i] = static_cast<double>(s >> 11) * (2.0 / 9007199254740992.0) - 1.0;
  }
}

// D-orthonormalise the k columns of X (n x k, column-major) by modified
// Gram-Schmidt, twice; a column that loses its information (a multiple of the
// previous ones) is replaced by a fresh start vector.
void orthonormalize(const std::vector<double> &d, int k, std::vector<double> &X,
                    uint64_t &seed) {
  const size_t n = d.size();
  for (int j = 0; j < k; ++j) {
    double *xj = X.data() + static_cast<size_t>(j) * n;
    for (int attempt = 0; attempt < 3; ++attempt) {
      const double before = std::sqrt(ddot(d, xj, xj));
      for (int pass = 0; pass < 2; ++pass)
        for (int i = 0; i < j; ++i) {
          const double *xi = X.data() + static_cast<size_t>(i) * n;
          const double c = ddot(d, xi, xj);
          for (size_t r = 0; r < n; ++r) xj[r] -= c * xi[r];
        }
      const double after = std::sqrt(ddot(d, xj, xj));
      if (after > 1e-10 * before && after > 0.0) {
        for (size_t r = 0; r < n; ++r) xj[r] /= after;
        break;
      }
      if (attempt == 2)
        throw Error(RN_ERR_INTERNAL, "stability: orthonormalisation failed");
      fill_start(n, ++seed, xj);
    }
  }
}

// The k x k symmetric eigenproblem G y = mu y (G overwritten by the eigenvectors,
// column-major; mu ascending).
void small_eigen(int k, std::vector<double> &G, std::vector<double> &mu) {
  mu.assign(static_cast<size_t>(k), 0.0);
  int lwork = std::max(1, 3 * k - 1), info = 0;
  std::vector<double> work(static_cast<size_t>(lwork));
  dsyev_("V", "U", &k, G.data(), &k, mu.data(), work.data(), &lwork, &info, 1, 1);
  if (info != 0) throw Error(RN_ERR_LAPACK, "stability: dsyev failed");
}

// Y <- Y C for an n x k block Y and a k x k matrix C (column-major).
void rotate(size_t n, int k, std::vector<double> &Y, const std::vector<double> &C) {
  std::vector<double> row(static_cast<size_t>(k));
  for (size_t r = 0; r < n; ++r) {
    for (int j = 0; j < k; ++j) {
      double s = 0.0;
      for (int i = 0; i < k; ++i)
        s += Y[static_cast<size_t>(i) * n + r] * C[static_cast<size_t>(j * k + i)];
      row[static_cast<size_t>(j)] = s;
    }
    for (int j = 0; j < k; ++j)
      Y[static_cast<size_t>(j) * n + r] = row[static_cast<size_t>(j)];
  }
}

struct RitzPairs {
  std::vector<double> mu, residual; // ascending Ritz values, ||H x - mu x||
  bool converged = false;           // every pair the verdict needs has converged
};

// Subspace iteration with the factorisation f of H + s D (positive definite): the
// lowest Ritz pairs of the pencil (H, D).  Stops once the pairs up to the first one
// outside the zero band [-delta, delta] have converged (only the first if it is
// below -delta).
RitzPairs subspace_iteration(Problem &p, const SpdFactor &f, const std::vector<double> &d,
                             double delta, double scale) {
  const size_t n = p.size();
  const int k = static_cast<int>(std::min<size_t>(n, kStabilityBlock));
  std::vector<double> X(n * static_cast<size_t>(k)), W(X.size()),
      G(static_cast<size_t>(k * k));
  uint64_t seed = 1;
  for (int j = 0; j < k; ++j)
    fill_start(n, seed++, X.data() + static_cast<size_t>(j) * n);
  RitzPairs rp;
  for (int sweep = 0; sweep < kMaxSweeps && !rp.converged; ++sweep) {
    for (int j = 0; j < k; ++j) {
      double *x = X.data() + static_cast<size_t>(j) * n;
      for (size_t r = 0; r < n; ++r) x[r] *= d[r];
      f.solve(x);
    }
    orthonormalize(d, k, X, seed);
    for (int j = 0; j < k; ++j)
      p.hessian_apply(X.data() + static_cast<size_t>(j) * n,
                      W.data() + static_cast<size_t>(j) * n);
    for (int j = 0; j < k; ++j)
      for (int i = 0; i <= j; ++i) {
        const double g = 0.5 * (dot(n, X.data() + static_cast<size_t>(i) * n,
                                    W.data() + static_cast<size_t>(j) * n) +
                                dot(n, X.data() + static_cast<size_t>(j) * n,
                                    W.data() + static_cast<size_t>(i) * n));
        G[static_cast<size_t>(j * k + i)] = G[static_cast<size_t>(i * k + j)] = g;
      }
    small_eigen(k, G, rp.mu);
    rotate(n, k, X, G);
    rotate(n, k, W, G);
    rp.residual.assign(static_cast<size_t>(k), 0.0);
    for (int j = 0; j < k; ++j) {
      const double *x = X.data() + static_cast<size_t>(j) * n,
                   *w = W.data() + static_cast<size_t>(j) * n;
      double s = 0.0; // ||H x - mu D x|| in the D^{-1} norm
      for (size_t r = 0; r < n; ++r) {
        const double e = w[r] - rp.mu[static_cast<size_t>(j)] * d[r] * x[r];
        s += e * e / d[r];
      }
      rp.residual[static_cast<size_t>(j)] = std::sqrt(s);
    }
    // the pairs the verdict needs: through the first Ritz value outside the zero band
    int need = 0;
    while (need < k && std::fabs(rp.mu[static_cast<size_t>(need)]) <= delta) ++need;
    need = std::min(need + 1, k);
    if (rp.mu[0] < -delta) need = 1;
    rp.converged = static_cast<size_t>(k) == n; // the whole space: exact
    if (!rp.converged) {
      rp.converged = true;
      for (int j = 0; j < need; ++j)
        if (rp.residual[static_cast<size_t>(j)] >
            std::max(kResidualRel * std::fabs(rp.mu[static_cast<size_t>(j)]),
                     kResidualAbs * scale))
          rp.converged = false;
    }
  }
  return rp;
}

} // namespace

rn_stability hessian_stability(Problem &p, rn_factorization kind) {
  const auto start = std::chrono::steady_clock::now();
  const long factorizations0 = p.counters.factorizations;
  rn_stability st{};
  st.checked = 1;
  st.method = RN_STABILITY_CHOLESKY;
  const size_t n = p.size();
  const std::vector<double> d = hessian_metric(p, kMetricFloor);
  st.scale = row_sum_norm(p, d);
  if (!std::isfinite(st.scale))
    throw Error(RN_ERR_NOT_FINITE, "stability: non-finite Hessian");
  if (n == 0) { // nothing free: trivially a minimum
    st.verified_minimum = 1;
  } else if (!(st.scale > 0.0)) { // H = 0: every mode is a zero mode
    st.zero_modes = static_cast<int>(std::min<size_t>(n, kStabilityBlock));
  } else {
    const double delta = kZeroModeTol * st.scale;
    const std::vector<double> dvals = diagonal_on_pattern(p, d);
    auto f = make_spd_factor(p, kind);
    if (f->factor(p, -delta, dvals.data())) {
      // every eigenvalue above delta: the lowest by shift-and-invert Lanczos on
      // (H - delta D)^{-1} D, whose Ritz value bounds 1 / (lambda_min - delta) from
      // below
      std::vector<double> v(n);
      fill_start(n, 7, v.data());
      const LanczosResult lr = lanczos_largest(*f, d, kLanczosSteps, 1e-6, v);
      st.lowest_eigenvalue = 1.0 / lr.theta + delta;
      st.verified_minimum = 1;
    } else {
      // lambda_min <= delta: the smallest shift s with H + s D positive definite
      // (delta, or 10^k scale, k >= -10), for which f then holds the factorisation
      if (!f->factor(p, delta, dvals.data())) {
        std::vector<double> scaled(dvals);
        for (double &e : scaled) e *= st.scale;
        factor_shifted(*f, p, 0.0, scaled.data(), false);
      }
      const RitzPairs rp = subspace_iteration(p, *f, d, delta, st.scale);
      size_t j = 0;
      while (j < rp.mu.size() && std::fabs(rp.mu[j]) <= delta) ++j;
      st.zero_modes = static_cast<int>(rp.mu[0] < -delta ? 0 : j);
      if (rp.mu[0] < -delta) {
        st.lowest_eigenvalue = rp.mu[0];
        for (double mu : rp.mu) st.zero_modes += std::fabs(mu) <= delta;
      } else if (j < rp.mu.size()) {
        st.lowest_eigenvalue = rp.mu[j];
        st.verified_minimum = rp.converged && rp.mu[j] > delta;
      }
    }
  }
  st.factorizations = p.counters.factorizations - factorizations0;
  st.time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return st;
}

} // namespace rodnet
