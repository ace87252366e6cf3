// homogenize_dist.cpp - rn_homogenize on a part of a distributed periodic cell
// (docs/homogenization.md, "Under mpirun"): the effective stiffness through the
// distributed solver.
//
// The strain DOFs are global unknowns (owned by rank 0, a border of the rod-level DD's
// coarse problem).  With the whole Hessian K = [K_uu K_ue; K_eu K_ee] (fluctuations u,
// strain e), the strain block of K^-1 is the inverse of the Schur complement
// S = K_ee - K_eu K_uu^-1 K_ue, so the ns load cases K [x_u; x_e] = [0; e_b], solved
// at once (Belos block CG preconditioned by the solve's preconditioner, the DD by
// default, which applies the whole block per message), give X_e = S^-1 and
// C = S / measure = X_e^-1 / measure.  On an exact DD (direct coarse solve, no shifted
// piece) block CG takes one or two iterations; then one step of iterative refinement
// on the true residuals brings the answer to round-off.  K must be positive definite
// (a stable cell without mechanisms): a shifted preconditioner, a solve that does not
// converge or an X_e that is not positive definite is RN_ERR_SOLVER.  Collective over
// the ranks.
#include <cmath>
#include <string>
#include <vector>

#include <BelosBlockCGSolMgr.hpp>
#include <BelosLinearProblem.hpp>
#include <BelosTpetraAdapter.hpp>
#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_oblackholestream.hpp>

#include "base/lapack.hpp"
#include "base/runtime.hpp"
#include "base/shim_error.hpp"
#include "pc/preconditioner.hpp"
#include "pc/registry.hpp"
#include "periodic/homogenize.hpp"
#include "system/dist_system.hpp"

namespace rodnet {

namespace {

const char *const kWhere = "rn_homogenize";

// X = K^-1 B (X overwritten) by Belos block CG with the preconditioner's inverse as
// the left preconditioner, to 1e-13 of each column's initial residual (implicit
// residuals; at most 500 iterations).  True if it converged.
bool block_cg(const System &sys, const Preconditioner &prec, const TMV &B, TMV &X) {
  using OP = Tpetra::Operator<>;
  X.putScalar(0.0);
  auto problem = Teuchos::rcp(new Belos::LinearProblem<double, TMV, OP>(
      sys.hessian(), Teuchos::rcpFromRef(X), Teuchos::rcpFromRef(B)));
  problem->setLeftPrec(prec.inverse());
  if (!problem->setProblem())
    throw Error(RN_ERR_SOLVER, std::string(kWhere) + ": Belos rejected the block solve");
  auto params = Teuchos::rcp(new Teuchos::ParameterList);
  params->set("Block Size", static_cast<int>(B.getNumVectors()));
  params->set("Maximum Iterations", 500);
  params->set("Convergence Tolerance", 1e-13);
  params->set("Verbosity", static_cast<int>(Belos::Errors));
  params->set("Output Stream", Teuchos::rcp<std::ostream>(new Teuchos::oblackholestream));
  Belos::BlockCGSolMgr<double, TMV, OP> solver(problem, params);
  try {
    return solver.solve() == Belos::Converged;
  } catch (const std::exception &) {
    return false; // e.g. a loss of orthogonality: the refinement and residual check
  }
}

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
  // The ns load cases at once: block CG (K is SPD here) preconditioned by the DD,
  // which applies a block with one halo exchange and one coarse solve; then one
  // step of iterative refinement on the true residuals.
  TMV rhs(map, static_cast<size_t>(ns)), X(map, static_cast<size_t>(ns));
  TMV R(map, static_cast<size_t>(ns)), dX(map, static_cast<size_t>(ns));
  if (owner)
    for (int b = 0; b < ns; ++b)
      rhs.getDataNonConst(static_cast<size_t>(b))[static_cast<size_t>(sidx[b])] = 1.0;
  const bool converged = block_cg(sys, *prec, rhs, X);
  sys.hessian()->apply(X, R);
  R.update(1.0, rhs, -1.0);
  const bool refined = block_cg(sys, *prec, R, dX);
  X.update(1.0, dX, 1.0);
  sys.hessian()->apply(X, R);
  R.update(1.0, rhs, -1.0);
  Teuchos::Array<double> nr(static_cast<size_t>(ns)), nb(static_cast<size_t>(ns));
  R.norm2(nr());
  rhs.norm2(nb());
  for (int b = 0; b < ns; ++b)
    if (!(converged || refined) ||
        !(nr[static_cast<size_t>(b)] <= 1e-8 * nb[static_cast<size_t>(b)]))
      throw Error(RN_ERR_SOLVER, std::string(kWhere) +
                                     ": block CG did not solve strain load case " +
                                     std::to_string(b) + " (relative residual " +
                                     std::to_string(nr[static_cast<size_t>(b)]) + ")");
  double xe[36] = {0.0}, mine[36] = {0.0};
  if (owner)
    for (int b = 0; b < ns; ++b) {
      auto d = X.getData(static_cast<size_t>(b));
      for (int a = 0; a < ns; ++a) mine[a * ns + b] = d[static_cast<size_t>(sidx[a])];
    }
  Teuchos::reduceAll(comm, Teuchos::REDUCE_SUM, ns * ns, mine, xe);
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
