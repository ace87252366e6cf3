// nox_solver.cpp - RN_SOLVER_NOX: NOX Newton on grad E = 0 (issue 7, section 3).
//
// The path that works in Debian's Trilinos 13.2 (TRILINOS.md): a
// Thyra::StateFuncModelEvaluatorBase whose residual f(x) is the gradient of the energy
// and whose W is the assembled Hessian (a Thyra wrapper of the System's
// Tpetra::CrsMatrix), solved by NOX::Thyra::Group's line-search-based Newton with full
// steps and a Stratimikos Belos MINRES linear solver, left-preconditioned by the same
// SPD Preconditioner as the Newton-Krylov trust region.
//
// With a couple fixed in space (rodnet_couple.h) the residual is the gradient of
// the conservative terms minus the couple's generalised force, W its (nonsymmetric)
// Jacobian, and the linear solver restarted GMRES.
//
// NOX solves grad E = 0, so it converges to stationary points: minima, saddles or
// maxima alike (it neither measures the energy nor follows negative curvature).
// RESULT.json says so ("finds": "stationary point").
//
// Reference state: after every Newton step an observer accepts the new iterate
// (System::accept: explicit reference update, rigid-joint rotations moved into the
// reference); when that changes x the group gets the new x and recomputes f.  The
// stopping decision is rodnet's Monitor (the same tests as the trust regions), wrapped
// as a NOX status test together with NOX's finite-value check.
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include <NOX_Observer.hpp>
#include <NOX_Solver_Factory.H>
#include <NOX_Solver_Generic.H>
#include <NOX_StatusTest_Combo.H>
#include <NOX_StatusTest_FiniteValue.H>
#include <NOX_StatusTest_Generic.H>
#include <NOX_Thyra_Group.H>
#include <NOX_Thyra_Vector.H>
#include <Stratimikos_DefaultLinearSolverBuilder.hpp>
#include <Teuchos_ParameterList.hpp>
#include <Thyra_DefaultPreconditioner.hpp>
#include <Thyra_StateFuncModelEvaluatorBase.hpp>
#include <Thyra_TpetraThyraWrappers.hpp>

#include "system/dist_system.hpp"
#include "newton/monitor.hpp"
#include "pc/preconditioner.hpp"
#include "rodnet_couple.h"
#include "base/shim_error.hpp"
#include "newton/solvers.hpp"
#include "system/system.hpp"
#include "system/system_serial.hpp"

namespace rodnet {

namespace {

using ThyraVector = ::Thyra::VectorBase<double>;
using Extract = ::Thyra::TpetraOperatorVectorExtraction<double, LO, GO>;

// y = M^{-1} x through the preconditioner, counting applications: preconditioned
// MINRES applies M^{-1} once per iteration plus once at the start, so the count
// gives the Krylov iterations (NOX's Thyra group does not report them).
class CountingInverse : public Tpetra::Operator<> {
public:
  explicit CountingInverse(const Preconditioner &prec) : prec_(prec) {}
  Teuchos::RCP<const TMap> getDomainMap() const override {
    return prec_.inverse()->getDomainMap();
  }
  Teuchos::RCP<const TMap> getRangeMap() const override {
    return prec_.inverse()->getRangeMap();
  }
  void apply(const TMV &X, TMV &Y, Teuchos::ETransp mode, double alpha,
             double beta) const override {
    ++applies_;
    prec_.inverse()->apply(X, Y, mode, alpha, beta);
  }
  long applies() const { return applies_; }

private:
  const Preconditioner &prec_;
  mutable long applies_ = 0;
};

// W: applies the System's Hessian of the moment (with contact, assemble_hessian may
// replace the matrix by one on a new pattern, system_serial.hpp).
class CurrentHessian : public Tpetra::Operator<> {
public:
  explicit CurrentHessian(const System &sys) : sys_(sys) {}
  Teuchos::RCP<const TMap> getDomainMap() const override { return sys_.map(); }
  Teuchos::RCP<const TMap> getRangeMap() const override { return sys_.map(); }
  void apply(const TMV &X, TMV &Y, Teuchos::ETransp mode, double alpha,
             double beta) const override {
    sys_.hessian()->apply(X, Y, mode, alpha, beta);
  }

private:
  const System &sys_;
};

// Residual f(x) = grad E(x), Jacobian W = Hessian, preconditioner = the SPD M^{-1}.
class GradientModel : public ::Thyra::StateFuncModelEvaluatorBase<double> {
  using InArgs = ::Thyra::ModelEvaluatorBase::InArgs<double>;
  using OutArgs = ::Thyra::ModelEvaluatorBase::OutArgs<double>;
  using InArgsSetup = ::Thyra::ModelEvaluatorBase::InArgsSetup<double>;
  using OutArgsSetup = ::Thyra::ModelEvaluatorBase::OutArgsSetup<double>;
  using MEB = ::Thyra::ModelEvaluatorBase;

public:
  GradientModel(System &sys, Preconditioner &prec)
      : sys_(sys), prec_(prec), space_(::Thyra::createVectorSpace<double>(sys.map())),
        counter_(Teuchos::rcp(new CountingInverse(prec))) {
    x0_ = ::Thyra::createMember(space_);
    TMV x(sys.map(), 1);
    sys.get_state(x);
    Extract::getTpetraMultiVector(x0_)->assign(x);
    InArgsSetup in;
    in.setModelEvalDescription("rodnet gradient model");
    in.setSupports(MEB::IN_ARG_x);
    in_ = in;
    nominal_ = in_;
    nominal_.set_x(x0_);
  }

  Teuchos::RCP<const ::Thyra::VectorSpaceBase<double>> get_x_space() const override {
    return space_;
  }
  Teuchos::RCP<const ::Thyra::VectorSpaceBase<double>> get_f_space() const override {
    return space_;
  }
  InArgs getNominalValues() const override { return nominal_; }
  InArgs createInArgs() const override { return in_; }
  Teuchos::RCP<::Thyra::LinearOpBase<double>> create_W_op() const override {
    // The Hessian, whose values assemble_hessian() overwrites in place.
    return ::Thyra::createLinearOp<double, LO, GO>(
        Teuchos::rcp_implicit_cast<Tpetra::Operator<>>(
            Teuchos::rcp(new CurrentHessian(sys_))),
        space_, space_);
  }
  Teuchos::RCP<::Thyra::PreconditionerBase<double>> create_W_prec() const override {
    return Teuchos::rcp(new ::Thyra::DefaultPreconditioner<double>());
  }
  Teuchos::RCP<const ::Thyra::LinearOpWithSolveFactoryBase<double>>
  get_W_factory() const override {
    return Teuchos::null; // given to the group explicitly
  }

  // Evaluations since construction (reported by the solver).
  int evaluations() const { return evaluations_; }
  // Preconditioner applications so far: the Krylov iterations plus one per solve.
  long preconditioner_applies() const { return counter_->applies(); }

private:
  OutArgs createOutArgsImpl() const override {
    OutArgsSetup out;
    out.setModelEvalDescription("rodnet gradient model");
    out.setSupports(MEB::OUT_ARG_f);
    out.setSupports(MEB::OUT_ARG_W_op);
    out.setSupports(MEB::OUT_ARG_W_prec);
    return out;
  }

  void evalModelImpl(const InArgs &in, const OutArgs &out) const override {
    ++evaluations_;
    auto x = Extract::getConstTpetraMultiVector(in.get_x());
    const Teuchos::RCP<ThyraVector> f = out.get_f();
    if (!f.is_null()) {
      auto g = Extract::getTpetraMultiVector(f);
      if (sys_.gradient(*x, nullptr, *g) != RN_OK)
        throw Error(RN_ERR_SOLVER, "rn_solve (nox): the gradient is degenerate at a "
                                   "Newton iterate (full Newton steps do not stay in "
                                   "the admissible set; try a trust-region solver)");
    }
    // NOX asks for W and for its preconditioner in separate calls at the same x:
    // assemble and set up once per x.
    if (!out.get_W_op().is_null()) assemble_at(*x);
    const auto W_prec = out.get_W_prec();
    if (!W_prec.is_null()) {
      assemble_at(*x);
      if (!prec_ready_) {
        prec_.setup(sys_);
        prec_ready_ = true;
      }
      auto M =
          Teuchos::rcp_dynamic_cast<::Thyra::DefaultPreconditioner<double>>(W_prec, true);
      M->initializeLeft(::Thyra::createLinearOp<double, LO, GO>(
          Teuchos::rcp_implicit_cast<Tpetra::Operator<>>(counter_), space_, space_));
    }
  }

  // The Hessian at x (and a fresh preconditioner set-up), unless the last one was
  // assembled at this very x.
  void assemble_at(const TMV &x) const {
    if (!hessian_x_.is_null()) {
      TMV d(x, Teuchos::Copy);
      d.update(-1.0, *hessian_x_, 1.0);
      Teuchos::Array<double> n(1);
      d.normInf(n());
      if (n[0] == 0.0) return;
    }
    sys_.assemble_hessian(x);
    hessian_x_ = Teuchos::rcp(new TMV(x, Teuchos::Copy));
    prec_ready_ = false;
  }

  System &sys_;
  Preconditioner &prec_;
  Teuchos::RCP<const ::Thyra::VectorSpaceBase<double>> space_;
  Teuchos::RCP<ThyraVector> x0_;
  InArgs in_, nominal_;
  Teuchos::RCP<CountingInverse> counter_;
  mutable Teuchos::RCP<TMV> hessian_x_;
  mutable bool prec_ready_ = false;
  mutable int evaluations_ = 0;
};

// The Tpetra view of a NOX::Thyra vector.
Teuchos::RCP<const TMV> tpetra_of(const NOX::Abstract::Vector &v) {
  const auto &nv = dynamic_cast<const NOX::Thyra::Vector &>(v);
  return Extract::getConstTpetraMultiVector(nv.getThyraRCPVector());
}

// After each Newton step: explicit reference update of the new iterate.
class AcceptObserver : public NOX::Observer {
public:
  explicit AcceptObserver(System &sys) : sys_(sys) {}
  void runPostIterate(const NOX::Solver::Generic &solver) override {
    auto &group = const_cast<NOX::Thyra::Group &>(
        dynamic_cast<const NOX::Thyra::Group &>(solver.getSolutionGroup()));
    auto x = tpetra_of(group.getX());
    TMV accepted(*x, Teuchos::Copy);
    sys_.accept(accepted);
    TMV diff(accepted, Teuchos::Copy);
    diff.update(-1.0, *x, 1.0);
    Teuchos::Array<double> n(1);
    diff.normInf(n());
    if (n[0] == 0.0) return; // only the reference frames moved: f is unchanged
    // Rigid-joint rotations moved into the reference: a new chart, so a new x and f.
    auto thyra_x = ::Thyra::createMember(::Thyra::createVectorSpace<double>(sys_.map()));
    Extract::getTpetraMultiVector(thyra_x)->assign(accepted);
    group.setX(NOX::Thyra::Vector(thyra_x));
    group.computeF();
  }

private:
  System &sys_;
};

// rodnet's stopping tests (Monitor) as a NOX status test.  Also reports progress, so
// it is called once per Newton iteration (NOX checks the status once per step).
class MonitorTest : public NOX::StatusTest::Generic {
public:
  MonitorTest(System &sys, Monitor &mon, const GradientModel &model)
      : sys_(sys), mon_(mon), model_(model) {}

  NOX::StatusTest::StatusType checkStatus(const NOX::Solver::Generic &solver,
                                          NOX::StatusTest::CheckType) override {
    const auto &group = solver.getSolutionGroup();
    auto x = tpetra_of(group.getX());
    double E = std::numeric_limits<double>::quiet_NaN();
    if (sys_.energy(*x, &E) != RN_OK) E = std::numeric_limits<double>::quiet_NaN();
    Teuchos::Array<double> n(1);
    x->norm2(n());
    IterationView it;
    it.iteration = solver.getNumIterations();
    it.energy = E;
    it.gnorm = group.getNormF();
    it.eq = sys_.equilibrium(
        *x, *tpetra_of(dynamic_cast<const NOX::Thyra::Group &>(group).getF()));
    it.krylov = krylov_of();
    it.x_norm = n[0];
    if (it.iteration > 0) {
      it.accepted = true;
      it.unconstrained = true; // full Newton steps
      TMV s(*x, Teuchos::Copy);
      s.update(-1.0, *tpetra_of(solver.getPreviousSolutionGroup().getX()), 1.0);
      s.norm2(n());
      it.step_norm = n[0];
      it.energy_change = E - last_energy_;
    }
    last_energy_ = E;
    status_ = mon_.check(it) ? (mon_.converged() ? NOX::StatusTest::Converged
                                                 : NOX::StatusTest::Failed)
                             : NOX::StatusTest::Unconverged;
    return status_;
  }
  NOX::StatusTest::StatusType getStatus() const override { return status_; }
  std::ostream &print(std::ostream &stream, int indent) const override {
    for (int i = 0; i < indent; ++i) stream << ' ';
    return stream << "rodnet monitor: " << rn_solve_stop_name(mon_.reason()) << "\n";
  }

private:
  // MINRES iterations of the last Newton step: its preconditioner applications but
  // the first (the initial residual).
  int krylov_of() {
    const long applies = model_.preconditioner_applies(), last = applies - applies_seen_;
    applies_seen_ = applies;
    return last > 0 ? static_cast<int>(last - 1) : 0;
  }

  System &sys_;
  Monitor &mon_;
  const GradientModel &model_;
  double last_energy_ = 0.0;
  long applies_seen_ = 0;
  NOX::StatusTest::StatusType status_ = NOX::StatusTest::Unevaluated;
};

// The network a System evaluates (nullptr if it is neither kind).
const rn_network *network_of(System &sys) {
  if (auto *serial = dynamic_cast<SerialSystem *>(&sys))
    return serial->problem().network();
  if (auto *dist = dynamic_cast<DistSystem *>(&sys)) return dist->network();
  return nullptr;
}

// Stratimikos' parameters of the linear solves: Belos MINRES (restarted GMRES for a
// nonsymmetric Jacobian) to krylov_tol, preconditioned by the model's W_prec.
Teuchos::RCP<Teuchos::ParameterList> linear_solver_parameters(const rn_solve_options &opt,
                                                              bool nonsymmetric) {
  auto lsp = Teuchos::rcp(new Teuchos::ParameterList);
  lsp->set("Linear Solver Type", "Belos");
  auto &belos = lsp->sublist("Linear Solver Types").sublist("Belos");
  const char *krylov = nonsymmetric ? "Pseudo Block GMRES" : "MINRES";
  belos.set("Solver Type", krylov);
  auto &minres = belos.sublist("Solver Types").sublist(krylov);
  minres.set("Convergence Tolerance", opt.krylov_tol);
  minres.set("Maximum Iterations", opt.krylov_max_iterations);
  if (nonsymmetric) minres.set("Num Blocks", std::min(opt.krylov_max_iterations, 200));
  lsp->set("Preconditioner Type", "None"); // the model's W_prec
  return lsp;
}

// NOX's parameters: full Newton steps with inexact-Newton forcing terms, the
// observer that accepts every iterate into sys, no printing.
Teuchos::RCP<Teuchos::ParameterList> newton_parameters(const rn_solve_options &opt,
                                                       System &sys) {
  auto params = Teuchos::rcp(new Teuchos::ParameterList);
  params->set("Nonlinear Solver", "Line Search Based");
  params->sublist("Line Search").set("Method", "Full Step");
  params->sublist("Direction").set("Method", "Newton");
  auto &newton = params->sublist("Direction").sublist("Newton");
  // Inexact Newton with the forcing terms of the Newton-Krylov trust region
  // (Eisenstat-Walker choice 2: eta_k = 0.9 (|F_k| / |F_k-1|)^2, at most 0.1), never
  // below what MINRES can reach in double precision with an exact preconditioner of
  // an ill-conditioned Hessian (measured: M^-1 H v = v to 5e-10 on a 101-vertex
  // cantilever; a tighter request stagnates there for the maximum iterations).
  newton.set("Forcing Term Method", "Type 2");
  newton.set("Forcing Term Initial Tolerance", 0.1);
  newton.set("Forcing Term Maximum Tolerance", 0.1);
  newton.set("Forcing Term Minimum Tolerance", std::max(opt.krylov_tol, 1e-4));
  newton.set("Forcing Term Alpha", 2.0);
  newton.set("Forcing Term Gamma", 0.9);
  if (opt.forcing > 0.0) { // a constant forcing (rn_solve_options.forcing)
    newton.set("Forcing Term Method", "Constant");
    newton.sublist("Linear Solver").set("Tolerance", opt.forcing);
  }
  params->sublist("Printing").set("Output Information", 0);
  params->sublist("Solver Options")
      .set<Teuchos::RCP<NOX::Observer>>("Observer",
                                        Teuchos::rcp(new AcceptObserver(sys)));
  params->sublist("Solver Options").set("Status Test Check Type", "Minimal");
  return params;
}

} // namespace

void run_nox(System &sys, Preconditioner &prec, Monitor &mon,
             const rn_solve_options &opt) {
  auto model = Teuchos::rcp(new GradientModel(sys, prec));
  // A couple fixed in space (rodnet_couple.h) makes the residual's Jacobian
  // nonsymmetric: restarted GMRES instead of MINRES, the same preconditioner (built
  // from the assembled Jacobian; it stays a preconditioner, GMRES does not need it
  // symmetric).
  const bool nonsymmetric =
      rn_network_fixed_couples(network_of(sys), nullptr, nullptr) > 0;

  Stratimikos::DefaultLinearSolverBuilder builder;
  builder.setParameterList(linear_solver_parameters(opt, nonsymmetric));
  auto lows = builder.createLinearSolveStrategy("");

  auto x0 = ::Thyra::createMember(model->get_x_space());
  ::Thyra::V_V(x0.ptr(), *model->getNominalValues().get_x());
  NOX::Thyra::Vector nx0(x0);
  auto W = model->create_W_op();
  auto M = model->create_W_prec();
  auto group = Teuchos::rcp(
      new NOX::Thyra::Group(nx0, model, W, lows, M,
                            Teuchos::RCP<::Thyra::PreconditionerFactoryBase<double>>()));

  auto params = newton_parameters(opt, sys);

  auto monitor_test = Teuchos::rcp(new MonitorTest(sys, mon, *model));
  auto tests = Teuchos::rcp(new NOX::StatusTest::Combo(NOX::StatusTest::Combo::OR));
  tests->addStatusTest(Teuchos::rcp(new NOX::StatusTest::FiniteValue));
  tests->addStatusTest(monitor_test);

  auto solver = NOX::Solver::buildSolver(group, tests, params);
  solver->solve();
  // The final iterate is the network's state (reference updated by the observer).
  sys.set_state(*tpetra_of(solver->getSolutionGroup().getX()));
}

rn_preconditioner run_nox(System &sys, Monitor &mon, const rn_solve_options &opt) {
  rn_preconditioner used = RN_PRECOND_AUTO;
  const std::unique_ptr<Preconditioner> prec = make_preconditioner(sys, opt, &used);
  struct Account { // the preconditioner's time, also when the run throws
    System &s;
    const Preconditioner &p;
    ~Account() {
      s.add_preconditioner_time(p.stats().setup_seconds, p.stats().apply_seconds);
    }
  } account{sys, *prec};
  run_nox(sys, *prec, mon, opt);
  return used;
}

rn_preconditioner run_nox(Problem &p, Monitor &mon, const rn_solve_options &opt) {
  SerialSystem sys(p);
  return run_nox(sys, mon, opt);
}

} // namespace rodnet
