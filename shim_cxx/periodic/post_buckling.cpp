// post_buckling.cpp - past the first (local) instability of a cell path: the
// supercell the critical wave vector calls for, the pattern state, and the
// continuation of the principal and bifurcated branches in it
// (rn_cell_instability_supercell, rn_cell_pattern_state, rn_cell_post_buckling;
// docs/homogenization.md, "Post-buckling").  Written on the public entry points
// (rn_cell_relax, rn_cell_minimize, rn_cell_bloch_eigen, rn_network_stability);
// no Trilinos here.
#include <cmath>
#include <complex>
#include <cstdlib>
#include <cstring>
#include <new>
#include <vector>

#include "periodic/homogenize.hpp"
#include "rodnet_solve.h"

namespace rodnet {
namespace {

constexpr double kTwoPi = 6.283185307179586;

// The smallest m <= 12 with m xi an integer (to 1e-3); 0 if none.
int period_of(double xi) {
  for (int m = 1; m <= 12; ++m)
    if (std::fabs(m * xi - std::round(m * xi)) < 1e-3) return m;
  return 0;
}

int gcd_int(int a, int b) { return b ? gcd_int(b, a % b) : a; }

int cell_dim(const rn_network *net) {
  int dim = 0;
  rn_network_cell_info(net, &dim, nullptr, nullptr, nullptr);
  return dim;
}

// The cell size of a supercell of copies cells: (measure / copies)^(1/dim).
double cell_size(const rn_network *net, int copies) {
  int dim = 0;
  double measure = 0.0;
  rn_network_cell_info(net, &dim, nullptr, &measure, nullptr);
  return std::pow(measure / copies, 1.0 / dim);
}

// The critical mode of the current state: the lowest Bloch mode at xi = 0 in
// modes (the real part of its fluctuation entries in mode[nfl]), its eigenvalue
// and the largest |entry|.
rn_status critical_mode(rn_network *net, rn_bloch_modes modes, std::vector<double> &mode,
                        double *eigenvalue, double *vmax) {
  size_t nb = 0;
  rn_status st = rn_network_bloch_dofs(net, &nb, nullptr, nullptr);
  if (st) return st;
  int ns = 0;
  rn_network_cell_info(net, nullptr, &ns, nullptr, nullptr);
  const size_t nfl = rn_network_num_dofs(net) - static_cast<size_t>(ns);
  std::vector<double> vec(2 * (nb ? nb : 1));
  const double zero[3] = {0.0, 0.0, 0.0};
  if ((st = rn_cell_bloch_eigen(net, zero, modes, 1, eigenvalue, vec.data()))) return st;
  mode.assign(nfl, 0.0);
  *vmax = 0.0;
  for (size_t i = 0; i < nfl && i < nb; ++i) {
    mode[i] = vec[2 * i];
    *vmax = std::fmax(*vmax, std::fabs(mode[i]));
  }
  if (!(*vmax > 0.0))
    return rn_context_set_error(rn_network_context(net), RN_ERR_SOLVER,
                                "the critical mode has no real part");
  return RN_OK;
}

// x_u <- x_u + scale mode / vmax on the current DOFs (the strain DOFs are last).
rn_status add_mode(rn_network *net, const std::vector<double> &mode, double scale,
                   double vmax, bool update_reference) {
  std::vector<double> x(rn_network_num_dofs(net));
  rn_status st = rn_network_get_dofs(net, x.data());
  if (st) return st;
  for (size_t i = 0; i < mode.size(); ++i) x[i] += scale * mode[i] / vmax;
  if ((st = rn_network_set_dofs(net, x.data()))) return st;
  return update_reference ? rn_network_update_reference(net, x.data()) : RN_OK;
}

// Stress, elastic energy per cell and stability of the current state.
rn_status measure(rn_network *net, int copies, double *stress, double *energy,
                  int *verified, double *lowest) {
  double E[RN_TERM_COUNT];
  std::vector<double> x(rn_network_num_dofs(net));
  rn_status st = rn_network_get_dofs(net, x.data());
  if (!st) st = rn_network_cell_stress(net, x.data(), stress);
  if (!st) st = rn_network_energy_terms(net, x.data(), E);
  if (st) return st;
  *energy = (E[RN_TERM_STRETCH] + E[RN_TERM_BEND] + E[RN_TERM_TWIST]) / copies;
  rn_stability stab;
  if ((st = rn_network_stability(net, &stab))) return st;
  *verified = stab.verified_minimum;
  *lowest = stab.lowest_eigenvalue;
  return RN_OK;
}

// Positions of every rod vertex (3 per vertex, rods in order).
rn_status positions(const rn_network *net, std::vector<double> &xyz) {
  size_t at = 0;
  for (int r = 0; r < rn_network_num_rods(net); ++r) {
    rn_status st = rn_network_rod_vertices(net, r, xyz.data() + at);
    if (st) return st;
    at += 3 * static_cast<size_t>(rn_network_rod_num_vertices(net, r));
  }
  return RN_OK;
}

// Strain of the cell path at parameter t (linear between the recorded steps).
void strain_at(const rn_cell_path_result *p, double t, double *eps) {
  int k = 1;
  while (k < p->done && p->step[k].t < t) ++k;
  const rn_cell_path_step &a = p->step[k - 1], &b = p->step[k];
  double w = b.t > a.t ? (t - a.t) / (b.t - a.t) : 1.0;
  for (int v = 0; v < p->ns; ++v) eps[v] = (1.0 - w) * a.strain[v] + w * b.strain[v];
}

// The shares of the displacement d (3 per rod vertex, rods in order) over the
// supercell's harmonics (rn_cell_post_result).
void harmonics(const rn_network *net, int dim, const rn_cell_post_options &o,
               const std::vector<double> &d, rn_cell_post_result *res) {
  const int *rep = res->rep, nrod = rn_network_num_rods(net);
  const int nh = rep[0] * rep[1] * (dim == 3 ? rep[2] : 1);
  res->nharm = (!o.rod_base || !o.rod_cell || nh > RN_CELL_POST_MAX_HARMONICS) ? 0 : nh;
  if (!res->nharm) return;
  // offsets of every rod's vertices in d; accumulators per base-rod entry
  std::vector<size_t> off(static_cast<size_t>(nrod) + 1, 0);
  for (int r = 0; r < nrod; ++r)
    off[r + 1] = off[r] + 3 * static_cast<size_t>(rn_network_rod_num_vertices(net, r));
  std::vector<std::complex<double>> acc(off[nrod]);
  double total = 0.0;
  for (int h = 0; h < nh; ++h) {
    const int hc[3] = {h % rep[0], (h / rep[0]) % rep[1],
                       dim == 3 ? h / (rep[0] * rep[1]) : 0};
    std::fill(acc.begin(), acc.end(), std::complex<double>(0.0, 0.0));
    for (int r = 0; r < nrod; ++r) {
      const int b = o.rod_base[r];
      if (b < 0 || b >= nrod || off[b + 1] - off[b] != off[r + 1] - off[r]) continue;
      double ph = 0.0;
      for (int m = 0; m < dim; ++m) ph += kTwoPi * hc[m] * o.rod_cell[3 * r + m] / rep[m];
      const std::complex<double> w(std::cos(ph), -std::sin(ph));
      for (size_t k = 0; k < off[r + 1] - off[r]; ++k)
        acc[off[b] + k] += d[off[r] + k] * w;
    }
    double power = 0.0;
    for (int r = 0; r < nrod; ++r)
      if (o.rod_base[r] == r)
        for (size_t k = off[r]; k < off[r + 1]; ++k) power += std::norm(acc[k]);
    for (int m = 0; m < 3; ++m) {
      double xi = m < dim ? static_cast<double>(hc[m]) / rep[m] : 0.0;
      res->harm_xi[h][m] = xi > 0.5 ? xi - 1.0 : xi;
    }
    res->harm[h] = power;
    total += power;
  }
  for (int h = 0; h < nh; ++h) res->harm[h] = total > 0.0 ? res->harm[h] / total : 0.0;
}

// The principal and bifurcated states of the continuation and its scratch.
struct PostRun {
  rn_network *net = nullptr;
  rn_state *prin = nullptr, *bif = nullptr;
  rn_state *before = nullptr; // the principal branch at the last path step before the
                              // critical strain (K_uu positive definite)
  std::vector<double> mode, xp, xb;
  double vmax = 0.0;
  ~PostRun() {
    rn_state_destroy(&prin);
    rn_state_destroy(&bif);
    rn_state_destroy(&before);
  }
};

// The principal branch through the path's steps to the critical strain and the
// critical mode there.
rn_status post_start(const rn_cell_path_result *p, const rn_cell_post_options &o,
                     rn_cell_post_result *res, PostRun &q) {
  rn_network *net = q.net;
  const rn_cell_path_instability &in = p->inst;
  rn_cell_relax_report rep;
  rn_status st;
  for (int k = 1; k <= p->done && p->step[k].t < in.t; ++k)
    if ((st = rn_cell_relax(net, p->step[k].strain, &rep))) return st;
  if ((st = rn_network_state_save(net, &q.before))) return st;
  if ((st = rn_cell_relax(net, in.strain, &rep))) return st;
  size_t npos = 0;
  for (int r = 0; r < rn_network_num_rods(net); ++r)
    npos += 3 * static_cast<size_t>(rn_network_rod_num_vertices(net, r));
  q.xp.assign(npos, 0.0);
  q.xb.assign(npos, 0.0);
  if ((st = critical_mode(net, o.modes, q.mode, &res->mode_eigenvalue, &q.vmax)))
    return st;
  if ((st = rn_network_state_save(net, &q.prin))) return st;
  // perturbation: 1e-3 of the cell size at the largest entry of the mode
  res->perturbation = 1e-3 * cell_size(net, res->copies);
  return RN_OK;
}

// Step s on both branches, each measured, and the amplitude of their difference.
rn_status post_step(rn_cell_post_result *res, PostRun &q, rn_cell_post_step *s) {
  rn_network *net = q.net;
  rn_cell_relax_report rep;
  rn_status st;
  // The first step starts from the principal state before the critical strain, not
  // at it: there K_uu is singular along the critical mode, and the indefinite
  // predictor's step from it (its right-hand side has round-off along that mode)
  // throws the state onto the bifurcated branch.
  if ((st = rn_network_state_restore(net, q.bif ? q.prin : q.before)) ||
      (st = rn_cell_relax(net, s->strain, &rep)))
    return st;
  s->principal_converged = rep.converged;
  rn_state_destroy(&q.prin);
  if ((st = rn_network_state_save(net, &q.prin)) ||
      (st = measure(net, res->copies, s->principal_stress, &s->principal_energy,
                    &s->principal_verified, &s->principal_lowest)) ||
      (st = positions(net, q.xp)))
    return st;
  if (q.bif)
    st = rn_network_state_restore(net, q.bif);
  else
    st = add_mode(net, q.mode, res->perturbation, q.vmax, true);
  if (st || (st = rn_cell_minimize(net, s->strain, &rep))) return st;
  s->converged = rep.converged;
  s->iterations = rep.iterations;
  rn_state_destroy(&q.bif);
  if ((st = rn_network_state_save(net, &q.bif)) ||
      (st = measure(net, res->copies, s->stress, &s->energy, &s->verified, &s->lowest)) ||
      (st = positions(net, q.xb)))
    return st;
  s->amplitude = 0.0;
  for (size_t i = 0; i < q.xb.size(); ++i) {
    q.xb[i] -= q.xp[i];
    s->amplitude = std::fmax(s->amplitude, std::fabs(q.xb[i]));
  }
  return RN_OK;
}

rn_status check_args(rn_network *net, const rn_cell_path_result *path,
                     const rn_cell_post_options *opt, rn_cell_post_result *res,
                     const char *where) {
  rn_context *ctx = rn_network_context(net);
  if (!path || !opt || !res)
    return rn_context_set_error(ctx, RN_ERR_ARG, "%s: a NULL argument", where);
  const int dim = cell_dim(net);
  if (dim != 2 && dim != 3)
    return rn_context_set_error(ctx, RN_ERR_ARG, "%s: the network is not periodic",
                                where);
  if (!path->inst.found || path->inst.kind_macroscopic || !path->step || path->done < 1)
    return rn_context_set_error(ctx, RN_ERR_ARG, "%s: the path has no local instability",
                                where);
  if (opt->steps < 1)
    return rn_context_set_error(ctx, RN_ERR_ARG, "%s: steps %d: needs at least 1", where,
                                opt->steps);
  for (int i = 0; i < 3; ++i)
    if (opt->rep[i] < 1 || opt->rep[i] > 12 || (i >= dim && opt->rep[i] != 1))
      return rn_context_set_error(ctx, RN_ERR_ARG,
                                  "%s: rep[%d] = %d: expected 1 to 12 (1 past the "
                                  "cell's dimension)",
                                  where, i, opt->rep[i]);
  int ns = 0;
  rn_network_cell_info(net, nullptr, &ns, nullptr, nullptr);
  if (ns != path->ns)
    return rn_context_set_error(ctx, RN_ERR_ARG,
                                "%s: the network has %d strain DOFs, the path %d", where,
                                ns, path->ns);
  return RN_OK;
}

rn_status run_post(rn_network *net, const rn_cell_path_result *p,
                   const rn_cell_post_options &o, rn_cell_post_result *res) {
  PostRun q;
  q.net = net;
  rn_status st = post_start(p, o, res, q);
  if (st) return st;
  const rn_cell_path_instability &in = p->inst;
  const double t_end = p->step[p->done].t;
  res->step = static_cast<rn_cell_post_step *>(
      std::calloc(static_cast<size_t>(o.steps), sizeof(rn_cell_post_step)));
  if (!res->step) throw std::bad_alloc();
  res->steps = o.steps;
  for (int j = 1; j <= o.steps; ++j) {
    rn_cell_post_step *s = &res->step[j - 1];
    s->t = in.t + (t_end - in.t) * j / o.steps;
    strain_at(p, s->t, s->strain);
    if ((st = post_step(res, q, s))) return st;
    res->done = j;
    if (o.progress) o.progress(o.user, res);
    if (!s->converged) break;
  }
  harmonics(net, cell_dim(net), o, q.xb, res);
  return RN_OK;
}

} // namespace
} // namespace rodnet

extern "C" int rn_cell_instability_supercell(const rn_cell_path_instability *in, int dim,
                                             int rep[3]) {
  if (!in || !rep || (dim != 2 && dim != 3)) return 0;
  rep[0] = rep[1] = rep[2] = 1;
  if (!in->found || in->kind_macroscopic) return 0;
  for (int i = 0; i < dim; ++i) {
    if (!(rep[i] = rodnet::period_of(in->xi[i]))) return 0;
    for (int e = 0; e < in->nequiv && e < 12; ++e) {
      int m = rodnet::period_of(in->xi_equiv[e][i]);
      if (!m) return 0;
      rep[i] = rep[i] / rodnet::gcd_int(rep[i], m) * m;
      if (rep[i] > 12) return 0;
    }
  }
  return 1;
}

extern "C" rn_status rn_cell_pattern_state(rn_network *net,
                                           const rn_cell_path_instability *in, int copies,
                                           rn_bloch_modes modes,
                                           double amplitude_fraction, double *eigenvalue,
                                           double *amplitude, int *converged) {
  if (!net) return RN_ERR_ARG;
  rn_context *ctx = rn_network_context(net);
  const char *where = "rn_cell_pattern_state";
  if (!in || !eigenvalue || !amplitude || !converged)
    return rn_context_set_error(ctx, RN_ERR_ARG, "%s: a NULL argument", where);
  if (copies < 1 || !(amplitude_fraction > 0.0) || !std::isfinite(amplitude_fraction))
    return rn_context_set_error(ctx, RN_ERR_ARG,
                                "%s: copies %d, amplitude fraction %g: expected >= 1 and "
                                "a positive number",
                                where, copies, amplitude_fraction);
  const int dim = rodnet::cell_dim(net);
  if (dim != 2 && dim != 3)
    return rn_context_set_error(ctx, RN_ERR_ARG, "%s: the network is not periodic",
                                where);
  rn_status ran = RN_OK;
  rn_status st = rodnet::guarded(net, where, [&] {
    int ns = 0;
    rn_network_cell_info(net, nullptr, &ns, nullptr, nullptr);
    rn_cell_relax_report rep;
    double eps[6];
    for (int k = 1; k <= 10; ++k) {
      for (int v = 0; v < ns; ++v) eps[v] = 0.1 * k * in->strain[v];
      if ((ran = rn_cell_relax(net, eps, &rep))) return;
    }
    *converged = rep.converged;
    std::vector<double> mode;
    double vmax = 0.0;
    if ((ran = rodnet::critical_mode(net, modes, mode, eigenvalue, &vmax))) return;
    *amplitude = amplitude_fraction * rodnet::cell_size(net, copies);
    ran = rodnet::add_mode(net, mode, *amplitude, vmax, false);
  });
  return st ? st : ran;
}

extern "C" void rn_cell_post_options_default(rn_cell_post_options *opt) {
  if (!opt) return;
  *opt = rn_cell_post_options{};
  opt->steps = 4;
  opt->modes = RN_BLOCH_ALL;
  opt->rep[0] = opt->rep[1] = opt->rep[2] = 1;
}

extern "C" void rn_cell_post_result_free(rn_cell_post_result *res) {
  if (!res) return;
  std::free(res->step);
  *res = rn_cell_post_result{};
}

extern "C" rn_status rn_cell_post_buckling(rn_network *net,
                                           const rn_cell_path_result *path,
                                           const rn_cell_post_options *opt,
                                           rn_cell_post_result *res) {
  if (!net) return RN_ERR_ARG;
  const char *where = "rn_cell_post_buckling";
  if (res) *res = rn_cell_post_result{};
  rn_status st = rodnet::check_args(net, path, opt, res, where);
  if (st) return st;
  res->copies = 1;
  for (int i = 0; i < 3; ++i) res->copies *= (res->rep[i] = opt->rep[i]);
  rn_status ran = RN_OK;
  st = rodnet::guarded(net, where, [&] { ran = rodnet::run_post(net, path, *opt, res); });
  return st ? st : ran;
}
