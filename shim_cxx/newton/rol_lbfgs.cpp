// rol_lbfgs.cpp - ROL limited-memory BFGS with a line search (RN_SOLVER_ROL_LBFGS).
//
// ROL::TypeU::LineSearchAlgorithm with the "Quasi-Newton Method" descent and the
// "Limited-Memory BFGS" secant (ROL_SecantFactory.hpp: 10 stored pairs, default initial
// scaling y's / y'y) and a backtracking line search with the Armijo condition.  ROL's
// backtracking and cubic-interpolation searches test no curvature condition; the
// secant skips pairs with s'y <= eps |s|^2, which keeps it positive definite.
// Backtracking, not cubic interpolation: a trial point where the energy is undefined
// (a degenerate edge: value +inf) makes the cubic fit NaN, while backtracking halves
// the step.  Gradients only:
// no Hessian, no preconditioner, no Krylov solver (krylov_iterations stays 0), so the
// cost per iteration is a few energy and gradient evaluations.  A first-order method on
// the stiff rod energies (stretching against bending): expect many iterations; it is
// the quasi-Newton reference of the optimiser benchmark (docs/benchmarking.md).
#include <ROL_TypeU_LineSearchAlgorithm.hpp>
#include <Teuchos_oblackholestream.hpp>

#include "newton/rol_objective.hpp"
#include "base/shim_error.hpp"
#include "newton/solvers.hpp"

namespace rodnet {

void run_rol_lbfgs(Problem &p, Monitor &mon, const rn_solve_options &opt) {
  auto map = make_local_map(p.size());
  auto xmv = Teuchos::rcp(new MV(map, 1));
  check_status(rn_network_get_dofs(p.network(), host_data(*xmv)), "rn_network_get_dofs");
  TpetraVector x(xmv);
  RodObjective obj(p, opt);

  ROL::ParameterList list;
  set_common_rol_parameters(list, opt);
  ROL::ParameterList &secant = list.sublist("General").sublist("Secant");
  secant.set("Type", "Limited-Memory BFGS");
  secant.set("Maximum Storage", 10);
  secant.set("Use Default Scaling", true);
  ROL::ParameterList &ls = list.sublist("Step").sublist("Line Search");
  ls.sublist("Descent Method").set("Type", "Quasi-Newton Method");
  ls.sublist("Line-Search Method").set("Type", "Backtracking");
  ls.sublist("Curvature Condition").set("Type", "Null Curvature Condition");
  ls.set("Function Evaluation Limit", 40);

  ROL::TypeU::LineSearchAlgorithm<double> alg(list);
  auto status = ROL::makePtr<RodStatusTest>(mon, obj, true);
  alg.setStatusTest(status, false);
  Teuchos::oblackholestream out;
  ROL::TypeU::Algorithm<double> &base = alg; // LineSearchAlgorithm hides run(x, obj)
  base.run(x, obj, out);
}

} // namespace rodnet
