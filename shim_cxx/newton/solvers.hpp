// solvers.hpp - one minimisation at the network's current load factor, per solver
// kind (no Trilinos types here, so the C entry points compile fast).
//
// Each run_* starts from the network's current state, calls monitor.check() once per
// Newton iteration until it says stop, and leaves the last accepted iterate as the
// network's state (reference frames updated on every accepted step).  Counters go to
// problem.counters.  Errors throw rodnet::Error (or a Trilinos exception).
#ifndef RODNET_SHIM_SOLVERS_HPP
#define RODNET_SHIM_SOLVERS_HPP

#include <memory>

#include "rodnet_solve.h"

namespace rodnet {

class Problem;
class Monitor;
class System;
class Preconditioner;

void run_tr_minres(Problem &problem, Monitor &monitor, const rn_solve_options &opt);
void run_rol_tr_tcg(Problem &problem, Monitor &monitor, const rn_solve_options &opt);
void run_rol_ls_newton(Problem &problem, Monitor &monitor, const rn_solve_options &opt);
void run_rol_lbfgs(Problem &problem, Monitor &monitor, const rn_solve_options &opt);
// The preconditioner opt.preconditioner names for sys (auto: dd, the rod-level domain
// decomposition; factor on several ranks is RN_ERR_ARG); *used is the kind chosen
// (tr_krylov.cpp).
std::unique_ptr<Preconditioner> make_preconditioner(const System &sys,
                                                    const rn_solve_options &opt,
                                                    rn_preconditioner *used);
// The System and the preconditioner of tr-krylov for one load step: the load-step
// predictor and the trust region share one set-up of the Hessian's graph and of the
// preconditioner's structure (for dd: the rods' blocks, the condensation's index
// maps, the coarse matrix's ordering and symbolic factorisation; for factor: the
// symbolic analysis), which would otherwise be built twice.  On a part of a
// distributed network the System is the DistSystem given (built once per solve).
class KrylovWorkspace {
public:
  // system: a distributed System, or nullptr for a SerialSystem of problem.
  KrylovWorkspace(Problem &problem, System *system, const rn_solve_options &opt);
  ~KrylovWorkspace();
  KrylovWorkspace(const KrylovWorkspace &) = delete;
  KrylovWorkspace &operator=(const KrylovWorkspace &) = delete;
  System &system() { return *sys_; }
  Preconditioner &preconditioner() { return *prec_; }
  rn_preconditioner kind() const { return kind_; }
  // Adds the preconditioner's set-up and apply seconds since the last call to the
  // System's counters (the report's time split).
  void account();

private:
  std::unique_ptr<System> own_;
  System *sys_ = nullptr;
  std::unique_ptr<Preconditioner> prec_;
  rn_preconditioner kind_ = RN_PRECOND_AUTO;
  double setup_seen_ = 0.0, apply_seen_ = 0.0;
};
// The Newton-Krylov trust region on the workspace's System with its preconditioner;
// returns the preconditioner kind it used.
rn_preconditioner run_tr_krylov(KrylovWorkspace &ws, Monitor &monitor,
                                const rn_solve_options &opt);
// NOX Newton on grad E = 0 with Belos MINRES (nox_solver.cpp), the same ways; the
// last form with a given preconditioner.
rn_preconditioner run_nox(Problem &problem, Monitor &monitor,
                          const rn_solve_options &opt);
rn_preconditioner run_nox(System &system, Monitor &monitor, const rn_solve_options &opt);
void run_nox(System &system, Preconditioner &prec, Monitor &monitor,
             const rn_solve_options &opt);
// The load-step predictor for tr-krylov on a whole network: the workspace's
// preconditioner and preconditioned MINRES to opt.krylov_tol instead of a
// factorisation of the whole Hessian (predictor.hpp).
bool predict_step_krylov(Problem &problem, KrylovWorkspace &ws,
                         const rn_solve_options &opt, double t_prev, double t);

} // namespace rodnet

#endif
