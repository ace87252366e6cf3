// problem.hpp - the solver's view of a finalized rn_network (no Trilinos here).
//
// Problem wraps the pure evaluation functions of rodnet.h (energy, gradient, HVP,
// CSR Hessian), counts every evaluation for rn_solve_report, keeps the assembled
// Hessian values of one state and applies (H + shift D) from them.  Reduced DOF
// vectors are plain host arrays of length size().
#ifndef RODNET_SHIM_PROBLEM_HPP
#define RODNET_SHIM_PROBLEM_HPP

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "factor/csr_matrix.hpp"
#include "rodnet.h"

namespace rodnet {

struct Counters {
  long energy = 0, gradient = 0, hvp = 0, hessian = 0, krylov = 0;
  long factorizations = 0; // numeric Cholesky factorisations (SpdFactor::factor)
  // wall seconds in Hessian assembly, and in the setups and applications of the
  // Newton-Krylov solvers' Preconditioner (tr-krylov, nox, their predictors)
  double hessian_seconds = 0.0, setup_seconds = 0.0, apply_seconds = 0.0;
};

// Seconds since t0 on the steady clock.
double seconds_since_steady(double t0);
// The steady clock now, in seconds.
double steady_now();

// The assembled Hessian is the CsrMatrix (factor/csr_matrix.hpp) the SPD
// factorisations take: size(), bandwidth(), pattern_version(), rowptr(), col(),
// values(), mutable_values() and the shared symbolic analyses come from there.
class Problem : public CsrMatrix {
public:
  explicit Problem(rn_network *net); // throws Error if the network is not finalized

  rn_network *network() const { return net_; }
  // Whether the network has contact (its Hessian pattern may change, see below).
  bool has_contact() const { return contact_; }
  // pattern_version(): the version of the Hessian pattern held here
  // (rn_network_pattern_version when it was last taken).  With contact a new
  // accepted state may rebuild the network's pattern; assemble_hessian() takes the
  // new one (a copy: rowptr(), col() and the values stay consistent until then),
  // resizes the values and drops the symbolic analyses.

  // Pure evaluations.  Return RN_OK or a positive, recoverable status (RN_DEGENERATE,
  // RN_OVERFLOW: a trial point to reject); throw Error on any error status.  E may be
  // NULL for gradient().
  rn_status energy(const double *x, double *E);
  rn_status gradient(const double *x, double *E, double *g);
  void hvp(const double *x, const double *v, double *Hv);

  // Assemble the CSR Hessian values at x (kept until the next assembly).
  void assemble_hessian(const double *x);
  // y = (H + shift M) v with the assembled values; M is a matrix on the Hessian's
  // pattern given by its CSR values m (NULL: shift ignored).  Counted as an HVP.
  void hessian_apply(const double *v, double *y, double shift = 0.0,
                     const double *m = nullptr);
  // y = M v for CSR values m on the Hessian's pattern (not counted).
  void pattern_apply(const double *m, const double *v, double *y) const;

  // Accept x as the new state (explicit reference update).  x is updated in place
  // (rigid-joint rotation DOFs move into the reference; the energy is unchanged).
  void accept(double *x);

  // Every numeric factorisation of the Hessian (SpdFactor::factor).
  void count_factorization() const override { ++counters.factorizations; }

  mutable Counters counters; // counted by const users too (factorisations)

private:
  void take_pattern(); // the network's pattern, its version and bandwidth

  rn_network *net_;
  bool contact_ = false;
};

// Small dense vector helpers on host arrays of length n.
inline double dot(size_t n, const double *a, const double *b) {
  double s = 0.0;
  for (size_t i = 0; i < n; ++i) s += a[i] * b[i];
  return s;
}
inline double norm2(size_t n, const double *a) { return std::sqrt(dot(n, a, a)); }
// sqrt(sum d_i a_i^2): the norm of the metric diag(d).
inline double wnorm(size_t n, const double *d, const double *a) {
  double s = 0.0;
  for (size_t i = 0; i < n; ++i) s += d[i] * a[i] * a[i];
  return std::sqrt(s);
}

// D = |diag H| of the assembled Hessian, floored at floor_rel * max |H_ii| (1
// everywhere if the diagonal vanishes).
std::vector<double> hessian_metric(const Problem &p, double floor_rel = 1e-8);
// CSR values on the Hessian's pattern of diag(d) (throws if a diagonal entry is not
// in the pattern).
std::vector<double> diagonal_on_pattern(const Problem &p, const std::vector<double> &d);
// CSR values of H + shift diag(d) (assembled H).
std::vector<double> shifted_hessian_values(const Problem &p, double shift,
                                           const std::vector<double> &d);

} // namespace rodnet

#endif
