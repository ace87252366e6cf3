// rol_tr_tcg.cpp - ROL trust region with truncated CG (RN_SOLVER_ROL_TR_TCG).
//
// ROL::TypeU::TrustRegionAlgorithm, "Truncated CG" subproblem (Steihaug-Toint, in the
// preconditioner's norm), preconditioned by RodObjective::precond (Cholesky
// factorisation of the shifted Hessian, spd_factor.hpp).  Krylov iterations are counted
// as Hessian-vector products (one per CG iteration).
#include <ROL_TypeU_TrustRegionAlgorithm.hpp>
#include <Teuchos_oblackholestream.hpp>

#include "newton/rol_objective.hpp"
#include "base/shim_error.hpp"
#include "newton/solvers.hpp"

namespace rodnet {

void run_rol_tr_tcg(Problem &p, Monitor &mon, const rn_solve_options &opt) {
  auto map = make_local_map(p.size());
  auto xmv = Teuchos::rcp(new MV(map, 1));
  check_status(rn_network_get_dofs(p.network(), host_data(*xmv)), "rn_network_get_dofs");
  TpetraVector x(xmv), g(Teuchos::rcp(new MV(map, 1)));
  RodObjective obj(p, opt);

  ROL::ParameterList list;
  set_common_rol_parameters(list, opt);
  ROL::ParameterList &tr = list.sublist("Step").sublist("Trust Region");
  tr.set("Subproblem Solver", "Truncated CG");
  if (opt.initial_radius > 0.0) tr.set("Initial Radius", opt.initial_radius);

  ROL::TypeU::TrustRegionAlgorithm<double> alg(list);
  auto status = ROL::makePtr<RodStatusTest>(mon, obj, false);
  status->set_krylov_counter(&p.counters.hvp);
  alg.setStatusTest(status, false);
  Teuchos::oblackholestream out;
  alg.run(x, g, obj, out);
}

} // namespace rodnet
