// min_eigenvalue.cpp - smallest eigenvalue of the assembled Hessian with the sparse
// Cholesky factorisation (networks with joints; see spd_factor.hpp).
//
// Sylvester's law of inertia through Cholesky: H - sigma I factors exactly when
// sigma < lambda_min.  Bisection between a Gershgorin lower bound (factors) and the
// smallest diagonal entry (an upper bound) brackets lambda_min to 5 % (or to 1e-12
// of the Gershgorin scale when it is near 0); inverse iteration with the
// factorisation at the lower end of the bracket then converges to the lowest
// eigenvector, whose Rayleigh quotient is returned (accurate to round-off when
// lambda_min is separated from the rest of the spectrum, and within the cluster
// otherwise).  No Trilinos here.
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "base/shim_error.hpp"
#include "eigen/stability.hpp"
#include "factor/spd_factor.hpp"

namespace rodnet {

namespace {

// Gershgorin interval [lo, hi] of the assembled Hessian and its smallest diagonal.
void gershgorin(const Problem &p, double *lo, double *hi, double *dmin) {
  *lo = std::numeric_limits<double>::max();
  *hi = -*lo;
  *dmin = *lo;
  for (size_t i = 0; i < p.size(); ++i) {
    double d = 0.0, off = 0.0;
    for (int64_t k = p.rowptr()[i]; k < p.rowptr()[i + 1]; ++k) {
      if (static_cast<size_t>(p.col()[k]) == i)
        d = p.values()[k];
      else
        off += std::fabs(p.values()[k]);
    }
    *lo = std::min(*lo, d - off);
    *hi = std::max(*hi, d + off);
    *dmin = std::min(*dmin, d);
  }
}

} // namespace

double sparse_min_eigenvalue(Problem &p) {
  const size_t n = p.size();
  if (n == 0) throw Error(RN_ERR_ARG, "rn_hessian_min_eigenvalue: no free DOFs");
  double glo, ghi, dmin;
  gershgorin(p, &glo, &ghi, &dmin);
  const double scale = std::max(std::fabs(glo), std::fabs(ghi));
  if (!std::isfinite(scale))
    throw Error(RN_ERR_NOT_FINITE, "rn_hessian_min_eigenvalue: non-finite Hessian");
  if (!(scale > 0.0)) return 0.0; // H = 0
  const std::vector<double> ident = diagonal_on_pattern(p, std::vector<double>(n, 1.0));
  auto f = make_spd_factor(p, RN_FACTOR_SPARSE);
  double below = glo - 1e-3 * scale, above = dmin; // factors / does not
  if (!f->factor(p, -below, ident.data()))
    throw Error(RN_ERR_SOLVER, "rn_hessian_min_eigenvalue: the Gershgorin shift does "
                               "not factor");
  if (f->factor(p, -above, ident.data())) below = above; // lambda_min = min diagonal
  while (above - below >
         std::max(0.05 * std::max(std::fabs(below), std::fabs(above)), 1e-12 * scale)) {
    const double mid = 0.5 * (below + above);
    (f->factor(p, -mid, ident.data()) ? below : above) = mid;
  }
  if (!f->factor(p, -below, ident.data()))
    throw Error(RN_ERR_SOLVER, "rn_hessian_min_eigenvalue: factorisation failed");
  std::vector<double> v(n), hv(n);
  for (size_t i = 0; i < n; ++i)
    v[i] = 1.0 + 0.5 * std::sin(0.7 * static_cast<double>(i));
  double mu = std::numeric_limits<double>::max();
  for (int it = 0; it < 300; ++it) {
    f->solve(v.data());
    const double nv = norm2(n, v.data());
    for (double &e : v) e /= nv;
    p.hessian_apply(v.data(), hv.data());
    const double mu_new = dot(n, v.data(), hv.data());
    const bool done = std::fabs(mu_new - mu) <= 1e-15 * scale + 1e-14 * std::fabs(mu_new);
    mu = mu_new;
    if (done) break;
  }
  if (!std::isfinite(mu))
    throw Error(RN_ERR_SOLVER, "rn_hessian_min_eigenvalue: inverse iteration failed");
  return mu;
}

} // namespace rodnet
