// tr_krylov.cpp - the Newton-Krylov trust region (RN_SOLVER_TR_KRYLOV, issue 7).
//
// Written against System (system.hpp) and Preconditioner (preconditioner.hpp) only:
// vectors are Tpetra vectors on sys.map(), dot products and norms are global
// reductions, the Hessian is applied as a Tpetra operator and M^{-1} by the
// preconditioner's inverse().  Nothing here assumes one rank.
//
// Iteration at the accepted state x (reference frames of x):
//  1. g = grad E(x); assemble H(x); set up the SPD preconditioner M (it defines the
//     trust-region norm ||s||_M = sqrt(s' M s)).  If M had to modify an indefinite
//     piece (stats().shifted), or if the stopping test is about to pass with a
//     preconditioner that cannot certify positive definiteness, Lanczos on the pencil
//     (H, M) (pencil_lanczos.hpp: preconditioned, M-orthonormal, full
//     reorthogonalisation, at most 30 steps) gives the lowest Ritz pair (mu, v):
//     mu < -kCurvTol means negative curvature, and no convergence test passes (a
//     saddle is never reported).
//  2. The step: preconditioned MINRES (Paige-Saunders) on H s = -g from s = 0, with
//     the trust region folded in (the MINRES analogue of Steihaug-Toint):
//       - its iterates grow monotonically in the M-norm while the Lanczos matrix T_k
//         is positive definite (Fong and Saunders 2012; Liu and Roosta, "MINRES: from
//         negative curvature detection to monotonicity properties", 2022); ||s_k||_M is
//         tracked exactly with M s_k, built from the same recurrences on the
//         unpreconditioned Lanczos vectors (no product with M is needed);
//       - nonpositive curvature is detected by the pivots of T_k = L D L' (d_k =
//         alpha_k - beta_k^2 / d_{k-1} <= 0: T_k is no longer positive definite); the
//         direction is the conjugate-gradient direction p_k = v_k - (beta_k / d_{k-1})
//         p_{k-1}, for which p_k' H p_k = d_k (Lanczos-CG connection): the step goes
//         from s_{k-1} along +-p_k to the boundary, the sign that lowers the model;
//       - an iterate outside the radius: back to the boundary along the last update;
//       - otherwise stop when ||r_k||_{M^{-1}} <= eta ||g||_{M^{-1}}, eta the inexact-
//         Newton forcing term min(0.1, 0.9 (||g_k|| / ||g_{k-1}||)^2) (Eisenstat and
//         Walker's choice 2), at least krylov_tol; on the first step of a solve,
//         with no ratio yet, kForcingFirst = 1e-4 (not Eisenstat and Walker's 0.1
//         or 0.5): a Newton step costs a Hessian assembly and a preconditioner setup,
//         worth many Krylov iterations, and each decade of the forcing that the first
//         step leaves costs a later step (choice 2 then squares it).  Measured on
//         the octet 16^3 under stretch with the multigrid coarse solve: 0.1 took 5
//         Newton steps (9 MINRES, 130 s CPU), 1e-4 took 2 (11 MINRES, 99 s CPU;
//         docs/solvers.md).
//     With negative curvature known from step 1 and an interior step (e.g. at a
//     symmetric saddle, where g is orthogonal to v and the Krylov space of g never
//     sees the negative direction), s + tau v on the boundary, tau of the sign that
//     lowers the model: the iteration leaves saddles.
//  3. Ratio test, radius update and watchdog as in tr_minres.cpp (steps 4-5a there;
//     the watchdog needs System::save_state()).
//  3a. Second-order correction of a step the ratio test rejects, as tr_minres.cpp's
//     step 5 (where the System provides System::stretch_correction): the Newton step
//     linearises rotations and so stretches the stiff edges to second order in the
//     step; x + s + c, c from the fixed point c = -M^{-1} f(s + c) (f the stretching
//     force the quadratic model misses), replaces x + s if its energy is lower.  M^{-1}
//     is the preconditioner, exact where it is an unshifted factorisation of H.
//
// Why not Belos::MinresIter: its iterate() keeps the Lanczos coefficients alpha_k,
// beta_k and the Givens rotations (cs, sn, gamma) in local variables and its state
// (getState(): Y, R1, R2, W, W1, W2) and status tests see only vectors and the
// residual estimate phibar; the trust region needs the pivots of T_k (nonpositive
// curvature) and ||s_k||_M after every iteration, and to stop inside an iteration.
#include <algorithm>
#include <cfloat>
#include <cmath>
#include <limits>
#include <memory>
#include <vector>

#include <Teuchos_Array.hpp>

#include "base/lapack.hpp"
#include "base/shim_error.hpp"
#include "krylov/minres.hpp"
#include "krylov/pencil_lanczos.hpp"
#include "newton/monitor.hpp"
#include "newton/predictor.hpp"
#include "newton/solvers.hpp"
#include "pc/preconditioner.hpp"
#include "system/system.hpp"

namespace rodnet {

namespace {

constexpr double kAccept = 1e-4;               // accept a step if rho > kAccept
constexpr double kCurvTol = 1e3 * DBL_EPSILON; // significant negative curvature
// Negative curvature that marks a saddle for the round-off acceptance rule (run());
// above it, e.g. a zero mode's Ritz value at round-off, the gradient decides.
constexpr double kNoiseCurv = 1e-8;
constexpr int kWatchdogSteps = 2;      // as in tr_minres.cpp
constexpr double kForcingFirst = 1e-4; // forcing term of the first step (see the top)
// The second-order correction (step 3a at the top), as in tr_minres.cpp.
constexpr double kCorrectionTol = 1e-4;
constexpr int kCorrectionIts = 50;
constexpr double kCorrectionGrowth = 1e3;

using Vec = TMV; // one column

double dot(const Vec &a, const Vec &b) {
  Teuchos::Array<double> r(1);
  a.dot(b, r());
  return r[0];
}

// y = H x
void apply_h(const System &sys, const Vec &x, Vec &y) { sys.hessian()->apply(x, y); }

// The trust-region step of one iteration.
struct KrylovStep {
  explicit KrylovStep(const Teuchos::RCP<const TMap> &map) : s(map, 1), Ms(map, 1) {}
  Vec s, Ms;             // the step and M s
  int iterations = 0;    // MINRES iterations
  bool boundary = false; // stopped at the radius
  bool negative = false; // met nonpositive curvature
};

// Preconditioned MINRES for H s = -g inside ||s||_M <= radius (see the top).
class TrustMinres {
public:
  TrustMinres(System &sys, const Tpetra::Operator<> &Minv, int max_iterations)
      : sys_(sys), Minv_(&Minv), maxit_(max_iterations), map_(sys.map()), r1_(map_, 1),
        r2_(map_, 1), y_(map_, 1), v_(map_, 1), w_(map_, 1), w1_(map_, 1), w2_(map_, 1),
        Mw_(map_, 1), Mw1_(map_, 1), Mw2_(map_, 1), p_(map_, 1), Mp_(map_, 1),
        tmp_(map_, 1) {}

  // ||g||_{M^{-1}} of the last solve (beta_1).
  double beta1() const { return beta1_; }
  // The preconditioner of the next solves (after a setup; the work vectors stay);
  // beta1() is 0 again until the next solve, as for a new solver.
  void rebind(const Tpetra::Operator<> &Minv) {
    Minv_ = &Minv;
    beta1_ = 0.0;
  }

  void solve(const Vec &g, double radius, double eta, KrylovStep &st) {
    st.s.putScalar(0.0);
    st.Ms.putScalar(0.0);
    st.iterations = 0;
    st.boundary = st.negative = false;
    r1_.update(-1.0, g, 0.0); // b = -g
    r2_.assign(r1_);
    Minv_->apply(r1_, y_);
    double beta = dot(r1_, y_);
    if (beta < 0.0 || !std::isfinite(beta))
      throw Error(RN_ERR_SOLVER, "rn_solve: the preconditioner is not positive definite");
    beta = std::sqrt(beta);
    beta1_ = beta;
    if (beta == 0.0) return;
    p_.putScalar(0.0);
    Mp_.putScalar(0.0);
    double oldb = 0.0, dbar = 0.0, epsln = 0.0, phibar = beta, cs = -1.0, sn = 0.0;
    double pivot = 0.0, snorm2 = 0.0; // LDL' pivot d_{k-1}; ||s||_M^2
    w_.putScalar(0.0), w2_.putScalar(0.0), Mw_.putScalar(0.0), Mw2_.putScalar(0.0);
    for (int k = 1; k <= maxit_; ++k) {
      st.iterations = k;
      // Lanczos: v = y / beta (M-orthonormal), M v = r2 / beta.
      const double s = 1.0 / beta;
      v_.update(s, y_, 0.0);
      apply_h(sys_, v_, y_);
      if (k >= 2) y_.update(-beta / oldb, r1_, 1.0);
      const double alfa = dot(v_, y_);
      // The CG direction p_k and its curvature d_k = p' H p (pivot of T_k = L D L').
      const double l = k >= 2 ? beta / pivot : 0.0;
      const double d = alfa - (k >= 2 ? beta * beta / pivot : 0.0);
      p_.update(1.0, v_, -l);
      Mp_.update(s, r2_, -l);
      if (!(d > 0.0)) {
        to_boundary_on_curvature(g, radius, st);
        return;
      }
      pivot = d;
      y_.update(-alfa / beta, r2_, 1.0);
      // M w needs M v = r2 / beta before r2 moves on
      Mw1_.assign(Mw2_);
      Mw2_.assign(Mw_);
      Mw_.update(s, r2_, 0.0);
      r1_.assign(r2_);
      r2_.assign(y_);
      Minv_->apply(r2_, y_);
      oldb = beta;
      beta = dot(r2_, y_);
      if (beta < 0.0 || !std::isfinite(beta))
        throw Error(RN_ERR_SOLVER,
                    "rn_solve: the preconditioner is not positive definite");
      beta = std::sqrt(beta);
      // QR of the tridiagonal, Paige-Saunders
      const double oldeps = epsln;
      const double delta = cs * dbar + sn * alfa;
      const double gbar = sn * dbar - cs * alfa;
      epsln = sn * beta;
      dbar = -cs * beta;
      const double gamma = std::max(std::hypot(gbar, beta), DBL_MIN);
      cs = gbar / gamma;
      sn = beta / gamma;
      const double phi = cs * phibar;
      phibar = std::fabs(sn * phibar);
      // w_k = (v_k - oldeps w_{k-2} - delta w_{k-1}) / gamma, and M w_k alike
      w1_.assign(w2_);
      w2_.assign(w_);
      w_.update(1.0 / gamma, v_, 0.0);
      w_.update(-oldeps / gamma, w1_, -delta / gamma, w2_, 1.0);
      Mw_.update(-oldeps / gamma, Mw1_, -delta / gamma, Mw2_, 1.0 / gamma);
      // s_k = s_{k-1} + phi w_k: inside the radius?
      const double sw = dot(st.s, Mw_), ww = dot(w_, Mw_);
      const double next = snorm2 + 2.0 * phi * sw + phi * phi * ww;
      if (std::sqrt(std::max(next, 0.0)) >= radius) {
        const double tau = boundary_root(snorm2, phi * sw, phi * phi * ww, radius);
        st.s.update(tau * phi, w_, 1.0);
        st.Ms.update(tau * phi, Mw_, 1.0);
        st.boundary = true;
        return;
      }
      st.s.update(phi, w_, 1.0);
      st.Ms.update(phi, Mw_, 1.0);
      snorm2 = next;
      if (phibar <= eta * beta1_ || beta == 0.0) return;
    }
  }

private:
  // The larger root tau of ||s + tau u||_M^2 = ss + 2 tau su + tau^2 uu = radius^2.
  static double boundary_root(double ss, double su, double uu, double radius) {
    if (!(uu > 0.0)) return 0.0;
    const double disc = std::sqrt(std::max(0.0, su * su - uu * (ss - radius * radius)));
    return (-su + disc) / uu;
  }

  // Nonpositive curvature along p: from s to the boundary along +-p, the sign that
  // lowers the model m(s) = g's + s'Hs/2.
  void to_boundary_on_curvature(const Vec &g, double radius, KrylovStep &st) {
    apply_h(sys_, p_, tmp_);
    const double pp = dot(p_, Mp_), sp = dot(st.s, Mp_), ss = dot(st.s, st.Ms);
    const double slope = dot(g, p_) + dot(st.s, tmp_); // (g + H s)' p
    const double pHp = dot(p_, tmp_);                  // = d up to round-off
    const double disc = std::sqrt(std::max(0.0, sp * sp - pp * (ss - radius * radius)));
    double best = std::numeric_limits<double>::max(), tau_best = 0.0;
    for (double tau : {(-sp + disc) / pp, (-sp - disc) / pp}) {
      const double m = tau * slope + 0.5 * tau * tau * pHp;
      if (m < best) best = m, tau_best = tau;
    }
    st.s.update(tau_best, p_, 1.0);
    st.Ms.update(tau_best, Mp_, 1.0);
    st.boundary = st.negative = true;
  }

  System &sys_;
  const Tpetra::Operator<> *Minv_;
  int maxit_;
  Teuchos::RCP<const TMap> map_;
  Vec r1_, r2_, y_, v_, w_, w1_, w2_, Mw_, Mw1_, Mw2_, p_, Mp_, tmp_;
  double beta1_ = 0.0;
};

// The watchdog (step 3 at the top, as tr_minres.cpp): the point the tentative steps
// started from, and what going back to it needs.
struct Anchor {
  bool active = false;  // tentative steps from the anchor are being taken
  bool blocked = false; // went back to it: no new anchor before a step is accepted
  int steps = 0;        // tentative steps taken
  double energy = 0.0, pred = 0.0, radius = 0.0, step = 0.0; // E, pred, radius, ||s||_M
};

// What becomes of a trial step.
enum class Move { Reject, Accept, Tentative, Back };

// A trial step s and the trial point x + s.
struct Trial {
  double snorm = 0.0;   // ||s||_M
  bool limited = false; // the step was computed with the trust radius
  double pred = 0.0;    // the model's decrease
  double ftrial = 0.0;  // the energy at the trial point (+inf if undefined)
  double rho = 0.0;     // actual over predicted decrease
  double safe = 0.0;    // the energy's round-off level
};

class TrustRegionKrylov {
public:
  TrustRegionKrylov(System &sys, Preconditioner &prec, Monitor &mon,
                    const rn_solve_options &opt)
      : sys_(sys), prec_(prec), mon_(mon), opt_(opt), map_(sys.map()), x_(map_, 1),
        g_(map_, 1), gt_(map_, 1), xt_(map_, 1), xa_(map_, 1), hs_(map_, 1), v_(map_, 1),
        Mv_(map_, 1), sig_(map_, 1), f_(map_, 1), q_(map_, 1), xc_(map_, 1) {}

  void run();

private:
  void set_up();
  double forcing() const;
  Trial solve_step(double eta, KrylovStep &st);
  void evaluate_trial(const KrylovStep &st, Trial &t);
  bool noise_move(const Trial &t, Move *move);
  Move watchdog_move(const Trial &t);
  bool apply_move(Move move, const Trial &t, const KrylovStep &st, bool noise);
  void analyse(const IterationView &it);
  double model(const Vec &s) { // g's + s'Hs/2
    apply_h(sys_, s, hs_);
    return dot(g_, s) + 0.5 * dot(s, hs_);
  }
  void add_curvature_direction(double radius, KrylovStep &st);
  bool correct_step(const KrylovStep &st, Vec &xc);
  double gradient_radius() { // ||M^{-1} g||_M = sqrt(g' M^{-1} g)
    prec_.inverse()->apply(g_, hs_);
    return std::sqrt(std::max(dot(g_, hs_), 0.0));
  }
  void take(const Vec &x) { // accept x (reference update), gradient there
    x_.assign(x);
    sys_.accept(x_);
    if (sys_.gradient(x_, &energy_, g_) != RN_OK)
      throw Error(RN_ERR_SOLVER, "rn_solve: gradient at an accepted point is degenerate");
  }

  System &sys_;
  Preconditioner &prec_;
  Monitor &mon_;
  const rn_solve_options &opt_;
  Teuchos::RCP<const TMap> map_;
  Vec x_, g_, gt_, xt_, xa_, hs_, v_, Mv_, sig_, f_, q_, xc_;
  double energy_ = 0.0, mu_ = 0.0;
  bool negcurv_ = false, have_v_ = false;
  // the state of run()
  double radius_ = 0.0, beta1_prev_ = 0.0; // trust radius; beta1 of the last step
  Anchor anchor_;
  std::unique_ptr<TrustMinres> minres_;
};

// Negative curvature at x (step 1): Lanczos on (H, M) when the preconditioner had to
// modify an indefinite piece, or when the stopping test is about to pass and the
// preconditioner cannot certify positive definiteness (Preconditioner::exact: "factor"
// can, the Cholesky factorisation of H itself when unshifted; so can "dd" with
// unshifted rod blocks and an unshifted direct coarse solve, an exact block
// factorisation of H).  A preconditioner with a coarse pencil (S, A) whose
// definiteness is H's certifies by Lanczos on it instead (Preconditioner::
// coarse_pencil: "dd" with unshifted rod blocks and the multigrid coarse solve, H
// positive definite iff its Schur complement S is), the whole pencil only if that
// finds S's lowest Ritz value below kCurvTol.
void TrustRegionKrylov::analyse(const IterationView &it) {
  negcurv_ = have_v_ = false;
  mu_ = 0.0;
  const bool certified = !prec_.stats().shifted && prec_.exact();
  if (!prec_.stats().shifted && (certified || !mon_.equilibrium_passes(it))) return;
  int steps = 0;
  Teuchos::RCP<const Tpetra::Operator<>> S, Ainv;
  if (!prec_.stats().shifted && prec_.coarse_pencil(S, Ainv)) {
    Vec sv(S->getDomainMap(), 1), Msv(S->getDomainMap(), 1);
    const double mu_s = pencil_lowest(*S, *Ainv, sv, Msv, &steps);
    sys_.counters.krylov += steps;
    if (mu_s > kCurvTol) return; // S, hence H, positive definite
  }
  mu_ = pencil_lowest(*sys_.hessian(), *prec_.inverse(), map_, v_, Mv_, &steps);
  sys_.counters.krylov += steps;
  have_v_ = true;
  negcurv_ = mu_ < -kCurvTol;
}

// Hard case: from an interior step s along the negative-curvature vector v to the
// boundary, the root with the lower model value.
void TrustRegionKrylov::add_curvature_direction(double radius, KrylovStep &st) {
  const double sv = dot(st.s, Mv_), ss = dot(st.s, st.Ms), vv = dot(v_, Mv_);
  if (!(vv > 0.0)) return;
  const double disc = std::sqrt(std::max(0.0, sv * sv - vv * (ss - radius * radius)));
  double best = std::numeric_limits<double>::max(), tau_best = 0.0;
  for (double tau : {(-sv + disc) / vv, (-sv - disc) / vv}) {
    xt_.assign(st.s);
    xt_.update(tau, v_, 1.0);
    const double m = model(xt_);
    if (m < best) best = m, tau_best = tau;
  }
  st.s.update(tau_best, v_, 1.0);
  st.Ms.update(tau_best, Mv_, 1.0);
  st.boundary = true;
}

// The second-order correction of the step st from x_ (step 3a at the top): xc = x +
// sigma, sigma the fixed point of sigma = s - M^{-1} f(x, sigma), f the stretching
// force of the lengths the step gives beyond their linearisation (System::
// stretch_correction), from sigma = s until the change is below kCorrectionTol of
// ||M^{-1} f||, at most kCorrectionIts passes (then the last iterate: the energy
// decides).  M^{-1} is the preconditioner: H^{-1} where it is exact, a positive
// definite stand-in for (H + lambda M)^{-1} where H was shifted.  False without the
// System's support, where the preconditioner was shifted without significant
// negative curvature (a singular H: rigid motions, where the solve amplifies
// round-off, tr_minres.cpp), at a degenerate state or when the iteration diverges.
bool TrustRegionKrylov::correct_step(const KrylovStep &st, Vec &xc) {
  if (!sys_.has_stretch_correction() || (prec_.stats().shifted && !negcurv_))
    return false;
  sig_.assign(st.s);
  double first = 0.0;
  for (int k = 0; k < kCorrectionIts; ++k) {
    if (sys_.stretch_correction(x_, sig_, f_) != RN_OK) return false;
    prec_.inverse()->apply(f_, hs_); // w = M^{-1} f
    q_.update(1.0, st.s, -1.0, hs_, 0.0);
    q_.update(-1.0, sig_, 1.0); // q = s - w - sigma
    const double change = q_.getVector(0)->norm2();
    if (!std::isfinite(change)) return false;
    if (k == 0) first = change;
    if (!(change <= kCorrectionGrowth * first)) return false;
    sig_.update(1.0, q_, 1.0);
    if (change <= kCorrectionTol * hs_.getVector(0)->norm2()) break;
  }
  xc.assign(x_);
  xc.update(1.0, sig_, 1.0);
  return true;
}

// At a new iterate: assemble H, set up the preconditioner M and give MINRES the new
// M^{-1} (its work vectors for the whole run: page faults of large ones).
void TrustRegionKrylov::set_up() {
  sys_.assemble_hessian(x_);
  prec_.setup(sys_);
  if (minres_)
    minres_->rebind(*prec_.inverse());
  else
    minres_.reset(new TrustMinres(sys_, *prec_.inverse(), opt_.krylov_max_iterations));
}

// The inexact-Newton forcing term: Eisenstat-Walker choice 2 from the second step on;
// the first step of a solve (no ratio yet) to kForcingFirst (see the top).
double TrustRegionKrylov::forcing() const {
  double eta = kForcingFirst;
  if (beta1_prev_ > 0.0 && minres_->beta1() > 0.0) {
    const double ratio = minres_->beta1() / beta1_prev_;
    eta = std::min(0.1, 0.9 * ratio * ratio);
  }
  return std::max(eta, opt_.krylov_tol);
}

// The step (step 2 at the top) in st.  Automatic first radius: the Newton step, or
// ||M^{-1} g||_M (a preconditioned gradient step) where the curvature is negative.
// The watchdog's tentative steps are not limited either (Newton steps that repair
// the stretch of the anchor's step): the M-norm changes with H, and the anchor's
// radius, measured with the anchor's M, means little at a stretched point whose M is
// much stiffer.
Trial TrustRegionKrylov::solve_step(double eta, KrylovStep &st) {
  const bool automatic = !(radius_ > 0.0), unlimited = automatic || anchor_.active;
  const double floor_radius = automatic ? 1e-8 : radius_;
  double rad = unlimited ? std::numeric_limits<double>::max() : radius_;
  if (unlimited && negcurv_) rad = std::max(gradient_radius(), floor_radius);
  minres_->solve(g_, rad, eta, st);
  if (unlimited && st.negative && !negcurv_) { // met in the Krylov space only
    rad = std::max(gradient_radius(), floor_radius);
    minres_->solve(g_, rad, eta, st);
  }
  if (negcurv_ && have_v_ && !st.negative && !st.boundary)
    add_curvature_direction(rad, st);
  Trial t;
  t.snorm = std::sqrt(std::max(dot(st.s, st.Ms), 0.0));
  if (automatic) radius_ = std::max(std::min(rad, t.snorm), 1e-300);
  t.limited = rad == radius_; // the step was computed with the radius
  return t;
}

// The trial point x + s in xt_, its energy and the ratio rho; the second-order
// correction of a rejected step (step 3a at the top): x + s + c replaces x + s if its
// energy is lower.  Not at the round-off level (noise_move).
void TrustRegionKrylov::evaluate_trial(const KrylovStep &st, Trial &t) {
  t.pred = -model(st.s);
  xt_.assign(x_);
  xt_.update(1.0, st.s, 1.0);
  t.ftrial = std::numeric_limits<double>::infinity();
  if (sys_.energy(xt_, &t.ftrial) != RN_OK)
    t.ftrial = std::numeric_limits<double>::infinity();
  t.safe = 10.0 * DBL_EPSILON * std::max(1.0, std::fabs(energy_));
  const auto ratio = [&](double f) {
    return std::isfinite(f) ? (energy_ - f + t.safe) / (t.pred + t.safe)
                            : -std::numeric_limits<double>::infinity();
  };
  t.rho = ratio(t.ftrial);
  if (!(t.rho > kAccept) && std::isfinite(t.ftrial) && !(t.pred < t.safe) &&
      correct_step(st, xc_)) {
    double fc = std::numeric_limits<double>::infinity();
    if (sys_.energy(xc_, &fc) == RN_OK && std::isfinite(fc) && fc < t.ftrial) {
      xt_.assign(xc_);
      t.ftrial = fc;
      t.rho = ratio(fc);
    }
  }
}

// At the energy's round-off level (the model's decrease below safe) rho is noise and
// would accept steps that raise E by up to safe: repeated, they random-walk along
// soft or zero modes and the residual grows (loop_joint.json: 1800 iterations
// hovering between |g| 1e-12 and 1e-7).  There the gradient decides: the step is kept
// iff it lowers ||g||_{M^-1}, the norm MINRES reduces (no watchdog).  Not at a saddle
// (Lanczos curvature below -kNoiseCurv): leaving it raises |g|.  True if this rule
// decided *move.
bool TrustRegionKrylov::noise_move(const Trial &t, Move *move) {
  const bool round_off = !anchor_.active && !(negcurv_ && mu_ < -kNoiseCurv) &&
                         std::isfinite(t.ftrial) && t.pred < t.safe &&
                         minres_->beta1() > 0.0;
  if (!round_off) return false;
  double Et = 0.0;
  if (sys_.gradient(xt_, &Et, gt_) != RN_OK) return false;
  prec_.inverse()->apply(gt_, hs_);
  const double gt_norm = std::sqrt(std::max(dot(gt_, hs_), 0.0));
  *move = gt_norm < minres_->beta1() ? Move::Accept : Move::Reject;
  return true;
}

// The ratio test with the watchdog (step 3 at the top): from an anchor, accept what
// lowers the anchor's energy enough, take up to kWatchdogSteps tentative steps, then
// go back; otherwise a rejected step with a finite energy becomes the first
// tentative step from a new anchor (x), where the System can save its state.
Move TrustRegionKrylov::watchdog_move(const Trial &t) {
  Anchor &a = anchor_;
  if (a.active) {
    if (std::isfinite(t.ftrial) && t.ftrial <= a.energy - kAccept * a.pred)
      return Move::Accept;
    if (a.steps < kWatchdogSteps && t.rho > kAccept) return Move::Tentative;
    return Move::Back;
  }
  if (t.rho > kAccept) return Move::Accept;
  if (!a.blocked && std::isfinite(t.ftrial) && sys_.save_state()) {
    a.active = true;
    a.steps = 0;
    xa_.assign(x_);
    a.energy = energy_;
    a.pred = t.pred;
    a.radius = radius_;
    a.step = t.snorm;
    return Move::Tentative;
  }
  return Move::Reject;
}

// Carries out the move: the iterate, the radius and the watchdog's state.  True if
// the iterate changed (H and M are set up again).
bool TrustRegionKrylov::apply_move(Move move, const Trial &t, const KrylovStep &st,
                                   bool noise) {
  switch (move) {
  case Move::Accept:
    if (anchor_.active)
      anchor_.active = false;
    else
      anchor_.blocked = false;
    if (t.rho < 0.25)
      radius_ = 0.25 * std::min(radius_, t.snorm);
    else if (t.rho > 0.75 && st.boundary && t.limited)
      radius_ *= 2.0;
    beta1_prev_ = minres_->beta1();
    take(xt_);
    return true;
  case Move::Tentative:
    ++anchor_.steps;
    beta1_prev_ = minres_->beta1();
    take(xt_);
    return true;
  case Move::Back:
    sys_.restore_state();
    x_.assign(xa_);
    if (sys_.gradient(x_, &energy_, g_) != RN_OK)
      throw Error(RN_ERR_SOLVER, "rn_solve: gradient at the anchor is degenerate");
    radius_ = 0.25 * std::min(anchor_.radius, anchor_.step);
    anchor_.active = false;
    anchor_.blocked = true;
    return true;
  case Move::Reject:
    if (t.rho < 0.25 || noise) radius_ = 0.25 * std::min(radius_, t.snorm);
    return false;
  }
  return false;
}

void TrustRegionKrylov::run() {
  sys_.get_state(x_);
  if (sys_.gradient(x_, &energy_, g_) != RN_OK)
    throw Error(RN_ERR_GEOMETRY, "rn_solve: the starting state is degenerate");
  radius_ = opt_.initial_radius;
  beta1_prev_ = 0.0;
  anchor_ = Anchor();
  bool fresh = true, check = true;
  int iteration = 0;
  IterationView it;
  KrylovStep st(map_);
  for (;;) {
    if (fresh) set_up();
    it.iteration = iteration;
    it.energy = energy_;
    it.gnorm = g_.getVector(0)->norm2();
    it.radius = radius_;
    it.x_norm = x_.getVector(0)->norm2();
    it.eq = sys_.equilibrium(x_, g_);
    if (fresh) analyse(it);
    fresh = false;
    it.negative_curvature = negcurv_;
    if (check && mon_.check(it)) break;
    check = true;
    Trial t = solve_step(forcing(), st);
    evaluate_trial(st, t);
    ++iteration;
    Move move = Move::Reject;
    const bool noise = noise_move(t, &move);
    if (!noise) move = watchdog_move(t);
    it.krylov = st.iterations;
    it.accepted = move == Move::Accept || move == Move::Tentative;
    it.unconstrained = !st.boundary && move == Move::Accept && !anchor_.active;
    it.step_norm = st.s.getVector(0)->norm2();
    it.energy_change = it.accepted ? t.ftrial - energy_ : 0.0;
    it.radius_collapsed =
        move == Move::Reject && it.step_norm <= 10.0 * DBL_EPSILON * (1.0 + it.x_norm);
    fresh = apply_move(move, t, st, noise);
    if (move == Move::Back) check = false; // (no stopping test at the anchor again)
  }
}

// Adapts a Tpetra operator to MinresSolver's VectorOperator.
class OperatorAdapter : public VectorOperator {
public:
  explicit OperatorAdapter(const Tpetra::Operator<> &A) : A_(A) {}
  void apply(const MV &x, MV &y) const override { A_.apply(x, y); }

private:
  const Tpetra::Operator<> &A_;
};

} // namespace

rn_preconditioner run_tr_krylov(KrylovWorkspace &ws, Monitor &mon,
                                const rn_solve_options &opt) {
  struct Account { // the preconditioner's time, also when the run throws
    KrylovWorkspace &w;
    ~Account() { w.account(); }
  } account{ws};
  TrustRegionKrylov(ws.system(), ws.preconditioner(), mon, opt).run();
  return ws.kind();
}

bool predict_step_krylov(Problem &p, KrylovWorkspace &ws, const rn_solve_options &opt,
                         double t_prev, double t) {
  return predict_load_step(
      p,
      [&opt, &ws](Problem &q, const std::vector<double> &x, std::vector<double> &s) {
        System &sys = ws.system();
        Preconditioner &prec = ws.preconditioner();
        TMV xv(sys.map(), 1), b(sys.map(), 1), sv(sys.map(), 1);
        std::copy(x.begin(), x.end(), host_data(xv));
        std::copy(s.begin(), s.end(), host_data(b));
        sys.assemble_hessian(xv);
        prec.setup(sys);
        MinresSolver minres(sys.map(), opt.krylov_tol, opt.krylov_max_iterations);
        const MinresResult r = minres.solve(OperatorAdapter(*sys.hessian()),
                                            OperatorAdapter(*prec.inverse()), b, sv);
        q.counters.krylov += r.iterations;
        ws.account();
        std::copy(host_data(sv), host_data(sv) + s.size(), s.begin());
        return true;
      },
      t_prev, t);
}

} // namespace rodnet
