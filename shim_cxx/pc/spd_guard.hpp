// spd_guard.hpp - shared by the Trilinos preconditioners that must be symmetric
// positive definite for MINRES (multigrid.cpp: MueLu, Ifpack2; frosch.cpp: FROSch):
// the shift of an indefinite Hessian until a CG probe meets no nonpositive
// curvature, and an operator wrapper that counts applications.
#ifndef RODNET_SHIM_SPD_GUARD_HPP
#define RODNET_SHIM_SPD_GUARD_HPP

#include <chrono>
#include <string>
#include <utility>

#include "pc/preconditioner.hpp"
#include "base/shim_error.hpp"
#include "system/system.hpp"

namespace rodnet {

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

// Applies a CoarseSolver-like callable as a Tpetra operator, counting in stats.
template <class Apply>
class StatsOperator : public Tpetra::Operator<> {
public:
  StatsOperator(Teuchos::RCP<const TMap> map, Apply apply, PreconditionerStats *stats)
      : map_(std::move(map)), apply_(std::move(apply)), stats_(stats), tmp_(map_, 1) {}
  Teuchos::RCP<const TMap> getDomainMap() const override { return map_; }
  Teuchos::RCP<const TMap> getRangeMap() const override { return map_; }
  void apply(const TMV &X, TMV &Y, Teuchos::ETransp, double alpha,
             double beta) const override {
    const auto t0 = std::chrono::steady_clock::now();
    if (alpha == 1.0 && beta == 0.0) {
      apply_(X, Y);
    } else {
      if (tmp_.getNumVectors() != X.getNumVectors()) tmp_ = TMV(map_, X.getNumVectors());
      apply_(X, tmp_);
      Y.update(alpha, tmp_, beta);
    }
    stats_->applies++;
    stats_->apply_seconds +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }

private:
  Teuchos::RCP<const TMap> map_;
  Apply apply_;
  PreconditionerStats *stats_;
  mutable TMV tmp_;
};

template <class Apply>
Teuchos::RCP<const Tpetra::Operator<>> stats_operator(Teuchos::RCP<const TMap> map,
                                                      Apply apply,
                                                      const PreconditionerStats *stats) {
  return Teuchos::rcp(new StatsOperator<Apply>(std::move(map), std::move(apply),
                                               const_cast<PreconditionerStats *>(stats)));
}

} // namespace rodnet

#endif
