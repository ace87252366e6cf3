// homogenize_dist.cpp - rn_homogenize on a part of a distributed periodic cell
// (docs/homogenization.md, "Under mpirun"): the effective stiffness through the
// distributed solver.
//
// The strain DOFs are global unknowns (owned by rank 0, a border of the rod-level DD's
// coarse problem).  With the whole Hessian K = [K_uu K_ue; K_eu K_ee] (fluctuations u,
// strain e), the strain block of K^-1 is the inverse of the Schur complement
// S = K_ee - K_eu K_uu^-1 K_ue, so the ns load cases K [x_u; x_e] = [0; e_b] (MINRES
// preconditioned by the solve's preconditioner, the DD by default) give
// X_e = S^-1 and C = S / measure = X_e^-1 / measure.  On an exact DD (direct coarse
// solve, no shifted piece) each case takes one or two MINRES iterations; then one step
// of iterative refinement on the residual brings the answer to round-off.  K must be
// positive definite (a stable cell without mechanisms): a shifted preconditioner, a
// MINRES that does not converge or an X_e that is not positive definite is
// RN_ERR_SOLVER.  Collective over the ranks.
#include <cmath>
#include <string>
#include <vector>

#include <Teuchos_CommHelpers.hpp>

#include "base/lapack.hpp"
#include "base/runtime.hpp"
#include "base/shim_error.hpp"
#include "krylov/minres.hpp"
#include "pc/operators.hpp"
#include "pc/preconditioner.hpp"
#include "pc/registry.hpp"
#include "periodic/homogenize.hpp"
#include "system/dist_system.hpp"

namespace rodnet {

namespace {

const char *const kWhere = "rn_homogenize";

} // namespace

void homogenize_dist(rn_network *net, rn_homogenization *h) {
  ensure_runtime();
  DistSystem sys(net, world_comm());
  const auto &comm = *sys.comm();
  int dim = 0, ns = 0;
  double measure = 0.0;
  check_status(rn_network_cell_info(net, &dim, &ns, &measure, nullptr),
               "rn_network_cell_info");
  if (dim == 0)
    throw Error(RN_ERR_ARG, std::string(kWhere) + ": the network is not periodic");
  int64_t sidx[6];
  check_status(rn_network_cell_strain_dofs(net, sidx), "rn_network_cell_strain_dofs");
  for (int v = 0; v < ns; ++v) // every part holds the strain DOFs: the same answer
    if (sidx[v] < 0)
      throw Error(RN_ERR_ARG, std::string(kWhere) +
                                  ": every strain component must be a DOF (strain "
                                  "component " +
                                  std::to_string(v) + " is prescribed)");
  const bool owner = comm.getRank() == 0; // part 0 owns the strain DOFs
  const auto map = sys.map();
  TMV x(map, 1);
  sys.get_state(x);
  sys.assemble_hessian(x);
  rn_solve_options opt;
  rn_solve_options_default(&opt);
  rn_preconditioner used = RN_PRECOND_AUTO;
  std::unique_ptr<Preconditioner> prec = make_preconditioner(sys, opt, &used);
  prec->setup(sys);
  if (prec->stats().shifted)
    throw Error(RN_ERR_SOLVER,
                std::string(kWhere) +
                    ": the Hessian of the cell is not positive definite: the cell has a "
                    "mechanism (a periodic fluctuation of zero energy, e.g. a joint or "
                    "rod end that nothing holds) or is unstable at this state");
  const SystemHessianOp A(sys);
  const PreconditionerInverseOp M(*prec);
  MinresSolver minres(map, 1e-14, 1000);
  double xe[36] = {0.0};
  for (int b = 0; b < ns; ++b) {
    TMV rhs(map, 1), s(map, 1), r(map, 1), ds(map, 1);
    if (owner) rhs.getDataNonConst(0)[static_cast<size_t>(sidx[b])] = 1.0;
    MinresResult res = minres.solve(A, M, rhs, s);
    // one step of iterative refinement: r = rhs - K s, K ds = r
    A.apply(s, r);
    r.update(1.0, rhs, -1.0);
    MinresResult res2 = minres.solve(A, M, r, ds);
    s.update(1.0, ds, 1.0);
    Teuchos::Array<double> nr(1), nb(1);
    A.apply(s, r);
    r.update(1.0, rhs, -1.0);
    r.norm2(nr());
    rhs.norm2(nb());
    if (!(res.converged || res2.converged) || !(nr[0] <= 1e-8 * nb[0]))
      throw Error(RN_ERR_SOLVER, std::string(kWhere) +
                                     ": MINRES did not solve strain load case " +
                                     std::to_string(b) + " (relative residual " +
                                     std::to_string(nr[0]) + ")");
    double col[6] = {0.0}, all[6] = {0.0};
    if (owner) {
      auto d = s.getData(0);
      for (int a = 0; a < ns; ++a) col[a] = d[static_cast<size_t>(sidx[a])];
    }
    Teuchos::reduceAll(comm, Teuchos::REDUCE_SUM, ns, col, all);
    for (int a = 0; a < ns; ++a) xe[a * ns + b] = all[a];
  }
  // C = X_e^-1 / measure (X_e symmetric up to round-off; Cholesky proves it SPD)
  for (int a = 0; a < ns; ++a)
    for (int b = a + 1; b < ns; ++b)
      xe[a * ns + b] = xe[b * ns + a] = 0.5 * (xe[a * ns + b] + xe[b * ns + a]);
  int n = ns, info = 0;
  const char uplo = 'L';
  double inv[36] = {0.0};
  for (int a = 0; a < ns; ++a) inv[a * ns + a] = 1.0;
  dpotrf_(&uplo, &n, xe, &n, &info, 1);
  if (info == 0) dpotrs_(&uplo, &n, &n, xe, &n, inv, &n, &info, 1);
  if (info != 0)
    throw Error(RN_ERR_SOLVER,
                std::string(kWhere) +
                    ": the strain block of the inverse Hessian is not "
                    "positive definite: the cell is unstable at this state");
  for (int a = 0; a < ns; ++a)
    for (int b = 0; b < ns; ++b) // symmetric: row- and column-major agree
      h->C[a * ns + b] = 0.5 * (inv[a * ns + b] + inv[b * ns + a]) / measure;
  h->dim = dim;
  h->nstrain = ns;
  h->measure = measure;
  h->fluctuation_dofs = static_cast<size_t>(sys.global_size()) - static_cast<size_t>(ns);
  double rho = 0.0;
  check_status(rn_network_cell_relative_density(net, &rho),
               "rn_network_cell_relative_density");
  Teuchos::reduceAll(comm, Teuchos::REDUCE_SUM, 1, &rho, &h->relative_density);
}

} // namespace rodnet
