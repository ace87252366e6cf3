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
// The Newton-Krylov trust region on a SerialSystem of the problem, or on any System
// (a distributed one: shim_cxx/dist_system.hpp); returns the preconditioner it used.
rn_preconditioner run_tr_krylov(Problem &problem, Monitor &monitor,
                                const rn_solve_options &opt);
rn_preconditioner run_tr_krylov(System &system, Monitor &monitor,
                                const rn_solve_options &opt);
// NOX Newton on grad E = 0 with Belos MINRES (nox_solver.cpp), the same ways; the
// last form with a given preconditioner.
rn_preconditioner run_nox(Problem &problem, Monitor &monitor,
                          const rn_solve_options &opt);
rn_preconditioner run_nox(System &system, Monitor &monitor, const rn_solve_options &opt);
void run_nox(System &system, Preconditioner &prec, Monitor &monitor,
             const rn_solve_options &opt);
// The load-step predictor for tr-krylov: its preconditioner (opt.preconditioner) and
// preconditioned MINRES to opt.krylov_tol instead of a factorisation of the whole
// Hessian (predictor.hpp).
bool predict_step_krylov(Problem &problem, const rn_solve_options &opt, double t_prev,
                         double t);

} // namespace rodnet

#endif
