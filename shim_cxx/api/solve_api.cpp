// solve_api.cpp - extern "C" entry points of rodnet_solve.h: options, names of stop
// reasons and factorisations (those of solver kinds and preconditioners read the
// registry, c_api/registry/registry.c), rn_solve with load stepping, Hessian eigenvalue.
// Every entry catches all exceptions; none crosses into C.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <string>
#include <vector>

#include <Teuchos_CommHelpers.hpp>

#include "factor/banded.hpp"
#include "newton/dist_predictor.hpp"
#include "system/dist_system.hpp"
#include "newton/monitor.hpp"
#include "base/nonconservative.hpp"
#include "continuation/path.hpp"
#include "newton/predictor.hpp"
#include "system/problem.hpp"
#include "rodnet_ramp.h"
#include "rodnet_solve.h"
#include "rodnet_registry.h"
#include "base/runtime.hpp"
#include "base/shim_error.hpp"
#include "base/snapshot.hpp"
#include "newton/solvers.hpp"
#include "factor/spd_factor.hpp"
#include "rodnet_couple.h"
#include "eigen/stability.hpp"

namespace rodnet {
namespace {

// The integer value of a C enum field.  A C caller may store any int in it; read as
// the C++ enum type, a value outside the enumerators' range is undefined behaviour.
template <class Enum>
int enum_value(const Enum &e) {
  static_assert(sizeof(Enum) == sizeof(int), "C enums are int-sized");
  int v = 0;
  std::memcpy(&v, &e, sizeof v);
  return v;
}

// The enumerator of kinds whose name_of is name (RN_ERR_ARG if none).
template <class Enum, size_t N>
rn_status value_of_name(const char *name, const Enum (&kinds)[N],
                        const char *(*name_of)(Enum), Enum *out) {
  if (!name || !out) return RN_ERR_ARG;
  for (Enum kind : kinds)
    if (std::strcmp(name, name_of(kind)) == 0) {
      *out = kind;
      return RN_OK;
    }
  return RN_ERR_ARG;
}

rn_status validate_options(const rn_solve_options &o, rn_context *ctx) {
  const char *bad = nullptr;
  const int kind = enum_value(o.solver), precond = enum_value(o.preconditioner);
  if (kind < 0 || !rn_solver_info_at(static_cast<size_t>(kind)))
    bad = "unknown solver kind";
  else if (o.max_iterations < 1)
    bad = "max_iterations must be >= 1";
  else if (!(o.gtol_rel >= 0.0) || !std::isfinite(o.gtol_rel))
    bad = "gtol_rel must be >= 0";
  else if (!(o.gtol_abs >= 0.0) || !std::isfinite(o.gtol_abs))
    bad = "gtol_abs must be >= 0";
  else if (!(o.step_tol >= 0.0) || !std::isfinite(o.step_tol))
    bad = "step_tol must be >= 0";
  else if (!(o.energy_tol >= 0.0) || !std::isfinite(o.energy_tol))
    bad = "energy_tol must be >= 0";
  else if (o.krylov_max_iterations < 1)
    bad = "krylov_max_iterations must be >= 1";
  else if (!(o.krylov_tol > 0.0 && o.krylov_tol < 1.0))
    bad = "krylov_tol must be in (0, 1)";
  else if (!(o.forcing >= 0.0 && o.forcing < 1.0))
    bad = "forcing must be 0 (Eisenstat-Walker) or in (0, 1)";
  else if (!(o.initial_radius >= 0.0) || !std::isfinite(o.initial_radius))
    bad = "initial_radius must be >= 0 (0: automatic)";
  else if (o.load_steps < 0)
    bad = "load_steps must be >= 0";
  else if (o.max_load_cuts < 0 || o.max_load_cuts > 60)
    bad = "max_load_cuts must be in [0, 60]";
  else if (enum_value(o.factorization) != RN_FACTOR_AUTO &&
           enum_value(o.factorization) != RN_FACTOR_BANDED &&
           enum_value(o.factorization) != RN_FACTOR_SPARSE &&
           enum_value(o.factorization) != RN_FACTOR_CHOLMOD)
    bad = "unknown factorization";
  else if (o.predictor != 0 && o.predictor != 1)
    bad = "predictor must be 0 or 1";
  else if (o.stability != 0 && o.stability != 1)
    bad = "stability must be 0 or 1";
  else if (o.stability_method < RN_STABILITY_AUTO ||
           o.stability_method > RN_STABILITY_LOBPCG)
    bad = "unknown stability_method";
  else if (precond < 0 || !rn_preconditioner_info_at(static_cast<size_t>(precond)))
    bad = "unknown preconditioner";
  if (!bad) return RN_OK;
  return rn_context_set_error(ctx, RN_ERR_ARG, "rn_solve: %s", bad);
}

// Totals over the load steps of one rn_solve.
struct SolveTotals {
  int iterations = 0, load_steps = 0, predictor_steps = 0;
  long krylov = 0;
  rn_solve_stop stop = RN_STOP_FAILED;
  double energy = 0.0, gnorm = 0.0;
  rn_factorization factorization = RN_FACTOR_AUTO;
  EquilibriumView eq; // at the last iterate checked
  double force_tol = 0.0, moment_tol = 0.0;
  rn_preconditioner preconditioner = RN_PRECOND_AUTO;
  DistSystem *dist = nullptr; // the System of a part (nullptr: a whole network)
  // tr-krylov's System and preconditioner for the load step in progress: made by its
  // predictor or its trust region, whichever comes first, and dropped when the load
  // step ends (the next one starts from a set-up at its own state).
  std::unique_ptr<KrylovWorkspace> krylov_ws;
  // The last load step's tr-krylov workspace, its preconditioner set up at the state
  // the load step returned: the stability check's LOBPCG preconditioner (not set up
  // a second time); dropped when the next workspace is made.
  std::unique_ptr<KrylovWorkspace> last_ws;
  KrylovWorkspace &krylov_workspace(Problem &p, const rn_solve_options &opt) {
    if (!krylov_ws) {
      last_ws.reset();
      krylov_ws = std::make_unique<KrylovWorkspace>(p, dist, opt);
    }
    return *krylov_ws;
  }
};

// The flags of the solver kind's row (rodnet_registry.h; validate_options checked it).
unsigned solver_flags(rn_solver_kind k) { return rn_solver_info_of(k)->flags; }

// Whether a load step starts with the predictor (opt.predictor; rol-lbfgs uses
// gradients only: no predictor, which would factor the Hessian).
bool uses_predictor(const rn_solve_options &opt) {
  return opt.predictor && (solver_flags(opt.solver) & RN_SOLVER_PREDICTOR);
}

// The load-step predictor from t_prev to t (predictor.hpp): true if its state was
// accepted (the network at t either way).  With tr-krylov it uses its preconditioner
// and MINRES, distributed on a part; the other kinds factor the whole Hessian.
bool run_predictor(Problem &p, const rn_solve_options &opt, double t_prev, double t,
                   SolveTotals &tot) {
  bool accepted = false;
  if (tot.dist) {
    KrylovWorkspace &ws = tot.krylov_workspace(p, opt);
    accepted = predict_load_step(*tot.dist, ws.preconditioner(), opt, t_prev, t);
    ws.account();
  } else if (opt.solver == RN_SOLVER_TR_KRYLOV) {
    accepted = predict_step_krylov(p, tot.krylov_workspace(p, opt), opt, t_prev, t);
  } else {
    accepted = predict_load_step(p, tot.factorization, t_prev, t);
  }
  if (accepted) ++tot.predictor_steps;
  return accepted;
}

// One minimisation at load factor t from the current state (the predictor's, if
// predicted), converged at t_prev (0: the starting state); first the predictor
// (uses_predictor) unless predicted.
bool solve_load_step(Problem &p, const rn_solve_options &opt, double t_prev, double t,
                     double force_scale, Clock::time_point start, SolveTotals &tot,
                     bool predicted = false) {
  if (!predicted && uses_predictor(opt)) run_predictor(p, opt, t_prev, t, tot);
  check_status(rn_network_set_load_factor(p.network(), t), "rn_network_set_load_factor");
  Monitor mon(opt, force_scale, t, start, tot.iterations);
  switch (opt.solver) {
  case RN_SOLVER_TR_MINRES:
    run_tr_minres(p, mon, opt);
    break;
  case RN_SOLVER_ROL_TR_TCG:
    run_rol_tr_tcg(p, mon, opt);
    break;
  case RN_SOLVER_ROL_LS_NEWTON:
    run_rol_ls_newton(p, mon, opt);
    break;
  case RN_SOLVER_ROL_LBFGS:
    run_rol_lbfgs(p, mon, opt);
    break;
  case RN_SOLVER_TR_KRYLOV:
    tot.preconditioner = run_tr_krylov(tot.krylov_workspace(p, opt), mon, opt);
    break;
  case RN_SOLVER_NOX:
    tot.preconditioner = tot.dist ? run_nox(*tot.dist, mon, opt) : run_nox(p, mon, opt);
    break;
  }
  if (opt.solver == RN_SOLVER_TR_KRYLOV) // (its trust region set it up last)
    tot.last_ws = std::move(tot.krylov_ws);
  tot.krylov_ws.reset();
  tot.iterations += mon.iterations();
  tot.krylov += mon.krylov_total();
  tot.load_steps += 1;
  tot.stop = mon.reason();
  tot.energy = mon.energy();
  tot.gnorm = mon.gradient_norm();
  tot.eq = mon.equilibrium();
  tot.force_tol = mon.force_tolerance();
  tot.moment_tol = mon.moment_tolerance();
  return mon.converged();
}

// The sub-step rule of a load step (docs/solvers.md, "Prescribed motions of any
// size"): within one sub-step no prescribed rotation turns by more than kRampAngle
// and the first trial state shortens no rod edge along itself by more than
// kRampShortening of its length.  The trial state is the predictor's where it is
// accepted (the interior moved with the prescribed motion), else the jumped one (free
// DOFs held).  kRampMaxSubsteps bounds the sub-steps of one load step, kRampDepth the
// nested splits.
constexpr double kRampShortening = 0.5;
constexpr double kRampAngle = 0.7853981633974483; // pi/4
constexpr int kRampMaxSubsteps = 1 << 16;
constexpr int kRampDepth = 8;

// The largest of v over the parts of a distributed network (v on a whole network).
double max_over_parts(const SolveTotals &tot, double v) {
  if (!tot.dist) return v;
  double all = v;
  Teuchos::reduceAll(*tot.dist->comm(), Teuchos::REDUCE_MAX, v, Teuchos::outArg(all));
  return all;
}

// Sub-steps for a measure (need = measure / limit): at least 1, at most
// kRampMaxSubsteps (also for an infinite or NaN measure).
int substeps_for(double need) {
  return !(need <= kRampMaxSubsteps) ? kRampMaxSubsteps
                                     : std::max(1, static_cast<int>(std::ceil(need)));
}

// Whether the network (a part: its owned rods) holds rod ir's current state.
bool owns_rod(const rn_network *net, int part, int ir) {
  return rn_network_rod_owner(net, ir) == part;
}

// The network's part (0: a whole network).
int part_of(const rn_network *net) {
  rn_part_info info;
  check_status(rn_network_part_info(net, &info), "rn_network_part_info");
  return info.part;
}

// The current vertex positions of the rods the network owns, rod after rod.
std::vector<double> rod_positions(const rn_network *net) {
  std::vector<double> xyz;
  const int part = part_of(net);
  for (int ir = 0, nr = rn_network_num_rods(net); ir < nr; ++ir) {
    if (!owns_rod(net, part, ir)) continue;
    const size_t at = xyz.size();
    xyz.resize(at + 3 * static_cast<size_t>(rn_network_rod_num_vertices(net, ir)));
    check_status(rn_network_rod_vertices(net, ir, xyz.data() + at),
                 "rn_network_rod_vertices");
  }
  return xyz;
}

// The largest shortening of a rod edge along itself over its length from positions
// a to b (rod_positions of the same network): -(e_b - e_a) . e_a / |e_a|^2, > 1 where
// the edge turned over (HUGE_VAL for a zero-length edge that changes).
double largest_shortening(const rn_network *net, const std::vector<double> &a,
                          const std::vector<double> &b) {
  double ratio = 0.0;
  size_t v0 = 0;
  const int part = part_of(net);
  for (int ir = 0, nr = rn_network_num_rods(net); ir < nr; ++ir) {
    if (!owns_rod(net, part, ir)) continue;
    const int nv = rn_network_rod_num_vertices(net, ir);
    const int ne = rn_network_rod_is_closed(net, ir) == 1 ? nv : nv - 1;
    for (int j = 0; j < ne; ++j) {
      const size_t i0 = 3 * (v0 + j), i1 = 3 * (v0 + (j + 1) % nv);
      double e2 = 0.0, de = 0.0;
      for (int k = 0; k < 3; ++k) {
        const double e = a[i1 + k] - a[i0 + k];
        e2 += e * e;
        de += ((b[i1 + k] - b[i0 + k]) - e) * e;
      }
      if (de < 0.0) ratio = e2 > 0.0 ? std::max(ratio, -de / e2) : HUGE_VAL;
      if (std::isnan(de)) ratio = HUGE_VAL;
    }
    v0 += static_cast<size_t>(nv);
  }
  return ratio;
}

// Sub-steps of a load step from t_prev to t (each a load step of its own) so that
// the first trial state of each is never one where the prescribed motion jumped past
// the edges next to it: the rule above, applied again within each sub-step.
bool ramped_load_step(Problem &p, const rn_solve_options &opt, double t_prev, double t,
                      double force_scale, Clock::time_point start, SolveTotals &tot,
                      int depth = 0) {
  rn_network *net = p.network();
  // The free DOFs belong to t_prev after a load step and to load factor 0 for the
  // initial geometry; when rn_solve is called again at a larger load factor they
  // belong to the last one converged, between t_prev = 0 and t: the prescribed
  // motion jumps from there (rn_network_dofs_load_factor), and sub-steps go on from
  // there too.
  const double t_x = rn_network_dofs_load_factor(net);
  const double from =
      (t_x > std::min(t_prev, t) && t_x < std::max(t_prev, t)) ? t_x : t_prev;
  double stretch = 0.0, angle = 0.0;
  rn_status st = rn_network_load_step_size(net, from, t, &stretch, &angle);
  if (tot.dist) st = tot.dist->agree(st); // an error on any part throws on all
  check_status(st, "rn_network_load_step_size");
  int n = substeps_for(max_over_parts(tot, angle) / kRampAngle);
  bool predicted = false;
  // (an edge's shortening over its length is at most its stretch)
  if (n == 1 && max_over_parts(tot, stretch) > kRampShortening && depth < kRampDepth) {
    Snapshot before;
    before.save(net);
    // (the network itself may sit at the target load factor, finalize's)
    check_status(rn_network_set_load_factor(net, from), "rn_network_set_load_factor");
    const std::vector<double> x0 = rod_positions(net);
    check_status(rn_network_set_load_factor(net, t), "rn_network_set_load_factor");
    const double held =
        max_over_parts(tot, largest_shortening(net, x0, rod_positions(net)));
    before.restore(net);
    if (held > kRampShortening) { // the jumped state is too far: try the predictor's
      if (uses_predictor(opt) && run_predictor(p, opt, t_prev, t, tot)) {
        const double r =
            max_over_parts(tot, largest_shortening(net, x0, rod_positions(net)));
        predicted = r <= kRampShortening;
        if (!predicted) n = std::max(2, substeps_for(r / kRampShortening));
      } else {
        n = substeps_for(held / kRampShortening);
      }
      if (!predicted) before.restore(net);
    }
  }
  if (n == 1)
    return solve_load_step(p, opt, t_prev, t, force_scale, start, tot, predicted);
  for (int k = 1; k <= n; ++k) {
    const double a = k == 1 ? from : from + (t - from) * static_cast<double>(k - 1) / n;
    const double b = k == n ? t : from + (t - from) * static_cast<double>(k) / n;
    if (!ramped_load_step(p, opt, a, b, force_scale, start, tot, depth + 1)) return false;
  }
  return true;
}

// Fixed continuation: load_steps equal increments up to the target.
void fixed_stepping(Problem &p, const rn_solve_options &opt, double target,
                    double force_scale, Clock::time_point start, SolveTotals &tot) {
  for (int k = 1; k <= opt.load_steps; ++k) {
    const double t =
        target * static_cast<double>(k) / static_cast<double>(opt.load_steps);
    const double t_prev =
        target * static_cast<double>(k - 1) / static_cast<double>(opt.load_steps);
    if (!ramped_load_step(p, opt, t_prev, t, force_scale, start, tot)) return;
  }
}

// Nothing depends on the load factor: no applied loads, no prescribed motions, not a
// periodic cell, no couple fixed in space, and a zero load increment (a knot, a ring
// with rest curvature, a free relaxation).  A smaller load step would then solve the
// same problem again, so automatic_stepping does not cut a failed attempt back.  x:
// work space of the network's size.  Collective over the ranks of a part.
bool nothing_depends_on_load(rn_network *net, Problem &p, DistSystem *dist,
                             std::vector<double> &x, double target) {
  double stretch = 0.0, angle = 0.0, fload = 0.0, mload = 0.0, dgmax = 0.0;
  int dim = 0;
  rn_status st = rn_network_load_step_size(net, 0.0, target, &stretch, &angle);
  if (st == RN_OK) st = rn_network_applied_load_max(net, &fload, &mload);
  if (st == RN_OK) st = rn_network_cell_info(net, &dim, nullptr, nullptr, nullptr);
  if (st == RN_OK && !dist) {
    std::vector<double> dg(p.size());
    st = rn_network_load_increment(net, x.data(), 0.0, target, dg.data());
    for (double v : dg) dgmax = std::max(dgmax, std::fabs(v));
  }
  int moving = st != RN_OK || stretch != 0.0 || angle != 0.0 || fload != 0.0 ||
                       mload != 0.0 || dim != 0 ||
                       rn_network_fixed_couples(net, nullptr, nullptr) > 0
                   ? 1
                   : 0;
  if (dist) { // (collective)
    TMV xd(dist->map(), 1), dg(dist->map(), 1);
    dist->get_state(xd);
    dist->load_increment(xd, 0.0, target, dg);
    Teuchos::Array<double> nrm(1);
    dg.normInf(nrm());
    dgmax = nrm[0];
    int any = 0;
    Teuchos::reduceAll(*world_comm(), Teuchos::REDUCE_MAX, moving, Teuchos::outArg(any));
    moving = any;
  }
  return !moving && dgmax == 0.0;
}

// Automatic continuation: the full step first; on failure back to the last converged
// state (its snapshot: exact, reference frames and joint rotations included) with
// half the increment (at most max_load_cuts times), doubling it again after each
// success.
void automatic_stepping(Problem &p, const rn_solve_options &opt, double target,
                        double force_scale, Clock::time_point start, SolveTotals &tot,
                        bool load_free) {
  Snapshot done;
  done.save(p.network());
  double t_done = 0.0, inc = target;
  int cuts = 0;
  for (;;) {
    const double t = (target - t_done <= inc) ? target : t_done + inc;
    if (ramped_load_step(p, opt, t_done, t, force_scale, start, tot)) {
      if (t >= target) return;
      t_done = t;
      done.save(p.network());
      inc *= 2.0;
    } else {
      if (tot.stop == RN_STOP_INTERRUPTED) return; // the caller stops: no load cut
      if (cuts >= opt.max_load_cuts || target <= 0.0 || load_free) return;
      ++cuts;
      inc *= 0.5;
      done.restore(p.network());
    }
  }
}

void fill_report(const Problem &p, const SolveTotals &tot, double g0, double seconds,
                 rn_solve_report *rep) {
  const Counters &c = tot.dist ? tot.dist->counters : p.counters;
  rep->status = RN_OK;
  rep->stop = tot.stop;
  rep->converged = (tot.stop == RN_STOP_GRADIENT || tot.stop == RN_STOP_STEP ||
                    tot.stop == RN_STOP_ENERGY);
  rep->iterations = tot.iterations;
  rep->energy_evals = c.energy;
  rep->gradient_evals = c.gradient;
  rep->hvp_evals = c.hvp;
  rep->hessian_evals = c.hessian;
  rep->factorizations = c.factorizations;
  rep->krylov_iterations = tot.krylov;
  rep->load_steps = tot.load_steps;
  rep->energy = tot.energy;
  rep->gradient_norm = tot.gnorm;
  rep->initial_gradient_norm = g0;
  rep->time_s = seconds;
  rep->factorization = tot.factorization;
  rep->predictor_steps = tot.predictor_steps;
  rep->force_residual = tot.eq.force_residual;
  rep->moment_residual = tot.eq.moment_residual;
  rep->force_scale = tot.eq.force_scale;
  rep->moment_scale = tot.eq.moment_scale;
  rep->force_tolerance = tot.force_tol;
  rep->moment_tolerance = tot.moment_tol;
  rep->preconditioner = tot.preconditioner;
  rep->hessian_seconds = c.hessian_seconds;
  rep->preconditioner_setup_seconds = c.setup_seconds;
  rep->preconditioner_apply_seconds = c.apply_seconds;
}

void solve(rn_network *net, const rn_solve_options &opt, rn_solve_report *rep) {
  ensure_runtime(); // one-time cost, not part of the solve time
  const Clock::time_point start = Clock::now();
  Problem p(net);
  const double target = rn_network_load_factor(net);
  std::vector<double> x(p.size()), g(p.size());
  check_status(rn_network_get_dofs(net, x.data()), "rn_network_get_dofs");
  // A part of a distributed network: its System on all ranks (collective from here;
  // its graph is built once for the solve), the gradient norm over all ranks.
  std::unique_ptr<DistSystem> dist;
  if (rn_network_is_part(net)) dist = std::make_unique<DistSystem>(net, world_comm());
  // The gradient norm at the start (the fallback scale of the stopping test).  A
  // prescribed motion that jumps past the edges next to it makes the state at the
  // target degenerate: then the scale is taken at load factor 0 (the solve ramps
  // the motion in sub-steps, ramped_load_step); degenerate there too is bad input.
  double force_scale = 0.0;
  auto start_gradient = [&](double *scale) {
    if (dist) {
      TMV xd(dist->map(), 1), gd(dist->map(), 1);
      dist->get_state(xd);
      if (dist->gradient(xd, nullptr, gd) != RN_OK) return false;
      Teuchos::Array<double> nrm(1);
      gd.norm2(nrm());
      *scale = nrm[0];
      return true;
    }
    if (p.gradient(x.data(), nullptr, g.data()) != RN_OK) return false;
    *scale = norm2(p.size(), g.data());
    return true;
  };
  const bool start_at_target = start_gradient(&force_scale);
  if (!start_at_target) {
    bool ok = target > 0.0;
    if (ok) {
      check_status(rn_network_set_load_factor(net, 0.0), "rn_network_set_load_factor");
      ok = start_gradient(&force_scale);
      check_status(rn_network_set_load_factor(net, target), "rn_network_set_load_factor");
    }
    if (!ok) throw Error(RN_ERR_GEOMETRY, "rn_solve: the starting state is degenerate");
  }
  SolveTotals tot;
  tot.dist = dist.get();
  tot.factorization = choose_factor_kind(p, opt.factorization);
  if ((dist ? static_cast<size_t>(dist->global_size()) : p.size()) == 0) {
    // every DOF is prescribed: nothing to solve
    double E = 0.0;
    rn_status st = RN_OK;
    if (dist) {
      TMV xd(dist->map(), 1);
      dist->get_state(xd);
      st = dist->energy(xd, &E);
    } else {
      st = p.energy(x.data(), &E);
    }
    if (st != RN_OK)
      throw Error(RN_ERR_GEOMETRY, "rn_solve: the prescribed state is degenerate");
    tot.stop = RN_STOP_GRADIENT;
    tot.energy = E;
  } else if (opt.load_steps > 0) {
    fixed_stepping(p, opt, target, force_scale, start, tot);
  } else {
    // Decided at a start that is not degenerate at the target.
    const bool load_free = target > 0.0 && start_at_target &&
                           nothing_depends_on_load(net, p, dist.get(), x, target);
    automatic_stepping(p, opt, target, force_scale, start, tot, load_free);
  }
  // The last workspace serves the LOBPCG check only: not held through a Cholesky one
  if (!rep || !opt.stability || (!dist && opt.stability_method == RN_STABILITY_CHOLESKY))
    tot.last_ws.reset();
  if (rep) {
    fill_report(p, tot, force_scale,
                std::chrono::duration<double>(Clock::now() - start).count(), rep);
    // the stability of the returned state (LOBPCG on a part: collective); none
    // after an interrupt (the caller asked to stop)
    if (opt.stability && tot.stop != RN_STOP_INTERRUPTED) {
      if (!dist) {
        check_status(rn_network_get_dofs(net, x.data()), "rn_network_get_dofs");
        p.assemble_hessian(x.data());
      }
      rep->stability =
          solve_stability(p, dist.get(), opt, tot.factorization, tot.last_ws.get());
      rep->stability.verified_minimum = rep->stability.verified_minimum && rep->converged;
    }
  }
}

// Runs f; converts any exception to a status with the message in the context.
template <class F>
rn_status guarded(rn_network *net, const char *where, F &&f) {
  rn_context *ctx = net ? rn_network_context(net) : nullptr;
  try {
    f();
    return RN_OK;
  } catch (const Error &e) {
    if (e.recorded()) return e.status();
    return ctx ? rn_context_set_error(ctx, e.status(), "%s", e.what()) : e.status();
  } catch (const std::bad_alloc &) {
    return ctx ? rn_context_set_error(ctx, RN_ERR_ALLOC, "%s: out of memory", where)
               : RN_ERR_ALLOC;
  } catch (const std::exception &e) {
    return ctx ? rn_context_set_error(ctx, RN_ERR_TRILINOS, "%s: %s", where, e.what())
               : RN_ERR_TRILINOS;
  } catch (...) {
    return ctx ? rn_context_set_error(ctx, RN_ERR_SOLVER, "%s: unknown exception", where)
               : RN_ERR_SOLVER;
  }
}

} // namespace
} // namespace rodnet

using rodnet::guarded;

extern "C" {

void rn_solve_options_default(rn_solve_options *opt) {
  if (!opt) return;
  std::memset(opt, 0, sizeof *opt);
  opt->solver = RN_SOLVER_TR_MINRES;
  opt->max_iterations = 200;
  opt->gtol_rel = 1e-9;
  opt->gtol_abs = 0.0;
  opt->step_tol = 1e-12;
  opt->energy_tol = 0.0; // off: a tiny energy change does not certify equilibrium
  opt->krylov_max_iterations = 500;
  opt->krylov_tol = 1e-10;
  opt->forcing = 0.0;
  opt->initial_radius = 0.0;
  opt->load_steps = 0;
  opt->max_load_cuts = 8;
  opt->progress = nullptr;
  opt->progress_user = nullptr;
  opt->factorization = RN_FACTOR_AUTO;
  opt->predictor = 1;
  opt->preconditioner = RN_PRECOND_AUTO;
  opt->stability = 1;
  opt->stability_method = RN_STABILITY_AUTO;
  opt->interrupt = nullptr;
}

const char *rn_solve_stop_name(rn_solve_stop s) {
  switch (rodnet::enum_value(s)) {
  case RN_STOP_GRADIENT:
    return "gradient";
  case RN_STOP_STEP:
    return "step";
  case RN_STOP_ENERGY:
    return "energy";
  case RN_STOP_MAX_ITER:
    return "max_iterations";
  case RN_STOP_RADIUS:
    return "radius";
  case RN_STOP_FAILED:
    return "failed";
  case RN_STOP_INTERRUPTED:
    return "interrupted";
  }
  return "unknown";
}

const char *rn_factorization_name(rn_factorization f) {
  switch (rodnet::enum_value(f)) {
  case RN_FACTOR_AUTO:
    return "auto";
  case RN_FACTOR_BANDED:
    return "banded";
  case RN_FACTOR_SPARSE:
    return "sparse";
  case RN_FACTOR_CHOLMOD:
    return "cholmod";
  }
  return "unknown";
}

rn_status rn_factorization_from_name(const char *name, rn_factorization *f) {
  const rn_factorization kinds[] = {RN_FACTOR_AUTO, RN_FACTOR_BANDED, RN_FACTOR_SPARSE,
                                    RN_FACTOR_CHOLMOD};
  return rodnet::value_of_name(name, kinds, rn_factorization_name, f);
}

rn_status rn_solve(rn_network *net, const rn_solve_options *opt, rn_solve_report *rep) {
  if (rep) {
    std::memset(rep, 0, sizeof *rep);
    rep->stop = RN_STOP_FAILED;
  }
  if (!net) {
    if (rep) rep->status = RN_ERR_ARG;
    return RN_ERR_ARG;
  }
  rn_solve_options defaults;
  rn_solve_options_default(&defaults);
  const rn_solve_options &o = opt ? *opt : defaults;
  rn_status s = rodnet::validate_options(o, rn_network_context(net));
  if (s == RN_OK && rn_network_is_part(net) && !rn_solver_is_distributed(o.solver))
    s = rn_context_set_error(
        rn_network_context(net), RN_ERR_ARG,
        "rn_solve: solver '%s' needs the whole network on one process; "
        "a part of a distributed network needs a distributed solver "
        "(docs/parallel.md)",
        rn_solver_name(o.solver));
  // A couple fixed in space: NOX on the residual only; no predictor (it solves with
  // the factored Hessian as a symmetric matrix) and no stability check (no energy).
  rn_solve_options onc = o;
  const bool nonconservative = rn_network_fixed_couples(net, nullptr, nullptr) > 0;
  if (s == RN_OK && nonconservative &&
      !(rodnet::solver_flags(o.solver) & RN_SOLVER_FIXED_COUPLES)) {
    const std::string what =
        std::string("the energy minimiser '") + rn_solver_name(o.solver) + "'";
    s = rodnet::refuse_nonconservative(net, "rn_solve", what.c_str());
  }
  if (nonconservative) {
    onc.predictor = onc.stability = 0;
    onc.energy_tol = 0.0; // the energy does not hold the couple's work
  }
  // Newton on the residual finds stationary points and does not descend the
  // energy: the conservative couple's tilt check (rodnet_couple.h) is for the
  // minimisers
  const int tilt_check = rn_network_set_couple_tilt_check(
      net, s == RN_OK && (rodnet::solver_flags(o.solver) & RN_SOLVER_DESCENDS));
  if (s == RN_OK) s = guarded(net, "rn_solve", [&] { rodnet::solve(net, onc, rep); });
  rn_network_set_couple_tilt_check(net, tilt_check);
  if (rep && s != RN_OK) {
    rep->status = s;
    rep->stop = RN_STOP_FAILED;
    rep->converged = 0;
  }
  return s;
}

rn_status rn_network_stability(rn_network *net, rn_stability *out) {
  if (!net) return RN_ERR_ARG;
  if (!out)
    return rn_context_set_error(rn_network_context(net), RN_ERR_ARG,
                                "rn_network_stability: out is NULL");
  if (rn_status st = rodnet::refuse_nonconservative(net, "rn_network_stability",
                                                    "the stability check"))
    return st;
  return guarded(net, "rn_network_stability", [&] {
    if (rn_network_is_part(net)) { // LOBPCG on the distributed Hessian (collective)
      rodnet::DistSystem sys(net, rodnet::world_comm());
      rodnet::TMV x(sys.map(), 1);
      sys.get_state(x);
      sys.assemble_hessian(x);
      rn_solve_options opt;
      rn_solve_options_default(&opt);
      *out = rodnet::lobpcg_stability(sys, opt);
      return;
    }
    rodnet::Problem p(net);
    std::vector<double> x(p.size());
    rodnet::check_status(rn_network_get_dofs(net, x.data()), "rn_network_get_dofs");
    p.assemble_hessian(x.data());
    *out = rodnet::hessian_stability(p, rodnet::choose_factor_kind(p, RN_FACTOR_AUTO));
  });
}

rn_status rn_hessian_min_eigenvalue(rn_network *net, double *lambda_min) {
  if (!net) return RN_ERR_ARG;
  if (!lambda_min)
    return rn_context_set_error(rn_network_context(net), RN_ERR_ARG,
                                "rn_hessian_min_eigenvalue: lambda_min is NULL");
  if (rn_status st = rodnet::refuse_nonconservative(net, "rn_hessian_min_eigenvalue",
                                                    "the lowest Hessian eigenvalue"))
    return st;
  return guarded(net, "rn_hessian_min_eigenvalue", [&] {
    rodnet::Problem p(net);
    std::vector<double> x(p.size());
    rodnet::check_status(rn_network_get_dofs(net, x.data()), "rn_network_get_dofs");
    p.assemble_hessian(x.data());
    *lambda_min = rodnet::choose_factor_kind(p, RN_FACTOR_AUTO) == RN_FACTOR_BANDED
                      ? rodnet::banded_min_eigenvalue(p)
                      : rodnet::sparse_min_eigenvalue(p);
  });
}

void rn_path_options_default(rn_path_options *opt) {
  if (!opt) return;
  std::memset(opt, 0, sizeof *opt);
  opt->control = RN_PATH_LOAD;
  opt->dof = 0;
  opt->monitor = -1;
  opt->max_steps = 200;
  opt->ds = 0.01;
  opt->ds_min = 1e-8;
  opt->ds_max = 0.05;
  opt->direction = 1.0;
  opt->target = std::nan("");
  opt->max_corrector_iterations = 15;
  opt->tol = 1e-9;
  opt->eigenvalues = 1;
  opt->branch_switch = 0;
  opt->branch_sign = 1.0;
  opt->factorization = RN_FACTOR_AUTO;
  opt->callback = nullptr;
  opt->user = nullptr;
}

const char *rn_path_event_name(rn_path_event e) {
  switch (rodnet::enum_value(e)) {
  case RN_PATH_POINT:
    return "point";
  case RN_PATH_LIMIT:
    return "limit";
  case RN_PATH_BIFURCATION:
    return "bifurcation";
  case RN_PATH_BRANCH_SWITCH:
    return "branch-switch";
  }
  return "unknown";
}

const char *rn_path_stop_name(rn_path_stop s) {
  switch (rodnet::enum_value(s)) {
  case RN_PATH_STOP_TARGET:
    return "target";
  case RN_PATH_STOP_MAX_STEPS:
    return "max-steps";
  case RN_PATH_STOP_STEP_MIN:
    return "step-min";
  case RN_PATH_STOP_RANGE:
    return "range";
  case RN_PATH_STOP_CALLBACK:
    return "callback";
  }
  return "unknown";
}

rn_status rn_path_follow(rn_network *net, const rn_path_options *opt,
                         rn_path_report *rep) {
  rn_path_report local;
  rn_path_report &r = rep ? *rep : local;
  std::memset(&r, 0, sizeof r);
  const double nan = std::nan("");
  r.limit_load_factor = r.limit_control = r.limit_force = nan;
  r.bifurcation_load_factor = r.bifurcation_control = r.bifurcation_force = nan;
  if (!net) return RN_ERR_ARG;
  if (rn_status st = rodnet::refuse_nonconservative(net, "rn_path_follow",
                                                    "path following (on the energy)"))
    return st;
  rn_path_options defaults;
  rn_path_options_default(&defaults);
  const rn_path_options &o = opt ? *opt : defaults;
  return guarded(net, "rn_path_follow", [&] { rodnet::follow_path(net, o, r); });
}

} // extern "C"
