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

#include "rodnet.h"

namespace rodnet {

class SparseAnalysis;
class CholmodAnalysis;

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

class Problem {
public:
  explicit Problem(rn_network *net); // throws Error if the network is not finalized

  rn_network *network() const { return net_; }
  size_t size() const { return n_; }
  size_t bandwidth() const { return kd_; }
  // Whether the network has contact (its Hessian pattern may change, see below).
  bool has_contact() const { return contact_; }
  // The version of the Hessian pattern held here (rn_network_pattern_version when it
  // was last taken).  With contact a new accepted state may rebuild the network's
  // pattern; assemble_hessian() takes the new one (a copy: rowptr(), col() and the
  // values stay consistent until then), resizes the values and drops the symbolic
  // analyses.  Whatever is built on the pattern (factorisations, metrics on the
  // pattern, Tpetra graphs) is rebuilt when this changes.
  unsigned long pattern_version() const { return version_; }

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
  // Entry (i, j) of the assembled Hessian in CSR form.
  const int64_t *rowptr() const { return rowptr_.data(); }
  const int32_t *col() const { return col_.data(); }
  const double *values() const { return vals_.data(); }
  // The assembled values, to be modified in place (e.g. a constrained Hessian for
  // path following: path.cpp); hessian_apply and the factorisations use them.
  double *mutable_values() { return vals_.data(); }

  // Symbolic analysis of the Hessian's pattern for the sparse Cholesky factorisation
  // (sparse_cholesky.hpp), computed on first use and shared by every factorisation.
  // (Of the pattern of pattern_version().)
  std::shared_ptr<const SparseAnalysis> sparse_analysis() const;
  // The same for CHOLMOD (cholmod_factor.hpp).
  std::shared_ptr<const CholmodAnalysis> cholmod_analysis() const;

  // Accept x as the new state (explicit reference update).  x is updated in place
  // (rigid-joint rotation DOFs move into the reference; the energy is unchanged).
  void accept(double *x);

  mutable Counters counters; // counted by const users too (factorisations)

private:
  void take_pattern(); // the network's pattern, its version and bandwidth

  rn_network *net_;
  size_t n_ = 0, nnz_ = 0, kd_ = 0;
  bool contact_ = false;
  unsigned long version_ = 0;
  std::vector<int64_t> rowptr_;
  std::vector<int32_t> col_;
  std::vector<double> vals_;
  mutable std::shared_ptr<const SparseAnalysis> analysis_;
  mutable std::shared_ptr<const CholmodAnalysis> cholmod_analysis_;
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
