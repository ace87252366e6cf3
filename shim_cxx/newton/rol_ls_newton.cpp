// rol_ls_newton.cpp - ROL line-search Newton-Krylov with Belos MINRES as the Krylov
// solver (RN_SOLVER_ROL_LS_NEWTON).
//
// ROL::TypeU::LineSearchAlgorithm with ROL::NewtonKrylov_U and a user ROL::Krylov
// (MinresKrylov) that runs Belos MINRES on the Hessian operator ROL gives it,
// preconditioned by the inverse of ROL's preconditioner (RodObjective::precond, SPD).
// ROL does not check that the Newton direction descends: MinresKrylov does and falls
// back to the preconditioned gradient direction (P^{-1} g, descent since P is SPD).
// Line search: backtracking with the Armijo condition only (no gradients at trial
// points).
#include <cmath>

#include <ROL_Krylov.hpp>
#include <ROL_LinearOperator.hpp>
#include <ROL_NewtonKrylov_U.hpp>
#include <ROL_TypeU_LineSearchAlgorithm.hpp>
#include <Teuchos_oblackholestream.hpp>

#include "newton/rol_objective.hpp"
#include "base/shim_error.hpp"
#include "newton/solvers.hpp"

namespace rodnet {

namespace {

// A ROL linear operator (or its inverse) as a VectorOperator on Tpetra vectors.
class RolOperator : public VectorOperator {
public:
  RolOperator(ROL::LinearOperator<double> &op, bool inverse)
      : op_(op), inverse_(inverse) {}
  void apply(const MV &x, MV &y) const override {
    const TpetraVector xv(Teuchos::rcpFromRef(const_cast<MV &>(x)));
    TpetraVector yv(Teuchos::rcpFromRef(y));
    double tol = std::sqrt(ROL::ROL_EPSILON<double>());
    if (inverse_)
      op_.applyInverse(yv, xv, tol);
    else
      op_.apply(yv, xv, tol);
  }

private:
  ROL::LinearOperator<double> &op_;
  bool inverse_;
};

class MinresKrylov : public ROL::Krylov<double> {
public:
  MinresKrylov(const Teuchos::RCP<const Map> &map, const rn_solve_options &opt,
               long *iterations)
      : ROL::Krylov<double>(0.0, opt.krylov_tol,
                            static_cast<unsigned>(opt.krylov_max_iterations)),
        minres_(map, opt.krylov_tol, opt.krylov_max_iterations), iterations_(iterations) {
  }

  // Solves A x = b (b is the gradient; ROL steps along -x).
  double run(RolVector &x, ROL::LinearOperator<double> &A, const RolVector &b,
             ROL::LinearOperator<double> &M, int &iter, int &flag) override {
    const RolOperator Aop(A, false), Pop(M, true);
    MV &xm = *dynamic_cast<TpetraVector &>(x).getVector();
    const MV &bm = *dynamic_cast<const TpetraVector &>(b).getVector();
    const MinresResult r = minres_.solve(Aop, Pop, bm, xm);
    iter = r.iterations;
    flag = r.converged ? 0 : 1;
    *iterations_ += r.iterations;
    const double bx = x.dot(b), scale = x.norm() * b.norm();
    if (!(bx > 1e-12 * scale)) { // not a descent direction: preconditioned gradient
      double tol = std::sqrt(ROL::ROL_EPSILON<double>());
      M.applyInverse(x, b, tol);
      flag = 0;
    }
    return r.achieved_tol;
  }

private:
  MinresSolver minres_;
  long *iterations_;
};

} // namespace

void run_rol_ls_newton(Problem &p, Monitor &mon, const rn_solve_options &opt) {
  auto map = make_local_map(p.size());
  auto xmv = Teuchos::rcp(new MV(map, 1));
  check_status(rn_network_get_dofs(p.network(), host_data(*xmv)), "rn_network_get_dofs");
  TpetraVector x(xmv), g(Teuchos::rcp(new MV(map, 1)));
  RodObjective obj(p, opt);

  ROL::ParameterList list;
  set_common_rol_parameters(list, opt);
  ROL::ParameterList &ls = list.sublist("Step").sublist("Line Search");
  ls.sublist("Descent Method").set("Type", "Newton-Krylov");
  ls.sublist("Line-Search Method").set("Type", "Backtracking");
  ls.sublist("Curvature Condition").set("Type", "Null Curvature Condition");
  ls.set("Function Evaluation Limit", 40);

  long krylov_its = 0;
  auto krylov = ROL::makePtr<MinresKrylov>(map, opt, &krylov_its);
  ROL::Ptr<ROL::Secant<double>> secant = ROL::nullPtr;
  auto descent = ROL::makePtr<ROL::NewtonKrylov_U<double>>(list, krylov, secant);
  ROL::TypeU::LineSearchAlgorithm<double> alg(list, descent);
  auto status = ROL::makePtr<RodStatusTest>(mon, obj, true);
  status->set_krylov_counter(&krylov_its);
  alg.setStatusTest(status, false);
  Teuchos::oblackholestream out;
  ROL::TypeU::Algorithm<double> &base = alg; // LineSearchAlgorithm hides run(x, obj)
  base.run(x, obj, out);
}

} // namespace rodnet
