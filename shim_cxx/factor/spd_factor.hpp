// spd_factor.hpp - the factorisation behind the trust region and the SPD
// preconditioners: A = H + shift M (H the problem's assembled Hessian, M an SPD
// matrix given by its CSR values on the Hessian's pattern) is factored by Cholesky;
// factor() says whether A is positive definite, and solve() applies A^{-1}.
//
// Three implementations, chosen by choose_factor_kind():
//  - BandedSpd (banded.hpp): LAPACK dpbtrf on the band; exact and fastest for single
//    rods and networks without joints (half bandwidth <= kBandedMaxBandwidth);
//  - SparseSpd: supernodal multifrontal Cholesky with a METIS nested-dissection
//    ordering (sparse_cholesky.hpp) for networks with joints, whose joint DOFs come
//    after all rods (half bandwidth ~ n).  The symbolic analysis is done once per
//    pattern (CsrMatrix) and shared by every factorisation;
//  - CholmodSpd (RN_FACTOR_CHOLMOD only): SuiteSparse CHOLMOD's supernodal
//    Cholesky with METIS ordering (cholmod_factor.hpp), the library reference for
//    SparseSpd (about 2x slower on lattices, docs/solvers.md); analysis shared too.
// No Trilinos here.
#ifndef RODNET_SHIM_SPD_FACTOR_HPP
#define RODNET_SHIM_SPD_FACTOR_HPP

#include <cstddef>
#include <memory>

#include "factor/csr_matrix.hpp"
#include "rodnet_solve.h"

namespace rodnet {

class SpdFactor {
public:
  virtual ~SpdFactor() = default;
  // Factor H + shift M (m: CSR values of M on H's pattern, NULL: H alone); true if
  // the matrix is positive definite.  Counted by H.count_factorization() (a
  // Problem's counters.factorizations).
  virtual bool factor(const CsrMatrix &H, double shift, const double *m) = 0;
  // x <- A^{-1} x with the last successful factorisation (throws Error otherwise).
  virtual void solve(double *x) const = 0;
  virtual bool factored() const = 0;
};

// Largest half bandwidth for which the automatic choice is the banded factorisation.
constexpr size_t kBandedMaxBandwidth = 64;

// RN_FACTOR_AUTO: banded if the half bandwidth is at most kBandedMaxBandwidth and
// the pattern cannot change (no contact), sparse otherwise; the other values
// (banded, sparse, cholmod) force one.
rn_factorization choose_factor_kind(const CsrMatrix &H, rn_factorization requested);
// A factorisation of the chosen kind.  Throws Error (RN_ERR_ARG) for a forced banded
// factorisation whose band would need more than 4 GiB.
std::unique_ptr<SpdFactor> make_spd_factor(const CsrMatrix &H,
                                           rn_factorization requested);

// Factor H + (shift + sigma) M with the smallest sigma in {0, 1e-10, ..., 10^K} that
// gives a positive definite matrix, K = max(10, 1 + log10 of the Gershgorin bound of
// the shift) (bisection on the exponent: 7 factorisations while K = 10); returns
// sigma.  Throws Error (RN_ERR_LAPACK) on non-finite entries or a non-positive M_ii.
// try_zero = false: the caller knows that sigma = 0 fails (skips that factorisation).
double factor_shifted(SpdFactor &f, const CsrMatrix &H, double shift, const double *m,
                      bool try_zero = true);

} // namespace rodnet

#endif
