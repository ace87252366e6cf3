// equilibrium.cpp - residual of equilibrium on a physical scale (see equilibrium.hpp).
#include "system/equilibrium.hpp"
#include "system/equilibrium_scale.hpp"

#include <algorithm>
#include <cfloat>
#include <cmath>

#include "base/shim_error.hpp"

namespace rodnet {

std::vector<double> eq_levers(rn_network *net, const std::vector<int> &kind) {
  const size_t n = kind.size();
  std::vector<double> lever(n, 1.0);
  if (!n) return lever;
  std::vector<rn_dof_info> info(n);
  check_status(rn_network_dof_info(net, info.data()), "rn_network_dof_info");
  // rest lengths of every (local) rod's edges; the shortest of them for joints
  std::vector<std::vector<double>> len(static_cast<size_t>(rn_network_num_rods(net)));
  double shortest = HUGE_VAL;
  for (size_t r = 0; r < len.size(); ++r) {
    const int nv = rn_network_rod_num_vertices(net, static_cast<int>(r));
    if (nv < 2 || !rn_network_rod_is_local(net, static_cast<int>(r)))
      continue; // (a part's ghost rod: held by another part)
    len[r].resize(static_cast<size_t>(nv - 1));
    check_status(rn_network_rod_rest_lengths(net, static_cast<int>(r), len[r].data()),
                 "rn_network_rod_rest_lengths");
    for (double l : len[r]) shortest = std::min(shortest, l);
  }
  if (!std::isfinite(shortest)) shortest = 0.0;
  for (size_t i = 0; i < n; ++i) {
    if (kind[i] == RN_DOF_STRAIN) {
      lever[i] = 0.0;
    } else if (kind[i] == RN_DOF_POSITION) {
      const rn_dof_info &d = info[i];
      lever[i] = shortest;
      if (d.rod >= 0 && static_cast<size_t>(d.rod) < len.size() && !len[d.rod].empty()) {
        const std::vector<double> &l = len[static_cast<size_t>(d.rod)];
        const size_t v = static_cast<size_t>(std::max(d.index, 0)), ne = l.size();
        if (v == 0)
          lever[i] = l[0];
        else if (v >= ne)
          lever[i] = l[ne - 1];
        else
          lever[i] = 0.5 * (l[v - 1] + l[v]);
      }
    }
  }
  return lever;
}

double eq_internal_moment(const std::vector<int> &kind, const std::vector<double> &lever,
                          const double *gabs, size_t n) {
  double m = 0.0;
  for (size_t i = 0; i < n; ++i) {
    const double f = kind[i] == RN_DOF_POSITION ? 0.25 : 0.5;
    m = std::max(m, f * lever[i] * gabs[i]);
  }
  return m;
}

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
  // Round-off floor: the rounding error of the DOFs propagated by the Hessian, plus
  // the rounding error of the sum of the stencils' forces at each DOF.
  for (size_t i = 0; i < n; ++i)
    delta_[i] = eq_sign_of(i) * DBL_EPSILON * (kind_[i] == RN_DOF_POSITION ? xmax : 1.0);
  if (n) {
    p_.hvp(x, delta_.data(), hdelta_.data());
    check_status(rn_network_gradient_magnitude(net, x, gabs_.data()),
                 "rn_network_gradient_magnitude");
  }
  // Forces and moments convert over the size L of the structure: a force F makes
  // moments of about F L, a moment M is carried by forces of about M / L.  The
  // internal moment gives self-stressed states a scale (levers: O(n), measured
  // again with the scales only).
  const double mint =
      n ? eq_internal_moment(kind_, eq_levers(net, kind_), gabs_.data(), n) : 0.0;
  const double f0 = std::max(fload, freac), m0 = std::max({mload, mreac, mint});
  v.force_scale = size_ > 0.0 ? std::max(f0, m0 / size_) : f0;
  v.moment_scale = std::max(m0, f0 * size_);
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
