// rol_objective.hpp - the network energy as a ROL objective over Tpetra vectors.
//
// RodObjective evaluates the pure functions of rodnet.h at whatever point ROL asks
// (trial points included) and moves the network's reference state only on
// update(x, UpdateType::Accept).  The Hessian at the accepted state is assembled
// once (CSR) and used for hessVec and for the SPD preconditioner (Cholesky of
// H + sigma D, banded or sparse (spd_factor.hpp), sigma >= 0 the smallest shift that
// factors, D = |diag H| floored);
// hessVec at any other point uses the matrix-free HVP.  A degenerate trial point has
// value +inf (ROL then rejects the step / backtracks).
//
// RodStatusTest replaces ROL's status test: it feeds the ROL algorithm state to a
// Monitor (rodnet's stopping tests and progress).
#ifndef RODNET_SHIM_ROL_OBJECTIVE_HPP
#define RODNET_SHIM_ROL_OBJECTIVE_HPP

#include <memory>
#include <vector>

#include <ROL_Objective.hpp>
#include <ROL_StatusTest.hpp>
#include <ROL_TpetraMultiVector.hpp>

#include "system/equilibrium.hpp"
#include "krylov/minres.hpp"
#include "newton/monitor.hpp"
#include "system/problem.hpp"
#include "factor/spd_factor.hpp"

namespace rodnet {

using RolVector = ROL::Vector<double>;
using TpetraVector = ROL::TpetraMultiVector<double>;

// Host data of a ROL::TpetraMultiVector (throws for any other vector type).
const double *host_data(const RolVector &v);
double *host_data(RolVector &v);

class RodObjective : public ROL::Objective<double> {
public:
  RodObjective(Problem &p, const rn_solve_options &opt);

  double value(const RolVector &x, double &tol) override;
  void gradient(RolVector &g, const RolVector &x, double &tol) override;
  void hessVec(RolVector &hv, const RolVector &v, const RolVector &x,
               double &tol) override;
  void precond(RolVector &pv, const RolVector &v, const RolVector &x,
               double &tol) override;
  void update(const RolVector &x, ROL::UpdateType type, int iter) override;

  Problem &problem() { return p_; }
  // Accepted steps since the last call: whether one happened, its Euclidean norm and
  // the energy change (new - old); clears the record.
  bool take_accepted(double *step_norm, double *energy_change);
  // Diagonal shift sigma of the current preconditioner (0: exact Hessian).
  double preconditioner_shift() const { return sigma_; }
  const std::vector<double> &accepted_state() const { return x_acc_; }
  double accepted_energy() const { return e_acc_; }

private:
  bool at_accepted(const double *x) const;
  void ensure_hessian();
  void ensure_factor();

  Problem &p_;
  rn_factorization factorization_;
  std::vector<double> x_acc_, x_prev_;
  std::vector<double> metric_; // D = |diag H| (first Hessian), CSR values on its pattern
  std::vector<double> metric_d_;     // D itself
  unsigned long metric_version_ = 0; // of the pattern metric_ is on
  std::vector<double> x_last_; // point of the last finite value() (E there: e_last_)
  double e_last_ = 0.0;
  double e_acc_ = 0.0, e_prev_ = 0.0, sigma_ = 0.0;
  bool have_energy_ = false, accepted_ = false, hess_ok_ = false, factor_ok_ = false;
  std::unique_ptr<SpdFactor> factor_; // created on first use
};

class RodStatusTest : public ROL::StatusTest<double> {
public:
  // line_search: the step was unconstrained if the step length was 1; otherwise
  // (trust region) if it was shorter than the radius it was computed for.
  RodStatusTest(Monitor &monitor, RodObjective &obj, bool line_search);
  ~RodStatusTest() override;
  bool check(ROL::AlgorithmState<double> &state) override;
  // Krylov iterations of the iteration just finished (set by the caller's Krylov
  // solver or counted as Hessian-vector products).
  void set_krylov_counter(const long *counter) { krylov_counter_ = counter; }

private:
  Monitor &mon_;
  RodObjective &obj_;
  bool line_search_;
  double radius_prev_ = 0.0;
  long krylov_seen_ = 0;
  const long *krylov_counter_ = nullptr;
  std::unique_ptr<Equilibrium> equilibrium_;
};

// Parameters shared by the ROL algorithms: ROL's own status test is disabled
// (RodStatusTest decides), output off.
void set_common_rol_parameters(ROL::ParameterList &list, const rn_solve_options &opt);

} // namespace rodnet

#endif
