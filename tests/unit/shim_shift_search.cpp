// shim_shift_search.cpp - the shifted factorisation's search (factor_shifted,
// shim_cxx/factor/spd_factor.cpp) where the Hessian has outgrown the metric M: tr-minres
// fixes M = |diag H_0| for a load step, and on a rod started nearly folded (179
// degrees) H grew 10^4-fold while it unfolded, so that no shift up to 10^10 (the
// old, fixed end of the search) made H + sigma M positive definite although one
// exists (RN_ERR_LAPACK, docs/hard-cases.md).  Here the Hessian of that rod at its
// folded start with M = 10^-k |diag H| (k = 0, 6, 12, 16), banded and sparse:
//  - factor_shifted succeeds, the factor holds H + sigma M (a solve has a backward
//    error below 1e-8 relative), sigma is the smallest decade (sigma / 10 fails) and
//    grows as 10^k (so k = 12 and 16 need shifts far above 10^10);
//  - a non-finite metric or Hessian entry throws Error(RN_ERR_LAPACK).
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <vector>

#include "system/problem.hpp"
#include "rodnet.h"
#include "base/shim_error.hpp"
#include "factor/spd_factor.hpp"

extern "C" {
#include "testutil.h"
}

namespace {

constexpr double kPi = 3.14159265358979323846;

// The clamped rod of hard_cases.c (folded): a Z whose two folds turn by `deg`.
rn_network *folded_rod(rn_context *ctx, double deg) {
  constexpr int nv = 13;
  const double h = 0.1, turn = deg * kPi / 180.0;
  double xyz[3 * nv] = {0.0}, len[nv - 1], kappa[2 * (nv - 2)] = {0.0}, dir = 0.0;
  for (int e = 0; e < nv - 1; ++e) {
    if (e == 4) dir += turn;
    if (e == 8) dir -= turn;
    xyz[3 * (e + 1)] = xyz[3 * e] + h * std::cos(dir);
    xyz[3 * (e + 1) + 1] = xyz[3 * e + 1] + h * std::sin(dir);
    len[e] = h;
  }
  rn_network *net = nullptr;
  rn_material m;
  rn_section s;
  int rod = -1;
  const double d1[3] = {0.0, 0.0, 1.0};
  CHECK_STATUS(rn_network_create(ctx, &net), RN_OK);
  CHECK_STATUS(rn_material_from_E_nu(1e7, 0.3, 0.0, &m), RN_OK);
  CHECK_STATUS(rn_section_circle(0.01, &s), RN_OK);
  CHECK_STATUS(rn_network_add_rod(net, "rod", nv, xyz, d1, &rod), RN_OK);
  CHECK_STATUS(rn_network_set_material(net, rod, -1, &m), RN_OK);
  CHECK_STATUS(rn_network_set_section(net, rod, -1, &s), RN_OK);
  CHECK_STATUS(rn_network_set_rest_curvature(net, rod, kappa), RN_OK);
  CHECK_STATUS(rn_network_set_rest_lengths(net, rod, len), RN_OK);
  CHECK_STATUS(rn_network_clamp(net, rod, RN_START), RN_OK);
  CHECK_STATUS(rn_network_finalize(net), RN_OK);
  return net;
}

// ||(H + sigma M) y - b|| / (||H + sigma M||_1 ||y|| + ||b||) for y = factor \ b.
double backward_error(rodnet::Problem &p, const rodnet::SpdFactor &f, double sigma,
                      const std::vector<double> &m) {
  const size_t n = p.size();
  std::vector<double> b(n), y(n), r(n);
  for (size_t i = 0; i < n; ++i) b[i] = std::sin(1.0 + 0.37 * static_cast<double>(i));
  y = b;
  f.solve(y.data());
  p.hessian_apply(y.data(), r.data(), sigma, m.data());
  double rn = 0.0, yn = 0.0, bn = 0.0, an = 0.0;
  for (size_t i = 0; i < n; ++i) {
    rn += (r[i] - b[i]) * (r[i] - b[i]);
    yn += y[i] * y[i];
    bn += b[i] * b[i];
    double row = 0.0;
    for (int64_t k = p.rowptr()[i]; k < p.rowptr()[i + 1]; ++k)
      row += std::fabs(p.values()[k] + sigma * m[static_cast<size_t>(k)]);
    an = std::max(an, row);
  }
  return std::sqrt(rn) / (an * std::sqrt(yn) + std::sqrt(bn));
}

} // namespace

int main() {
  rn_context *ctx = nullptr;
  CHECK_STATUS(rn_context_create(&ctx), RN_OK);
  rn_network *net = folded_rod(ctx, 179.0);
  const size_t n = rn_network_num_dofs(net);
  std::vector<double> x(n);
  CHECK_STATUS(rn_network_get_dofs(net, x.data()), RN_OK);
  rodnet::Problem p(net);
  p.assemble_hessian(x.data());
  const std::vector<double> d0 = rodnet::hessian_metric(p);
  for (rn_factorization kind : {RN_FACTOR_BANDED, RN_FACTOR_SPARSE}) {
    double sigma_k0 = 0.0;
    for (int k : {0, 6, 12, 16}) {
      std::vector<double> d = d0;
      for (double &v : d) v *= std::pow(10.0, -k);
      const std::vector<double> m = rodnet::diagonal_on_pattern(p, d);
      std::unique_ptr<rodnet::SpdFactor> f = rodnet::make_spd_factor(p, kind);
      double sigma = -1.0;
      try {
        sigma = rodnet::factor_shifted(*f, p, 0.0, m.data(), true);
      } catch (const rodnet::Error &e) {
        std::printf("  %s, M = 1e-%d |diag H|: %s\n",
                    kind == RN_FACTOR_BANDED ? "banded" : "sparse", k, e.what());
      }
      const double berr = sigma > 0.0 ? backward_error(p, *f, sigma, m) : 1.0;
      std::unique_ptr<rodnet::SpdFactor> g = rodnet::make_spd_factor(p, kind);
      const bool below = sigma > 0.0 && g->factor(p, 0.1 * sigma, m.data());
      std::printf("  %s, M = 1e-%-2d |diag H|: sigma %.0e, backward error %.1e, "
                  "sigma / 10 factors: %d\n",
                  kind == RN_FACTOR_BANDED ? "banded" : "sparse", k, sigma, berr,
                  static_cast<int>(below));
      CHECK(sigma > 0.0); // the folded start is indefinite: a positive shift
      CHECK(f->factored());
      CHECK(berr < 1e-8);
      CHECK(!below); // the smallest decade
      if (k == 0) sigma_k0 = sigma;
      // the shift scales with 1 / M: exactly 10^k sigma_k0 up to one decade
      CHECK(sigma >= 0.1 * sigma_k0 * std::pow(10.0, k) &&
            sigma <= 10.0 * sigma_k0 * std::pow(10.0, k));
      if (k >= 12) CHECK(sigma > 1e10); // beyond the old end of the search
    }
    // a non-finite metric entry: a clear error
    std::vector<double> d = d0;
    d[n / 2] = std::numeric_limits<double>::quiet_NaN();
    const std::vector<double> m = rodnet::diagonal_on_pattern(p, d);
    std::unique_ptr<rodnet::SpdFactor> f = rodnet::make_spd_factor(p, kind);
    rn_status st = RN_OK;
    try {
      rodnet::factor_shifted(*f, p, 0.0, m.data(), true);
    } catch (const rodnet::Error &e) {
      st = e.status();
      std::printf("  non-finite metric: %s\n", e.what());
    }
    CHECK_STATUS(st, RN_ERR_LAPACK);
  }
  rn_network_destroy(&net);
  rn_context_destroy(&ctx);
  return rn_test_finish("shim_shift_search");
}
