// stability_lobpcg.cpp - the stability check without a factorisation of the whole
// Hessian: the lowest eigenvalues of the Jacobi-scaled Hessian D^{-1/2} H D^{-1/2}
// by Anasazi's LOBPCG on a System (serial or distributed; see stability.hpp).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <vector>

#include <AnasaziBasicEigenproblem.hpp>
#include <AnasaziLOBPCGSolMgr.hpp>
#include <AnasaziTpetraAdapter.hpp>
#include <Teuchos_ParameterList.hpp>
#include <Tpetra_Import.hpp>
#include <Tpetra_Vector.hpp>

#include "pc/preconditioner.hpp"
#include "factor/sparse_cholesky.hpp"
#include "factor/spd_factor.hpp"
#include "system/system_serial.hpp"
#include "base/shim_error.hpp"
#include "newton/solvers.hpp"
#include "eigen/stability.hpp"
#include "system/system.hpp"

namespace rodnet {

namespace {

using TOp = Tpetra::Operator<>;
using TVec = Tpetra::Vector<>;

constexpr int kLobpcgMaxIterations = 1000;
constexpr double kLobpcgResidual = 1e-10; // ||A y - mu y|| <= 1e-10 scale, ||y|| = 1
constexpr double kMetricFloor = 1e-20;    // as stability.cpp

// y = beta y + alpha W op(W x), W = diag(w): the operator op scaled on both sides
// (by_column: op applied to one column at a time).
class ScaledOperator : public TOp {
public:
  ScaledOperator(Teuchos::RCP<const TOp> op, Teuchos::RCP<const TVec> w, bool by_column)
      : op_(std::move(op)), w_(std::move(w)), by_column_(by_column) {}
  Teuchos::RCP<const TMap> getDomainMap() const override { return w_->getMap(); }
  Teuchos::RCP<const TMap> getRangeMap() const override { return w_->getMap(); }
  void apply(const TMV &x, TMV &y, Teuchos::ETransp /*mode*/, double alpha,
             double beta) const override {
    const size_t k = x.getNumVectors();
    if (a_.is_null() || a_->getNumVectors() != k) {
      a_ = Teuchos::rcp(new TMV(w_->getMap(), k));
      b_ = Teuchos::rcp(new TMV(w_->getMap(), k));
    }
    a_->elementWiseMultiply(1.0, *w_, x, 0.0);
    if (by_column_) // (Preconditioner::takes_blocks: the gathered and local take one)
      for (size_t j = 0; j < k; ++j)
        op_->apply(*a_->getVector(j), *b_->getVectorNonConst(j));
    else
      op_->apply(*a_, *b_);
    y.elementWiseMultiply(alpha, *w_, *b_, beta);
  }

private:
  Teuchos::RCP<const TOp> op_;
  Teuchos::RCP<const TVec> w_;
  bool by_column_;
  mutable Teuchos::RCP<TMV> a_, b_;
};

// D = |diag H| floored at kMetricFloor of its largest entry (over all ranks).
Teuchos::RCP<TVec> metric(const TCrs &H) {
  auto d = Teuchos::rcp(new TVec(H.getRowMap()));
  H.getLocalDiagCopy(*d);
  d->abs(*d);
  const double dmax = d->normInf();
  auto v = d->getLocalViewHost(Tpetra::Access::ReadWrite);
  for (size_t i = 0; i < v.extent(0); ++i)
    v(i, 0) = std::max(v(i, 0), kMetricFloor * dmax);
  return d;
}

// ||W H W||_inf over all ranks (w on the row map).
double scaled_norm_inf(const TCrs &H, const TVec &w) {
  TVec wc(H.getColMap());
  Tpetra::Import<> imp(H.getRowMap(), H.getColMap());
  wc.doImport(w, imp, Tpetra::INSERT);
  auto wr = w.getLocalViewHost(Tpetra::Access::ReadOnly);
  auto wcv = wc.getLocalViewHost(Tpetra::Access::ReadOnly);
  double s = 0.0;
  TCrs::local_inds_host_view_type cols;
  TCrs::values_host_view_type vals;
  for (size_t i = 0; i < H.getNodeNumRows(); ++i) {
    H.getLocalRowView(static_cast<LO>(i), cols, vals);
    double r = 0.0;
    for (size_t k = 0; k < cols.extent(0); ++k)
      r += std::fabs(vals(k)) * wcv(static_cast<size_t>(cols(k)), 0);
    s = std::max(s, r * wr(i, 0));
  }
  double g = 0.0;
  Teuchos::reduceAll(*H.getComm(), Teuchos::REDUCE_MAX, s, Teuchos::outArg(g));
  return g;
}

// Pseudo-random start vectors in [-1, 1], a function of the global DOF index and
// the column only: the same on any number of ranks.
void start_block(TMV &X) {
  const TMap &map = *X.getMap();
  auto v = X.getLocalViewHost(Tpetra::Access::OverwriteAll);
  for (size_t j = 0; j < X.getNumVectors(); ++j)
    for (size_t i = 0; i < v.extent(0); ++i) {
      uint64_t h = static_cast<uint64_t>(map.getGlobalElement(static_cast<LO>(i))) *
                       0x9E3779B97F4A7C15ULL +
                   (j + 1) * 0xBF58476D1CE4E5B9ULL;
      h ^= h >> 31;
      h *= 0x94D049BB133111EBULL;
      h ^= h >> 29;
      v(i, j) = static_cast<double>(h >> 11) * (2.0 / 9007199254740992.0) - 1.0;
    }
}

// The scalings of the metric d: w = d^{-1/2} and winv = d^{1/2}.
void scaling(const TVec &d, TVec &w, TVec &winv) {
  auto dv = d.getLocalViewHost(Tpetra::Access::ReadOnly);
  auto wv = w.getLocalViewHost(Tpetra::Access::OverwriteAll);
  auto iv = winv.getLocalViewHost(Tpetra::Access::OverwriteAll);
  for (size_t i = 0; i < dv.extent(0); ++i) {
    wv(i, 0) = 1.0 / std::sqrt(dv(i, 0));
    iv(i, 0) = std::sqrt(dv(i, 0));
  }
}

// Anasazi LOBPCG's parameters: the block's smallest real eigenvalues to an absolute
// residual kLobpcgResidual scale, locking, full orthogonalisation, no output.
Teuchos::ParameterList lobpcg_parameters(int block, double scale) {
  Teuchos::ParameterList pl;
  pl.set("Which", std::string("SR"));
  pl.set("Block Size", block);
  pl.set("Maximum Iterations", kLobpcgMaxIterations);
  pl.set("Convergence Tolerance", kLobpcgResidual * scale);
  pl.set("Relative Convergence Tolerance", false);
  pl.set("Use Locking", true);
  pl.set("Locking Tolerance", 0.1 * kLobpcgResidual * scale);
  pl.set("Relative Locking Tolerance", false);
  pl.set("Full Ortho", true);
  // library code prints nothing: Anasazi's messages (errors included) go to a sink
  pl.set("Verbosity", static_cast<int>(Anasazi::Errors));
  pl.set("Output Stream",
         Teuchos::getFancyOStream(Teuchos::rcp(new Teuchos::oblackholestream)));
  return pl;
}

// The verdict from the ascending Ritz values mu when the zero modes are not
// separated (distributed): every value in the zero band [-delta, delta] a zero mode.
void zero_band_verdict(const std::vector<double> &mu, double delta, bool converged,
                       rn_stability &st) {
  size_t j = 0;
  while (j < mu.size() && std::fabs(mu[j]) <= delta) ++j;
  if (mu[0] < -delta) {
    st.lowest_eigenvalue = mu[0];
    for (double m : mu) st.zero_modes += std::fabs(m) <= delta;
  } else {
    st.zero_modes = static_cast<int>(j);
    if (j < mu.size()) {
      st.lowest_eigenvalue = mu[j];
      st.verified_minimum = converged && mu[j] > delta;
    }
  }
}

// The verdict with the number of symmetries known: the `symmetries` Ritz values in
// the zero band nearest 0 are the symmetries; the other ones in the band are soft
// modes, whose sign LOBPCG's residuals (1e-10 scale) cannot resolve: no verified
// minimum with any.
void symmetry_verdict(const std::vector<double> &mu, double delta, int symmetries,
                      bool converged, rn_stability &st) {
  std::vector<size_t> band;
  for (size_t i = 0; i < mu.size(); ++i)
    if (std::fabs(mu[i]) <= delta) band.push_back(i);
  std::sort(band.begin(), band.end(),
            [&](size_t a, size_t b) { return std::fabs(mu[a]) < std::fabs(mu[b]); });
  std::vector<char> sym(mu.size(), 0);
  st.symmetries = std::min(symmetries, static_cast<int>(band.size()));
  for (int i = 0; i < st.symmetries; ++i) sym[band[static_cast<size_t>(i)]] = 1;
  st.soft_modes = static_cast<int>(band.size()) - st.symmetries;
  st.zero_modes = static_cast<int>(band.size());
  size_t lo = 0;
  while (lo < mu.size() && sym[lo]) ++lo;
  if (lo < mu.size()) {
    st.lowest_eigenvalue = mu[lo];
    st.verified_minimum = converged && st.soft_modes == 0 && mu[lo] > delta;
  }
}

} // namespace

rn_stability lobpcg_stability(System &sys, const rn_solve_options &opt,
                              Preconditioner *given, int symmetries) {
  const auto start = std::chrono::steady_clock::now();
  rn_stability st{};
  st.checked = 1;
  st.method = RN_STABILITY_LOBPCG;
  st.symmetries = st.soft_modes = -1; // not separated unless the count is given
  const GO n = sys.global_size();
  const Teuchos::RCP<const TCrs> H = sys.hessian();
  const Teuchos::RCP<TVec> d = metric(*H);
  auto w = Teuchos::rcp(new TVec(d->getMap())),
       winv = Teuchos::rcp(new TVec(d->getMap()));
  scaling(*d, *w, *winv);
  st.scale = scaled_norm_inf(*H, *w);
  if (!std::isfinite(st.scale))
    throw Error(RN_ERR_NOT_FINITE, "stability: non-finite Hessian");
  if (n == 0) {
    st.verified_minimum = 1;
    st.symmetries = st.soft_modes = 0;
  } else if (!(st.scale > 0.0)) {
    st.zero_modes = static_cast<int>(std::min<GO>(n, kStabilityBlock));
  } else {
    const double delta = kZeroModeTol * st.scale;
    // the solver's SPD preconditioner M^{-1} ~ H^{-1}, scaled as W^{-1} M^{-1} W^{-1}:
    // the one given (the solve's, set up at the state: not a second set-up), else
    // one made and set up here
    rn_preconditioner used = RN_PRECOND_AUTO;
    std::unique_ptr<Preconditioner> own;
    Preconditioner *prec = given;
    if (!prec) {
      own = make_preconditioner(sys, opt, &used);
      own->setup(sys);
      prec = own.get();
    }
    auto A = Teuchos::rcp(new ScaledOperator(H, w, false));
    auto P =
        Teuchos::rcp(new ScaledOperator(prec->inverse(), winv, !prec->takes_blocks()));
    const int block = static_cast<int>(std::min<GO>(n, kStabilityBlock));
    const int nev = std::max(1, std::min(block, kStabilityBlock - 2));
    auto X0 = Teuchos::rcp(new TMV(sys.map(), static_cast<size_t>(block)));
    start_block(*X0);
    auto problem = Teuchos::rcp(new Anasazi::BasicEigenproblem<double, TMV, TOp>(A, X0));
    problem->setHermitian(true);
    problem->setNEV(nev);
    problem->setPrec(P);
    if (!problem->setProblem())
      throw Error(RN_ERR_INTERNAL, "stability: Anasazi rejected the eigenproblem");
    Teuchos::ParameterList pl = lobpcg_parameters(block, st.scale);
    Anasazi::LOBPCGSolMgr<double, TMV, TOp> solver(problem, pl);
    Anasazi::ReturnType ret = Anasazi::Unconverged;
    try {
      ret = solver.solve();
    } catch (const Error &) {
      throw;
    } catch (const std::exception &) {
      // a breakdown inside Anasazi (a rank-deficient block, a preconditioner that is
      // not SPD enough for the Rayleigh-Ritz step): no verdict, not an error of the solve
      st.checked = 0;
    }
    st.iterations = solver.getNumIters();
    const Anasazi::Eigensolution<double, TMV> &sol = problem->getSolution();
    std::vector<double> mu;
    for (int i = 0; i < sol.numVecs; ++i)
      mu.push_back(sol.Evals[static_cast<size_t>(i)].realpart);
    std::sort(mu.begin(), mu.end());
    // no Ritz pair came out (LOBPCG broke down or converged none): the check did
    // not happen, which is not the same as a lowest eigenvalue of 0
    if (mu.empty()) st.checked = 0;
    const bool converged = ret == Anasazi::Converged;
    if (st.checked && !mu.empty() && symmetries < 0) // zero modes not separated
      zero_band_verdict(mu, delta, converged, st);
    else if (st.checked && !mu.empty())
      symmetry_verdict(mu, delta, symmetries, converged, st);
  }
  st.time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return st;
}

rn_stability solve_stability(Problem &p, System *dist, const rn_solve_options &opt,
                             rn_factorization kind, KrylovWorkspace *ws) {
  const int method = opt.stability_method;
  if (dist) {
    if (method == RN_STABILITY_CHOLESKY) return rn_stability{}; // needs the whole H
    System &sys = ws ? ws->system() : *dist; // (the workspace's System is dist)
    TMV x(sys.map(), 1);
    sys.get_state(x);
    sys.assemble_hessian(x);
    return lobpcg_stability(sys, opt, ws ? &ws->preconditioner() : nullptr);
  }
  double flops = 0.0;
  bool lobpcg = method == RN_STABILITY_LOBPCG;
  if (method == RN_STABILITY_AUTO) {
    const bool krylov_only =
        (opt.solver == RN_SOLVER_TR_KRYLOV || opt.solver == RN_SOLVER_NOX) &&
        opt.preconditioner != RN_PRECOND_FACTOR;
    if (kind == RN_FACTOR_BANDED) {
      const double b = static_cast<double>(p.bandwidth()) + 1.0;
      flops = static_cast<double>(p.size()) * b * b;
    } else if (krylov_only) {
      flops = p.sparse_analysis()->factor_flops();
    }
    lobpcg = krylov_only && flops > RN_STABILITY_MAX_FLOPS;
  }
  rn_stability st{};
  if (lobpcg && ws) { // the solve's System (on p) and preconditioner
    System &sys = ws->system();
    TMV x(sys.map(), 1);
    sys.get_state(x);
    sys.assemble_hessian(x);
    st = lobpcg_stability(sys, opt, &ws->preconditioner(), count_symmetries(p));
  } else if (lobpcg) {
    SerialSystem sys(p);
    TMV x(sys.map(), 1);
    sys.get_state(x);
    sys.assemble_hessian(x);
    st = lobpcg_stability(sys, opt, nullptr, count_symmetries(p));
  } else {
    st = hessian_stability(p, kind);
  }
  st.cholesky_flops = flops;
  return st;
}

} // namespace rodnet
