// dist_predictor.cpp - the load-step predictor (predictor.hpp) on a distributed System
// (dist_predictor.hpp).
#include "newton/dist_predictor.hpp"

#include <memory>

#include "system/dist_system.hpp"
#include "krylov/minres.hpp"
#include "pc/preconditioner.hpp"
#include "base/shim_error.hpp"
#include "newton/solvers.hpp"

namespace rodnet {

namespace {

// y = H x with the System's assembled Hessian; y = M^{-1} x with a preconditioner.
class HessianOp : public VectorOperator {
public:
  explicit HessianOp(const System &s) : s_(s) {}
  void apply(const MV &x, MV &y) const override { s_.hessian()->apply(x, y); }

private:
  const System &s_;
};

class InverseOp : public VectorOperator {
public:
  explicit InverseOp(const Preconditioner &p) : p_(p) {}
  void apply(const MV &x, MV &y) const override { p_.inverse()->apply(x, y); }

private:
  const Preconditioner &p_;
};

} // namespace

bool predict_load_step(DistSystem &sys, Preconditioner &prec, const rn_solve_options &opt,
                       double t_prev, double t) {
  rn_network *net = sys.network();
  const auto map = sys.map();
  TMV x(map, 1), r(map, 1), dg(map, 1), s(map, 1), xs(map, 1);
  sys.get_state(x);
  // r = g(x; t_prev) + dg: the gradient at t linearised in the load factor
  sys.agree(rn_network_set_load_factor(net, t_prev));
  const bool have = sys.global_size() > 0 && sys.gradient(x, nullptr, r) == RN_OK;
  if (have) {
    sys.load_increment(x, t_prev, t, dg);
    r.update(1.0, dg, 1.0);
    sys.assemble_hessian(x);
  }
  sys.agree(rn_network_set_load_factor(net, t));
  if (!have) return false;
  // H s = -r by MINRES preconditioned as the solve is, as tr-krylov's predictor on
  // one rank (predict_step_krylov), also where M had to be shifted (H not positive
  // definite): the same step on any number of ranks
  prec.setup(sys);
  r.scale(-1.0);
  MinresSolver minres(map, opt.krylov_tol, opt.krylov_max_iterations);
  sys.counters.krylov += minres.solve(HessianOp(sys), InverseOp(prec), r, s).iterations;
  double E0 = 0.0, E1 = 0.0;
  xs.update(1.0, x, 1.0, s, 0.0);
  // (the jumped state x may be degenerate: then the evaluable prediction is better)
  if (sys.energy(xs, &E1) != RN_OK) return false;
  if (sys.energy(x, &E0) == RN_OK && !(E1 < E0)) return false;
  sys.accept(xs);
  return true;
}

} // namespace rodnet
