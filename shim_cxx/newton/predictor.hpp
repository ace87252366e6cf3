// predictor.hpp - the linearised load-increment predictor of a load step (no
// Trilinos here).  From a converged state x at load factor t_prev, the step to t
// starts at x + s with
//   H(x; t_prev) s = -(g(x; t_prev) + dg),  dg = rn_network_load_increment(x, t_prev, t),
// the Newton step of the linearised problem at t (prescribed motions and loads
// moved to t, the free DOFs following to first order), instead of at x, where only
// the prescribed DOFs have jumped.  H is factored as the solver does (shifted by
// the metric |diag H| if it is not positive definite).  The prediction is accepted
// (x + s becomes the state, reference updated) only if it lowers the energy at t
// (or the energy at x cannot be evaluated at t: the prescribed motion jumped the
// state to a degenerate one).
#ifndef RODNET_SHIM_PREDICTOR_HPP
#define RODNET_SHIM_PREDICTOR_HPP

#include <functional>
#include <vector>

#include "system/problem.hpp"
#include "rodnet_solve.h"

namespace rodnet {

// Leaves the network at load factor t, its state x + s if accepted (returns true),
// else unchanged (false).  The network's state must be at load factor t_prev's
// prescribed values (its current load factor is ignored).  Throws Error.
bool predict_load_step(Problem &p, rn_factorization kind, double t_prev, double t);

// The same with the linear solve given: solve(p, x, s) replaces s by (an SPD
// approximation of, converged to a tolerance) H(x)^{-1} s, assembling H itself;
// false: no step.  The Newton-Krylov trust region's preconditioned MINRES
// (predict_step_krylov, solvers.hpp) avoids factoring the whole Hessian.
using PredictorSolve =
    std::function<bool(Problem &p, const std::vector<double> &x, std::vector<double> &s)>;
bool predict_load_step(Problem &p, const PredictorSolve &solve, double t_prev, double t);

} // namespace rodnet

#endif
