// muelu.cpp - algebraic multigrid (MueLu): the rod-level domain decomposition's AMG
// coarse solve (coarse_solver.hpp, make_amg_coarse_solver) and the "muelu"
// preconditioner on the whole Hessian (muelu.hpp).  The only translation unit with
// MueLu headers (they compile slowly).
#include <string>
#include <utility>

#include <MueLu_CreateTpetraPreconditioner.hpp>
#include <Teuchos_ParameterList.hpp>
#include <Teuchos_XMLParameterListHelpers.hpp>

#include "base/clock.hpp"
#include "base/shim_error.hpp"
#include "pc/impls/muelu/muelu.hpp"
#include "pc/spd_guard.hpp"

namespace rodnet {

namespace {

using MueluOp = MueLu::TpetraOperator<double, LO, GO, Tpetra::Map<>::node_type>;

// Chebyshev polynomial of the given degree over [lambda_max / ratio, lambda_max],
// lambda_max of D^-1 A estimated safely (see below).
void chebyshev(Teuchos::ParameterList &c, int degree, double ratio) {
  c.set("chebyshev: degree", degree);
  c.set("chebyshev: ratio eigenvalue", ratio);
  c.set("chebyshev: eigenvalue max iterations", 50);
  c.set("chebyshev: boost factor", 1.3);
}

// Smoothed aggregation, Chebyshev smoothing of degree 3 (symmetric: the V-cycle is an SPD
// operator for an SPD matrix), rigid-body near-null space.  Coarsest level: KLU2 on
// one rank; on several ranks Jacobi relaxation (an Amesos2 solve of a matrix
// distributed over ranks is wrong in Trilinos 13.2, TRILINOS.md).
Teuchos::ParameterList
amg_parameters(int nranks, const Teuchos::RCP<const TMV> &nullspace, int block) {
  Teuchos::ParameterList p;
  p.set("verbosity", "none");
  p.set("multigrid algorithm", "sa");
  p.set("max levels", 10);
  p.set("coarse: max size", 1000);
  p.set("aggregation: type", "uncoupled");
  // Chebyshev needs an upper bound of the spectrum of D^-1 A: with MueLu's default
  // estimate (10 power iterations, boost 1.1) the V-cycle was indefinite for a
  // positive definite coarse matrix of a 36x36 honeycomb (the SPD probe then shifted
  // it by 100 |diag|: 2353 MINRES iterations); 50 iterations and a boost of 1.3 were
  // safe on every lattice measured (docs/solvers.md).
  p.set("smoother: type", "CHEBYSHEV");
  chebyshev(p.sublist("smoother: params"), 3, 20.0);
  if (nranks > 1) {
    // No direct solve of a distributed matrix: a coarsest level of at most 200 rows
    // smoothed by Chebyshev of degree 10 (Jacobi relaxation there: 137 MINRES
    // iterations on a 48x48 honeycomb on 2 ranks instead of 68).
    p.set("coarse: max size", 200);
    p.set("coarse: type", "CHEBYSHEV");
    chebyshev(p.sublist("coarse: params"), 10, 100.0);
  } else {
    p.set("coarse: type", "KLU2");
  }
  p.set("repartition: enable", false);
  p.set("number of equations", block);
  if (!nullspace.is_null())
    p.sublist("user data").set("Nullspace", Teuchos::rcp_const_cast<TMV>(nullspace));
  return p;
}

class AmgCoarse : public CoarseSolver {
public:
  // block: DOFs per node (rows 6 n .. 6 n + 5 for the DD's coarse matrix), 1 for a
  // matrix without node structure.
  explicit AmgCoarse(int block, std::string xml = std::string())
      : block_(block), xml_(std::move(xml)) {}
  void setup(const Teuchos::RCP<const TCrs> &S,
             const Teuchos::RCP<const TMV> &nullspace) override {
    if (!mpi_backed(*S->getComm()))
      throw Error(
          RN_ERR_TRILINOS,
          "algebraic multigrid (MueLu) needs the MPI runtime in Trilinos 13.2: run "
          "under mpirun or with RODNET_MPI=1 (docs/solvers.md)");
    const int nranks = S->getComm()->getSize();
    guard_.setup(
        *S,
        [&](const Teuchos::RCP<TCrs> &A) -> Teuchos::RCP<Tpetra::Operator<>> {
          Teuchos::ParameterList params = amg_parameters(nranks, nullspace, block_);
          if (!xml_.empty())
            Teuchos::updateParametersFromXmlFile(xml_, Teuchos::inOutArg(params));
          return MueLu::CreateTpetraPreconditioner(Teuchos::RCP<Tpetra::Operator<>>(A),
                                                   params);
        },
        "AMG");
    // matrix and hierarchy (operator complexity of smoothed aggregation ~1.5): estimate
    bytes_ = 2.5 * 12.0 * static_cast<double>(guard_.A->getNodeNumEntries());
  }
  void solve(const TMV &b, TMV &y) const override { guard_.P->apply(b, y); }
  double shift() const override { return guard_.shift; }
  double bytes() const override { return bytes_; }
  std::string name() const override { return "amg"; }

private:
  int block_;
  std::string xml_;
  SpdGuard guard_;
  double bytes_ = 0.0;
};

} // namespace

std::unique_ptr<CoarseSolver> make_amg_coarse_solver(const std::string &xml) {
  return std::unique_ptr<CoarseSolver>(new AmgCoarse(6, xml));
}

// ---- MueLu on the whole Hessian ------------------------------------------------------
MueluPreconditioner::MueluPreconditioner(const Teuchos::RCP<const TMV> &nullspace)
    : nullspace_(nullspace), amg_(new AmgCoarse(1)) {}
MueluPreconditioner::~MueluPreconditioner() = default;

void MueluPreconditioner::setup(System &sys) {
  const Clock::time_point t0 = Clock::now();
  map_ = sys.map();
  amg_->setup(sys.hessian(), nullspace_);
  stats_.setups++;
  stats_.setup_seconds += seconds_since(t0);
  stats_.bytes = amg_->bytes();
  stats_.shifted = amg_->shift() > 0.0;
}

Teuchos::RCP<const Tpetra::Operator<>> MueluPreconditioner::inverse() const {
  if (op_.is_null()) { // one operator for the preconditioner's life (callers keep it)
    std::shared_ptr<CoarseSolver> amg = amg_;
    op_ = stats_operator(
        map_, [amg](const TMV &x, TMV &y) { amg->solve(x, y); }, &stats_);
  }
  return op_;
}

double MueluPreconditioner::shift() const { return amg_->shift(); }

} // namespace rodnet
