// dist_predictor.hpp - the linearised load-increment predictor (predictor.hpp) on a
// distributed System: from the converged state x at t_prev, x + s with
// H(x; t_prev) s = -(g(x; t_prev) + dg), dg the load increment summed over the parts,
// solved by MINRES preconditioned as the solve is (the solve's preconditioner; when that
// preconditioner had to be shifted, s = -M^{-1} (g + dg), as the serial predictor's
// shifted factor), kept only if it lowers the energy at t.  Collective.
#ifndef RODNET_SHIM_DIST_PREDICTOR_HPP
#define RODNET_SHIM_DIST_PREDICTOR_HPP

#include "rodnet_solve.h"

namespace rodnet {

class DistSystem;
class Preconditioner;

// Leaves every part at load factor t, the state x + s if accepted (returns true on
// every rank), else unchanged (false); prec is the solve's preconditioner for sys
// (set up here at x).  Throws Error on every rank.
bool predict_load_step(DistSystem &sys, Preconditioner &prec, const rn_solve_options &opt,
                       double t_prev, double t);

} // namespace rodnet

#endif
