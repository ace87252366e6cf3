// tr_minres.cpp - rodnet's trust-region Newton-MINRES (RN_SOLVER_TR_MINRES).
//
// A ROL::TypeU::Algorithm over ROL::TpetraMultiVector.  Iteration k at the accepted
// state x (reference frames of x):
//  1. gradient g and CSR Hessian H at x; metric D = |diag H| of the first iteration
//     (floored), fixed for the load step; trust-region norm ||s||_D = sqrt(s' D s).
//  2. Factor H (Cholesky: banded for single rods, sparse with a nested-dissection
//     ordering for networks with joints; spd_factor.hpp).  If it fails, H + sigma D is
//     factored with sigma = 1.5 |mu| of the last indefinite Hessian if that works,
//     else the smallest decade that does, and shift-and-invert Lanczos with that
//     factorisation (lanczos.hpp, at most kLanczosSteps solves) gives the lowest
//     eigenpair (mu, v) of the pencil (H, D) (mu >= the lowest eigenvalue).
//  3. Multiplier lambda >= max(0, -mu): lambda = 0 if H is positive definite and the
//     Newton step fits the radius; otherwise a More-Sorensen iteration on lambda
//     (Newton on 1/||s(lambda)||_D - 1/radius, safeguarded, with factorisations of
//     H + lambda D) until ||s||_D is within 5 % of the radius.  A factorisation that
//     fails raises the lower bound to that lambda, and the next trial lies above it
//     by a gap that grows tenfold with each consecutive failure.  After a rejected
//     step (same H and g, smaller radius) the search starts from the last multiplier,
//     a lower bound of the new one whose factorisation is kept.  Hard case (H
//     indefinite, step too short even at lambda ~ -mu, e.g. at a symmetric saddle
//     where g is orthogonal to v): s(lambda) + tau v on the boundary, with the sign of
//     tau that lowers the model, so the iteration leaves saddles.
//  4. The step solves (H + lambda D) s = -g by Belos MINRES preconditioned with the
//     Cholesky factorisation of H + (lambda + sigma) D, sigma >= 0 the smallest shift
//     that factors (exact preconditioner when sigma = 0).
//  5. Ratio test rho = (E(x) - E(x+s)) / (-(g's + s'Hs/2)) (with the usual 10 eps |E|
//     safeguard), accept if rho > 1e-4, radius /4 if rho < 1/4, x2 if rho > 3/4 on
//     the boundary.  A degenerate trial point (rn_network_energy > 0) is rejected
//     and the radius shrinks.  Accepted steps call update(x, Accept), i.e.
//     rn_network_update_reference.  Second-order correction: a step the ratio test
//     rejects is corrected for the stretching, x + s + c replacing x + s (and its
//     ratio, with the same predicted decrease) if its energy is lower.  A Newton
//     step linearises rotations, so it stretches the very stiff edges to second order in
//     the step (energy ~ EA |s|^4) while it is right to first order in the soft bending
//     directions (the Maratos effect of stiff, penalty-like terms).  The
//     correction puts the exact edge lengths into the model, keeping everything
//     else quadratic: sigma = s + c solves (H + lambda M) sigma = -g - f(sigma),
//     f(sigma) = sum_j (EA_j / lbar_j) r_j(sigma) dL_j/dx, r_j the length edge j
//     gets from the step beyond its linearisation at x (rn_network_stretch_
//     correction), by fixed-point iteration with the factorisation already there
//     (a solve and one pass over the edges per iteration, no Hessian).  The
//     forces act along the edges at x, which H(x) resists with the stretching
//     stiffness; the correction with the residual g(x + s) - g - Hs instead (the
//     textbook one) has stiff forces along the rotated edges, whose transverse
//     part meets only the soft bending stiffness of H(x) (measured: energies 1e5
//     to 1e20).  Measured in docs/solvers.md: arch P = 8 95 -> 8 iterations.
//     Correcting every step (steps with rho ~ 1 stretch too, which shows in the
//     next gradient) saved a few more iterations (arch 7, 10x10 honeycomb 24
//     instead of 27) but changed the last Newton steps, and the 3201-vertex
//     cantilever then stopped at 1.3 times the round-off floor of the residual,
//     1.6e-4 away from the equilibrium tr-krylov finds.
//  5a. Watchdog (nonmonotone acceptance; Chamberlain, Powell, Lemarechal and Pedersen
//     1982).  A step that fails the ratio test only because its trial point has a
//     higher energy (finite) is taken tentatively: x becomes the trial point
//     (reference updated) and the iteration continues from there for at most
//     kWatchdogSteps steps, each of which must pass its own ratio test.  As soon as a
//     trial point's energy is below E(anchor) - 1e-4 pred(anchor step), it is
//     accepted for good; otherwise the state goes back to the anchor (an exact
//     snapshot, rn_network_state_save) and the anchor's step counts as rejected
//     (radius /4), and the next watchdog waits for a monotone acceptance.  Why: a
//     Newton step linearises rotations, so it stretches the very stiff edges to
//     second order in the step (energy ~ EA |s|^4) while it is right to first order
//     in the soft bending directions: the ratio test then rejects good steps and
//     the radius shrinks to what the stretching allows (the Maratos effect of stiff,
//     penalty-like terms).  The next Newton step, from the stretched point, removes
//     the stretch (measured in docs/solvers.md: cantilever alpha = 5, 45 -> 7
//     iterations); where the second-order correction of step 5 does not suffice,
//     the watchdog still does.
//  6. Monitor::check once per iteration; no convergence test passes while the
//     pencil has a significant negative eigenvalue (mu < -1e3 eps), so a saddle is
//     never reported as a solution.  A rejected step at the round-off size of x
//     means the radius collapsed (not converged).
#include <algorithm>
#include <cfloat>
#include <cmath>
#include <limits>
#include <memory>

#include <ROL_TypeU_Algorithm.hpp>
#include <Teuchos_oblackholestream.hpp>

#include "krylov/lanczos.hpp"
#include "krylov/minres.hpp"
#include "newton/monitor.hpp"
#include "system/problem.hpp"
#include "newton/rol_objective.hpp"
#include "base/shim_error.hpp"
#include "newton/solvers.hpp"
#include "factor/spd_factor.hpp"

namespace rodnet {

namespace {

constexpr double kAccept = 1e-4;               // accept a step if rho > kAccept
constexpr double kCurvTol = 1e3 * DBL_EPSILON; // significant negative pencil eigenvalue
constexpr double kBoundaryTol = 0.05; // |  ||s||_D - radius | <= kBoundaryTol radius
constexpr int kMaxMultiplierIts = 60;
// Lanczos steps (solves, and vectors kept) for the lowest eigenpair at most.  It need
// not be exact: mu (>= the lowest eigenvalue) starts the multiplier search from
// below, and v has to be a direction of negative curvature.
constexpr int kLanczosSteps = 30;
// Tentative steps of the watchdog at most (measured: 1 step leaves the arch of
// docs/solvers.md at 46 iterations, 2 or more give 14).
constexpr int kWatchdogSteps = 2;
constexpr double kSaddleRadius = 1e-2; // see saddle_radius()
// Second-order correction (step 5 at the top): its fixed-point iteration stops at a
// relative change of kCorrectionTol or after kCorrectionIts solves.  Measured on the
// arch P = 8 of docs/solvers.md: 1e-1, 1e-2, 1e-3, 1e-4 give 60, 36, 18, 8
// iterations, smaller tolerances 8; stopping as soon as the change grows instead
// (the map need not be a contraction from the start) made the 10x10 honeycomb worse
// (36 -> 41).
constexpr double kCorrectionTol = 1e-4;
constexpr int kCorrectionIts = 50;
constexpr double kCorrectionGrowth = 1e3; // change / first change: diverging

// y = (H + shift M) x with the assembled Hessian and the metric's CSR values m.
class ShiftedHessian : public VectorOperator {
public:
  ShiftedHessian(Problem &p, const double *m, double shift)
      : p_(p), m_(m), shift_(shift) {}
  void apply(const MV &x, MV &y) const override {
    p_.hessian_apply(host_data(x), host_data(y), shift_, m_);
  }

private:
  Problem &p_;
  const double *m_;
  double shift_;
};

// y = A^{-1} x with a Cholesky factorisation.
class FactorPreconditioner : public VectorOperator {
public:
  explicit FactorPreconditioner(const SpdFactor &f) : f_(f) {}
  void apply(const MV &x, MV &y) const override {
    const double *in = host_data(x);
    double *out = host_data(y);
    std::copy(in, in + x.getLocalLength(), out);
    f_.solve(out);
  }

private:
  const SpdFactor &f_;
};

struct Step {
  std::vector<double> s;
  double lambda = 0.0;
  bool boundary = false;
  int krylov = 0;
};

class TrustRegionMinres : public ROL::TypeU::Algorithm<double> {
public:
  TrustRegionMinres(Problem &p, Monitor &mon, const rn_solve_options &opt,
                    const Teuchos::RCP<const Map> &map)
      : p_(p), mon_(mon), opt_(opt), n_(p.size()),
        f0_(make_spd_factor(p, opt.factorization)),
        fl_(make_spd_factor(p, opt.factorization)),
        minres_(map, opt.krylov_tol, opt.krylov_max_iterations), equilibrium_(p),
        rhs_(map, 1), sol_(map, 1), w_(n_), q_(n_), hs_(n_), ms_(n_) {}

  using ROL::TypeU::Algorithm<double>::run;
  void run(RolVector &x, const RolVector &g, ROL::Objective<double> &obj,
           std::ostream &out) override;

private:
  // The last point accepted by the ratio test while the iteration tries tentative
  // steps from it (watchdog, step 5a).
  struct Anchor {
    bool active = false;
    int steps = 0;         // tentative steps taken from it
    std::vector<double> x; // its state
    double energy = 0.0;   // E(x)
    double pred = 0.0;     // predicted decrease of its (rejected) step
    double radius = 0.0;   // radius and D-norm of that step
    double step = 0.0;
    rn_state *snapshot = nullptr; // the network's whole mutable state there
    ~Anchor() { rn_state_destroy(&snapshot); }
  };

  // What becomes of a trial point: accepted (for good), taken tentatively
  // (watchdog), rejected, or the watchdog given up and the anchor taken back.
  enum class Move { Reject, Accept, Tentative, Back };

  double trial_energy(RolVector &x, RolVector &xtrial, RolVector &xcorr,
                      ROL::Objective<double> &obj, const Step &st, double pred,
                      double tol, double *rho);
  Move choose_move(const double *x, double ftrial, double rho, double pred, double radius,
                   double snorm);
  void analyse_hessian(const double *x);
  void lowest_eigenpair();
  Step solve_subproblem(const double *g, double radius);
  double upper_multiplier(const double *g, double radius) const;
  double gradient_radius(const double *g) const;
  double saddle_radius() const;
  double mdot(const double *a, const double *b);
  double mnorm(const double *a) { return std::sqrt(std::max(0.0, mdot(a, a))); }
  bool trial_step(const double *g, double lambda, double *ns);
  void minres_step(const double *g, double lambda, Step &st);
  void add_curvature_direction(const double *g, double radius, Step &st);
  bool correct_step(const double *x, const Step &st, RolVector &xc);
  double model(const double *g, const double *s);

  Problem &p_;
  Monitor &mon_;
  const rn_solve_options &opt_;
  size_t n_;
  std::vector<double> d_;       // D = |diag H_0| (floored)
  std::vector<double> m_;       // metric M = D as CSR values on the Hessian's pattern
  unsigned long m_version_ = 0; // the pattern's version (Problem::pattern_version)
  // Factorisations of H + sigma0 M (f0_) and of H + fl_lambda_ M (fl_; fl_lambda_ is
  // NaN when fl_ holds no factorisation of the current H at a known multiplier).
  std::unique_ptr<SpdFactor> f0_, fl_;
  double sigma0_ = 0.0, fl_lambda_ = std::numeric_limits<double>::quiet_NaN();
  // The multiplier of the last subproblem at the current H and g (0: none): a
  // lower bound of the next one, whose radius is smaller after a rejected step.
  double lambda_floor_ = 0.0;
  bool negcurv_ = false;
  double mu_ = 0.0;       // lowest eigenvalue estimate of the pencil (H, M)
  double mu_last_ = 0.0;  // mu_ of the last indefinite Hessian (0: none yet)
  std::vector<double> v_; // its eigenvector, ||v||_M = 1
  MinresSolver minres_;
  Equilibrium equilibrium_;
  MV rhs_, sol_;
  std::vector<double> w_, q_, hs_, ms_, sigma_;
  // the watchdog of run()
  Anchor anchor_;
  bool watchdog_blocked_ = false; // after a failed watchdog, until a monotone accept
};

// Hessian analysis at the accepted x: positive definiteness and, if H is not, the
// lowest eigenpair of the pencil (H, M).  The metric M = D = |diag H_0| (floored) is
// fixed for the load step.  (The code takes any SPD M on the Hessian's pattern: the
// shifted current or initial Hessian were measured too, with iteration counts within
// 10 % of the diagonal one on the cantilever and buckling problems.)
void TrustRegionMinres::analyse_hessian(const double *x) {
  p_.assemble_hessian(x);
  if (m_.empty()) d_ = hessian_metric(p_);
  if (m_.empty() || m_version_ != p_.pattern_version()) { // (contact: a new pattern)
    m_ = diagonal_on_pattern(p_, d_);
    m_version_ = p_.pattern_version();
  }
  negcurv_ = false;
  mu_ = 0.0;
  fl_lambda_ = std::numeric_limits<double>::quiet_NaN();
  lambda_floor_ = 0.0;
  sigma0_ = 0.0;
  if (f0_->factor(p_, 0.0, m_.data())) return;
  // Not positive definite.  A shift of 1.5 |mu| of the last indefinite Hessian is
  // tried first (H changes little between iterations: one factorisation, and a shift
  // close to the lowest eigenvalue speeds up Lanczos), then the smallest decade.
  const double guess = -1.5 * mu_last_;
  if (guess > 0.0 && f0_->factor(p_, guess, m_.data()))
    sigma0_ = guess;
  else
    sigma0_ = factor_shifted(*f0_, p_, 0.0, m_.data(), false);
  lowest_eigenpair();
  negcurv_ = mu_ < -kCurvTol;
  mu_last_ = std::min(mu_, 0.0);
}

double TrustRegionMinres::mdot(const double *a, const double *b) {
  p_.pattern_apply(m_.data(), a, ms_.data());
  return dot(n_, ms_.data(), b);
}

// Shift-and-invert Lanczos with the factorisation of H + sigma M (in f0_) gives the
// lowest eigenpair of the pencil (H, M); mu_ is the Rayleigh quotient of the Ritz
// vector (>= the lowest eigenvalue).
void TrustRegionMinres::lowest_eigenpair() {
  v_.assign(n_, 0.0);
  for (size_t i = 0; i < n_; ++i)
    v_[i] = (1.0 + 0.5 * std::sin(0.7 * static_cast<double>(i) + 0.3)) / std::sqrt(d_[i]);
  lanczos_largest([this](double *x) { f0_->solve(x); }, d_, kLanczosSteps, 1e-8, v_);
  p_.hessian_apply(v_.data(), hs_.data());
  mu_ = dot(n_, v_.data(), hs_.data()); // ||v||_M = 1
}

// Initial upper bound of the multiplier (enlarged in the iteration if too small):
// ||g||_{D^-1} / radius + ||D^-1/2 H D^-1/2||_inf.
double TrustRegionMinres::upper_multiplier(const double *g, double radius) const {
  double hn = 0.0;
  for (size_t i = 0; i < n_; ++i) {
    double row = 0.0;
    for (int64_t k = p_.rowptr()[i]; k < p_.rowptr()[i + 1]; ++k)
      row += std::fabs(p_.values()[k]) / std::sqrt(d_[i] * d_[p_.col()[k]]);
    hn = std::max(hn, row);
  }
  return gradient_radius(g) / radius + hn;
}

// ||D^-1 g||_D = sqrt(g' D^-1 g): the length of a diagonally scaled gradient step.
double TrustRegionMinres::gradient_radius(const double *g) const {
  double gn = 0.0;
  for (size_t i = 0; i < n_; ++i) gn += g[i] * g[i] / d_[i];
  return std::sqrt(gn);
}

// Where a load step starts at an indefinite Hessian the first radius is at least a
// displacement of kSaddleRadius times the structure's size at every position DOF,
// in the D-norm.  The gradient says nothing about the size of a step there: the
// load-step predictor often lands on the straight, unstable branch, where g ~ 1e-12
// (the buckling column of shim_buckling.c), and the radius ||D^-1 g||_D then took 25
// doublings to grow to a useful size (109 iterations; 34 with this floor; measured
// 80 with 1e-3 and 91 with 3e-2, docs/solvers.md).
double TrustRegionMinres::saddle_radius() const {
  double dsum = 0.0;
  for (size_t i = 0; i < n_; ++i)
    if (equilibrium_.kinds()[i] == RN_DOF_POSITION) dsum += d_[i];
  return std::max(kSaddleRadius * equilibrium_.size() * std::sqrt(dsum), 1e-8);
}

// Factor H + lambda M into fl_ and put s(lambda) = -(H + lambda M)^{-1} g in w_;
// false if H + lambda M is not positive definite.
bool TrustRegionMinres::trial_step(const double *g, double lambda, double *ns) {
  if (!(fl_lambda_ == lambda && fl_->factored())) { // else: factored there already
    fl_lambda_ = std::numeric_limits<double>::quiet_NaN();
    if (!fl_->factor(p_, lambda, m_.data())) return false;
    fl_lambda_ = lambda;
  }
  for (size_t i = 0; i < n_; ++i) w_[i] = -g[i];
  fl_->solve(w_.data());
  *ns = mnorm(w_.data());
  return true;
}

double TrustRegionMinres::model(const double *g, const double *s) {
  p_.hessian_apply(s, hs_.data());
  return dot(n_, g, s) + 0.5 * dot(n_, s, hs_.data());
}

// Solve (H + lambda M) s = -g with Belos MINRES, preconditioned by the Cholesky
// factorisation of H + (lambda + sigma) M.
void TrustRegionMinres::minres_step(const double *g, double lambda, Step &st) {
  const SpdFactor *prec = f0_.get();
  if (lambda > 0.0 || sigma0_ > 0.0) {
    if (!(fl_->factored() && fl_lambda_ == lambda)) {
      fl_lambda_ = std::numeric_limits<double>::quiet_NaN();
      if (factor_shifted(*fl_, p_, lambda, m_.data()) == 0.0) fl_lambda_ = lambda;
    }
    prec = fl_.get();
  }
  double *b = host_data(rhs_);
  for (size_t i = 0; i < n_; ++i) b[i] = -g[i];
  const ShiftedHessian A(p_, m_.data(), lambda);
  const FactorPreconditioner P(*prec);
  const MinresResult r = minres_.solve(A, P, rhs_, sol_);
  const double *s = host_data(sol_);
  st.s.assign(s, s + n_);
  st.lambda = lambda;
  st.krylov = r.iterations;
}

// Hard case: move along the lowest eigenvector v to the boundary, choosing the root
// tau of ||s + tau v||_M = radius with the lower model value.
void TrustRegionMinres::add_curvature_direction(const double *g, double radius,
                                                Step &st) {
  const double sv = mdot(st.s.data(), v_.data()), ss = mdot(st.s.data(), st.s.data());
  const double disc = std::sqrt(std::max(0.0, sv * sv - (ss - radius * radius)));
  const double taus[2] = {-sv + disc, -sv - disc};
  double best = std::numeric_limits<double>::max(), tau_best = 0.0;
  std::vector<double> trial(n_);
  for (double tau : taus) {
    for (size_t i = 0; i < n_; ++i) trial[i] = st.s[i] + tau * v_[i];
    const double m = model(g, trial.data());
    if (m < best) {
      best = m;
      tau_best = tau;
    }
  }
  for (size_t i = 0; i < n_; ++i) st.s[i] += tau_best * v_[i];
  st.boundary = true;
}

Step TrustRegionMinres::solve_subproblem(const double *g, double radius) {
  Step st;
  double lo = 0.0, lambda = 0.0, ns = 0.0;
  bool lo_ok = false;        // H + lo M is known to be positive definite
  if (lambda_floor_ > 0.0) { // same H and g, smaller radius: lambda >= the last one
    lo = lambda = lambda_floor_;
    lo_ok = true;
  } else if (sigma0_ == 0.0) { // H positive definite: try the Newton step
    for (size_t i = 0; i < n_; ++i) w_[i] = -g[i];
    f0_->solve(w_.data());
    ns = mnorm(w_.data());
    if (ns <= radius) {
      minres_step(g, 0.0, st);
      return st;
    }
    lo_ok = true;
  } else {
    lo = std::max(0.0, -mu_);
    lambda = lo * (1.0 + 1e-6) + 1e-14;
  }
  double hi = upper_multiplier(g, radius) + lo;
  bool hard = false, ok = (sigma0_ == 0.0 && lambda_floor_ == 0.0);
  double gap = 0.0; // lambda - lo after the last failed factorisation
  for (int it = 0; it < kMaxMultiplierIts; ++it) {
    if (it > 0 || !ok) {
      if (!((lambda > lo || (lambda == lo && lo_ok)) && lambda < hi))
        lambda = std::max(std::sqrt(lo * hi), lo + 1e-2 * (hi - lo));
      ok = trial_step(g, lambda, &ns);
      if (!ok) {     // below the lowest eigenvalue: raise the lower bound, and the gap
        lo = lambda; // above it tenfold on every consecutive failure
        lo_ok = false;
        gap = std::max(10.0 * gap, 1e-6 * lo + 1e-14);
        lambda = lo + gap;
        if (lo >= hi) hi = 10.0 * lo;
        continue;
      }
      gap = 0.0;
    }
    if (std::fabs(ns - radius) <= kBoundaryTol * radius) break;
    if (ns < radius) {
      hi = lambda;
      if (sigma0_ > 0.0 && lambda - lo <= 1e-3 * lo + 1e-12) { // hard case
        hard = negcurv_;
        break;
      }
      if (lambda <= lo) break; // at an admissible lower bound: no smaller multiplier
    } else {
      lo = lambda;
      lo_ok = true;
      if (lo >= hi) hi = 10.0 * lo;
    }
    // Newton step on 1/||s(lambda)||_M - 1/radius: q = (H + lambda M)^{-1} M s.
    p_.pattern_apply(m_.data(), w_.data(), q_.data());
    (lambda == 0.0 && sigma0_ == 0.0 ? *f0_ : *fl_).solve(q_.data());
    lambda += (ns / radius - 1.0) * ns * ns / mdot(w_.data(), q_.data());
  }
  minres_step(g, lambda, st);
  lambda_floor_ = fl_lambda_ == lambda ? lambda : 0.0;
  st.boundary = !(hard || (sigma0_ > 0.0 && !negcurv_ && ns < radius));
  if (hard) add_curvature_direction(g, radius, st);
  const double sn = mnorm(st.s.data());
  if (sn > (1.0 + kBoundaryTol) * radius)
    for (double &e : st.s) e *= radius / sn;
  return st;
}

// The second-order correction of the step st from x (step 5 at the top):
// xc = x + sigma, sigma the fixed point of
//   sigma = s - (H + lambda M)^{-1} f(x, sigma),
// f(x, sigma) = sum_j (E A_j / lbar_j) r_j(sigma) dL_j/dx the stretching force of
// the lengths the step gives beyond their linearisation (rn_network_stretch_
// correction), iterated from sigma = s with the factorisation of the step (H +
// lambda M, or its shifted preconditioner) until the change is below
// kCorrectionTol of ||sigma - s||_M, at most kCorrectionIts solves (then the last
// iterate: the energy decides).  False if there is no exact factorisation, an edge
// degenerates or the iteration diverges (a change kCorrectionGrowth times the
// first).
bool TrustRegionMinres::correct_step(const double *x, const Step &st, RolVector &xc) {
  // Only with the exact factorisation of H + lambda M, and not where H is singular
  // without significant negative curvature (rigid motions of a free rod: lambda is
  // then at round-off and the solve amplifies round-off along the rigid motions).
  // Measured on the free rods of val_rest_curvature: with a shifted factorisation
  // the iteration diverged (energies up to 1e193), and with the exact one at such a
  // lambda the corrected points kept the watchdog cycling until max_iterations.
  if (sigma0_ > 0.0 && !negcurv_) return false;
  const SpdFactor *f = nullptr;
  if (st.lambda == 0.0 && sigma0_ == 0.0)
    f = f0_.get();
  else if (st.lambda > 0.0 && fl_lambda_ == st.lambda && fl_->factored())
    f = fl_.get();
  if (!f) return false;
  const auto dnorm = [&](const std::vector<double> &v) { // ||v||_M, M = D diagonal
    double sum = 0.0;
    for (size_t i = 0; i < n_; ++i) sum += d_[i] * v[i] * v[i];
    return std::sqrt(sum);
  };
  sigma_ = st.s;
  double first = 0.0; // the change of the first pass, ||c_1||_M
  for (int k = 0; k < kCorrectionIts; ++k) {
    if (check_status(
            rn_network_stretch_correction(p_.network(), x, sigma_.data(), w_.data()),
            "rn_network_stretch_correction") != RN_OK)
      return false;
    f->solve(w_.data()); // sigma_new = s - w
    for (size_t i = 0; i < n_; ++i) q_[i] = st.s[i] - w_[i] - sigma_[i];
    const double change = dnorm(q_);
    if (k == 0) first = change;
    if (!(change <= kCorrectionGrowth * first)) return false; // diverges
    for (size_t i = 0; i < n_; ++i) sigma_[i] += q_[i];
    if (change <= kCorrectionTol * dnorm(w_)) break;
  }
  double *xcp = host_data(xc);
  for (size_t i = 0; i < n_; ++i) xcp[i] = x[i] + sigma_[i];
  return true;
}

// The energy at the trial point x + s (xtrial; obj updated there) and the ratio *rho
// of the actual to the predicted decrease pred; the second-order correction of the
// stretching (step 5 at the top) of a rejected step: x + s + c replaces x + s if its
// energy is lower.
double TrustRegionMinres::trial_energy(RolVector &x, RolVector &xtrial, RolVector &xcorr,
                                       ROL::Objective<double> &obj, const Step &st,
                                       double pred, double tol, double *rho) {
  obj.update(xtrial, ROL::UpdateType::Trial, state_->iter);
  double ftrial = obj.value(xtrial, tol);
  state_->nfval++;
  const double safe = 10.0 * DBL_EPSILON * std::max(1.0, std::fabs(state_->value));
  const auto ratio = [&](double f) {
    return std::isfinite(f) ? (state_->value - f + safe) / (pred + safe)
                            : -std::numeric_limits<double>::infinity();
  };
  *rho = ratio(ftrial);
  if (!(*rho > kAccept) && std::isfinite(ftrial) &&
      correct_step(host_data(x), st, xcorr)) {
    const double fc = obj.value(xcorr, tol);
    state_->nfval++;
    if (std::isfinite(fc) && fc < ftrial) {
      xtrial.set(xcorr);
      ftrial = fc;
      *rho = ratio(fc);
    }
  }
  return ftrial;
}

// The ratio test with the watchdog (step 5a at the top): from an anchor, accept what
// lowers the anchor's energy enough, take up to kWatchdogSteps tentative steps, then
// go back; otherwise a rejected step with a finite energy becomes the first
// tentative step from a new anchor at x (its state saved).
TrustRegionMinres::Move TrustRegionMinres::choose_move(const double *x, double ftrial,
                                                       double rho, double pred,
                                                       double radius, double snorm) {
  Anchor &anchor = anchor_;
  if (anchor.active) {
    if (std::isfinite(ftrial) && ftrial <= anchor.energy - kAccept * anchor.pred)
      return Move::Accept;
    if (anchor.steps < kWatchdogSteps && rho > kAccept) return Move::Tentative;
    return Move::Back;
  }
  if (rho > kAccept) return Move::Accept;
  if (watchdog_blocked_ || !std::isfinite(ftrial)) return Move::Reject;
  anchor.active = true;
  anchor.steps = 0;
  anchor.x.assign(x, x + n_);
  anchor.energy = state_->value;
  anchor.pred = pred;
  anchor.radius = radius;
  anchor.step = snorm;
  rn_state_destroy(&anchor.snapshot);
  check_status(rn_network_state_save(p_.network(), &anchor.snapshot),
               "rn_network_state_save");
  return Move::Tentative;
}

void TrustRegionMinres::run(RolVector &x, const RolVector &g, ROL::Objective<double> &obj,
                            std::ostream & /*out*/) {
  double tol = std::sqrt(ROL::ROL_EPSILON<double>());
  initialize(x, g);
  ROL::Ptr<RolVector> xtrial = x.clone(), xcorr = x.clone(), gvec = state_->gradientVec;
  auto take_state = [&](const RolVector &xnew, ROL::UpdateType type) {
    x.set(xnew);
    obj.update(x, type, state_->iter);
    state_->value = obj.value(x, tol);
    obj.gradient(*gvec, x, tol);
    state_->nfval++;
    state_->ngrad++;
    state_->gnorm = gvec->norm();
    state_->iterateVec->set(x);
  };
  take_state(x, ROL::UpdateType::Initial);
  double radius = opt_.initial_radius;
  IterationView it;
  bool fresh = true, check = true;
  Anchor &anchor = anchor_;
  bool &watchdog_blocked = watchdog_blocked_;
  for (;;) {
    const double *xp = host_data(x);
    if (fresh) analyse_hessian(xp);
    fresh = false;
    it.iteration = state_->iter;
    it.energy = state_->value;
    it.gnorm = state_->gnorm;
    it.radius = radius;
    it.negative_curvature = negcurv_;
    it.x_norm = norm2(n_, xp);
    const double *gp = host_data(*gvec);
    if (check) {
      it.eq = equilibrium_.measure(xp, gp);
      if (mon_.check(it)) break;
    }
    check = true;
    if (!(radius > 0.0)) // automatic: the Newton step, or see saddle_radius()
      radius = sigma0_ == 0.0 ? std::numeric_limits<double>::max()
                              : std::max(gradient_radius(gp), saddle_radius());
    Step st = solve_subproblem(gp, radius);
    const double snorm = mnorm(st.s.data());
    if (radius == std::numeric_limits<double>::max()) radius = std::max(snorm, 1e-300);
    const double pred = -model(gp, st.s.data());
    double *sp = host_data(*state_->stepVec);
    std::copy(st.s.begin(), st.s.end(), sp);
    xtrial->set(x);
    xtrial->plus(*state_->stepVec);
    double rho = 0.0;
    const double ftrial = trial_energy(x, *xtrial, *xcorr, obj, st, pred, tol, &rho);
    state_->iter++;
    state_->snorm = norm2(n_, st.s.data());
    const Move move = choose_move(xp, ftrial, rho, pred, radius, snorm);
    it.krylov = st.krylov;
    it.accepted = move == Move::Accept || move == Move::Tentative;
    // The step and energy tests only after a monotone interior (Newton) step.
    it.unconstrained = !st.boundary && move == Move::Accept && !anchor.active;
    it.step_norm = state_->snorm;
    it.energy_change = it.accepted ? ftrial - state_->value : 0.0;
    // A rejected step at the round-off level of x: the radius has collapsed.
    it.radius_collapsed =
        move == Move::Reject && state_->snorm <= 10.0 * DBL_EPSILON * (1.0 + it.x_norm);
    switch (move) {
    case Move::Accept:
      if (anchor.active) // the watchdog succeeded
        anchor.active = false;
      else
        watchdog_blocked = false;
      if (rho < 0.25) // (rho of this step from its own start)
        radius = 0.25 * std::min(radius, snorm);
      else if (rho > 0.75 && st.boundary)
        radius *= 2.0;
      take_state(*xtrial, ROL::UpdateType::Accept);
      fresh = true;
      break;
    case Move::Tentative:
      ++anchor.steps;
      take_state(*xtrial, ROL::UpdateType::Accept);
      fresh = true;
      break;
    case Move::Back: // exact return to the anchor, whose step counts as rejected
      check_status(rn_network_state_restore(p_.network(), anchor.snapshot),
                   "rn_network_state_restore");
      std::copy(anchor.x.begin(), anchor.x.end(), host_data(*xtrial));
      take_state(*xtrial, ROL::UpdateType::Initial);
      radius = 0.25 * std::min(anchor.radius, anchor.step);
      anchor.active = false;
      watchdog_blocked = true;
      fresh = true;
      check = false; // the anchor was checked already
      it.accepted = false;
      break;
    case Move::Reject:
      obj.update(x, ROL::UpdateType::Revert, state_->iter);
      if (rho < 0.25) radius = 0.25 * std::min(radius, snorm);
      break;
    }
    state_->searchSize = radius;
  }
}

} // namespace

void run_tr_minres(Problem &p, Monitor &mon, const rn_solve_options &opt) {
  auto map = make_local_map(p.size());
  auto xmv = Teuchos::rcp(new MV(map, 1));
  check_status(rn_network_get_dofs(p.network(), host_data(*xmv)), "rn_network_get_dofs");
  TpetraVector x(xmv), g(Teuchos::rcp(new MV(map, 1)));
  RodObjective obj(p, opt);
  TrustRegionMinres alg(p, mon, opt, map);
  Teuchos::oblackholestream out;
  alg.run(x, g, obj, out);
}

} // namespace rodnet
