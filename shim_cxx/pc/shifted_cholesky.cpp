// shifted_cholesky.cpp - diagonal metric and smallest shift of a sparse Cholesky
// factorisation (shifted_cholesky.hpp).
#include "pc/shifted_cholesky.hpp"

#include <algorithm>
#include <cmath>

#include "factor/sparse_cholesky.hpp"

namespace rodnet {

double max_abs_diagonal(size_t n, const int64_t *rowptr, const int32_t *col,
                        const double *vals) {
  double dmax = 0.0;
  for (size_t i = 0; i < n; ++i)
    for (int64_t k = rowptr[i]; k < rowptr[i + 1]; ++k)
      if (static_cast<size_t>(col[k]) == i) dmax = std::max(dmax, std::fabs(vals[k]));
  return dmax;
}

std::vector<double> floored_diagonal(size_t n, const int64_t *rowptr, const int32_t *col,
                                     const double *vals, double dmax) {
  std::vector<double> m(static_cast<size_t>(rowptr[n]), 0.0);
  const bool flat = !(dmax > 0.0) || !std::isfinite(dmax);
  for (size_t i = 0; i < n; ++i)
    for (int64_t k = rowptr[i]; k < rowptr[i + 1]; ++k)
      if (static_cast<size_t>(col[k]) == i)
        m[static_cast<size_t>(k)] =
            flat ? 1.0 : std::max(std::fabs(vals[k]), 1e-8 * dmax);
  return m;
}

double factor_smallest_shift(SparseCholesky &chol, const double *vals, const double *m) {
  if (chol.factor(vals, 0.0, m)) return 0.0;
  int lo = -11, hi = 11;
  bool holds_hi = false;
  while (hi - lo > 1) {
    const int mid = lo + (hi - lo) / 2;
    holds_hi = chol.factor(vals, std::pow(10.0, mid), m);
    (holds_hi ? hi : lo) = mid;
  }
  const double sigma = std::pow(10.0, hi);
  if (hi > 10 || (!holds_hi && !chol.factor(vals, sigma, m))) return -1.0;
  return sigma;
}

} // namespace rodnet
