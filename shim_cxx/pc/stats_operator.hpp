// stats_operator.hpp - a preconditioner's M^{-1} as a Tpetra operator from a callable
// y = M^{-1} x, counting its applications and their time in the preconditioner's
// stats (every preconditioner of pc/impls/ but the DD, which counts its own).
#ifndef RODNET_SHIM_STATS_OPERATOR_HPP
#define RODNET_SHIM_STATS_OPERATOR_HPP

#include <utility>

#include "base/clock.hpp"
#include "pc/preconditioner.hpp"

namespace rodnet {

// Applies apply(x, y) (y = M^{-1} x) as a Tpetra operator, y = alpha M^{-1} x + beta y,
// counting in stats.
template <class Apply>
class StatsOperator : public Tpetra::Operator<> {
public:
  StatsOperator(Teuchos::RCP<const TMap> map, Apply apply, PreconditionerStats *stats)
      : map_(std::move(map)), apply_(std::move(apply)), stats_(stats), tmp_(map_, 1) {}
  Teuchos::RCP<const TMap> getDomainMap() const override { return map_; }
  Teuchos::RCP<const TMap> getRangeMap() const override { return map_; }
  void apply(const TMV &X, TMV &Y, Teuchos::ETransp, double alpha,
             double beta) const override {
    const Clock::time_point t0 = Clock::now();
    if (alpha == 1.0 && beta == 0.0) {
      apply_(X, Y);
    } else {
      if (tmp_.getNumVectors() != X.getNumVectors()) tmp_ = TMV(map_, X.getNumVectors());
      apply_(X, tmp_);
      Y.update(alpha, tmp_, beta);
    }
    stats_->applies++;
    stats_->apply_seconds += seconds_since(t0);
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
