// rol_objective.cpp - ROL objective adapter and status test (see rol_objective.hpp).
#include "newton/rol_objective.hpp"

#include <algorithm>
#include <cstring>
#include <limits>

#include <ROL_TypeU_Algorithm.hpp>

#include "base/shim_error.hpp"

namespace rodnet {

const double *host_data(const RolVector &v) {
  const auto *tv = dynamic_cast<const TpetraVector *>(&v);
  if (!tv) throw Error(RN_ERR_INTERNAL, "rn_solve: ROL vector is not a Tpetra vector");
  return host_data(*tv->getVector());
}

double *host_data(RolVector &v) {
  auto *tv = dynamic_cast<TpetraVector *>(&v);
  if (!tv) throw Error(RN_ERR_INTERNAL, "rn_solve: ROL vector is not a Tpetra vector");
  return host_data(*tv->getVector());
}

RodObjective::RodObjective(Problem &p, const rn_solve_options &opt)
    : p_(p), factorization_(opt.factorization), x_acc_(p.size()), x_prev_(p.size()) {}

bool RodObjective::at_accepted(const double *x) const {
  return std::memcmp(x, x_acc_.data(), x_acc_.size() * sizeof(double)) == 0;
}

double RodObjective::value(const RolVector &x, double & /*tol*/) {
  const double *xp = host_data(x);
  if (have_energy_ && at_accepted(xp)) return e_acc_;
  double E = 0.0;
  if (p_.energy(xp, &E) != RN_OK) return std::numeric_limits<double>::infinity();
  x_last_.assign(xp, xp + p_.size());
  e_last_ = E;
  return E;
}

void RodObjective::gradient(RolVector &g, const RolVector &x, double & /*tol*/) {
  if (p_.gradient(host_data(x), nullptr, host_data(g)) != RN_OK)
    throw Error(RN_ERR_SOLVER, "rn_solve: gradient requested at a degenerate point");
}

void RodObjective::hessVec(RolVector &hv, const RolVector &v, const RolVector &x,
                           double & /*tol*/) {
  const double *xp = host_data(x);
  if (at_accepted(xp)) {
    ensure_hessian();
    p_.hessian_apply(host_data(v), host_data(hv));
  } else {
    p_.hvp(xp, host_data(v), host_data(hv));
  }
}

void RodObjective::precond(RolVector &pv, const RolVector &v, const RolVector & /*x*/,
                           double & /*tol*/) {
  ensure_factor();
  double *out = host_data(pv);
  std::copy(host_data(v), host_data(v) + p_.size(), out);
  factor_->solve(out);
}

// Accept moves the reference state and may change x (rigid-joint rotations move into
// the reference): the objective keeps the accepted x and writes it back into ROL's
// iterate, on Accept and on Revert (ROL reverts to its own stale copy).
void RodObjective::update(const RolVector &x, ROL::UpdateType type, int /*iter*/) {
  const size_t n = p_.size();
  if (type == ROL::UpdateType::Revert) {
    double *xw = host_data(const_cast<RolVector &>(x));
    std::copy(x_acc_.begin(), x_acc_.end(), xw);
    return;
  }
  if (type != ROL::UpdateType::Initial && type != ROL::UpdateType::Accept) return;
  const double *xp = host_data(x);
  const bool known =
      x_last_.size() == n && std::memcmp(xp, x_last_.data(), n * sizeof(double)) == 0;
  double E = e_last_;
  if (!known && p_.energy(xp, &E) != RN_OK)
    throw Error(RN_ERR_SOLVER, "rn_solve: accepted a degenerate point");
  const bool accept = (type == ROL::UpdateType::Accept);
  if (accept) {
    x_prev_ = x_acc_;
    e_prev_ = e_acc_;
  }
  std::copy(xp, xp + n, x_acc_.begin());
  if (accept) {
    p_.accept(x_acc_.data());
    double *xw = host_data(const_cast<RolVector &>(x));
    std::copy(x_acc_.begin(), x_acc_.end(), xw);
  }
  e_acc_ = E;
  have_energy_ = true;
  accepted_ = accept;
  hess_ok_ = factor_ok_ = false;
}

bool RodObjective::take_accepted(double *step_norm, double *energy_change) {
  if (!accepted_) return false;
  double s = 0.0;
  for (size_t i = 0; i < x_acc_.size(); ++i)
    s += (x_acc_[i] - x_prev_[i]) * (x_acc_[i] - x_prev_[i]);
  *step_norm = std::sqrt(s);
  *energy_change = e_acc_ - e_prev_;
  accepted_ = false;
  return true;
}

void RodObjective::ensure_hessian() {
  if (hess_ok_) return;
  p_.assemble_hessian(x_acc_.data());
  if (metric_d_.empty()) metric_d_ = hessian_metric(p_);
  if (metric_.empty() || metric_version_ != p_.pattern_version()) {
    metric_ = diagonal_on_pattern(p_, metric_d_);
    metric_version_ = p_.pattern_version();
  }
  hess_ok_ = true;
}

void RodObjective::ensure_factor() {
  if (factor_ok_) return;
  ensure_hessian();
  if (!factor_) factor_ = make_spd_factor(p_, factorization_);
  sigma_ = factor_shifted(*factor_, p_, 0.0, metric_.data());
  factor_ok_ = true;
}

RodStatusTest::RodStatusTest(Monitor &monitor, RodObjective &obj, bool line_search)
    : mon_(monitor), obj_(obj), line_search_(line_search),
      equilibrium_(new Equilibrium(obj.problem())) {}

RodStatusTest::~RodStatusTest() = default;

bool RodStatusTest::check(ROL::AlgorithmState<double> &base) {
  // Only the TypeU algorithms use this test: their state carries the radius / step
  // length (searchSize).
  auto &state = static_cast<ROL::TypeU::AlgorithmState<double> &>(base);
  IterationView it;
  it.iteration = state.iter;
  it.energy = state.value;
  it.gnorm = state.gnorm;
  it.radius = line_search_ ? 0.0 : state.searchSize;
  it.accepted = obj_.take_accepted(&it.step_norm, &it.energy_change);
  const std::vector<double> &x = obj_.accepted_state();
  it.x_norm = norm2(x.size(), x.data());
  it.unconstrained =
      line_search_ ? (state.searchSize == 1.0) : (state.snorm < 0.9 * radius_prev_);
  it.radius_collapsed =
      !line_search_ && state.iter > 0 && state.searchSize <= 1e-14 * (1.0 + it.x_norm);
  radius_prev_ = state.searchSize;
  if (krylov_counter_) {
    it.krylov = static_cast<int>(*krylov_counter_ - krylov_seen_);
    krylov_seen_ = *krylov_counter_;
  }
  if (state.gradientVec && x.size() == obj_.problem().size())
    it.eq = equilibrium_->measure(x.data(), host_data(*state.gradientVec));
  if (!mon_.check(it)) return true;
  state.statusFlag =
      mon_.converged() ? ROL::EXITSTATUS_CONVERGED : ROL::EXITSTATUS_MAXITER;
  return false;
}

void set_common_rol_parameters(ROL::ParameterList &list, const rn_solve_options &opt) {
  list.sublist("General").set("Output Level", 0);
  ROL::ParameterList &krylov = list.sublist("General").sublist("Krylov");
  krylov.set("Absolute Tolerance", std::numeric_limits<double>::max());
  krylov.set("Relative Tolerance", opt.krylov_tol);
  krylov.set("Iteration Limit", opt.krylov_max_iterations);
  ROL::ParameterList &status = list.sublist("Status Test");
  status.set("Gradient Tolerance", 0.0);
  status.set("Step Tolerance", 0.0);
  status.set("Iteration Limit", opt.max_iterations);
}

} // namespace rodnet
