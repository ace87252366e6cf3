// factor_preconditioner.cpp - Cholesky factorisation of the shifted Hessian as an SPD
// preconditioner (factor_preconditioner.hpp).
#include "pc/impls/factor/factor_preconditioner.hpp"

#include <algorithm>
#include <chrono>

#include "krylov/minres.hpp"
#include "base/shim_error.hpp"
#include "system/system_serial.hpp"

namespace rodnet {

namespace {

using Clock = std::chrono::steady_clock;

// y = alpha M^{-1} x + beta y with the factorisation.
class FactorInverse : public Tpetra::Operator<> {
public:
  FactorInverse(const Teuchos::RCP<const TMap> &map, const SpdFactor &f,
                PreconditionerStats &stats)
      : map_(map), f_(f), stats_(stats), tmp_(map, 1) {}
  Teuchos::RCP<const TMap> getDomainMap() const override { return map_; }
  Teuchos::RCP<const TMap> getRangeMap() const override { return map_; }
  void apply(const TMV &X, TMV &Y, Teuchos::ETransp /*symmetric*/, double alpha,
             double beta) const override {
    if (X.getNumVectors() != 1 || Y.getNumVectors() != 1)
      throw Error(RN_ERR_INTERNAL, "rn_solve: preconditioner applied to a block");
    const Clock::time_point t0 = Clock::now();
    const size_t n = X.getLocalLength();
    const double *in = host_data(X);
    double *out = host_data(tmp_);
    std::copy(in, in + n, out);
    f_.solve(out);
    Y.update(alpha, tmp_, beta);
    ++stats_.applies;
    stats_.apply_seconds += std::chrono::duration<double>(Clock::now() - t0).count();
  }

private:
  Teuchos::RCP<const TMap> map_;
  const SpdFactor &f_;
  PreconditionerStats &stats_;
  mutable TMV tmp_;
};

} // namespace

void FactorPreconditioner::setup(System &sys) {
  auto *serial = dynamic_cast<SerialSystem *>(&sys);
  if (!serial)
    throw Error(RN_ERR_ARG, "rn_solve: the factor preconditioner works on one rank only");
  const Clock::time_point t0 = Clock::now();
  Problem &p = serial->problem();
  if (!factor_) factor_ = make_spd_factor(p, kind_);
  if (metric_d_.empty()) metric_d_ = hessian_metric(p);
  if (metric_.empty() || metric_version_ != p.pattern_version()) {
    metric_ = diagonal_on_pattern(p, metric_d_);
    metric_version_ = p.pattern_version();
  }
  sigma_ = factor_shifted(*factor_, p, 0.0, metric_.data());
  if (op_.is_null()) op_ = Teuchos::rcp(new FactorInverse(sys.map(), *factor_, stats_));
  ++stats_.setups;
  stats_.shifted = sigma_ > 0.0;
  stats_.setup_seconds += std::chrono::duration<double>(Clock::now() - t0).count();
}

} // namespace rodnet
