// banded.hpp - LAPACK banded symmetric matrices built from the CSR Hessian.
//
// BandedSpd holds H + shift M in LAPACK lower band storage (half bandwidth kd from
// rn_network_hessian_bandwidth), factors it with dpbtrf and solves with dpbtrs: the
// SpdFactor of single rods (spd_factor.hpp).  No Trilinos here.
#ifndef RODNET_SHIM_BANDED_HPP
#define RODNET_SHIM_BANDED_HPP

#include <cstddef>
#include <vector>

#include "factor/csr_matrix.hpp"
#include "factor/spd_factor.hpp"

namespace rodnet {

class BandedSpd : public SpdFactor {
public:
  BandedSpd(size_t n, size_t kd); // throws Error if n or kd exceed LAPACK's int

  // Load H + shift M (band of the assembled Hessian; m: CSR values of M on its
  // pattern, NULL: H alone) and factor it; true if positive definite.
  bool factor(const CsrMatrix &p, double shift, const double *m) override;
  // x <- A^{-1} x with the factorisation (requires a successful factor()).
  void solve(double *x) const override;
  bool factored() const override { return factored_; }

private:
  size_t n_, kd_;
  std::vector<double> ab_;
  bool factored_ = false;
};

// Smallest eigenvalue of the symmetric matrix p, e.g. the assembled Hessian (LAPACK
// dsbevx on the band, exact up to round-off).  Throws Error on failure.
double banded_min_eigenvalue(const CsrMatrix &p);

} // namespace rodnet

#endif
