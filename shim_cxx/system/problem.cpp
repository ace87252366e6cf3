// problem.cpp - evaluation wrapper of a finalized rn_network (see problem.hpp).
#include "system/problem.hpp"

#include <chrono>

#include "rodnet_contact.h"

#include <algorithm>

#include "base/shim_error.hpp"

namespace rodnet {

Problem::Problem(rn_network *net) : net_(net) {
  if (!net) throw Error(RN_ERR_ARG, "rn_solve: network is NULL");
  contact_ = rn_network_get_contact(net, nullptr, nullptr, nullptr) == 1;
  take_pattern();
}

void Problem::take_pattern() {
  size_t nnz = 0;
  const int64_t *rowptr = nullptr;
  const int32_t *col = nullptr;
  check_status(rn_network_hessian_pattern(net_, &nnz, &rowptr, &col),
               "rn_network_hessian_pattern");
  set_pattern(rn_network_num_dofs(net_), nnz, rowptr, col,
              rn_network_hessian_bandwidth(net_), rn_network_pattern_version(net_),
              contact_);
}

rn_status Problem::energy(const double *x, double *E) {
  ++counters.energy;
  return check_status(rn_network_energy(net_, x, E), "rn_network_energy");
}

rn_status Problem::gradient(const double *x, double *E, double *g) {
  ++counters.gradient;
  return check_status(rn_network_gradient(net_, x, E, g), "rn_network_gradient");
}

void Problem::hvp(const double *x, const double *v, double *Hv) {
  ++counters.hvp;
  if (check_status(rn_network_hvp(net_, x, v, Hv), "rn_network_hvp") != RN_OK)
    throw Error(RN_ERR_SOLVER, "rn_solve: Hessian-vector product at a degenerate state");
}

double steady_now() {
  return std::chrono::duration<double>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

double seconds_since_steady(double t0) { return steady_now() - t0; }

void Problem::assemble_hessian(const double *x) {
  ++counters.hessian;
  if (rn_network_pattern_version(net_) != pattern_version()) take_pattern();
  const double t0 = steady_now();
  const rn_status st = check_status(rn_network_hessian_values(net_, x, mutable_values()),
                                    "rn_network_hessian_values");
  counters.hessian_seconds += seconds_since_steady(t0);
  if (st != RN_OK) throw Error(RN_ERR_SOLVER, "rn_solve: Hessian at a degenerate state");
}

void Problem::hessian_apply(const double *v, double *y, double shift, const double *m) {
  ++counters.hvp;
  const size_t n = size();
  const int64_t *rowptr = this->rowptr();
  const int32_t *col = this->col();
  const double *vals = values();
  for (size_t i = 0; i < n; ++i) {
    double s = 0.0;
    if (m) {
      for (int64_t k = rowptr[i]; k < rowptr[i + 1]; ++k)
        s += (vals[k] + shift * m[k]) * v[col[k]];
    } else {
      for (int64_t k = rowptr[i]; k < rowptr[i + 1]; ++k) s += vals[k] * v[col[k]];
    }
    y[i] = s;
  }
}

void Problem::pattern_apply(const double *m, const double *v, double *y) const {
  const size_t n = size();
  const int64_t *rowptr = this->rowptr();
  const int32_t *col = this->col();
  for (size_t i = 0; i < n; ++i) {
    double s = 0.0;
    for (int64_t k = rowptr[i]; k < rowptr[i + 1]; ++k) s += m[k] * v[col[k]];
    y[i] = s;
  }
}

void Problem::accept(double *x) {
  check_status(rn_network_update_reference(net_, x), "rn_network_update_reference");
}

std::vector<double> hessian_metric(const Problem &p, double floor_rel) {
  const size_t n = p.size();
  std::vector<double> d(n, 0.0);
  for (size_t i = 0; i < n; ++i)
    for (int64_t k = p.rowptr()[i]; k < p.rowptr()[i + 1]; ++k)
      if (static_cast<size_t>(p.col()[k]) == i) d[i] = std::fabs(p.values()[k]);
  double dmax = 0.0;
  for (double v : d) dmax = std::max(dmax, v);
  if (!(dmax > 0.0) || !std::isfinite(dmax)) return std::vector<double>(n, 1.0);
  for (double &v : d) v = std::max(v, floor_rel * dmax);
  return d;
}

std::vector<double> diagonal_on_pattern(const Problem &p, const std::vector<double> &d) {
  std::vector<double> m(static_cast<size_t>(p.rowptr()[p.size()]), 0.0);
  for (size_t i = 0; i < p.size(); ++i) {
    bool found = false;
    for (int64_t k = p.rowptr()[i]; k < p.rowptr()[i + 1]; ++k) {
      if (static_cast<size_t>(p.col()[k]) == i) {
        m[k] = d[i];
        found = true;
      }
    }
    if (!found)
      throw Error(RN_ERR_INTERNAL, "rn_solve: Hessian pattern lacks a diagonal entry");
  }
  return m;
}

std::vector<double> shifted_hessian_values(const Problem &p, double shift,
                                           const std::vector<double> &d) {
  std::vector<double> m = diagonal_on_pattern(p, d);
  for (size_t k = 0; k < m.size(); ++k) m[k] = p.values()[k] + shift * m[k];
  return m;
}

} // namespace rodnet
