// monitor.hpp - stopping tests and progress reporting shared by every solver kind.
//
// Each solver calls Monitor::check() once per Newton iteration (and once for the
// starting point, iteration 0) with what it knows about the current iterate; the
// monitor calls the user's progress callback and decides whether to stop:
//  - gradient (equilibrium on a physical scale, equilibrium.hpp): the largest force
//    residual (|g_i| over position DOFs) at most gtol_rel * force_scale and the
//    largest moment residual (angles, joint rotations) at most gtol_rel *
//    moment_scale (the scales: the loads, reactions and internal moment of the
//    state); or, where kFloorFactor times the round-off floor is larger, both within
//    max(gtol_rel * scale, kFloorFactor * floor) after an interior step (or at a
//    collapsed radius), ||s|| <= max(gtol_rel, 1e-9) (1 + ||x||) (a max norm cannot
//    tell round-off from a smooth residual; the Newton step can).  If gtol_abs > 0,
//    ||g|| <= gtol_abs is required too.  Only without significant negative
//    curvature (a saddle with a small gradient is not a minimum).  A solver that
//    provides no EquilibriumView falls back to ||g|| <= gtol_rel * max(||g_0||, f)
//    (g_0 the gradient at the start of the load step, f = the out-of-balance force
//    at the solve's start).
//  - step: after an accepted step that the globalisation did not shorten,
//    ||s|| <= step_tol (1 + ||x||).
//  - energy: after such a step, |dE| <= energy_tol (1 + |E|).
//  - max_iterations (per load step) and a collapsed trust radius: not converged.
#ifndef RODNET_SHIM_MONITOR_HPP
#define RODNET_SHIM_MONITOR_HPP

#include <chrono>

#include "system/equilibrium.hpp"
#include "rodnet_solve.h"

namespace rodnet {

using Clock = std::chrono::steady_clock;

struct IterationView {
  int iteration = 0;          // iterations done in this load step
  double energy = 0.0;        // at the current (accepted) iterate
  double gnorm = 0.0;         // Euclidean norm of the gradient there
  double radius = 0.0;        // trust radius (0 for line search)
  int krylov = 0;             // Krylov iterations of the last iteration
  bool accepted = false;      // the last iteration moved the iterate
  bool unconstrained = false; // ... by a step the globalisation did not shorten
  double step_norm = 0.0;     // Euclidean norm of that step
  double x_norm = 0.0;        // Euclidean norm of the iterate
  double energy_change = 0.0;
  bool negative_curvature = false; // significant negative curvature seen at x
  bool radius_collapsed = false;
  EquilibriumView eq; // residual on the physical scale at the current iterate
};

// A residual within this factor of the round-off floor counts as zero (measured:
// the residual of Newton's method stagnates at 1 to 4 times the floor estimate).
constexpr double kFloorFactor = 10.0;

class Monitor {
public:
  Monitor(const rn_solve_options &opt, double force_scale, double load_factor,
          Clock::time_point start, int iteration_offset);

  // Reports progress; returns true when a stopping test fires (see reason()).
  bool check(const IterationView &it);
  // Whether the gradient (equilibrium) test would pass at it, curvature aside; no
  // side effects.
  bool equilibrium_passes(const IterationView &it) const;

  rn_solve_stop reason() const { return reason_; }
  bool converged() const;
  int iterations() const { return last_.iteration; }
  double energy() const { return last_.energy; }
  double gradient_norm() const { return last_.gnorm; }
  double g_scale() const { return g_scale_; }
  // The residual at the last iterate checked and the tolerances it was tested
  // against (force_tol, moment_tol; 0 when no EquilibriumView was given).
  const EquilibriumView &equilibrium() const { return last_.eq; }
  double force_tolerance() const { return force_tol_; }
  double moment_tolerance() const { return moment_tol_; }
  // Krylov iterations reported so far (sum of IterationView::krylov).
  long krylov_total() const { return krylov_total_; }
  double seconds() const;

private:
  const rn_solve_options &opt_;
  double force_scale_, g_scale_ = 0.0, load_factor_;
  double force_tol_ = 0.0, moment_tol_ = 0.0;
  Clock::time_point start_;
  int offset_;
  bool started_ = false;
  long krylov_total_ = 0;
  IterationView last_;
  rn_solve_stop reason_ = RN_STOP_FAILED;
};

} // namespace rodnet

#endif
