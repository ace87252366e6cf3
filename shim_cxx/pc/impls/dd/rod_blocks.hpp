// rod_blocks.hpp - the rod blocks of the rod-level domain decomposition
// (dd_preconditioner.hpp): one rod's interior block H_rr, banded (LAPACK lower band
// storage), its factorisation (shifted if indefinite), the solves with it, and the
// rod's contribution H_Gr H_rr^-1 H_rG to the coarse (interface) matrix.
#ifndef RODNET_SHIM_DD_ROD_BLOCKS_HPP
#define RODNET_SHIM_DD_ROD_BLOCKS_HPP

#include <algorithm>
#include <cstddef>
#include <vector>

#include "system/system.hpp"

namespace rodnet {
namespace dd {

// One rod's interior block (banded, factored) and its coupling H_rG to the interface.
struct Rod {
  std::vector<LO> rows; // owned local rows of the interior, ascending
  int kd = 0;
  std::vector<size_t> band_src;  // H value index of each lower band entry
  std::vector<size_t> band_dst;  // its place in the band (LAPACK lower storage)
  std::vector<double> fac;       // factored band of H_rr (+ shift D_r)
  std::vector<LO> coarse;        // overlapping-coarse local index of each coupled DOF
  std::vector<int> b_row, b_col; // entries of H_rG: rod position, index in coarse
  std::vector<size_t> b_src;
  std::vector<double> b_val;
  std::vector<size_t> s_pos; // Sov value index of (a, b), a * m + b
  double shift = 0.0;
  // D_r of the uniform shift: |diag H_rr| (floored) at the first set-up that shifts
  // uniformly, then the entrywise largest of the set-ups since, for the
  // preconditioner's life (DdPreconditioner::setup)
  std::vector<double> d_uniform;
  int n() const { return static_cast<int>(rows.size()); }
  int m() const { return static_cast<int>(coarse.size()); }
};

// Factor the band of rod r from H's values plus shift D_r.  shift < 0: the smallest
// of smallest_shift's ladder (shifted only if indefinite), false if none up to 1e10
// works; shift >= 0: that shift only (the uniform-shift search,
// DdPreconditioner::setup), false if it is not positive definite.  ab: work.
bool factor_rod(Rod &r, const double *vals, std::vector<double> &ab, double shift = -1.0);

// C = H_Gr H_rr^-1 H_rG (m x m, both triangles, column-major) of a factored rod with
// m = r.m() > 0 coupled DOFs (r.b_val set).  Z, first: work.
void rod_schur(const Rod &r, std::vector<double> &Z, std::vector<int> &first,
               std::vector<double> &C);

// y <- L^-1 y (length n) for y zero before row j0, L the factor of dpbtrf in lower
// band storage.
inline void forward_rod(const Rod &r, double *y, size_t j0) {
  const size_t n = r.rows.size(), kd = static_cast<size_t>(r.kd), ld = kd + 1;
  const double *L = r.fac.data();
  for (size_t j = j0; j < n; ++j) {
    const double *Lj = L + j * ld;
    const double yj = (y[j] /= Lj[0]);
    const size_t m = std::min(kd, n - 1 - j);
    for (size_t i = 1; i <= m; ++i) y[j + i] -= Lj[i] * yj;
  }
}

// z <- (L L^T)^-1 z for nrhs columns of length n (leading dimension n), L the factor
// of dpbtrf in lower band storage.  Written out: for the small bands of rods (kd ~ 10)
// LAPACK's dpbtrs spends its time in per-column BLAS calls (dtbsv -> ddot / daxpy).
inline void solve_rod(const Rod &r, double *z, int nrhs) {
  const size_t n = r.rows.size(), kd = static_cast<size_t>(r.kd), ld = kd + 1;
  const double *L = r.fac.data();
  for (int c = 0; c < nrhs; ++c) {
    double *y = z + static_cast<size_t>(c) * n;
    forward_rod(r, y, 0);          // L y = b
    for (size_t j = n; j-- > 0;) { // L^T x = y
      const double *Lj = L + j * ld;
      const size_t m = std::min(kd, n - 1 - j);
      double t = y[j];
      for (size_t i = 1; i <= m; ++i) t -= Lj[i] * y[j + i];
      y[j] = t / Lj[0];
    }
  }
}

} // namespace dd
} // namespace rodnet

#endif
