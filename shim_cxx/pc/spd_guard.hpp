// spd_guard.hpp - shared by the Trilinos preconditioners that must be symmetric
// positive definite for MINRES (pc/impls/: muelu, ifpack2, frosch; the DD's AMG coarse
// solve): the shift of an indefinite Hessian until a CG probe meets no nonpositive
// curvature, an operator wrapper that counts applications, and the test of the MPI
// runtime they need (spd_guard.cpp).
#ifndef RODNET_SHIM_SPD_GUARD_HPP
#define RODNET_SHIM_SPD_GUARD_HPP

#include <memory>
#include <string>
#include <utility>

#include "base/clock.hpp"
#include "base/shim_error.hpp"
#include "pc/preconditioner.hpp"
#include "pc/stats_operator.hpp"
#include "system/system.hpp"

namespace rodnet {

// MueLu and Ifpack2's additive Schwarz (Trilinos 13.2) need maps over a
// Teuchos::MpiComm and MPI initialised: MueLu's Hierarchy setup casts the
// communicator to an MpiComm unconditionally (a null dereference for the SerialComm
// of rodnet's serial runtime, runtime.hpp), and Ifpack2's Schwarz calls
// MPI_Comm_size (an abort before MPI_Init).  True if comm is an MpiComm.
bool mpi_backed(const Teuchos::Comm<int> &comm);

// A copy of S with t D added to the diagonal (D = |diag S| floored at 1e-8 max).
Teuchos::RCP<TCrs> shifted_copy(const TCrs &S, double t);

// Positive definiteness probe of A with the SPD preconditioner P: preconditioned CG
// from a random right-hand side for `its` iterations; false if it meets
// nonpositive curvature (p'Ap <= 0) or a nonpositive r'P r.  Every eigenvector of
// P^-1 A is in the random start, and CG's Ritz values reach the ends of the
// spectrum first, so a negative eigenvalue of A shows up in a few iterations unless
// it is tiny against the spectrum's spread (then the coarse matrix is nearly
// singular there, and the outer MINRES, not this probe, meets it).
bool probe_positive(const TCrs &A, const Tpetra::Operator<> &P, int its);

// Builds a preconditioner P of A = S + t |diag S| for t = 0 (or a hundredth of the
// last shift that worked: a buckled state stays buckled for a few Newton steps),
// 1e-8, 1e-6, ..., 1e10 until probe_positive(A, P) holds.  Throws Error if none does.
struct SpdGuard {
  double shift = 0.0;
  Teuchos::RCP<TCrs> A;
  Teuchos::RCP<Tpetra::Operator<>> P;
  static constexpr int probe_iterations = 20;

  template <class Build>
  void setup(const TCrs &S, Build &&build, const char *what) {
    double t = shift > 0.0 ? shift / 100.0 : 0.0;
    for (;;) {
      A = shifted_copy(S, t);
      P = build(A);
      if (probe_positive(*A, *P, probe_iterations)) break;
      if (t >= 1e10)
        throw Error(RN_ERR_LAPACK, std::string(what) +
                                       ": the matrix stays indefinite up to a shift of "
                                       "1e10 |diag| (non-finite entries?)");
      t = t == 0.0 ? 1e-8 : 100.0 * t;
    }
    shift = t;
  }
};

// A Preconditioner that applies an SpdGuard's P (ifpack2, frosch): the derived
// setup() builds it from the System's Hessian (guarded_setup); inverse() applies it,
// counting in stats(); shift() is the guard's t.
class GuardedPreconditioner : public Preconditioner {
public:
  Teuchos::RCP<const Tpetra::Operator<>> inverse() const override {
    if (op_.is_null()) { // one operator for the preconditioner's life (callers keep it)
      std::shared_ptr<SpdGuard> guard = guard_;
      op_ = stats_operator(
          map_, [guard](const TMV &x, TMV &y) { guard->P->apply(x, y); }, &stats_);
    }
    return op_;
  }
  double shift() const { return guard_->shift; } // t of H + t |diag H| in the last setup

protected:
  // The guard's setup on sys's Hessian with build (SpdGuard::setup), then the stats
  // of a setup that began at t0 (memory: the shifted copy of the matrix and the
  // subdomain factors, estimated at twice the matrix).
  template <class Build>
  void guarded_setup(System &sys, Build &&build, const char *what, Clock::time_point t0) {
    map_ = sys.map();
    guard_->setup(*sys.hessian(), std::forward<Build>(build), what);
    stats_.setups++;
    stats_.setup_seconds += seconds_since(t0);
    stats_.bytes = 12.0 * static_cast<double>(guard_->A->getNodeNumEntries()) * 2.0;
    stats_.shifted = guard_->shift > 0.0;
  }

private:
  std::shared_ptr<SpdGuard> guard_ = std::make_shared<SpdGuard>();
  Teuchos::RCP<const TMap> map_;
  mutable Teuchos::RCP<const Tpetra::Operator<>> op_;
};

} // namespace rodnet

#endif
