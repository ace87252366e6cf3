// equilibrium.cpp - residual of equilibrium on a physical scale (see equilibrium.hpp).
#include "equilibrium.hpp"

#include <algorithm>
#include <cfloat>
#include <cmath>

#include "shim_error.hpp"

namespace rodnet {

Equilibrium::Equilibrium(Problem &p) : p_(p) {
  rn_network *net = p.network();
  const size_t n = p.size();
  kind_.assign(n, RN_DOF_POSITION);
  if (n) check_status(rn_network_dof_kinds(net, kind_.data()), "rn_network_dof_kinds");
  reactions_.resize(static_cast<size_t>(rn_network_num_supports(net)));
  // The size of the structure: the diagonal of the bounding box of its initial
  // vertices.
  double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL},
         hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  for (int r = 0; r < rn_network_num_rods(net); ++r) {
    const int nv = rn_network_rod_num_vertices(net, r);
    std::vector<double> xyz(3 * static_cast<size_t>(std::max(nv, 0)));
    if (nv > 0)
      check_status(rn_network_rod_initial_vertices(net, r, xyz.data()),
                   "rn_network_rod_initial_vertices");
    for (size_t i = 0; i < xyz.size(); ++i) {
      lo[i % 3] = std::min(lo[i % 3], xyz[i]);
      hi[i % 3] = std::max(hi[i % 3], xyz[i]);
    }
  }
  for (int k = 0; k < 3; ++k)
    if (hi[k] >= lo[k]) size_ += (hi[k] - lo[k]) * (hi[k] - lo[k]);
  size_ = std::sqrt(size_);
  delta_.assign(n, 0.0);
  hdelta_.assign(n, 0.0);
  gabs_.assign(n, 0.0);
}

EquilibriumView Equilibrium::measure(const double *x, const double *g) {
  EquilibriumView v = last_;
  rn_network *net = p_.network();
  const size_t n = p_.size();
  double xmax = 0.0;
  v.force_residual = v.moment_residual = 0.0;
  for (size_t i = 0; i < n; ++i) {
    const double a = std::fabs(g[i]);
    if (kind_[i] == RN_DOF_POSITION) {
      v.force_residual = std::max(v.force_residual, a);
      xmax = std::max(xmax, std::fabs(x[i]));
    } else {
      v.moment_residual = std::max(v.moment_residual, a);
    }
  }
  // Scales and floors change slowly: measured again only when the residual comes
  // within kRemeasure of the last scale (far above any tolerance), or never was.
  if (last_.valid && v.force_residual > kRemeasure * last_.force_scale &&
      v.moment_residual > kRemeasure * last_.moment_scale)
    return v;
  double fload = 0.0, mload = 0.0, freac = 0.0, mreac = 0.0;
  check_status(rn_network_applied_load_max(net, &fload, &mload),
               "rn_network_applied_load_max");
  if (!reactions_.empty() &&
      check_status(rn_network_reactions(net, x, reactions_.data(),
                                        static_cast<int>(reactions_.size())),
                   "rn_network_reactions") == RN_OK) {
    for (const rn_reaction &r : reactions_) {
      freac = std::max(freac, eq_norm3(r.force));
      mreac = std::max(mreac, eq_norm3(r.moment));
    }
  }
  // Forces and moments convert over the size L of the structure: a force F makes
  // moments of about F L, a moment M is carried by forces of about M / L.
  const double f0 = std::max(fload, freac), m0 = std::max(mload, mreac);
  v.force_scale = size_ > 0.0 ? std::max(f0, m0 / size_) : f0;
  v.moment_scale = std::max(m0, f0 * size_);
  // Round-off floor: the rounding error of the DOFs propagated by the Hessian, plus
  // the rounding error of the sum of the stencils' forces at each DOF.
  for (size_t i = 0; i < n; ++i)
    delta_[i] = eq_sign_of(i) * DBL_EPSILON * (kind_[i] == RN_DOF_POSITION ? xmax : 1.0);
  if (n) {
    p_.hvp(x, delta_.data(), hdelta_.data());
    check_status(rn_network_gradient_magnitude(net, x, gabs_.data()),
                 "rn_network_gradient_magnitude");
  }
  v.force_floor = v.moment_floor = 0.0;
  for (size_t i = 0; i < n; ++i) {
    double &floor = kind_[i] == RN_DOF_POSITION ? v.force_floor : v.moment_floor;
    floor = std::max(floor, std::fabs(hdelta_[i]) + DBL_EPSILON * gabs_[i]);
  }
  v.valid = true;
  last_ = v;
  return v;
}

} // namespace rodnet
