// solvers.hpp - one minimisation at the network's current load factor, per solver
// kind (no Trilinos types here, so the C entry points compile fast).
//
// Each run_* starts from the network's current state, calls monitor.check() once per
// Newton iteration until it says stop, and leaves the last accepted iterate as the
// network's state (reference frames updated on every accepted step).  Counters go to
// problem.counters.  Errors throw rodnet::Error (or a Trilinos exception).
#ifndef RODNET_SHIM_SOLVERS_HPP
#define RODNET_SHIM_SOLVERS_HPP

#include "rodnet_solve.h"

namespace rodnet {

class Problem;
class Monitor;

void run_tr_minres(Problem &problem, Monitor &monitor, const rn_solve_options &opt);
void run_rol_tr_tcg(Problem &problem, Monitor &monitor, const rn_solve_options &opt);
void run_rol_ls_newton(Problem &problem, Monitor &monitor, const rn_solve_options &opt);
// The Newton-Krylov trust region on a SerialSystem of the problem; returns the
// preconditioner it used.
rn_preconditioner run_tr_krylov(Problem &problem, Monitor &monitor,
                                const rn_solve_options &opt);
// The same on any System (a distributed one: shim_cxx/dist_system.hpp) with the local
// (block Jacobi; the default) or the gathered preconditioner; RN_ERR_ARG for the
// factor preconditioner on several ranks.
class System;
rn_preconditioner run_tr_krylov(System &system, Monitor &monitor,
                                const rn_solve_options &opt);

} // namespace rodnet

#endif
