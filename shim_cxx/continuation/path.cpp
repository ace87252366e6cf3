// path.cpp - pseudo-arclength continuation of equilibria (rn_path_follow,
// rodnet_solve.h; docs/path-following.md).
//
// A point of the path is z = (x, mu): x the reduced DOFs, mu the load factor
// (RN_PATH_LOAD) or the value of the controlled DOF c (RN_PATH_DOF, where x[c] = mu
// always).  Equilibrium: r(x, mu) = 0, r the gradient with r[c] = 0 under
// displacement control.  Its Jacobian with respect to x is A: the Hessian, and under
// displacement control the Hessian with row and column c replaced by D_c e_c (the
// controlled DOF is not an unknown of x; the pattern and so the factorisations stay
// those of the Hessian); b = dr/dmu: under RN_PATH_LOAD the load derivative
// (rn_network_load_increment, exact for loads and prescribed translations), under
// RN_PATH_DOF column c of the Hessian (without its entry c).
//
// Step from z0 with unit tangent t0 (norm |z|_W^2 = sum w_i x_i^2 + w_mu mu^2):
// predictor z0 + ds t0, corrector Newton on [r; t0' W (z - z0) - ds] = 0, the
// bordered system [A b; a' d] (a = W t0_x, d = w_mu t0_mu) solved by bordering:
// A v1 = -r, A v2 = b, dmu = (-N - a'v1) / (d - a'v2), dx = v1 - dmu v2.  Solves
// with A: Cholesky if A is positive definite, else Belos MINRES preconditioned by the
// Cholesky factorisation of A + sigma D (factor_shifted).  The tangent at a point is
// (-A^{-1} b, 1) normalised, oriented along the previous one.
//
// Events: the lowest eigenvalue of A (dsbevx on the band, or bisection and inverse
// iteration with the sparse Cholesky) at every point; a sign change between two
// points is located by a secant search in the arclength from the first point (its
// tangent fixed) on the lowest eigenvalue; a limit point if dmu/ds changed sign over
// the step, a bifurcation otherwise.  Branch switching from a located bifurcation:
// tangent (phi, 0), phi the lowest eigenvector of A (inverse iteration).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <vector>

#include "factor/banded.hpp"
#include "krylov/minres.hpp"
#include "continuation/path.hpp"
#include "system/problem.hpp"
#include "base/runtime.hpp"
#include "base/shim_error.hpp"
#include "base/snapshot.hpp"
#include "eigen/stability.hpp"
#include "factor/spd_factor.hpp"

namespace rodnet {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kLoadDelta = 1e-4;  // load factor step of the load derivative
constexpr double kStableRel = 1e-12; // |lowest eigenvalue| / scale below: critical
constexpr int kSecantIts = 30;       // event location: secant/bisection steps
constexpr double kMinresTol = 1e-12; // relative MINRES residual of the solves
constexpr int kMinresIts = 1000;
constexpr double kMaxTurn = 0.5; // radians between consecutive tangents at most
// the corrected point at most this many step lengths (W metric) from the predictor
constexpr double kMaxCorrection = 1.0;

// y = A x with the (modified) assembled Hessian.
class HessianOp : public VectorOperator {
public:
  explicit HessianOp(Problem &p) : p_(p) {}
  void apply(const MV &x, MV &y) const override {
    p_.hessian_apply(host_data(x), host_data(y));
  }

private:
  Problem &p_;
};

// y = F^{-1} x with a Cholesky factorisation F.
class InverseOp : public VectorOperator {
public:
  explicit InverseOp(const SpdFactor &f) : f_(f) {}
  void apply(const MV &x, MV &y) const override {
    std::copy(host_data(x), host_data(x) + x.getLocalLength(), host_data(y));
    f_.solve(host_data(y));
  }

private:
  const SpdFactor &f_;
};

// A point of the path with what the next step needs.
struct Point {
  std::vector<double> x, tx; // state and tangent (x part)
  double mu = 0.0, tmu = 0.0;
  double lowest = kNaN, scale = 0.0;
  double energy = 0.0, force = 0.0;
  double sigma = 0.0; // located events: arclength from the point before
  int iterations = 0;
};

class PathFollower {
public:
  PathFollower(rn_network *net, const rn_path_options &o)
      : net_(net), o_(o), p_(net), n_(p_.size()),
        dof_(o.control == RN_PATH_DOF ? static_cast<long>(o.dof) : -1),
        factor_(make_spd_factor(p_, o.factorization)), map_(make_local_map(n_)),
        minres_(map_, kMinresTol, kMinresIts), rhs_(map_, 1), sol_(map_, 1) {}

  void run(rn_path_report &rep);
  long factorizations() const { return p_.counters.factorizations; }
  long corrector_iterations() const { return corrector_its_; }

private:
  void check_control();
  void set_weights();
  void check_target(double mu0) const;
  void choose_monitor();
  void start(Point &cur);
  bool next_point(const Point &cur, double ds, double target, Point &next, double &taken,
                  bool &last, rn_path_report &rep);
  bool land_on(Point &next, double mu_end, double *extra);
  bool switch_branch(Point &ev, const Point &cur, double target, double ds, Point &br,
                     double *dsb);
  double weighted_dot(const std::vector<double> &a, double amu,
                      const std::vector<double> &b, double bmu) const;
  void set_parameter(double mu, std::vector<double> &x);
  rn_status residual(std::vector<double> &x, double mu, std::vector<double> &r, double *E,
                     double *force);
  void linearise(const std::vector<double> &x, double mu);
  bool solve(std::vector<double> &v);
  bool tangent(Point &pt, const std::vector<double> &tx_prev, double tmu_prev);
  bool correct(Point &pt, const std::vector<double> &ax, double amu, double target);
  bool step_from(const Point &from, double ds, const std::vector<double> &tx, double tmu,
                 Point &to, bool check_turn = true);
  void eigen(Point &pt, std::vector<double> *vec);
  void scales(const std::vector<double> &x);
  double monitor_value(const Point &pt) const { return pt.x[monitor_]; }
  bool emit(const Point &pt, int step, rn_path_event ev, double arclength,
            rn_path_report &rep);
  bool locate(const Point &p0, const Point &p1, double ds, Point &ev, bool on_tmu);
  std::vector<double> other_branch(Point &ev, const Point &in, double target);

  rn_network *net_;
  const rn_path_options &o_;
  Problem p_;
  size_t n_;
  long dof_;           // controlled DOF, -1 under load control
  size_t monitor_ = 0; // the DOF reported as control and force
  std::vector<int> kind_;
  std::vector<double> w_; // arclength weights of x; w_mu_ of mu
  double w_mu_ = 1.0;
  std::vector<double> b_;      // dr/dmu at the last linearisation
  std::vector<double> metric_; // D on the Hessian's pattern
  double force_scale_ = 0.0, moment_scale_ = 0.0;
  double size_ = 1.0;                           // L, the bounding-box diagonal
  double base_force_ = 0.0, base_moment_ = 0.0; // the start's scales
  double start_monitor_ = 0.0;
  std::unique_ptr<SpdFactor> factor_;
  bool exact_ = false; // A itself factored (positive definite)
  Teuchos::RCP<const Map> map_;
  MinresSolver minres_;
  MV rhs_, sol_;
  long corrector_its_ = 0;
};

double PathFollower::weighted_dot(const std::vector<double> &a, double amu,
                                  const std::vector<double> &b, double bmu) const {
  double s = w_mu_ * amu * bmu;
  for (size_t i = 0; i < n_; ++i) s += w_[i] * a[i] * b[i];
  return s;
}

void PathFollower::set_parameter(double mu, std::vector<double> &x) {
  if (dof_ < 0)
    check_status(rn_network_set_load_factor(net_, mu), "rn_network_set_load_factor");
  else
    x[static_cast<size_t>(dof_)] = mu;
}

// r = gradient at (x, mu) (r[c] = 0 under displacement control); *force the
// conjugate force of the monitored DOF.  Positive status at a degenerate point.
rn_status PathFollower::residual(std::vector<double> &x, double mu,
                                 std::vector<double> &r, double *E, double *force) {
  if (!std::isfinite(mu) || (dof_ < 0 && !(mu >= 0.0 && mu <= 1.0)))
    return RN_DEGENERATE; // a trial point outside the load factor's range
  set_parameter(mu, x);
  const rn_status st = p_.gradient(x.data(), E, r.data());
  if (st != RN_OK) return st;
  for (double v : r)
    if (!std::isfinite(v)) return RN_OVERFLOW;
  if (dof_ >= 0) {
    if (force) *force = r[static_cast<size_t>(dof_)];
    r[static_cast<size_t>(dof_)] = 0.0;
  }
  return RN_OK;
}

// A, b and the factorisation at (x, mu) (parameter already set by residual()).
void PathFollower::linearise(const std::vector<double> &x, double mu) {
  p_.assemble_hessian(x.data());
  b_.assign(n_, 0.0);
  if (dof_ < 0) {
    const double t = mu + kLoadDelta <= 1.0 ? mu + kLoadDelta : mu - kLoadDelta;
    std::vector<double> xx = x;
    check_status(rn_network_load_increment(net_, xx.data(), mu, t, b_.data()),
                 "rn_network_load_increment");
    for (double &v : b_) v /= (t - mu);
  } else {
    const size_t c = static_cast<size_t>(dof_);
    double *vals = p_.mutable_values();
    double dmax = 0.0;
    for (size_t i = 0; i < n_; ++i)
      for (int64_t k = p_.rowptr()[i]; k < p_.rowptr()[i + 1]; ++k)
        if (static_cast<size_t>(p_.col()[k]) == i)
          dmax = std::max(dmax, std::fabs(vals[k]));
    for (size_t i = 0; i < n_; ++i)
      for (int64_t k = p_.rowptr()[i]; k < p_.rowptr()[i + 1]; ++k) {
        const size_t j = static_cast<size_t>(p_.col()[k]);
        if (i == c && j == c) {
          vals[k] = dmax > 0.0 ? dmax : 1.0;
        } else if (j == c) {
          b_[i] = vals[k];
          vals[k] = 0.0;
        } else if (i == c) {
          vals[k] = 0.0;
        }
      }
  }
  metric_ = diagonal_on_pattern(p_, hessian_metric(p_));
  exact_ = factor_->factor(p_, 0.0, nullptr);
  if (!exact_) factor_shifted(*factor_, p_, 0.0, metric_.data(), false);
}

// v <- A^{-1} v with the last linearisation; false if MINRES did not converge (A
// numerically singular: the caller shortens the step).
bool PathFollower::solve(std::vector<double> &v) {
  if (exact_) {
    factor_->solve(v.data());
    return true;
  }
  std::copy(v.begin(), v.end(), host_data(rhs_));
  HessianOp A(p_);
  InverseOp P(*factor_);
  const MinresResult res = minres_.solve(A, P, rhs_, sol_);
  if (!res.converged && !(res.achieved_tol < 1e-8)) return false;
  std::copy(host_data(sol_), host_data(sol_) + n_, v.begin());
  return true;
}

// Tangent at pt (A, b linearised there): (-A^{-1} b, 1) normalised, along the
// previous tangent (or dmu > 0 times o.direction without one).
bool PathFollower::tangent(Point &pt, const std::vector<double> &tx_prev,
                           double tmu_prev) {
  std::vector<double> v = b_;
  if (!solve(v)) return false;
  pt.tx.assign(n_, 0.0);
  for (size_t i = 0; i < n_; ++i) pt.tx[i] = -v[i];
  pt.tmu = 1.0;
  const double nrm = std::sqrt(weighted_dot(pt.tx, pt.tmu, pt.tx, pt.tmu));
  for (double &e : pt.tx) e /= nrm;
  pt.tmu /= nrm;
  const double orient = tx_prev.empty() ? pt.tmu * (o_.direction < 0 ? -1.0 : 1.0)
                                        : weighted_dot(pt.tx, pt.tmu, tx_prev, tmu_prev);
  if (orient < 0.0) {
    for (double &e : pt.tx) e = -e;
    pt.tmu = -pt.tmu;
  }
  return true;
}

// Force and moment scales of the convergence test at x (rn_network_gradient_magnitude,
// and the load derivative's size so that an unloaded start has one).
void PathFollower::scales(const std::vector<double> &x) {
  std::vector<double> gabs(n_);
  check_status(rn_network_gradient_magnitude(net_, x.data(), gabs.data()),
               "rn_network_gradient_magnitude");
  // at this iterate only (a diverging trial must not loosen later tests), but
  // never below the start's
  force_scale_ = base_force_;
  moment_scale_ = base_moment_;
  for (size_t i = 0; i < n_; ++i) {
    const double s = std::max(gabs[i], b_.empty() ? 0.0 : std::fabs(b_[i]));
    if (kind_[i] == RN_DOF_POSITION)
      force_scale_ = std::max(force_scale_, s);
    else
      moment_scale_ = std::max(moment_scale_, s);
  }
  // forces and moments balance each other over the size L (as rn_solve's test)
  force_scale_ = std::max(force_scale_, moment_scale_ / size_);
  moment_scale_ = std::max(moment_scale_, force_scale_ * size_);
}

// Newton on [r; a'(x - x0) + amu (mu - mu0) - ds] = 0 from pt (the predictor), with
// the border (ax, amu) (already W-weighted) and right-hand side target = a'x + amu mu
// at the solution.  Leaves A, b linearised at the solution.  False if it fails.
bool PathFollower::correct(Point &pt, const std::vector<double> &ax, double amu,
                           double target) {
  std::vector<double> r(n_), v1(n_), v2(n_);
  double rprev = std::numeric_limits<double>::max();
  for (int it = 0; it <= o_.max_corrector_iterations; ++it) {
    double E = 0.0, force = 0.0;
    if (residual(pt.x, pt.mu, r, &E, &force) != RN_OK) return false;
    linearise(pt.x, pt.mu);
    scales(pt.x);
    bool ok = true;
    double rmax = 0.0;
    for (size_t i = 0; i < n_; ++i) {
      const double s = kind_[i] == RN_DOF_POSITION ? force_scale_ : moment_scale_;
      if (std::fabs(r[i]) > o_.tol * s) ok = false;
      rmax = std::max(rmax, std::fabs(r[i]) / (s > 0.0 ? s : 1.0));
    }
    double N = amu * pt.mu - target;
    for (size_t i = 0; i < n_; ++i) N += ax[i] * pt.x[i];
    const double nscale = std::sqrt(weighted_dot(ax, amu, ax, amu)) *
                          (1.0 + std::sqrt(weighted_dot(pt.x, pt.mu, pt.x, pt.mu)));
    if (ok && std::fabs(N) <= 1e-12 * nscale) {
      pt.energy = E;
      pt.force = force;
      pt.iterations = it;
      return true;
    }
    if (it == o_.max_corrector_iterations || !(rmax < 1e3 * rprev + 1.0) ||
        !std::isfinite(rmax))
      return false;
    rprev = rmax;
    ++corrector_its_;
    for (size_t i = 0; i < n_; ++i) v1[i] = -r[i];
    v2 = b_;
    if (!solve(v1) || !solve(v2)) return false;
    const double den = amu - dot(n_, ax.data(), v2.data());
    if (!(std::fabs(den) > 0.0)) return false;
    const double dmu = (-N - dot(n_, ax.data(), v1.data())) / den;
    for (size_t i = 0; i < n_; ++i) pt.x[i] += v1[i] - dmu * v2[i];
    pt.mu += dmu;
    if (dof_ >= 0) pt.x[static_cast<size_t>(dof_)] = pt.mu;
  }
  return false;
}

// A point at arclength ds from `from` along (tx, tmu) (pseudo-arclength with that
// tangent), its tangent oriented along it.
bool PathFollower::step_from(const Point &from, double ds, const std::vector<double> &tx,
                             double tmu, Point &to, bool check_turn) {
  to.x = from.x;
  for (size_t i = 0; i < n_; ++i) to.x[i] += ds * tx[i];
  to.mu = from.mu + ds * tmu;
  if (dof_ >= 0) to.x[static_cast<size_t>(dof_)] = to.mu;
  std::vector<double> ax(n_);
  for (size_t i = 0; i < n_; ++i) ax[i] = w_[i] * tx[i];
  const double amu = w_mu_ * tmu;
  const double target = dot(n_, ax.data(), to.x.data()) + amu * to.mu;
  const std::vector<double> px = to.x;
  const double pmu = to.mu;
  if (!correct(to, ax, amu, target)) return false;
  if (check_turn) {
    // a corrector that moved farther from the predictor than the step is long
    // converged on another branch (the shallow arch's snap at steps near its limit
    // point, docs/path-following.md): shorter steps follow the path
    std::vector<double> dx(n_);
    for (size_t i = 0; i < n_; ++i) dx[i] = to.x[i] - px[i];
    const double dmu = to.mu - pmu;
    if (std::sqrt(weighted_dot(dx, dmu, dx, dmu)) > kMaxCorrection * std::fabs(ds))
      return false;
  }
  if (!tangent(to, tx, tmu)) return false;
  // a step whose tangent turned by more than kMaxTurn jumped (or may jump) between
  // branches: shorter steps follow the path
  return !check_turn || weighted_dot(to.tx, to.tmu, tx, tmu) >= std::cos(kMaxTurn);
}

// Lowest eigenvalue of A at pt (A linearised there) and optionally its eigenvector.
void PathFollower::eigen(Point &pt, std::vector<double> *vec) {
  pt.scale = 0.0;
  for (size_t i = 0; i < n_; ++i)
    for (int64_t k = p_.rowptr()[i]; k < p_.rowptr()[i + 1]; ++k)
      if (static_cast<size_t>(p_.col()[k]) == i)
        pt.scale = std::max(pt.scale, std::fabs(p_.values()[k]));
  if (!o_.eigenvalues && !vec) return;
  pt.lowest = choose_factor_kind(p_, o_.factorization) == RN_FACTOR_BANDED
                  ? banded_min_eigenvalue(p_)
                  : sparse_min_eigenvalue(p_);
  if (!vec) return;
  // inverse iteration with A - s I, s just below the lowest eigenvalue
  const std::vector<double> ident = diagonal_on_pattern(p_, std::vector<double>(n_, 1.0));
  double gap = std::max(1e-6 * pt.scale, 1e-3 * std::fabs(pt.lowest));
  while (!factor_->factor(p_, -(pt.lowest - gap), ident.data())) {
    gap *= 4.0;
    if (gap > 1e3 * pt.scale) throw Error(RN_ERR_SOLVER, "rn_path_follow: eigenvector");
  }
  vec->assign(n_, 0.0);
  for (size_t i = 0; i < n_; ++i)
    (*vec)[i] = 1.0 + 0.5 * std::sin(0.7 * static_cast<double>(i));
  if (dof_ >= 0) (*vec)[static_cast<size_t>(dof_)] = 0.0;
  for (int it = 0; it < 200; ++it) {
    factor_->solve(vec->data());
    const double nv = norm2(n_, vec->data());
    for (double &e : *vec) e /= nv;
  }
  if (dof_ >= 0) (*vec)[static_cast<size_t>(dof_)] = 0.0;
  size_t imax = 0;
  for (size_t i = 0; i < n_; ++i)
    if (std::fabs((*vec)[i]) > std::fabs((*vec)[imax])) imax = i;
  if ((*vec)[imax] < 0.0)
    for (double &e : *vec) e = -e;
  // the factorisation no longer holds A: refactor for the next solves
  exact_ = factor_->factor(p_, 0.0, nullptr);
  if (!exact_) factor_shifted(*factor_, p_, 0.0, metric_.data(), false);
}

int stability_of(const Point &pt, int computed) {
  if (!computed || std::isnan(pt.lowest)) return -2;
  if (pt.lowest > kStableRel * pt.scale) return 1;
  if (pt.lowest < -kStableRel * pt.scale) return -1;
  return 0;
}

bool PathFollower::emit(const Point &pt, int step, rn_path_event ev, double arclength,
                        rn_path_report &rep) {
  rn_path_point q{};
  q.step = step;
  q.event = ev;
  q.load_factor = rn_network_load_factor(net_);
  if (dof_ < 0) q.load_factor = pt.mu;
  q.control = monitor_value(pt);
  q.displacement = q.control - start_monitor_;
  // under load control the applied generalised load at the monitored DOF (b is
  // linearised at pt whenever a point is emitted)
  q.force = dof_ < 0 ? -pt.mu * b_[monitor_] : pt.force;
  q.energy = pt.energy;
  q.lowest_eigenvalue = pt.lowest;
  q.eigenvalue_scale = pt.scale;
  q.stability = stability_of(pt, o_.eigenvalues || ev != RN_PATH_POINT);
  q.arclength = arclength;
  q.corrector_iterations = pt.iterations;
  ++rep.points;
  if (ev == RN_PATH_LIMIT) {
    if (rep.limit_points++ == 0) {
      rep.limit_load_factor = q.load_factor;
      rep.limit_control = q.control;
      rep.limit_force = q.force;
    }
  } else if (ev == RN_PATH_BIFURCATION) {
    if (rep.bifurcations++ == 0) {
      rep.bifurcation_load_factor = q.load_factor;
      rep.bifurcation_control = q.control;
      rep.bifurcation_force = q.force;
    }
  }
  return o_.callback && o_.callback(o_.user, &q) != 0;
}

// Locates the zero of the lowest eigenvalue between p0 (tangent used as the border)
// and p1 = step ds from p0: Illinois-safeguarded secant on sigma in (0, ds).
bool PathFollower::locate(const Point &p0, const Point &p1, double ds, Point &ev,
                          bool on_tmu) {
  auto f = [&](const Point &q) { return on_tmu ? q.tmu : q.lowest; };
  double s0 = 0.0, f0 = f(p0), s1 = ds, f1 = f(p1);
  int side = 0;
  bool found = false;
  for (int it = 0; it < kSecantIts; ++it) {
    double s = (s0 * f1 - s1 * f0) / (f1 - f0);
    if (!(s > s0 && s < s1)) s = 0.5 * (s0 + s1);
    Point q;
    if (!step_from(p0, s, p0.tx, p0.tmu, q, false)) return found;
    eigen(q, nullptr);
    q.sigma = s;
    ev = q;
    found = true;
    const double fq = f(q);
    if (std::fabs(fq) <= (on_tmu ? 1e-12 : 1e-12 * q.scale) || s1 - s0 <= 1e-13 * ds)
      break;
    if ((fq > 0.0) == (f0 > 0.0)) {
      s0 = s;
      f0 = fq;
      if (side == -1) f1 *= 0.5;
      side = -1;
    } else {
      s1 = s;
      f1 = fq;
      if (side == 1) f0 *= 0.5;
      side = 1;
    }
  }
  return found;
}

// y = (A + alpha u u') x: A made regular on its (simple) null vector u at a
// bifurcation point.
class RankOneOp : public VectorOperator {
public:
  RankOneOp(Problem &p, const std::vector<double> &u, double alpha)
      : p_(p), u_(u), alpha_(alpha) {}
  void apply(const MV &x, MV &y) const override {
    const double *xv = host_data(x);
    double *yv = host_data(y);
    p_.hessian_apply(xv, yv);
    const double c = alpha_ * dot(u_.size(), u_.data(), xv);
    for (size_t i = 0; i < u_.size(); ++i) yv[i] += c * u_[i];
  }

private:
  Problem &p_;
  const std::vector<double> &u_;
  double alpha_;
};

// The unit tangent (x part, then mu) of the branch through the bifurcation point ev
// that the path did not come along (its tangent there ~ in's): the critical
// eigenvector (phi, 0), or the regular direction (v, 1), v the solution of A v = -b
// orthogonal to phi (b is orthogonal to phi at a symmetry-breaking bifurcation).
// The eigenvector's sign is branch_sign's; the regular direction heads for the
// target (or the path's direction).  A and b linearised at ev.
std::vector<double> PathFollower::other_branch(Point &ev, const Point &in,
                                               double target) {
  std::vector<double> phi;
  eigen(ev, &phi); // Euclidean unit, largest component positive
  const double bphi = dot(n_, b_.data(), phi.data());
  std::vector<double> rhs(n_);
  for (size_t i = 0; i < n_; ++i) rhs[i] = -(b_[i] - bphi * phi[i]);
  factor_shifted(*factor_, p_, 0.0, metric_.data(), true);
  std::copy(rhs.begin(), rhs.end(), host_data(rhs_));
  RankOneOp A(p_, phi, std::max(ev.scale, 1.0));
  InverseOp P(*factor_);
  minres_.solve(A, P, rhs_, sol_);
  std::vector<double> reg(n_ + 1), eig(n_ + 1, 0.0);
  std::copy(host_data(sol_), host_data(sol_) + n_, reg.begin());
  reg[n_] = 1.0;
  std::copy(phi.begin(), phi.end(), eig.begin());
  auto normalise = [&](std::vector<double> &t) {
    std::vector<double> tx(t.begin(), t.end() - 1);
    const double nrm = std::sqrt(weighted_dot(tx, t[n_], tx, t[n_]));
    for (double &e : t) e /= nrm;
  };
  normalise(reg);
  normalise(eig);
  auto along = [&](const std::vector<double> &t) {
    std::vector<double> tx(t.begin(), t.end() - 1);
    return std::fabs(weighted_dot(tx, t[n_], in.tx, in.tmu));
  };
  const bool use_eig = along(eig) <= along(reg);
  std::vector<double> t = use_eig ? eig : reg;
  double sign = o_.branch_sign < 0 ? -1.0 : 1.0;
  if (!use_eig) {
    const double want =
        !std::isnan(target) ? target - ev.mu : (o_.direction < 0 ? -1.0 : 1.0);
    sign = t[n_] * want >= 0.0 ? 1.0 : -1.0;
  }
  for (double &e : t) e *= sign;
  // the factorisation of A for the next solves
  exact_ = factor_->factor(p_, 0.0, nullptr);
  if (!exact_) factor_shifted(*factor_, p_, 0.0, metric_.data(), false);
  return t;
}

// The controlled DOF: in range and a position, an angle or a rotation (kind_ set).
void PathFollower::check_control() {
  if (n_ == 0) throw Error(RN_ERR_ARG, "rn_path_follow: the network has no free DOFs");
  if (dof_ >= static_cast<long>(n_))
    throw Error(RN_ERR_ARG, "rn_path_follow: the controlled DOF " + std::to_string(dof_) +
                                " is out of range (" + std::to_string(n_) +
                                " free DOFs)");
  kind_.assign(n_, 0);
  check_status(rn_network_dof_kinds(net_, kind_.data()), "rn_network_dof_kinds");
  if (dof_ >= 0 && kind_[static_cast<size_t>(dof_)] != RN_DOF_POSITION &&
      kind_[static_cast<size_t>(dof_)] != RN_DOF_THETA &&
      kind_[static_cast<size_t>(dof_)] != RN_DOF_ROTATION)
    throw Error(RN_ERR_ARG, "rn_path_follow: the controlled DOF is a strain");
}

// The arclength weights: 1/L^2 on positions, L the bounding-box diagonal of the DOFs'
// points; the RMS over the DOFs of a kind: positions / L and angles, each kind
// counted once (w_, w_mu_, size_ = L).
void PathFollower::set_weights() {
  std::vector<double> pts(3 * n_);
  std::vector<int32_t> blocks(n_);
  check_status(rn_network_dof_blocks(net_, blocks.data(), pts.data(), nullptr),
               "rn_network_dof_blocks");
  double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
  for (size_t i = 0; i < n_; ++i)
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], pts[3 * i + k]);
      hi[k] = std::max(hi[k], pts[3 * i + k]);
    }
  double L2 = 0.0;
  for (int k = 0; k < 3; ++k) L2 += (hi[k] - lo[k]) * (hi[k] - lo[k]);
  if (!(L2 > 0.0)) L2 = 1.0;
  size_ = std::sqrt(L2);
  size_t npos = 0;
  for (size_t i = 0; i < n_; ++i) npos += kind_[i] == RN_DOF_POSITION;
  const size_t nang = n_ - npos;
  w_.assign(n_, 0.0);
  for (size_t i = 0; i < n_; ++i)
    w_[i] = kind_[i] == RN_DOF_POSITION ? 1.0 / (L2 * static_cast<double>(npos))
                                        : 1.0 / static_cast<double>(nang);
  if (dof_ >= 0) {
    w_mu_ = 1.0 / L2;                    // the controlled coordinate / L
    w_[static_cast<size_t>(dof_)] = 0.0; // counted once, as mu
  }
}

// A target given at or behind the start mu0 (against the direction of the first
// step) is never met by a path that sets out away from it.
void PathFollower::check_target(double mu0) const {
  if (std::isnan(o_.target)) return;
  const double dir = o_.direction < 0 ? -1.0 : 1.0;
  if (!((o_.target - mu0) * dir > 0.0)) {
    char buf[320];
    std::snprintf(buf, sizeof buf,
                  "rn_path_follow: the target %.10g lies %s the start %.10g (the "
                  "path sets out with direction %+g)%s",
                  o_.target, o_.target == mu0 ? "at" : "behind", mu0, dir,
                  o_.target == mu0 ? ": nothing to follow"
                                   : ": give the other direction to head for it");
    throw Error(RN_ERR_ARG, buf);
  }
}

// The DOF reported as control and force: the controlled one; under load control the
// option's, or the position most sensitive to the load (|dr/dmu|, after linearise).
void PathFollower::choose_monitor() {
  if (dof_ >= 0) {
    monitor_ = static_cast<size_t>(dof_);
    return;
  }
  monitor_ = 0;
  if (o_.monitor >= 0) {
    if (o_.monitor >= static_cast<long>(n_))
      throw Error(RN_ERR_ARG, "rn_path_follow: the monitored DOF is out of range");
    monitor_ = static_cast<size_t>(o_.monitor);
  } else {
    double bmax = -1.0;
    for (size_t i = 0; i < n_; ++i)
      if (kind_[i] == RN_DOF_POSITION && std::fabs(b_[i]) > bmax) {
        bmax = std::fabs(b_[i]);
        monitor_ = i;
      }
  }
}

// The start: the network's state corrected at fixed mu (border e_mu), accepted, with
// its tangent and eigenvalues.
void PathFollower::start(Point &cur) {
  cur.x.assign(n_, 0.0);
  check_status(rn_network_get_dofs(net_, cur.x.data()), "rn_network_get_dofs");
  cur.mu = dof_ < 0 ? rn_network_load_factor(net_) : cur.x[static_cast<size_t>(dof_)];
  check_target(cur.mu);
  {
    std::vector<double> r(n_);
    if (residual(cur.x, cur.mu, r, nullptr, nullptr) != RN_OK)
      throw Error(RN_ERR_GEOMETRY, "rn_path_follow: the starting state is degenerate");
    linearise(cur.x, cur.mu);
  }
  choose_monitor();
  {
    const std::vector<double> ax(n_, 0.0);
    if (!correct(cur, ax, w_mu_, w_mu_ * cur.mu))
      throw Error(RN_ERR_SOLVER, "rn_path_follow: the starting state is not an "
                                 "equilibrium at its load factor (solve it first)");
  }
  base_force_ = force_scale_;
  base_moment_ = moment_scale_;
  p_.accept(cur.x.data());
  start_monitor_ = cur.x[monitor_];
  if (!tangent(cur, {}, 0.0))
    throw Error(RN_ERR_SOLVER, "rn_path_follow: no tangent at the start (MINRES did "
                               "not converge: a singular Hessian?)");
  eigen(cur, nullptr);
}

// The last step at fixed mu = mu_end from next (close to it): next moved along its
// tangent to mu_end and corrected there; true (next replaced, *extra the
// arclength of the move) if that converges and has a tangent.
bool PathFollower::land_on(Point &next, double mu_end, double *extra) {
  Point end = next;
  const double frac = (mu_end - next.mu) / next.tmu;
  for (size_t i = 0; i < n_; ++i) end.x[i] += frac * next.tx[i];
  end.mu = mu_end;
  if (dof_ >= 0) end.x[static_cast<size_t>(dof_)] = mu_end;
  const std::vector<double> ax(n_, 0.0);
  if (!(correct(end, ax, w_mu_, w_mu_ * mu_end) && tangent(end, next.tx, next.tmu)))
    return false;
  *extra =
      std::fabs(frac) * std::sqrt(weighted_dot(next.tx, next.tmu, next.tx, next.tmu));
  next = end;
  return true;
}

// The next point of the path from cur with step ds (halved until the corrector
// converges: taken), stopping at the target (or the load factor's range end) on the
// way: then last and rep.stop are set.  False (rep.stop = STEP_MIN) if the step
// falls below ds_min.
bool PathFollower::next_point(const Point &cur, double ds, double target, Point &next,
                              double &taken, bool &last, rn_path_report &rep) {
  bool ok = false;
  taken = ds;
  while (!ok) {
    // does this step pass the target (or leave [0, 1] for the load factor)?
    const double mu_pred = cur.mu + taken * cur.tmu;
    const bool past_target =
        !std::isnan(target) && (cur.mu - target) * (mu_pred - target) < 0.0;
    const bool out_of_range = dof_ < 0 && (mu_pred < 0.0 || mu_pred > 1.0);
    if (past_target || out_of_range) {
      // towards the target (or the range end): a pseudo-arclength step of the
      // length that reaches it to first order (the path may bend: then this is a
      // regular point and the next step tries again), and a last step at fixed mu
      // once the remaining distance is small
      const double mu_end = past_target ? target : (mu_pred < 0.0 ? 0.0 : 1.0);
      const double reach = (mu_end - cur.mu) / cur.tmu;
      ok = step_from(cur, reach, cur.tx, cur.tmu, next);
      if (ok) {
        taken = reach;
        double extra = 0.0;
        if (std::fabs(next.mu - mu_end) <= 1e-2 * std::fabs(mu_end - cur.mu) &&
            land_on(next, mu_end, &extra)) {
          taken = reach + extra;
          last = true;
          rep.stop = past_target ? RN_PATH_STOP_TARGET : RN_PATH_STOP_RANGE;
        }
        break;
      }
    } else {
      ok = step_from(cur, taken, cur.tx, cur.tmu, next);
    }
    if (!ok) {
      taken *= 0.5;
      if (taken < o_.ds_min) {
        rep.stop = RN_PATH_STOP_STEP_MIN;
        return false;
      }
    }
  }
  return true;
}

// Onto the other branch through the bifurcation point ev: along the critical
// eigenvector if the path came along the regular direction, else along the regular
// one; the first point br (step *dsb, halved from ds as needed) with its tangent
// oriented away from ev and its eigenvalues.  False if no step down to ds_min
// converges.
bool PathFollower::switch_branch(Point &ev, const Point &cur, double target, double ds,
                                 Point &br, double *dsb) {
  const std::vector<double> tb = other_branch(ev, cur, target);
  std::vector<double> phi(tb.begin(), tb.end() - 1);
  const double phimu = tb.back();
  bool bok = false;
  *dsb = ds;
  while (!bok && *dsb >= o_.ds_min) {
    bok = step_from(ev, *dsb, phi, phimu, br, false);
    if (!bok) *dsb *= 0.5;
  }
  if (!bok) return false;
  // orient the new tangent away from the bifurcation point
  std::vector<double> d(n_);
  for (size_t i = 0; i < n_; ++i) d[i] = br.x[i] - ev.x[i];
  if (weighted_dot(br.tx, br.tmu, d, br.mu - ev.mu) < 0.0) {
    for (double &e : br.tx) e = -e;
    br.tmu = -br.tmu;
  }
  eigen(br, nullptr);
  return true;
}

void PathFollower::run(rn_path_report &rep) {
  check_control();
  set_weights();
  const double target = dof_ < 0 ? (std::isnan(o_.target) ? 1.0 : o_.target) : o_.target;
  Point cur;
  start(cur);
  Snapshot snap;
  snap.save(net_);
  double arclength = 0.0;
  rep.stop = RN_PATH_STOP_MAX_STEPS;
  if (emit(cur, 0, RN_PATH_POINT, arclength, rep)) {
    rep.stop = RN_PATH_STOP_CALLBACK;
    return;
  }
  // next becomes the current point (reference frames updated, snapshot kept) and is
  // emitted; true if the callback stops the path
  auto advance = [&](Point &next, double taken, int step, rn_path_event kind) {
    p_.accept(next.x.data());
    snap.save(net_);
    arclength += taken;
    cur = next;
    rep.steps = step;
    if (!emit(cur, step, kind, arclength, rep)) return false;
    rep.stop = RN_PATH_STOP_CALLBACK;
    return true;
  };
  double ds = o_.ds;
  for (int step = 1; step <= o_.max_steps; ++step) {
    Point next;
    bool last = false;
    double taken = ds;
    if (!next_point(cur, ds, target, next, taken, last, rep)) {
      snap.restore(net_);
      rep.steps = step - 1;
      return;
    }
    eigen(next, nullptr);
    // an event between cur and next?
    // (a sign change of the lowest eigenvalue: a limit point if dmu/ds changed sign
    // too, else a bifurcation; dmu/ds changing sign while the eigenvalue keeps its
    // sign: the eigenvalue touched zero, a bifurcation reached along the
    // bifurcated branch, located on dmu/ds)
    const bool known = o_.eigenvalues && !std::isnan(cur.lowest) &&
                       !std::isnan(next.lowest) && stability_of(cur, 1) != 0 &&
                       stability_of(next, 1) != 0;
    const bool crossed = known && (cur.lowest > 0.0) != (next.lowest > 0.0);
    const bool turned = (cur.tmu > 0.0) != (next.tmu > 0.0);
    if (crossed || (known && turned)) {
      const bool limit = crossed && turned;
      Point ev;
      if (locate(cur, next, taken, ev, !crossed)) {
        const rn_path_event kind = limit ? RN_PATH_LIMIT : RN_PATH_BIFURCATION;
        if (emit(ev, step, kind, arclength + ev.sigma, rep)) {
          rep.stop = RN_PATH_STOP_CALLBACK;
          rep.steps = step;
          return;
        }
        Point br;
        double dsb = ds;
        if (!limit && o_.branch_switch && switch_branch(ev, cur, target, ds, br, &dsb)) {
          if (advance(br, dsb, step, RN_PATH_BRANCH_SWITCH)) return;
          continue;
        }
      }
      // back to next's linearisation (locate moved it)
      std::vector<double> r(n_);
      if (residual(next.x, next.mu, r, nullptr, nullptr) != RN_OK)
        throw Error(RN_ERR_SOLVER, "rn_path_follow: lost the path after an event");
      linearise(next.x, next.mu);
    }
    if (advance(next, taken, step, RN_PATH_POINT)) return;
    if (last) break;
    if (taken == ds) { // (a full step)
      if (cur.iterations <= 3)
        ds = std::min(o_.ds_max, 1.5 * ds);
      else if (cur.iterations >= 7)
        ds = std::max(o_.ds_min, 0.7 * ds);
    } else {
      ds = taken;
    }
  }
}

const char *validate(const rn_path_options &o) {
  if (o.control != RN_PATH_LOAD && o.control != RN_PATH_DOF) return "unknown control";
  if (o.max_steps < 1) return "max_steps must be >= 1";
  if (!(o.ds > 0.0) || !std::isfinite(o.ds)) return "ds must be > 0";
  if (!(o.ds_min > 0.0) || !(o.ds_min <= o.ds)) return "ds_min must be in (0, ds]";
  if (!(o.ds_max >= o.ds) || !std::isfinite(o.ds_max)) return "ds_max must be >= ds";
  if (!(o.direction == 1.0 || o.direction == -1.0)) return "direction must be +1 or -1";
  if (!(o.branch_sign == 1.0 || o.branch_sign == -1.0))
    return "branch_sign must be +1 or -1";
  if (o.max_corrector_iterations < 1) return "max_corrector_iterations must be >= 1";
  if (!(o.tol > 0.0 && o.tol < 1.0)) return "tol must be in (0, 1)";
  if (o.eigenvalues != 0 && o.eigenvalues != 1) return "eigenvalues must be 0 or 1";
  if (o.branch_switch != 0 && o.branch_switch != 1) return "branch_switch must be 0 or 1";
  if (o.control == RN_PATH_LOAD && !std::isnan(o.target) &&
      !(o.target >= 0.0 && o.target <= 1.0))
    return "the target load factor must be in [0, 1]";
  if (std::isinf(o.target)) return "target must be finite (or NaN: none)";
  if (o.branch_switch && !o.eigenvalues)
    return "branch_switch needs eigenvalues (bifurcations are found from them)";
  return nullptr;
}

} // namespace

void follow_path(rn_network *net, const rn_path_options &opt, rn_path_report &rep) {
  if (const char *bad = validate(opt))
    throw Error(RN_ERR_ARG, std::string("rn_path_follow: ") + bad);
  if (rn_network_is_part(net))
    throw Error(RN_ERR_ARG, "rn_path_follow: needs the whole network on one process");
  ensure_runtime();
  const auto start = std::chrono::steady_clock::now();
  PathFollower f(net, opt);
  f.run(rep);
  rep.factorizations = f.factorizations();
  rep.corrector_iterations = f.corrector_iterations();
  rep.time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

} // namespace rodnet
