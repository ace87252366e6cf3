// minres.cpp - Tpetra operator adapter and Belos MINRES (see minres.hpp).
#include "krylov/minres.hpp"
#include "krylov/minres_local.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include <BelosLinearProblem.hpp>
#include <BelosMinresIter.hpp>
#include <BelosStatusTestCombo.hpp>
#include <BelosStatusTestGenResNorm.hpp>
#include <BelosStatusTestMaxIters.hpp>
#include <BelosTpetraAdapter.hpp>
#include <Teuchos_oblackholestream.hpp>
#include <Tpetra_Operator.hpp>

#include "base/runtime.hpp"
#include "base/shim_error.hpp"

namespace rodnet {

namespace {

using OP = Tpetra::Operator<>;

// Tpetra::Operator applying a VectorOperator, honouring alpha and beta.
class AdaptedOperator : public OP {
public:
  explicit AdaptedOperator(const Teuchos::RCP<const Map> &map)
      : map_(map), tmp_(map, 1) {}
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

// A VectorOperator of a callback on the column's host array.
class CallbackOperator : public VectorOperator {
public:
  explicit CallbackOperator(const LocalApply &f) : f_(f) {}
  void apply(const MV &x, MV &y) const override { f_(host_data(x), host_data(y)); }

private:
  const LocalApply &f_;
};

} // namespace

LocalMinresResult minres_local(size_t n, const LocalApply &A, const LocalApply &Minv,
                               const double *b, double *x, double rel_tol,
                               int max_iterations) {
  ensure_runtime();
  auto map = make_local_map(n);
  MV bv(map, 1), xv(map, 1);
  std::copy(b, b + n, host_data(bv));
  MinresSolver solver(map, rel_tol, max_iterations);
  const MinresResult r =
      solver.solve(CallbackOperator(A), CallbackOperator(Minv), bv, xv);
  std::copy(host_data(xv), host_data(xv) + n, x);
  LocalMinresResult out;
  out.iterations = r.iterations;
  out.converged = r.converged;
  out.achieved_tol = r.achieved_tol;
  return out;
}

Teuchos::RCP<const Map> make_local_map(size_t n) {
  auto comm = self_comm();
  using GO = Map::global_ordinal_type;
  return Teuchos::rcp(new Map(static_cast<Tpetra::global_size_t>(n), GO(0), comm));
}

double *host_data(MV &v) { return v.getLocalViewHost(Tpetra::Access::ReadWrite).data(); }
const double *host_data(const MV &v) {
  return v.getLocalViewHost(Tpetra::Access::ReadOnly).data();
}

struct MinresSolver::Impl {
  Teuchos::RCP<AdaptedOperator> A, P;
  Teuchos::RCP<MV> work;
  double tol = 0.0;
  int max_iterations = 0;
};

MinresSolver::MinresSolver(const Teuchos::RCP<const Map> &map, double rel_tol,
                           int max_iterations)
    : impl_(new Impl) {
  impl_->A = Teuchos::rcp(new AdaptedOperator(map));
  impl_->P = Teuchos::rcp(new AdaptedOperator(map));
  impl_->work = Teuchos::rcp(new MV(map, 1));
  impl_->tol = rel_tol;
  impl_->max_iterations = max_iterations;
}

MinresSolver::~MinresSolver() = default;

// Belos::MinresIter driven directly (not MinresSolMgr): MinresSolMgr also requires
// the explicit, unpreconditioned residual to drop by the tolerance, which round-off
// forbids for the ill-conditioned rod Hessians (cond ~ n^4 EA / EI), so it would
// iterate to the limit.  Here the test is MINRES's own residual norm in the
// preconditioner's inverse norm, ||r||_{P^-1} <= tol ||b||_{P^-1}.
MinresResult MinresSolver::solve(const VectorOperator &A, const VectorOperator &prec,
                                 const MV &b, MV &x) {
  using ResNorm = Belos::StatusTestGenResNorm<double, MV, OP>;
  MinresResult res;
  x.putScalar(0.0);
  prec.apply(b, *impl_->work);
  Teuchos::Array<double> bPb(1);
  impl_->work->dot(b, bPb());
  if (!(bPb[0] > 0.0)) { // b = 0 (or a preconditioner that is not SPD)
    if (bPb[0] < 0.0 || !std::isfinite(bPb[0]))
      throw Error(RN_ERR_SOLVER,
                  "rn_solve: MINRES preconditioner is not positive definite");
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
  std::vector<int> index(1, 0);
  problem->setLSIndex(index);

  auto conv = Teuchos::rcp(new ResNorm(impl_->tol));
  conv->defineResForm(ResNorm::Implicit, Belos::TwoNorm);
  conv->defineScaleForm(Belos::None, Belos::TwoNorm, std::sqrt(bPb[0]));
  auto maxit =
      Teuchos::rcp(new Belos::StatusTestMaxIters<double, MV, OP>(impl_->max_iterations));
  auto test = Teuchos::rcp(new Belos::StatusTestCombo<double, MV, OP>(
      Belos::StatusTestCombo<double, MV, OP>::OR, maxit, conv));
  auto printer = Teuchos::rcp(new Belos::OutputManager<double>(
      Belos::Errors, Teuchos::rcp(new Teuchos::oblackholestream)));
  Teuchos::ParameterList params;
  Belos::MinresIter<double, MV, OP> iter(problem, printer, test, params);
  Belos::MinresIterationState<double, MV> state;
  state.Y = Teuchos::rcp_const_cast<MV>(problem->getInitResVec());
  iter.initializeMinres(state);
  iter.iterate();
  problem->setCurrLS();
  res.iterations = iter.getNumIters();
  res.converged = (conv->getStatus() == Belos::Passed);
  const std::vector<double> *value = conv->getTestValue();
  res.achieved_tol = (value && !value->empty()) ? (*value)[0] : 0.0;
  return res;
}

} // namespace rodnet
