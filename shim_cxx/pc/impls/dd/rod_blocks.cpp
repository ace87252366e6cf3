// rod_blocks.cpp - factorisation of the rods' interior blocks and their contributions
// to the coarse matrix (rod_blocks.hpp).
#include "pc/impls/dd/rod_blocks.hpp"

#include <cmath>

#include "base/lapack.hpp"
#include "pc/impls/dd/dd_common.hpp"

namespace rodnet {
namespace dd {

namespace {

// A rod coupled to at least this many interface DOFs forms its Schur block by BLAS
// (dsyrk) instead of sparse-aware loops (the usual 6 to 24 at joints).
constexpr int kSyrkMin = 48;

// |diag| floored at 1e-8 of its maximum (1 if it vanishes).
void floored_abs(std::vector<double> &d) {
  double mx = 0.0;
  for (double &v : d) mx = std::max(mx, v = std::fabs(v));
  for (double &v : d) v = mx > 0.0 ? std::max(v, 1e-8 * mx) : 1.0;
}

} // namespace

bool factor_rod(Rod &r, const double *vals, std::vector<double> &ab, double shift) {
  const int n = r.n(), ld = r.kd + 1;
  ab.assign(static_cast<size_t>(ld) * static_cast<size_t>(n), 0.0);
  for (size_t e = 0; e < r.band_src.size(); ++e) ab[r.band_dst[e]] = vals[r.band_src[e]];
  std::vector<double> d(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) d[static_cast<size_t>(i)] = ab[static_cast<size_t>(i * ld)];
  floored_abs(d);
  if (shift >= 0.0) { // the uniform shift's D_r: the largest since the first set-up
    if (r.d_uniform.empty())
      r.d_uniform = d;
    else
      for (size_t i = 0; i < d.size(); ++i)
        r.d_uniform[i] = std::max(r.d_uniform[i], d[i]);
    d = r.d_uniform;
  }
  auto try_factor = [&](double s) {
    r.fac = ab;
    for (int i = 0; i < n; ++i)
      r.fac[static_cast<size_t>(i * ld)] += s * d[static_cast<size_t>(i)];
    int info = 0;
    dpbtrf_("L", &n, &r.kd, r.fac.data(), &ld, &info, 1);
    return info == 0;
  };
  if (shift >= 0.0) {
    r.shift = shift;
    return try_factor(shift);
  }
  r.shift = smallest_shift(try_factor);
  return r.shift >= 0.0;
}

void rod_schur(const Rod &r, std::vector<double> &Z, std::vector<int> &first,
               std::vector<double> &C) {
  const int n = r.n(), m = r.m();
  // W = L^-1 H_rG (H_rr = L L^T), C = W^T W = H_Gr H_rr^-1 H_rG.  Each
  // column's forward sweep starts at its first nonzero (the rows next to the end
  // the coupled DOF sits at).
  Z.assign(static_cast<size_t>(n) * static_cast<size_t>(m), 0.0);
  first.assign(static_cast<size_t>(m), n);
  for (size_t e = 0; e < r.b_val.size(); ++e) {
    Z[static_cast<size_t>(r.b_row[e] + r.b_col[e] * n)] = r.b_val[e];
    int &f = first[static_cast<size_t>(r.b_col[e])];
    f = std::min(f, r.b_row[e]);
  }
  for (int a = 0; a < m; ++a)
    forward_rod(r, Z.data() + static_cast<size_t>(a) * static_cast<size_t>(n),
                static_cast<size_t>(first[static_cast<size_t>(a)]));
  C.assign(static_cast<size_t>(m) * static_cast<size_t>(m), 0.0);
  if (m >= kSyrkMin) { // many coupled DOFs (a rod in self contact): BLAS
    const double one = 1.0, zero = 0.0;
    dsyrk_("U", "T", &m, &n, &one, Z.data(), &n, &zero, C.data(), &m, 1, 1);
    for (int a = 0; a < m; ++a) // column-major upper -> both triangles
      for (int b2 = 0; b2 < a; ++b2)
        C[static_cast<size_t>(b2 * m + a)] = C[static_cast<size_t>(a * m + b2)];
  }
  for (int a = 0; a < m && m < kSyrkMin; ++a)
    for (int b2 = a; b2 < m; ++b2) {
      const double *za = Z.data() + static_cast<size_t>(a) * static_cast<size_t>(n);
      const double *zb = Z.data() + static_cast<size_t>(b2) * static_cast<size_t>(n);
      double sum = 0.0;
      for (int i =
               std::max(first[static_cast<size_t>(a)], first[static_cast<size_t>(b2)]);
           i < n; ++i)
        sum += za[i] * zb[i];
      C[static_cast<size_t>(a * m + b2)] = C[static_cast<size_t>(b2 * m + a)] = sum;
    }
}

} // namespace dd
} // namespace rodnet
