// predictor.cpp - the load-step predictor (predictor.hpp).
#include "newton/predictor.hpp"

#include <vector>

#include "base/shim_error.hpp"
#include "factor/spd_factor.hpp"

namespace rodnet {

namespace {

// s = -H^{-1} (g0 + dg) at x, load factor t_prev (network left there).  False if
// the gradient cannot be evaluated at x.
bool predicted_step(Problem &p, const PredictorSolve &solve, double t_prev, double t,
                    const std::vector<double> &x, std::vector<double> &s) {
  rn_network *net = p.network();
  const size_t n = p.size();
  std::vector<double> g0(n), dg(n);
  check_status(rn_network_set_load_factor(net, t_prev), "rn_network_set_load_factor");
  if (p.gradient(x.data(), nullptr, g0.data()) != RN_OK) return false;
  check_status(rn_network_load_increment(net, x.data(), t_prev, t, dg.data()),
               "rn_network_load_increment");
  for (size_t i = 0; i < n; ++i) s[i] = -(g0[i] + dg[i]);
  return solve(p, x, s);
}

} // namespace

bool predict_load_step(Problem &p, rn_factorization kind, double t_prev, double t) {
  return predict_load_step(
      p,
      [kind](Problem &q, const std::vector<double> &x, std::vector<double> &s) {
        q.assemble_hessian(x.data());
        std::unique_ptr<SpdFactor> f = make_spd_factor(q, kind);
        const std::vector<double> m = diagonal_on_pattern(q, hessian_metric(q));
        factor_shifted(*f, q, 0.0, m.data());
        f->solve(s.data());
        return true;
      },
      t_prev, t);
}

bool predict_load_step(Problem &p, const PredictorSolve &solve, double t_prev, double t) {
  rn_network *net = p.network();
  const size_t n = p.size();
  std::vector<double> x(n), s(n), xs(n);
  check_status(rn_network_get_dofs(net, x.data()), "rn_network_get_dofs");
  const bool have_step = n > 0 && predicted_step(p, solve, t_prev, t, x, s);
  check_status(rn_network_set_load_factor(net, t), "rn_network_set_load_factor");
  if (!have_step) return false;
  double E0 = 0.0, E1 = 0.0;
  for (size_t i = 0; i < n; ++i) xs[i] = x[i] + s[i];
  // (the jumped state x may be degenerate: then the evaluable prediction is better)
  if (p.energy(xs.data(), &E1) != RN_OK) return false;
  if (p.energy(x.data(), &E0) == RN_OK && !(E1 < E0)) return false;
  p.accept(xs.data());
  return true;
}

} // namespace rodnet
