// banded.hpp - LAPACK banded symmetric matrices built from the CSR Hessian.
//
// BandedSpd holds H + shift D in LAPACK lower band storage (half bandwidth kd from
// rn_network_hessian_bandwidth), factors it with dpbtrf and solves with dpbtrs.
// It is the SPD preconditioner of the Newton systems and the factorisation used to
// choose the trust-region multiplier.  No Trilinos here.
#ifndef RODNET_SHIM_BANDED_HPP
#define RODNET_SHIM_BANDED_HPP

#include <cstddef>
#include <vector>

#include "problem.hpp"

namespace rodnet {

class BandedSpd {
public:
  BandedSpd(size_t n, size_t kd); // throws Error if n or kd exceed LAPACK's int

  // Load H + shift M from the problem's assembled Hessian; M is given by its CSR
  // values m on the Hessian's pattern (NULL: H alone).
  void load(const Problem &p, double shift, const double *m);
  // Cholesky factorisation; true if the loaded matrix is positive definite.
  bool factor();
  // x <- A^{-1} x with the factorisation (requires a successful factor()).
  void solve(double *x) const;
  bool factored() const { return factored_; }

private:
  size_t n_, kd_;
  std::vector<double> ab_;
  bool factored_ = false;
};

// Factor H + (shift + sigma) M (M: CSR values m on the Hessian's pattern, SPD) with
// the smallest sigma in {0, 1e-10, 1e-9, ...} that gives a positive definite matrix;
// returns sigma.  Throws Error (RN_ERR_LAPACK) if no shift up to 1e10 works (e.g.
// non-finite entries).
double factor_shifted(BandedSpd &f, const Problem &p, double shift, const double *m);

// Smallest eigenvalue of the assembled Hessian (LAPACK dsbevx on the band, exact
// up to round-off).  Throws Error on failure.
double banded_min_eigenvalue(const Problem &p);

} // namespace rodnet

#endif
