// monitor.cpp - stopping tests and progress (see monitor.hpp).
#include "newton/monitor.hpp"

#include <algorithm>
#include <cmath>

namespace rodnet {

Monitor::Monitor(const rn_solve_options &opt, double force_scale, double load_factor,
                 Clock::time_point start, int iteration_offset)
    : opt_(opt), force_scale_(force_scale), load_factor_(load_factor), start_(start),
      offset_(iteration_offset) {}

double Monitor::seconds() const {
  return std::chrono::duration<double>(Clock::now() - start_).count();
}

bool Monitor::converged() const {
  return reason_ == RN_STOP_GRADIENT || reason_ == RN_STOP_STEP ||
         reason_ == RN_STOP_ENERGY;
}

namespace {

// Whether the residuals at it are within max(gtol_rel * scale, kFloorFactor * floor),
// the round-off band (false without an EquilibriumView).
bool within_floor_band(const rn_solve_options &opt, const IterationView &it) {
  return it.eq.valid &&
         it.eq.force_residual <= std::max(opt.gtol_rel * it.eq.force_scale,
                                          kFloorFactor * it.eq.force_floor) &&
         it.eq.moment_residual <= std::max(opt.gtol_rel * it.eq.moment_scale,
                                           kFloorFactor * it.eq.moment_floor);
}

} // namespace

bool Monitor::equilibrium_passes(const IterationView &it) const {
  const bool abs_ok = opt_.gtol_abs == 0.0 || it.gnorm <= opt_.gtol_abs;
  if (!it.eq.valid) {
    const double scale = started_ ? g_scale_ : std::max(it.gnorm, force_scale_);
    return it.gnorm <= opt_.gtol_rel * scale && abs_ok;
  }
  if (!abs_ok) return false;
  // Below gtol_rel times the scales: converged.
  if (it.eq.force_residual <= opt_.gtol_rel * it.eq.force_scale &&
      it.eq.moment_residual <= opt_.gtol_rel * it.eq.moment_scale)
    return true;
  // Within the round-off band only: after an interior (Newton) step no longer than
  // max(gtol_rel, kBandStep) (1 + ||x||).  The band's max norm cannot tell round-off
  // from a smooth residual that a long rod turns into a large displacement; the
  // Newton step can (docs/solvers.md, "Stopping tests").  kBandStep: a gtol_rel
  // below it asks for the round-off floor, not for steps at round-off, which the
  // trust region may no longer accept.
  // A trust radius collapsed within the band: no step is accepted at round-off.
  constexpr double kBandStep = 1e-9;
  const bool small_step =
      it.iteration > 0 && it.accepted && it.unconstrained &&
      it.step_norm <= std::max(opt_.gtol_rel, kBandStep) * (1.0 + it.x_norm);
  return (small_step || it.radius_collapsed) && within_floor_band(opt_, it);
}

bool Monitor::check(const IterationView &it) {
  if (!started_) {
    g_scale_ = std::max(it.gnorm, force_scale_);
    started_ = true;
  }
  last_ = it;
  krylov_total_ += it.krylov;
  if (opt_.progress) {
    rn_iteration_info info;
    info.iteration = offset_ + it.iteration;
    info.energy = it.energy;
    info.gradient_norm = it.gnorm;
    info.radius = it.radius;
    info.krylov_iterations = it.krylov;
    info.seconds = seconds();
    info.load_factor = load_factor_;
    opt_.progress(opt_.progress_user, &info);
  }
  if (it.eq.valid) {
    force_tol_ =
        std::max(opt_.gtol_rel * it.eq.force_scale, kFloorFactor * it.eq.force_floor);
    moment_tol_ =
        std::max(opt_.gtol_rel * it.eq.moment_scale, kFloorFactor * it.eq.moment_floor);
  }
  const bool small_gradient = equilibrium_passes(it);
  const bool newton_step = it.iteration > 0 && it.accepted && it.unconstrained;
  if (!std::isfinite(it.energy) || !std::isfinite(it.gnorm)) {
    reason_ = RN_STOP_FAILED;
  } else if (opt_.interrupt && *opt_.interrupt) { // the caller asked to stop
    reason_ = RN_STOP_INTERRUPTED;
  } else if (small_gradient && !it.negative_curvature) {
    reason_ = RN_STOP_GRADIENT;
  } else if (newton_step && !it.negative_curvature &&
             it.step_norm <= opt_.step_tol * (1.0 + it.x_norm)) {
    reason_ = RN_STOP_STEP;
  } else if (opt_.energy_tol > 0.0 && newton_step && !it.negative_curvature &&
             std::fabs(it.energy_change) <=
                 opt_.energy_tol * (1.0 + std::fabs(it.energy))) {
    reason_ = RN_STOP_ENERGY;
  } else if (it.iteration >= opt_.max_iterations) {
    reason_ = RN_STOP_MAX_ITER;
  } else if (it.radius_collapsed) {
    reason_ = RN_STOP_RADIUS;
  } else {
    return false;
  }
  return true;
}

} // namespace rodnet
