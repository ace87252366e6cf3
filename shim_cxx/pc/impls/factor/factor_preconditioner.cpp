// factor_preconditioner.cpp - Cholesky factorisation of the shifted Hessian as an SPD
// preconditioner (factor_preconditioner.hpp).
#include "pc/impls/factor/factor_preconditioner.hpp"

#include "base/clock.hpp"
#include "base/shim_error.hpp"
#include "krylov/minres.hpp"
#include "pc/stats_operator.hpp"
#include "system/system_serial.hpp"

namespace rodnet {

std::unique_ptr<Preconditioner> make_factor_preconditioner(const System &sys,
                                                           rn_factorization kind) {
  if (!dynamic_cast<const SerialSystem *>(&sys))
    throw Error(RN_ERR_ARG, "rn_solve: the factor preconditioner works on one rank only; "
                            "use dd or local (docs/parallel.md)");
  return std::make_unique<FactorPreconditioner>(kind);
}

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
  if (op_.is_null()) {
    const SpdFactor *f = factor_.get(); // made once
    op_ = stats_operator(
        sys.map(),
        [f](const TMV &x, TMV &y) {
          if (x.getNumVectors() != 1 || y.getNumVectors() != 1)
            throw Error(RN_ERR_INTERNAL, "rn_solve: preconditioner applied to a block");
          y.assign(x);
          f->solve(host_data(y));
        },
        &stats_);
  }
  ++stats_.setups;
  stats_.shifted = sigma_ > 0.0;
  stats_.setup_seconds += seconds_since(t0);
}

} // namespace rodnet
