// stress_path.cpp - macroscopic strain, stress, mixed and waypoint paths of a
// periodic cell with the Bloch-Floquet first instability and, under stress
// control, the limit point of the stress (rn_cell_path_run; docs/homogenization.md,
// "Strain paths and stability", "Stress and mixed paths").  Built on the public
// cell entries (rn_cell_relax, rn_homogenize, rn_cell_bloch); no Trilinos here.
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <new>
#include <vector>

#include "base/shim_error.hpp"
#include "periodic/homogenize.hpp"
#include "periodic/cell_part.hpp"
#include "rodnet_solve.h"

namespace rodnet {
namespace {

// The path being followed: its segments (with their start values), options and
// result, and the scales of the instability tests (from the rest state).
struct Path {
  rn_network *net;
  rn_cell_path_options opt;
  rn_cell_path_result *r;
  double local_scale = 0.0, acoustic_scale = 0.0;
};

bool local_unstable(const rn_bloch_result &b, const Path &p) {
  return b.local_min < -1e-9 * p.local_scale;
}
bool macro_unstable(const rn_bloch_result &b, const Path &p) {
  return b.acoustic_valid == 1 && b.acoustic_min < -1e-9 * p.acoustic_scale;
}
bool unstable(const rn_bloch_result &b, const Path &p) {
  return local_unstable(b, p) || macro_unstable(b, p) || b.acoustic_valid == 0;
}

// The effective tangent C (rn_homogenize) at the current state restricted to
// the components f[nf]: Cff (nf x nf).
rn_status tangent_ff(rn_network *net, int nf, const int *f, double *C, double *Cff) {
  rn_homogenization h;
  rn_status st = rn_homogenize(net, &h);
  if (st) return st;
  std::memcpy(C, h.C, sizeof(h.C));
  for (int i = 0; i < nf; ++i)
    for (int j = 0; j < nf; ++j) Cff[i * nf + j] = h.C[f[i] * h.nstrain + f[j]];
  return RN_OK;
}

// Lowest eigenvalue of Cff (nf x nf) and its eigenvector spread onto the strain
// components (mode[ns], if mode).
double lowest_mode(int ns, int nf, const int *f, const double *Cff, double *mode) {
  double w[6], v[6];
  sym_eigen(nf, Cff, w, v, "rn_cell_path_run");
  if (mode) {
    std::memset(mode, 0, (size_t)ns * sizeof(double));
    for (int i = 0; i < nf; ++i) mode[f[i]] = v[i];
  }
  return w[0];
}

// The stress-controlled components of segment g (f[nf]); returns nf.
int stress_components(const rn_cell_path_segment &g, int ns, int *f) {
  int nf = 0;
  for (int v = 0; v < ns; ++v)
    if (g.stress[v]) f[nf++] = v;
  return nf;
}

// The Newton (and predictor) correction of the stress-controlled strain
// components f[nf] at a state of strain eps and stress sig with the tangent C:
// C_ff d = (sigma_f* - sigma_f) - C_fp (e_p* - e_p).  false if C_ff is singular.
bool mixed_step(int ns, int nf, const int *f, const int *stress, const double *val,
                const double *eps, const double *sig, const double *C, double *d) {
  double Cff[36] = {0}, Sff[36], rhs[6];
  for (int i = 0; i < nf; ++i) {
    for (int j = 0; j < nf; ++j) Cff[i * nf + j] = C[f[i] * ns + f[j]];
    rhs[i] = val[f[i]] - sig[f[i]];
    for (int v = 0; v < ns; ++v)
      if (!stress[v]) rhs[i] -= C[f[i] * ns + v] * (val[v] - eps[v]);
  }
  if (!rn_homogenization_invert(nf, Cff, Sff)) return false;
  for (int i = 0; i < nf; ++i) {
    d[i] = 0.0;
    for (int j = 0; j < nf; ++j) d[i] += Sff[i * nf + j] * rhs[j];
  }
  return true;
}

// The state of the mixed solve of one step: the stress-controlled components
// f[nf], the controlled values val, the current strain, stress and tangent.
struct Mixed {
  int ns, nf, f[6];
  const int *stress;
  const double *val;
  double eps[6], sig[6], C[36] = {0}, Cff[36] = {0}, d[6];
  double pred = 0.0, e_pred[6]; // the predicted step and strain
};

// The predictor: the stress-controlled strain corrected with the tangent at the
// current (converged) state, the strain-controlled ones set to their values;
// m.pred the largest change.
void mixed_predict(rn_network *net, Mixed &m) {
  if (tangent_ff(net, m.nf, m.f, m.C, m.Cff) == RN_OK &&
      mixed_step(m.ns, m.nf, m.f, m.stress, m.val, m.eps, m.sig, m.C, m.d))
    for (int i = 0; i < m.nf; ++i) {
      m.eps[m.f[i]] += m.d[i];
      m.pred = std::fmax(m.pred, std::fabs(m.d[i]));
    }
  for (int v = 0; v < m.ns; ++v) {
    if (!m.stress[v]) {
      m.pred = std::fmax(m.pred, std::fabs(m.val[v] - m.eps[v]));
      m.eps[v] = m.val[v];
    }
  }
  std::memcpy(m.e_pred, m.eps, sizeof(m.eps));
}

// 1: the mixed solve converged at the relaxed state (m.eps, m.sig, m.C): the
// stress residual, or the Newton correction of the strain (m.d, computed here)
// below what the relaxed fluctuations resolve; 0: take the correction; -1: no
// equilibrium nearby (C_ff singular or a correction above 0.1).
int mixed_test(const Mixed &m, double tangent_scale, double *d) {
  double rn = 0.0, scale = 0.0, step = 0.0, emax = 0.0, off = 0.0;
  for (int v = 0; v < m.ns; ++v) {
    scale = std::fmax(scale, std::fabs(m.sig[v]));
    emax = std::fmax(emax, std::fabs(m.eps[v]));
    if (!m.stress[v]) off = std::fmax(off, std::fabs(m.eps[v] - m.val[v]));
  }
  for (int i = 0; i < m.nf; ++i) {
    rn = std::fmax(rn, std::fabs(m.sig[m.f[i]] - m.val[m.f[i]]));
    scale = std::fmax(scale, std::fabs(m.val[m.f[i]]));
  }
  bool invertible = mixed_step(m.ns, m.nf, m.f, m.stress, m.val, m.eps, m.sig, m.C, d);
  for (int i = 0; i < m.nf && invertible; ++i) step = std::fmax(step, std::fabs(d[i]));
  if (off == 0.0 && (rn <= 1e-10 * scale + (1e-12 * emax + 1e-20) * tangent_scale ||
                     (invertible && step <= 1e-8 * emax + 1e-12)))
    return 1;
  return (!invertible || step > 0.1) ? -1 : 0;
}

// The relaxed trial is good: it becomes the last good state (ok, eps_ok), its
// strain and stress in m.
rn_status accept(rn_network *net, rn_state **ok, Mixed &m, double *eps_ok) {
  rn_state_destroy(ok);
  rn_status st = rn_network_state_save(net, ok);
  if (!st) st = cell_state(net, m.eps, m.sig, nullptr);
  if (!st) std::memcpy(eps_ok, m.eps, sizeof(m.eps));
  return st;
}

// Mixed control at the current segment: the strain-controlled components held
// at val, the stress-controlled ones free with the homogenised stress val.
// Newton on those strain components with the effective tangent C_ff
// (rn_homogenize at each iterate), the fluctuations relaxed by rn_cell_relax at
// each; the first correction (the predictor) from the tangent at the current
// (converged) state.  Where a trial fails (the fluctuations do not converge or
// are unstable) the correction is halved from the last good state (up to 12
// times).  s->converged 0 if it fails (no equilibrium nearby: past a limit
// point, or unstable cell-periodic fluctuations: s->kuu_indefinite).
rn_status mixed_relax(rn_network *net, const Path &p, const int *stress,
                      const double *val, rn_cell_path_step *s) {
  Mixed m;
  m.ns = p.r->ns;
  m.stress = stress;
  m.val = val;
  m.nf = 0;
  for (int v = 0; v < m.ns; ++v)
    if (stress[v]) m.f[m.nf++] = v;
  int halvings = 0, tangent_ok = 1, seen_indefinite = 0;
  double eps_ok[6];
  rn_status st;
  rn_cell_relax_report rep = {};
  rn_state *ok = nullptr;
  s->converged = 0;
  s->newton = 0;
  if ((st = cell_state(net, m.eps, m.sig, nullptr))) return st;
  if ((st = rn_network_state_save(net, &ok))) return st;
  std::memcpy(eps_ok, m.eps, sizeof(m.eps));
  mixed_predict(net, m);
  for (s->outer = 1; s->outer <= 40; ++s->outer) {
    if ((st = rn_cell_relax_method(net, m.eps, p.opt.bloch_method, &rep))) break;
    s->newton += rep.iterations;
    tangent_ok = rep.converged && !rep.indefinite;
    seen_indefinite |= rep.converged && rep.indefinite;
    if (tangent_ok) {
      st = tangent_ff(net, m.nf, m.f, m.C, m.Cff);
      if (st && st != RN_ERR_SOLVER) break;
      tangent_ok = st == RN_OK;
      st = RN_OK;
    }
    if (!tangent_ok) { // a failed trial: halve it from the last good state
      if (++halvings > 12) break;
      if ((st = rn_network_state_restore(net, ok))) break;
      for (int v = 0; v < m.ns; ++v) m.eps[v] = eps_ok[v] + 0.5 * (m.eps[v] - eps_ok[v]);
      continue;
    }
    halvings = 0;
    if ((st = accept(net, &ok, m, eps_ok))) break;
    int test = mixed_test(m, p.r->tangent_scale, m.d);
    if (test > 0) {
      s->converged = 1;
      s->tangent_min = lowest_mode(m.ns, m.nf, m.f, m.Cff, nullptr) / p.r->tangent_scale;
      // corrected by more than the predicted step: it jumped to another branch
      // (snapped through a limit point between the steps)
      for (int i = 0; i < m.nf; ++i)
        if (std::fabs(m.eps[m.f[i]] - m.e_pred[m.f[i]]) > std::fmax(2.0 * m.pred, 1e-12))
          s->jumped = 1;
      break;
    }
    if (test < 0) break; // no equilibrium nearby
    for (int i = 0; i < m.nf; ++i) m.eps[m.f[i]] += m.d[i];
    for (int v = 0; v < m.ns; ++v)
      if (!stress[v]) m.eps[v] = val[v];
  }
  // failed next to unstable cell-periodic fluctuations: their instability
  if (!s->converged)
    s->kuu_indefinite = seen_indefinite || (rep.converged && !tangent_ok);
  rn_state_destroy(&ok);
  return st;
}

// Relax the cell at parameter u of segment j from the current state and record
// step s (strain, stress, energy).
rn_status relax_at(rn_network *net, const Path &p, int j, double u,
                   rn_cell_path_step *s) {
  const rn_cell_path_segment &g = p.r->seg[j];
  double val[6] = {0};
  int f[6];
  rn_status st;
  std::memset(s, 0, sizeof(*s));
  s->t = j + u;
  s->seg = j;
  s->tangent_min = NAN;
  for (int v = 0; v < p.r->ns; ++v) val[v] = g.start[v] + u * (g.target[v] - g.start[v]);
  if (stress_components(g, p.r->ns, f)) {
    if ((st = mixed_relax(net, p, g.stress, val, s))) return st;
  } else {
    rn_cell_relax_report rep;
    if ((st = rn_cell_relax_method(net, val, p.opt.bloch_method, &rep))) return st;
    s->newton = rep.iterations;
    s->converged = rep.converged;
  }
  return cell_state(net, s->strain, s->stress, &s->energy);
}

// The Bloch test at the current state: the full search (grid, refinement from the
// grid minima and from hint, the acoustic test), or with tracked set only what the
// secant of locate() follows: the acoustic test (macro) or the refinement from hint.
rn_status bloch_at(rn_network *net, const Path &p, const double *hint, rn_bloch_result *b,
                   bool tracked = false, bool macro = false) {
  rn_bloch_options o;
  rn_bloch_options_default(&o);
  o.grid = p.opt.grid;
  o.modes = p.opt.modes;
  o.xi_hint = tracked && macro ? nullptr : hint;
  o.method = p.opt.bloch_method;
  o.no_scan = tracked;
  o.no_acoustic = tracked && !macro;
  return rn_cell_bloch(net, &o, b);
}

int multiplicity(const rn_bloch_result &b) {
  int m = 1;
  double spread = std::fabs(b.eig[b.neig - 1] - b.eig[0]);
  for (int i = 1; i < b.neig; ++i)
    if (b.eig[i] - b.eig[0] <= 1e-3 * spread) ++m;
  return m;
}

// A limit point of the stress: under stress control, no equilibrium (the mixed
// solve failed) or the tangent on the stress-controlled components is not
// positive definite.
bool limit_passed(const rn_cell_path_step &s, int nstress) {
  return nstress && !s.kuu_indefinite &&
         (!s.converged || s.jumped || !(s.tangent_min > 1e-9));
}

// The bracket of the first instability in segment j: from the converged state
// lo (owned) at u_lo (Bloch result blo) to u_hi (result bhi); why: 1 the state
// at u_hi is past a limit point of the stress, 2 its cell-periodic fluctuations
// are unstable in modes the Bloch test does not examine, 0 the Bloch test failed
// there.
struct Bracket {
  int j;
  rn_state *lo;
  double u_lo, u_hi;
  rn_bloch_result blo, bhi;
  int why;
};

// Bisection of the bracket to 0.1 % of the parameter (at most 60 halvings); adds
// its halvings to *it.
rn_status bisect(rn_network *net, const Path &p, Bracket &b, int *it) {
  rn_status st;
  rn_cell_path_step s;
  int f[6], nstress = stress_components(p.r->seg[b.j], p.r->ns, f);
  for (int k = 0; b.u_hi - b.u_lo > 1e-3 * b.u_hi && k < 60; ++k) {
    double mid = 0.5 * (b.u_lo + b.u_hi);
    rn_bloch_result r;
    ++*it;
    if ((st = rn_network_state_restore(net, b.lo)) ||
        (st = relax_at(net, p, b.j, mid, &s)))
      return st;
    if (limit_passed(s, nstress)) {
      b.u_hi = mid;
      b.why = 1;
      continue;
    }
    if (!s.converged && !s.kuu_indefinite) break;
    if ((st = bloch_at(net, p, b.bhi.xi, &r))) return st;
    if (s.kuu_indefinite && !unstable(r, p)) { // outside the modes examined
      b.u_hi = mid;
      b.why = 2;
    } else if (unstable(r, p)) {
      b.u_hi = mid;
      b.bhi = r;
      b.why = 0;
    } else {
      rn_state_destroy(&b.lo);
      if ((st = rn_network_state_save(net, &b.lo))) return st;
      b.u_lo = mid;
      b.blo = r;
    }
  }
  return RN_OK;
}

// The quantity whose zero is the instability of the kind being located: the lowest
// eigenvalue of the acoustic tensor (macro) or of the Bloch Hessian near the tracked
// wave vector.
double critical_value(const rn_bloch_result &r, bool macro) {
  return macro ? r.acoustic_min : r.local_min;
}

// The critical parameter of a Bloch instability in the bracket by the Illinois
// (modified regula falsi) secant on critical_value(u), each value from the Bloch
// test tracked from the bracket's unstable end (no grid scan): superlinear, to
// 1e-7 of the parameter (at most 40 iterations).  *uc the estimate; *ok false
// where the secant does not apply or finish (no sign change, a trial state past a
// limit point, unconverged, or unstable outside the modes examined, the iteration
// limit: the bracket is then left to bisect()).  The ends it moves are judged by
// the tracked test only: an unstable end is unstable, a stable end need not be.
rn_status secant(rn_network *net, const Path &p, Bracket &b, int *it, double *uc,
                 bool *ok) {
  rn_cell_path_step s;
  int f[6], nstress = stress_components(p.r->seg[b.j], p.r->ns, f);
  const bool macro = macro_unstable(b.bhi, p);
  double flo = critical_value(b.blo, macro), fhi = critical_value(b.bhi, macro);
  *ok = false;
  if (b.why != 0 || !(flo > 0.0) || !(fhi < 0.0)) return RN_OK;
  // the values measured at the ends (flo, fhi are Illinois' halved ones)
  double mlo = flo, mhi = fhi;
  int side = 0;
  double prev = NAN;
  for (int k = 0; k < 40; ++k) {
    const double w = b.u_hi - b.u_lo, tol = 1e-7 * b.u_hi;
    double u = b.u_lo + w * flo / (flo - fhi);
    if (!(u > b.u_lo && u < b.u_hi)) u = 0.5 * (b.u_lo + b.u_hi);
    if (w <= tol || std::fabs(u - prev) <= tol) {
      *uc = u;
      *ok = true;
      return RN_OK;
    }
    prev = u;
    ++*it;
    rn_status st;
    rn_bloch_result r;
    if ((st = rn_network_state_restore(net, b.lo)) || (st = relax_at(net, p, b.j, u, &s)))
      return st;
    double fu = NAN;
    if (!limit_passed(s, nstress) && s.converged && !s.kuu_indefinite) {
      if ((st = bloch_at(net, p, b.bhi.xi, &r, true, macro))) return st;
      fu = critical_value(r, macro);
    }
    const bool lost = !std::isfinite(fu); // no value at the trial
    // A trial this close to the critical point left the branch: the Jacobian of the
    // relaxation is singular there, and Newton, started a parameter step of at most
    // 1e-6 from the stable end, converged elsewhere (an unconverged or indefinite
    // relaxation, or a value far outside the ends' on a branch along which it is
    // smooth: a distributed cell whose partition breaks the supercell's symmetry
    // at the level of the linear solves; the regular 20 x 20 honeycomb on 2 ranks).
    // The regula falsi of the measured ends is then the estimate (within the
    // bracket's width).
    const double lin = mlo + (mhi - mlo) * (u - b.u_lo) / w;
    if (w <= 1e-6 * b.u_hi &&
        (lost || std::fabs(fu - lin) > std::max(std::fabs(mlo), std::fabs(mhi)))) {
      *uc = b.u_lo + w * mlo / (mlo - mhi);
      *ok = true;
      return RN_OK;
    }
    if (lost) return RN_OK;
    if (fu < 0.0) { // the unstable side; Illinois: halve the other end's value
      b.u_hi = u;
      fhi = mhi = fu;
      if (side < 0) flo *= 0.5;
      side = -1;
    } else {
      rn_state_destroy(&b.lo);
      if ((st = rn_network_state_save(net, &b.lo))) return st;
      b.u_lo = u;
      flo = mlo = fu;
      if (side > 0) fhi *= 0.5;
      side = 1;
    }
  }
  return RN_OK;
}

// A limit point of the stress at the last equilibrium of the bracket (the state
// lo): its softest strain mode; not found if C_ff is not nearly singular there
// (the mixed solve merely failed: p.r->stopped says so).
rn_status record_stress_limit(rn_network *net, const Path &p, const Bracket &b) {
  rn_cell_path_instability *in = &p.r->inst;
  int ns = p.r->ns, f[6], nf = stress_components(p.r->seg[b.j], ns, f);
  double C[36], Cff[36];
  in->kind_macroscopic = 1;
  std::memset(in->xi, 0, sizeof(in->xi));
  in->multiplicity = 1;
  in->neig = 0;
  rn_status st = rn_network_state_restore(net, b.lo);
  if (st) return st;
  double lo_min = NAN, rest_min = NAN;
  if (tangent_ff(net, nf, f, C, Cff) == RN_OK)
    lo_min = lowest_mode(ns, nf, f, Cff, in->mode);
  for (int a = 0; a < nf; ++a)
    for (int c = 0; c < nf; ++c) Cff[a * nf + c] = p.r->c_rest[f[a] * ns + f[c]];
  rest_min = lowest_mode(ns, nf, f, Cff, nullptr);
  // a limit point: C_ff nearly singular at the last equilibrium (at 0.1 % of
  // the parameter from a fold its lowest eigenvalue is about 3 % of the rest
  // value); else the mixed solve merely failed
  if (!(lo_min < 0.1 * rest_min)) {
    in->found = 0;
    p.r->stopped = "the mixed solve did not converge or jumped, though the tangent on "
                   "the stress-controlled components stays positive definite (not a "
                   "limit point; try more --steps)";
  }
  return RN_OK;
}

// A local or macroscopic instability from the Bloch results across the bracket;
// returns the critical parameter (a secant estimate inside the bracket).
double record_bloch(const Path &p, const Bracket &b, double uc_secant) {
  rn_cell_path_instability *in = &p.r->inst;
  const rn_bloch_result &rlo = b.blo, &rhi = b.bhi;
  double uc = b.u_hi;
  in->kind_macroscopic = macro_unstable(rhi, p);
  double flo = critical_value(rlo, in->kind_macroscopic);
  double fhi = critical_value(rhi, in->kind_macroscopic);
  if (flo > 0.0 && fhi < 0.0) uc = b.u_lo + (b.u_hi - b.u_lo) * flo / (flo - fhi);
  if (std::isfinite(uc_secant)) uc = uc_secant;
  if (in->kind_macroscopic) {
    std::memset(in->xi, 0, sizeof(in->xi));
    in->multiplicity = 1;
    std::memcpy(in->direction, rhi.direction, sizeof(in->direction));
    std::memcpy(in->amplitude, rhi.amplitude, sizeof(in->amplitude));
  } else {
    std::memcpy(in->xi, rhi.xi, sizeof(in->xi));
    in->nequiv = rhi.nequiv;
    std::memcpy(in->xi_equiv, rhi.xi_equiv, sizeof(in->xi_equiv));
    in->multiplicity = multiplicity(rhi);
  }
  in->neig = rhi.neig;
  std::memcpy(in->eig, rhi.eig, sizeof(in->eig));
  return uc;
}

// The secant of a Bloch instability, then the full Bloch test at both ends of the
// final bracket: at the stable end it must find no other unstable wave vector (else
// another mode went unstable earlier elsewhere in the zone: the secant again, on
// that mode, from the bracket's start to there, at most 4 rounds); at the unstable
// end it gives the wave vector, its equivalents and the eigenvalues recorded.  *uc
// the secant's estimate, or NaN where bisect() is to finish the job: then the
// bracket runs from its start (the last state the full test found stable) to the
// nearest state found unstable.
rn_status secant_then_check(rn_network *net, const Path &p, Bracket &b, int *it,
                            double *uc) {
  rn_state *start = nullptr;
  rn_cell_path_step s;
  rn_bloch_result lo_full, hi_full;
  const double u0 = b.u_lo;
  const rn_bloch_result b0lo = b.blo;
  *uc = NAN;
  rn_status st = rn_network_state_restore(net, b.lo);
  if (!st) st = rn_network_state_save(net, &start); // the bracket's first state
  // back to the start, unstable at u_hi (result hi)
  auto restart = [&](double u_hi, const rn_bloch_result &hi) -> rn_status {
    rn_state_destroy(&b.lo);
    b.u_lo = u0;
    b.blo = b0lo;
    b.u_hi = u_hi;
    b.bhi = hi;
    rn_status rs = rn_network_state_restore(net, start);
    return rs ? rs : rn_network_state_save(net, &b.lo);
  };
  for (int round = 0; !st && round < 4; ++round) {
    bool ok = false;
    if ((st = secant(net, p, b, it, uc, &ok))) break;
    if (!ok) { // unfinished: the stable end is not verified
      *uc = NAN;
      if (b.u_lo != u0) st = restart(b.u_hi, b.bhi);
      break;
    }
    // the stable end: unstable nowhere in the zone
    if ((st = rn_network_state_restore(net, b.lo)) ||
        (st = bloch_at(net, p, b.bhi.xi, &lo_full)))
      break;
    if (unstable(lo_full, p)) { // another mode first: the secant on it
      *uc = NAN;
      if ((st = restart(b.u_lo, lo_full))) break;
      continue;
    }
    b.blo = lo_full;
    // the unstable end: the full test there for the record
    if (!(st = relax_at(net, p, b.j, b.u_hi, &s)) &&
        !(st = bloch_at(net, p, b.bhi.xi, &hi_full)) && unstable(hi_full, p))
      b.bhi = hi_full;
    rn_state_destroy(&start);
    return st;
  }
  *uc = NAN;
  rn_state_destroy(&start);
  return st;
}

// Locate the first instability in the bracket b (its state lo owned here) by the
// secant (Bloch instabilities) or bisection, then record it with the state at the
// critical parameter.
rn_status locate(rn_network *net, const Path &p, Bracket b) {
  rn_cell_path_instability *in = &p.r->inst;
  rn_cell_path_step s;
  int it = 0;
  double uc_secant = NAN;
  rn_status st = secant_then_check(net, p, b, &it, &uc_secant);
  if (!st && !std::isfinite(uc_secant)) st = bisect(net, p, b, &it);
  if (!st) {
    in->found = 1;
    in->bisections = it;
    in->stress_limit = b.why == 1;
    in->cell_periodic = b.why == 2;
    double uc = b.u_hi;
    if (b.why == 2) { // K_uu indefinite in modes the Bloch test does not examine
      uc = b.u_lo;
      in->kind_macroscopic = 0;
      std::memset(in->xi, 0, sizeof(in->xi));
      in->multiplicity = 1;
      in->neig = 0;
    } else if (b.why == 1) { // the last equilibrium before the limit
      uc = b.u_lo;
      st = record_stress_limit(net, p, b);
    } else
      uc = record_bloch(p, b, uc_secant);
    if (!st && in->found) {
      in->t = b.j + uc;
      if (!(st = rn_network_state_restore(net, b.lo)) &&
          !(st = relax_at(net, p, b.j, uc, &s)) && !s.converged) {
        // no equilibrium found at the critical parameter itself (a singular
        // Jacobian: Newton from the stable end did not converge there): the state of
        // the stable end, within the location's tolerance of it
        if (!(st = rn_network_state_restore(net, b.lo)))
          st = cell_state(net, s.strain, s.stress, &s.energy);
      }
      if (!st) {
        std::memcpy(in->strain, s.strain, sizeof(in->strain));
        std::memcpy(in->stress, s.stress, sizeof(in->stress));
      }
    }
  }
  rn_state_destroy(&b.lo);
  return st;
}

// The rest state: the tangent's scale (the largest eigenvalue of C at rest),
// step 0 (relaxed at zero strain) and its Bloch test (the scales of the
// instability tests; an instability at rest is reported there).
rn_status start(rn_network *net, Path &p, rn_bloch_result *b) {
  rn_cell_path_result *r = p.r;
  int all[6];
  double C[36], Cee[36], w[6], v[6];
  rn_status st;
  for (int k = 0; k < r->ns; ++k) all[k] = k;
  if ((st = tangent_ff(net, r->ns, all, C, Cee))) return st;
  sym_eigen(r->ns, Cee, w, v, "rn_cell_path_run");
  r->tangent_scale = std::fabs(w[r->ns - 1]) > 0.0 ? std::fabs(w[r->ns - 1]) : 1.0;
  std::memcpy(r->c_rest, C, sizeof(r->c_rest));
  rn_cell_path_step *s0 = &r->step[0];
  rn_cell_relax_report rep;
  double zero[6] = {0};
  if ((st = rn_cell_relax(net, zero, &rep))) return st;
  std::memset(s0, 0, sizeof(*s0));
  s0->newton = rep.iterations;
  s0->converged = rep.converged;
  s0->tangent_min = NAN;
  if ((st = cell_state(net, s0->strain, s0->stress, &s0->energy))) return st;
  if ((st = bloch_at(net, p, nullptr, b))) return st;
  p.local_scale = b->local_scale;
  p.acoustic_scale = b->acoustic_scale;
  s0->local_min = b->local_min;
  s0->acoustic_min = b->acoustic_min;
  s0->stable = !unstable(*b, p);
  r->done = 0;
  if (!s0->stable) { // unstable at rest: report it there
    r->inst.found = 1;
    r->inst.kind_macroscopic = macro_unstable(*b, p);
    std::memcpy(r->inst.xi, b->xi, sizeof(b->xi));
    r->inst.nequiv = b->nequiv;
    std::memcpy(r->inst.xi_equiv, b->xi_equiv, sizeof(b->xi_equiv));
    r->inst.multiplicity = multiplicity(*b);
    std::memcpy(r->inst.stress, s0->stress, sizeof(r->inst.stress));
  }
  return RN_OK;
}

// Step s at parameter u of segment j from the previous state prev (u0); under
// stress control a step that fails or jumps is taken again in 8 substeps from
// prev: a strongly nonlinear step, or the first sign of a limit point.
rn_status take_step(rn_network *net, const Path &p, int j, double u0, double u,
                    rn_state *prev, rn_cell_path_step *s) {
  int f[6], nstress = stress_components(p.r->seg[j], p.r->ns, f);
  rn_status st = relax_at(net, p, j, u, s);
  if (st || !nstress || !(s->jumped || !s->converged)) return st;
  if ((st = rn_network_state_restore(net, prev))) return st;
  for (int q = 1; q <= 8; ++q) {
    if ((st = relax_at(net, p, j, q == 8 ? u : u0 + (u - u0) * q / 8, s))) return st;
    if (!s->converged || s->jumped) break;
  }
  return RN_OK;
}

// The segments and the step records of r for the path seg[nseg].
rn_status allocate(rn_context *ctx, int nseg, const rn_cell_path_segment *seg,
                   rn_cell_path_result *r) {
  r->steps = 0;
  for (int j = 0; j < nseg; ++j) {
    if (seg[j].steps < 1)
      return rn_context_set_error(ctx, RN_ERR_ARG,
                                  "rn_cell_path_run: segment %d has no step", j);
    r->steps += seg[j].steps;
  }
  r->seg = static_cast<rn_cell_path_segment *>(calloc((size_t)nseg, sizeof(*r->seg)));
  r->step =
      static_cast<rn_cell_path_step *>(calloc((size_t)r->steps + 1, sizeof(*r->step)));
  if (!r->seg || !r->step)
    return rn_context_set_error(ctx, RN_ERR_ALLOC, "out of memory");
  std::memcpy(r->seg, seg, (size_t)nseg * sizeof(*seg));
  r->nseg = nseg;
  return RN_OK;
}

// The Bloch test of step s (k: its index) while the path is stable; at an
// instability its location (the path ends there under stress control).
// *cur: a state to come back to after locating; *prev is consumed by locate.
rn_status examine(rn_network *net, Path &p, int j, int i, rn_state **prev, rn_state **cur,
                  rn_bloch_result *bprev, rn_cell_path_step *s, bool *end) {
  rn_cell_path_result *r = p.r;
  int f[6], nstress = stress_components(r->seg[j], r->ns, f), n = r->seg[j].steps;
  bool limit = limit_passed(*s, nstress);
  rn_bloch_result b = *bprev; // (past a limit point: no Bloch test, the last one)
  rn_status st;
  if (!limit) {
    if ((st = bloch_at(net, p, bprev->xi, &b))) return st;
    s->local_min = b.local_min;
    s->acoustic_min = b.acoustic_min;
    s->stable = !s->kuu_indefinite && !unstable(b, p);
  } else
    s->stable = 0;
  if (!s->stable) {
    if (!limit && (st = rn_network_state_save(net, cur))) return st;
    int why = limit ? 1 : (s->kuu_indefinite && !unstable(b, p)) ? 2 : 0;
    Bracket br = {j, *prev, (double)(i - 1) / n, (double)i / n, *bprev, b, why};
    *prev = nullptr; // locate owns it
    if ((st = locate(net, p, br))) return st;
    if (limit) { // no state past a limit point: the path ends there
      r->limit_end = r->inst.found;
      *end = true;
      return RN_OK;
    }
    if (s->kuu_indefinite) { // no tangent for the stress control beyond
      r->limit_end = 2;
      *end = true;
      return RN_OK;
    }
    if ((st = rn_network_state_restore(net, *cur))) return st;
    rn_state_destroy(cur);
    // a part of a distributed cell: the path ends with this step (Newton on the
    // distributed system may leave the unstable principal branch further on)
    if (rn_network_is_part(net)) r->limit_end = 3;
  }
  *bprev = b;
  return RN_OK;
}

rn_status run(rn_network *net, Path &p) {
  rn_cell_path_result *r = p.r;
  rn_bloch_result b;
  rn_state *prev = nullptr, *cur = nullptr;
  int k = 0;
  rn_status st = start(net, p, &b);
  if (!st) st = rn_network_state_save(net, &prev);
  for (int j = 0; !st && j < r->nseg && !r->stopped && !r->limit_end; ++j) {
    rn_cell_path_segment *g = &r->seg[j];
    int n = g->steps, f[6], nstress = stress_components(*g, r->ns, f);
    bool end = false;
    for (int v = 0; v < r->ns; ++v) // start values from the state reached
      g->start[v] = g->stress[v] ? r->step[k].stress[v] : r->step[k].strain[v];
    for (int i = 1; i <= n && !end && !r->limit_end; ++i) {
      rn_cell_path_step *s = &r->step[k + 1];
      if ((st = take_step(net, p, j, (double)(i - 1) / n, (double)i / n, prev, s))) break;
      bool limit = limit_passed(*s, nstress);
      if (!s->converged && !((limit || s->kuu_indefinite) && !r->inst.found)) {
        r->stopped = nstress ? "no equilibrium under the stress control (past a limit "
                               "point of the principal branch)"
                             : "the fluctuations did not converge";
        break;
      }
      s->local_min = s->acoustic_min = NAN;
      s->stable = -1; // not examined (past the first instability)
      if (!r->inst.found) {
        if ((st = examine(net, p, j, i, &prev, &cur, &b, s, &end))) break;
        if (end) break;
      }
      rn_state_destroy(&prev);
      if ((st = rn_network_state_save(net, &prev))) break;
      r->done = ++k;
      if (p.opt.progress) p.opt.progress(p.opt.user, r);
    }
  }
  rn_state_destroy(&prev);
  rn_state_destroy(&cur);
  return st;
}

} // namespace
} // namespace rodnet

extern "C" int rn_homogenization_invert(int n, const double *C, double *S) {
  double M[6][12];
  if (n < 1 || n > 6 || !C || !S) return 0;
  for (int i = 0; i < n; i++)
    for (int j = 0; j < 2 * n; j++) M[i][j] = j < n ? C[i * n + j] : (j - n == i);
  for (int c = 0; c < n; c++) {
    int p = c;
    for (int r = c + 1; r < n; r++)
      if (std::fabs(M[r][c]) > std::fabs(M[p][c])) p = r;
    if (!(std::fabs(M[p][c]) > 1e-14 * std::fabs(C[0]) + 1e-300)) return 0;
    for (int j = 0; j < 2 * n; j++) {
      double t = M[c][j];
      M[c][j] = M[p][j];
      M[p][j] = t;
    }
    for (int r = 0; r < n; r++) {
      if (r == c) continue;
      double f = M[r][c] / M[c][c];
      for (int j = 0; j < 2 * n; j++) M[r][j] -= f * M[c][j];
    }
  }
  for (int i = 0; i < n; i++)
    for (int j = 0; j < n; j++) S[i * n + j] = M[i][n + j] / M[i][i];
  return 1;
}

extern "C" void rn_cell_path_options_default(rn_cell_path_options *opt) {
  if (!opt) return;
  *opt = rn_cell_path_options{};
  opt->modes = RN_BLOCH_ALL;
}

extern "C" void rn_cell_path_result_free(rn_cell_path_result *res) {
  if (!res) return;
  free(res->seg);
  free(res->step);
  *res = rn_cell_path_result{};
}

extern "C" rn_status rn_cell_path_run(rn_network *net, int nseg,
                                      const rn_cell_path_segment *seg,
                                      const rn_cell_path_options *opt,
                                      rn_cell_path_result *res) {
  if (!net) return RN_ERR_ARG;
  rn_context *ctx = rn_network_context(net);
  if (!res) return rn_context_set_error(ctx, RN_ERR_ARG, "rn_cell_path_run: res is NULL");
  *res = rn_cell_path_result{};
  if (nseg < 1 || !seg)
    return rn_context_set_error(ctx, RN_ERR_ARG,
                                "rn_cell_path_run: the path has no segment");
  rodnet::Path p{net, {}, res};
  if (opt)
    p.opt = *opt;
  else
    rn_cell_path_options_default(&p.opt);
  rn_network_cell_info(net, nullptr, &res->ns, nullptr, nullptr);
  rn_status st = rodnet::allocate(ctx, nseg, seg, res);
  if (st) return st;
  rn_status ran = RN_OK;
  st = rodnet::guarded(net, "rn_cell_path_run", [&] { ran = rodnet::run(net, p); });
  return st ? st : ran;
}
