// minres.cpp - Tpetra operator adapter and Belos MINRES (see minres.hpp).
#include "minres.hpp"

#include <mpi.h>

#include <BelosLinearProblem.hpp>
#include <BelosMinresSolMgr.hpp>
#include <BelosTpetraAdapter.hpp>
#include <Teuchos_DefaultMpiComm.hpp>
#include <Teuchos_oblackholestream.hpp>
#include <Tpetra_Operator.hpp>

#include "shim_error.hpp"

namespace rodnet {

namespace {

using OP = Tpetra::Operator<>;

// Tpetra::Operator applying a VectorOperator, honouring alpha and beta.
class AdaptedOperator : public OP {
public:
  explicit AdaptedOperator(const Teuchos::RCP<const Map> &map) : map_(map), tmp_(map, 1) {}
  void set(const VectorOperator *op) { op_ = op; }
  Teuchos::RCP<const Map> getDomainMap() const override { return map_; }
  Teuchos::RCP<const Map> getRangeMap() const override { return map_; }
  void apply(const MV &X, MV &Y, Teuchos::ETransp /*mode: symmetric*/, double alpha,
             double beta) const override {
    if (X.getNumVectors() != 1 || Y.getNumVectors() != 1)
      throw Error(RN_ERR_INTERNAL, "rn_solve: operator applied to a block of vectors");
    if (alpha == 1.0 && beta == 0.0) {
      op_->apply(X, Y);
    } else {
      op_->apply(X, tmp_);
      Y.update(alpha, tmp_, beta);
    }
  }

private:
  Teuchos::RCP<const Map> map_;
  const VectorOperator *op_ = nullptr;
  mutable MV tmp_;
};

} // namespace

Teuchos::RCP<const Map> make_local_map(size_t n) {
  int initialized = 0;
  MPI_Initialized(&initialized);
  if (!initialized) throw Error(RN_ERR_TRILINOS, "rn_solve: MPI is not initialized");
  auto comm = Teuchos::rcp(new Teuchos::MpiComm<int>(MPI_COMM_SELF));
  using GO = Map::global_ordinal_type;
  return Teuchos::rcp(new Map(static_cast<Tpetra::global_size_t>(n), GO(0), comm));
}

double *host_data(MV &v) { return v.getLocalViewHost(Tpetra::Access::ReadWrite).data(); }
const double *host_data(const MV &v) {
  return v.getLocalViewHost(Tpetra::Access::ReadOnly).data();
}

struct MinresSolver::Impl {
  Teuchos::RCP<AdaptedOperator> A, P;
  Belos::MinresSolMgr<double, MV, OP> solver;
};

MinresSolver::MinresSolver(const Teuchos::RCP<const Map> &map, double rel_tol,
                           int max_iterations)
    : impl_(new Impl) {
  impl_->A = Teuchos::rcp(new AdaptedOperator(map));
  impl_->P = Teuchos::rcp(new AdaptedOperator(map));
  auto params = Teuchos::parameterList();
  params->set("Convergence Tolerance", rel_tol);
  params->set("Maximum Iterations", max_iterations);
  params->set("Block Size", 1);
  params->set("Verbosity", static_cast<int>(Belos::Errors));
  params->set("Output Stream",
              Teuchos::RCP<std::ostream>(Teuchos::rcp(new Teuchos::oblackholestream)));
  impl_->solver.setParameters(params);
}

MinresSolver::~MinresSolver() = default;

MinresResult MinresSolver::solve(const VectorOperator &A, const VectorOperator &prec,
                                 const MV &b, MV &x) {
  MinresResult res;
  x.putScalar(0.0);
  Teuchos::Array<double> bnorm(1);
  b.norm2(bnorm());
  if (bnorm[0] == 0.0) {
    res.converged = true;
    return res;
  }
  impl_->A->set(&A);
  impl_->P->set(&prec);
  auto problem = Teuchos::rcp(new Belos::LinearProblem<double, MV, OP>(
      impl_->A, Teuchos::rcpFromRef(x), Teuchos::rcpFromRef(b)));
  problem->setLeftPrec(impl_->P);
  if (!problem->setProblem())
    throw Error(RN_ERR_SOLVER, "rn_solve: Belos rejected the MINRES problem");
  impl_->solver.setProblem(problem);
  const Belos::ReturnType ret = impl_->solver.solve();
  res.iterations = impl_->solver.getNumIters();
  res.converged = (ret == Belos::Converged);
  res.achieved_tol = impl_->solver.achievedTol();
  return res;
}

} // namespace rodnet
