/* homog_path.c - `rodnet homogenize --path` (homog_path.h). */
#define _POSIX_C_SOURCE 200809L
#include "cli/homog_path.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "io/num_format.h"

static double seconds_now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* Scales of the instability tests, from the rest state. */
typedef struct scales {
  double local, acoustic;
} scales;

static int local_unstable(const rn_bloch_result *r, const scales *sc) {
  return r->local_min < -1e-9 * sc->local;
}
static int macro_unstable(const rn_bloch_result *r, const scales *sc) {
  return r->acoustic_valid && r->acoustic_min < -1e-9 * sc->acoustic;
}
static int unstable(const rn_bloch_result *r, const scales *sc) {
  return local_unstable(r, sc) || macro_unstable(r, sc) || !r->acoustic_valid;
}

/* Strain and stress of the current state. */
static rn_status state_of(rn_network *net, double *strain, double *stress,
                          double *energy) {
  double E[RN_TERM_COUNT];
  size_t n = rn_network_num_dofs(net);
  double *x = malloc((n ? n : 1) * sizeof(double));
  if (!x)
    return rn_context_set_error(rn_network_context(net), RN_ERR_ALLOC, "out of memory");
  rn_status st = rn_network_get_dofs(net, x);
  if (!st) st = rn_network_cell_strain(net, x, strain);
  if (!st) st = rn_network_cell_stress(net, x, stress);
  if (!st && energy) st = rn_network_energy_terms(net, x, E);
  free(x);
  if (!st && energy) *energy = E[RN_TERM_STRETCH] + E[RN_TERM_BEND] + E[RN_TERM_TWIST];
  return st;
}

/* Symmetric eigenvalues (ascending) and eigenvectors (columns of V) of the
 * n x n matrix a (n <= 6; destroyed) by cyclic Jacobi rotations. */
static void sym_eigen(int n, double *a, double *ev, double *V) {
  for (int i = 0; i < n * n; ++i) V[i] = (i / n == i % n) ? 1.0 : 0.0;
  for (int sweep = 0; sweep < 60; ++sweep) {
    double off = 0.0, diag = 0.0;
    for (int i = 0; i < n; ++i) {
      diag += a[i * n + i] * a[i * n + i];
      for (int j = i + 1; j < n; ++j) off += a[i * n + j] * a[i * n + j];
    }
    if (off <= 1e-32 * diag || off == 0.0) break;
    for (int p = 0; p < n; ++p)
      for (int q = p + 1; q < n; ++q) {
        double apq = a[p * n + q];
        if (apq == 0.0) continue;
        double th = 0.5 * (a[q * n + q] - a[p * n + p]) / apq;
        double t = (th >= 0 ? 1.0 : -1.0) / (fabs(th) + sqrt(th * th + 1.0));
        double c = 1.0 / sqrt(t * t + 1.0), sn = t * c;
        for (int k = 0; k < n; ++k) { /* columns p, q */
          double akp = a[k * n + p], akq = a[k * n + q];
          a[k * n + p] = c * akp - sn * akq;
          a[k * n + q] = sn * akp + c * akq;
        }
        for (int k = 0; k < n; ++k) { /* rows p, q */
          double apk = a[p * n + k], aqk = a[q * n + k];
          a[p * n + k] = c * apk - sn * aqk;
          a[q * n + k] = sn * apk + c * aqk;
        }
        for (int k = 0; k < n; ++k) {
          double vkp = V[k * n + p], vkq = V[k * n + q];
          V[k * n + p] = c * vkp - sn * vkq;
          V[k * n + q] = sn * vkp + c * vkq;
        }
      }
  }
  for (int i = 0; i < n; ++i) ev[i] = a[i * n + i];
  for (int i = 0; i < n; ++i) /* sort ascending, columns along */
    for (int j = i + 1; j < n; ++j)
      if (ev[j] < ev[i]) {
        double t = ev[i];
        ev[i] = ev[j], ev[j] = t;
        for (int k = 0; k < n; ++k) {
          t = V[k * n + i];
          V[k * n + i] = V[k * n + j], V[k * n + j] = t;
        }
      }
}

/* The effective tangent C (rn_homogenize) at the current state restricted to
 * the components f[nf]: Cff (nf x nf). */
static rn_status tangent_ff(rn_network *net, int nf, const int *f, double *C,
                            double *Cff) {
  rn_homogenization h;
  rn_status st = rn_homogenize(net, &h);
  if (st) return st;
  memcpy(C, h.C, sizeof(h.C));
  for (int i = 0; i < nf; ++i)
    for (int j = 0; j < nf; ++j) Cff[i * nf + j] = h.C[f[i] * h.nstrain + f[j]];
  return RN_OK;
}

/* Lowest eigenvalue of Cff (nf x nf) and its eigenvector spread onto the
 * strain components (mode[ns]). */
static double lowest_mode(int ns, int nf, const int *f, const double *Cff, double *mode) {
  double a[36], ev[6], V[36];
  memcpy(a, Cff, (size_t)(nf * nf) * sizeof(double));
  sym_eigen(nf, a, ev, V);
  if (mode) {
    memset(mode, 0, (size_t)ns * sizeof(double));
    for (int i = 0; i < nf; ++i) mode[f[i]] = V[i * nf];
  }
  return ev[0];
}

/* The Newton (and predictor) correction of the stress-controlled strain
 * components f[nf] at a state of strain eps and stress sig with the tangent C:
 * C_ff d = (sigma_f* - sigma_f) - C_fp (e_p* - e_p).  0 if C_ff is singular. */
static int mixed_step(int ns, int nf, const int *f, const int *stress, const double *val,
                      const double *eps, const double *sig, const double *C, double *d) {
  double Cff[36] = {0}, Sff[36], rhs[6];
  for (int i = 0; i < nf; ++i) {
    for (int j = 0; j < nf; ++j) Cff[i * nf + j] = C[f[i] * ns + f[j]];
    rhs[i] = val[f[i]] - sig[f[i]];
    for (int v = 0; v < ns; ++v)
      if (!stress[v]) rhs[i] -= C[f[i] * ns + v] * (val[v] - eps[v]);
  }
  if (!rn_homog_invert(nf, Cff, Sff)) return 0;
  for (int i = 0; i < nf; ++i) {
    d[i] = 0.0;
    for (int j = 0; j < nf; ++j) d[i] += Sff[i * nf + j] * rhs[j];
  }
  return 1;
}

/* Mixed control at the current segment: the strain-controlled components held
 * at val, the stress-controlled ones (f[nf]) free with the homogenised stress
 * val.  Newton on those strain components with the effective tangent C_ff
 * (rn_homogenize at each iterate), the fluctuations relaxed by rn_cell_relax
 * at each; the first correction (the predictor) from the tangent at the current
 * (converged) state.  Where a trial fails (the fluctuations do not converge or
 * are unstable) the correction is halved from the last good state (up to 12
 * times).  s->converged 0 if it fails (no equilibrium nearby: past a limit
 * point, or unstable cell-periodic fluctuations: s->kuu_indefinite). */
static rn_status mixed_relax(rn_network *net, const hp_path *p, const int *stress,
                             const double *val, hp_step *s) {
  int ns = p->ns, nf = 0, f[6], halvings = 0, tangent_ok = 1, seen_indefinite = 0;
  double eps[6], sig[6], C[36] = {0}, Cff[36] = {0}, d[6], eps_ok[6];
  rn_status st;
  rn_cell_relax_report rep = {0};
  rn_state *ok = NULL;
  for (int v = 0; v < ns; ++v)
    if (stress[v]) f[nf++] = v;
  s->converged = 0;
  s->newton = 0;
  if ((st = state_of(net, eps, sig, NULL))) return st;
  if ((st = rn_network_state_save(net, &ok))) return st;
  memcpy(eps_ok, eps, sizeof(eps));
  /* the predictor from the tangent at the current state */
  double pred = 0.0, e_pred[6];
  if (tangent_ff(net, nf, f, C, Cff) == RN_OK &&
      mixed_step(ns, nf, f, stress, val, eps, sig, C, d))
    for (int i = 0; i < nf; ++i) {
      eps[f[i]] += d[i];
      pred = fmax(pred, fabs(d[i]));
    }
  for (int v = 0; v < ns; ++v) {
    if (!stress[v]) {
      pred = fmax(pred, fabs(val[v] - eps[v]));
      eps[v] = val[v];
    }
  }
  memcpy(e_pred, eps, sizeof(eps));
  for (s->outer = 1; s->outer <= 40; ++s->outer) {
    double rn = 0.0, scale = 0.0, step = 0.0, emax = 0.0, off = 0.0;
    if ((st = rn_cell_relax(net, eps, &rep))) goto done;
    s->newton += rep.iterations;
    tangent_ok = rep.converged && !rep.indefinite;
    seen_indefinite |= rep.converged && rep.indefinite;
    if (tangent_ok) {
      st = tangent_ff(net, nf, f, C, Cff);
      if (st && st != RN_ERR_SOLVER) goto done;
      tangent_ok = st == RN_OK;
      st = RN_OK;
    }
    if (!tangent_ok) { /* a failed trial: halve it from the last good state */
      if (++halvings > 12) goto done;
      if ((st = rn_network_state_restore(net, ok))) goto done;
      for (int v = 0; v < ns; ++v) eps[v] = eps_ok[v] + 0.5 * (eps[v] - eps_ok[v]);
      continue;
    }
    halvings = 0;
    rn_state_destroy(&ok);
    if ((st = rn_network_state_save(net, &ok))) goto done;
    if ((st = state_of(net, eps, sig, NULL))) goto done;
    memcpy(eps_ok, eps, sizeof(eps));
    for (int v = 0; v < ns; ++v) {
      scale = fmax(scale, fabs(sig[v]));
      emax = fmax(emax, fabs(eps[v]));
      if (!stress[v]) off = fmax(off, fabs(eps[v] - val[v]));
    }
    for (int i = 0; i < nf; ++i) {
      rn = fmax(rn, fabs(sig[f[i]] - val[f[i]]));
      scale = fmax(scale, fabs(val[f[i]]));
    }
    int invertible = mixed_step(ns, nf, f, stress, val, eps, sig, C, d);
    for (int i = 0; i < nf && invertible; ++i) step = fmax(step, fabs(d[i]));
    /* converged: the stress residual, or the Newton correction of the strain
     * below what the relaxed fluctuations resolve */
    if (off == 0.0 && (rn <= 1e-10 * scale + (1e-12 * emax + 1e-20) * p->tangent_scale ||
                       (invertible && step <= 1e-8 * emax + 1e-12))) {
      s->converged = 1;
      s->tangent_min = lowest_mode(ns, nf, f, Cff, NULL) / p->tangent_scale;
      /* corrected by more than the predicted step: it jumped to another branch
       * (snapped through a limit point between the steps) */
      for (int i = 0; i < nf; ++i)
        if (fabs(eps[f[i]] - e_pred[f[i]]) > fmax(2.0 * pred, 1e-12)) s->jumped = 1;
      goto done;
    }
    if (!invertible || step > 0.1) goto done; /* no equilibrium nearby */
    for (int i = 0; i < nf; ++i) eps[f[i]] += d[i];
    for (int v = 0; v < ns; ++v)
      if (!stress[v]) eps[v] = val[v];
  }
done:
  /* failed next to unstable cell-periodic fluctuations: their instability */
  if (!s->converged)
    s->kuu_indefinite = seen_indefinite || (rep.converged && !tangent_ok);
  rn_state_destroy(&ok);
  return st;
}

/* The controlled values of segment j at its local parameter u. */
static void controls_at(const hp_path *p, int j, double u, double *val) {
  const hp_segment *g = &p->seg[j];
  for (int v = 0; v < p->ns; ++v) val[v] = g->start[v] + u * (g->target[v] - g->start[v]);
}

static int stress_controlled(const hp_segment *g, int ns) {
  int n = 0;
  for (int v = 0; v < ns; ++v) n += g->stress[v];
  return n;
}

/* Relax the cell at parameter u of segment j from the current state and record
 * step s (strain, stress, energy). */
static rn_status relax_at(rn_network *net, const hp_path *p, int j, double u,
                          hp_step *s) {
  double val[6] = {0};
  rn_status st;
  memset(s, 0, sizeof(*s));
  s->t = j + u;
  s->seg = j;
  s->tangent_min = NAN;
  controls_at(p, j, u, val);
  if (stress_controlled(&p->seg[j], p->ns)) {
    if ((st = mixed_relax(net, p, p->seg[j].stress, val, s))) return st;
  } else {
    rn_cell_relax_report rep;
    if ((st = rn_cell_relax(net, val, &rep))) return st;
    s->newton = rep.iterations;
    s->converged = rep.converged;
  }
  return state_of(net, s->strain, s->stress, &s->energy);
}

static rn_status bloch_at(rn_network *net, const hp_path *p, const double *hint,
                          rn_bloch_result *r) {
  rn_bloch_options o;
  rn_bloch_options_default(&o);
  o.grid = p->grid;
  o.modes = p->modes;
  o.xi_hint = hint;
  return rn_cell_bloch(net, &o, r);
}

static int multiplicity(const rn_bloch_result *r) {
  int m = 1;
  double spread = fabs(r->eig[r->neig - 1] - r->eig[0]);
  for (int i = 1; i < r->neig; ++i)
    if (r->eig[i] - r->eig[0] <= 1e-3 * spread) ++m;
  return m;
}

/* A limit point of the stress: under stress control, no equilibrium (the mixed
 * solve failed) or the tangent on the stress-controlled components is not
 * positive definite. */
static int limit_passed(const hp_step *s, int nstress) {
  return nstress && !s->kuu_indefinite &&
         (!s->converged || s->jumped || !(s->tangent_min > 1e-9));
}

/* Locate the first instability in segment j between the converged state lo
 * (local parameter u_lo, its Bloch result rlo) and u_hi (result rhi; limit_hi:
 * 1 the state at u_hi is past a limit point of the stress, 2 its cell-periodic
 * fluctuations are unstable in modes the Bloch test does not examine, 0 the
 * Bloch test failed there) by bisection to
 * 0.1 % of the parameter, then a secant estimate inside the last bracket. */
static rn_status locate(rn_network *net, hp_path *p, const scales *sc, rn_state *lo,
                        int j, double u_lo, rn_bloch_result rlo, double u_hi,
                        rn_bloch_result rhi, int limit_hi) {
  rn_status st = RN_OK;
  hp_step s;
  hp_instability *in = &p->inst;
  int it = 0, nstress = stress_controlled(&p->seg[j], p->ns);
  while (u_hi - u_lo > 1e-3 * u_hi && it < 60) {
    double mid = 0.5 * (u_lo + u_hi);
    rn_bloch_result r;
    ++it;
    if ((st = rn_network_state_restore(net, lo)) || (st = relax_at(net, p, j, mid, &s)))
      goto done;
    if (limit_passed(&s, nstress)) {
      u_hi = mid;
      limit_hi = 1;
      continue;
    }
    if (!s.converged && !s.kuu_indefinite) break;
    if ((st = bloch_at(net, p, rhi.xi, &r))) goto done;
    if (s.kuu_indefinite && !unstable(&r, sc)) { /* outside the modes examined */
      u_hi = mid;
      limit_hi = 2;
    } else if (unstable(&r, sc)) {
      u_hi = mid;
      rhi = r;
      limit_hi = 0;
    } else {
      rn_state_destroy(&lo);
      if ((st = rn_network_state_save(net, &lo))) goto done;
      u_lo = mid;
      rlo = r;
    }
  }
  in->found = 1;
  in->bisections = it;
  in->stress_limit = limit_hi == 1;
  in->cell_periodic = limit_hi == 2;
  double uc = u_hi;
  if (limit_hi == 2) { /* K_uu indefinite in modes the Bloch test does not examine */
    uc = u_lo;
    in->kind_macroscopic = 0;
    memset(in->xi, 0, sizeof(in->xi));
    in->multiplicity = 1;
    in->neig = 0;
  } else if (limit_hi) {
    /* the last equilibrium before the limit; its softest strain mode */
    int f[6], nf = 0;
    double C[36], Cff[36];
    uc = u_lo;
    in->kind_macroscopic = 1;
    memset(in->xi, 0, sizeof(in->xi));
    in->multiplicity = 1;
    in->neig = 0;
    for (int v = 0; v < p->ns; ++v)
      if (p->seg[j].stress[v]) f[nf++] = v;
    if ((st = rn_network_state_restore(net, lo))) goto done;
    double lo_min = NAN, rest_min = NAN;
    if (tangent_ff(net, nf, f, C, Cff) == RN_OK)
      lo_min = lowest_mode(p->ns, nf, f, Cff, in->mode);
    for (int a = 0; a < nf; ++a)
      for (int b = 0; b < nf; ++b) Cff[a * nf + b] = p->c_rest[f[a] * p->ns + f[b]];
    rest_min = lowest_mode(p->ns, nf, f, Cff, NULL);
    /* a limit point: C_ff nearly singular at the last equilibrium (at 0.1 % of
     * the parameter from a fold its lowest eigenvalue is about 3 % of the rest
     * value); else the mixed solve merely failed */
    if (!(lo_min < 0.1 * rest_min)) {
      in->found = 0;
      p->stopped = "the mixed solve did not converge or jumped, though the tangent on "
                   "the stress-controlled components stays positive definite (not a "
                   "limit point; try more --steps)";
      goto done;
    }
  } else {
    in->kind_macroscopic = macro_unstable(&rhi, sc) && rhi.acoustic_valid;
    double flo = in->kind_macroscopic ? rlo.acoustic_min : rlo.local_min;
    double fhi = in->kind_macroscopic ? rhi.acoustic_min : rhi.local_min;
    if (flo > 0.0 && fhi < 0.0) uc = u_lo + (u_hi - u_lo) * flo / (flo - fhi);
    if (in->kind_macroscopic) {
      memset(in->xi, 0, sizeof(in->xi));
      in->multiplicity = 1;
      memcpy(in->direction, rhi.direction, sizeof(in->direction));
      memcpy(in->amplitude, rhi.amplitude, sizeof(in->amplitude));
    } else {
      memcpy(in->xi, rhi.xi, sizeof(in->xi));
      in->nequiv = rhi.nequiv;
      memcpy(in->xi_equiv, rhi.xi_equiv, sizeof(in->xi_equiv));
      in->multiplicity = multiplicity(&rhi);
    }
    in->neig = rhi.neig;
    memcpy(in->eig, rhi.eig, sizeof(in->eig));
  }
  in->t = j + uc;
  if ((st = rn_network_state_restore(net, lo)) || (st = relax_at(net, p, j, uc, &s)))
    goto done;
  memcpy(in->strain, s.strain, sizeof(in->strain));
  memcpy(in->stress, s.stress, sizeof(in->stress));
done:
  rn_state_destroy(&lo); /* (owned here) */
  return st;
}

/* Start values of segment j from the state of step s. */
static void begin_segment(hp_path *p, int j, const hp_step *s) {
  hp_segment *g = &p->seg[j];
  for (int v = 0; v < p->ns; ++v)
    g->start[v] = g->stress[v] ? s->stress[v] : s->strain[v];
}

rn_status hp_run(rn_network *net, hp_path *p) {
  rn_status st;
  rn_bloch_result r, rprev;
  scales sc = {0.0, 0.0};
  rn_state *prev = NULL, *cur = NULL;
  double t0 = seconds_now();
  rn_context *ctx = rn_network_context(net);
  int all[6], k = 0;
  double C[36], Cee[36];
  if (p->nseg < 1)
    return rn_context_set_error(ctx, RN_ERR_ARG, "hp_run: the path has no segment");
  p->steps = 0;
  for (int j = 0; j < p->nseg; ++j) p->steps += p->seg[j].steps;
  p->step = calloc((size_t)p->steps + 1, sizeof(hp_step));
  if (!p->step) return rn_context_set_error(ctx, RN_ERR_ALLOC, "out of memory");
  memset(&p->inst, 0, sizeof(p->inst));
  p->limit_end = 0;
  /* the tangent's scale: the largest eigenvalue of C at rest */
  for (int v = 0; v < p->ns; ++v) all[v] = v;
  if ((st = tangent_ff(net, p->ns, all, C, Cee))) goto done;
  {
    double ev[6], V[36];
    sym_eigen(p->ns, Cee, ev, V);
    p->tangent_scale = fabs(ev[p->ns - 1]) > 0.0 ? fabs(ev[p->ns - 1]) : 1.0;
    memcpy(p->c_rest, C, sizeof(p->c_rest));
  }
  {
    hp_step *s0 = &p->step[0];
    rn_cell_relax_report rep;
    double zero[6] = {0};
    if ((st = rn_cell_relax(net, zero, &rep))) goto done;
    memset(s0, 0, sizeof(*s0));
    s0->newton = rep.iterations;
    s0->converged = rep.converged;
    s0->tangent_min = NAN;
    if ((st = state_of(net, s0->strain, s0->stress, &s0->energy))) goto done;
  }
  if ((st = bloch_at(net, p, NULL, &r))) goto done;
  sc.local = r.local_scale;
  sc.acoustic = r.acoustic_scale;
  p->step[0].local_min = r.local_min;
  p->step[0].acoustic_min = r.acoustic_min;
  p->step[0].stable = !unstable(&r, &sc);
  p->done = 0;
  if (!p->step[0].stable) { /* unstable at rest: report it there */
    p->inst.found = 1;
    p->inst.kind_macroscopic = macro_unstable(&r, &sc);
    memcpy(p->inst.xi, r.xi, sizeof(r.xi));
    p->inst.nequiv = r.nequiv;
    memcpy(p->inst.xi_equiv, r.xi_equiv, sizeof(r.xi_equiv));
    p->inst.multiplicity = multiplicity(&r);
    memcpy(p->inst.stress, p->step[0].stress, sizeof(p->inst.stress));
  }
  rprev = r;
  if ((st = rn_network_state_save(net, &prev))) goto done;
  for (int j = 0; j < p->nseg && !p->stopped && !p->limit_end; ++j) {
    int n = p->seg[j].steps, nstress = stress_controlled(&p->seg[j], p->ns);
    begin_segment(p, j, &p->step[k]);
    for (int i = 1; i <= n; ++i) {
      hp_step *s = &p->step[k + 1];
      double u = (double)i / n;
      if ((st = relax_at(net, p, j, u, s))) goto done;
      if (nstress && (s->jumped || !s->converged)) {
        /* the same step again in 8 substeps from the previous state: a strongly
         * nonlinear step, or the first sign of a limit point */
        double u0 = (double)(i - 1) / n;
        if ((st = rn_network_state_restore(net, prev))) goto done;
        for (int q = 1; q <= 8; ++q) {
          if ((st = relax_at(net, p, j, q == 8 ? u : u0 + (u - u0) * q / 8, s)))
            goto done;
          if (!s->converged || s->jumped) break;
        }
      }
      int limit = limit_passed(s, nstress);
      if (!s->converged && !((limit || s->kuu_indefinite) && !p->inst.found)) {
        p->stopped = nstress ? "no equilibrium under the stress control (past a limit "
                               "point of the principal branch)"
                             : "the fluctuations did not converge";
        break;
      }
      s->local_min = s->acoustic_min = NAN;
      s->stable = -1; /* not examined (past the first instability) */
      if (!p->inst.found) {
        if (!limit) {
          if ((st = bloch_at(net, p, rprev.xi, &r))) goto done;
          s->local_min = r.local_min;
          s->acoustic_min = r.acoustic_min;
          s->stable = !s->kuu_indefinite && !unstable(&r, &sc);
        } else
          s->stable = 0;
        if (!s->stable) {
          if (!limit && (st = rn_network_state_save(net, &cur))) goto done;
          int why = limit ? 1 : (s->kuu_indefinite && !unstable(&r, &sc)) ? 2 : 0;
          st = locate(net, p, &sc, prev, j, (double)(i - 1) / n, rprev, u, r, why);
          prev = NULL; /* locate owns it */
          if (st) goto done;
          if (limit) { /* no state past a limit point: the path ends there */
            p->limit_end = p->inst.found;
            break;
          }
          if (s->kuu_indefinite) { /* no tangent for the stress control beyond */
            p->limit_end = 2;
            break;
          }
          if ((st = rn_network_state_restore(net, cur))) goto done;
          rn_state_destroy(&cur);
        }
        rprev = r;
      }
      rn_state_destroy(&prev);
      if ((st = rn_network_state_save(net, &prev))) goto done;
      p->done = ++k;
      if (!p->quiet) {
        fprintf(stderr, "rodnet homogenize: step %d/%d  t %.4f  stress ", k, p->steps,
                s->t);
        hp_print_vec(stderr, p->ns, s->stress, 4, 1);
        fprintf(stderr, "  %d Newton  %s\n", s->newton,
                s->stable == 1   ? "stable"
                : s->stable == 0 ? "UNSTABLE"
                                 : "-");
      }
    }
  }
done:
  rn_state_destroy(&prev);
  rn_state_destroy(&cur);
  p->seconds = seconds_now() - t0;
  return st;
}

void hp_print_vec(FILE *f, int n, const double *v, int prec, int exp) {
  fputc('[', f);
  for (int i = 0; i < n; ++i)
    fprintf(f, exp ? "%s%.*e" : "%s%.*g", i ? " " : "", prec, v[i]);
  fputc(']', f);
}

void hp_put_vec(FILE *f, int n, const double *v) {
  fputc('[', f);
  for (int i = 0; i < n; ++i) fprintf(f, "%s%.17g", i ? ", " : "", v[i]);
  fputc(']', f);
}

static void put_num(FILE *f, double v) {
  if (isfinite(v))
    fprintf(f, "%.17g", v);
  else
    fputs("null", f);
}

static void put_control(FILE *f, int ns, const int *stress) {
  fputc('[', f);
  for (int v = 0; v < ns; ++v)
    fprintf(f, "%s\"%s\"", v ? ", " : "", stress[v] ? "stress" : "strain");
  fputc(']', f);
}

static void put_pattern(FILE *f, const hp_path *p) {
  const hp_pattern *pt = &p->pattern;
  if (pt->requested && !pt->written) { /* why nothing was written */
    fputs("  \"pattern\": {\"written\": false, \"reason\": ", f);
    rn_put_json_string(f, pt->why_not[0] ? pt->why_not : "not computed");
    fputs("},\n", f);
    return;
  }
  if (!pt->written) return;
  fputs("  \"pattern\": {\"written\": true, \"supercell\": ", f);
  double rep[3] = {pt->rep[0], pt->rep[1], pt->rep[2]};
  hp_put_vec(f, p->dim, rep);
  fprintf(f,
          ", \"what\": \"principal branch at the critical strain plus the critical "
          "mode\", \"critical_mode_eigenvalue\": %.17g, \"amplitude\": %.17g, "
          "\"converged\": %s},\n",
          pt->eigenvalue, pt->amplitude, pt->converged ? "true" : "false");
}

void hp_write_json(FILE *f, const hp_path *p) {
  static const char *const mode_names[] = {"all", "in-plane", "out-of-plane"};
  fputs("  \"path_target\": ", f);
  hp_put_vec(f, p->ns, p->target);
  fprintf(f, ",\n  \"path_steps\": %d,\n  \"bloch_modes\": \"%s\",\n", p->steps,
          mode_names[p->modes]);
  fprintf(f, "  \"path_kind\": \"%s\",\n  \"path_segments\": [", p->kind);
  for (int j = 0; j < p->nseg; ++j) {
    fprintf(f, "%s\n    {\"control\": ", j ? "," : "");
    put_control(f, p->ns, p->seg[j].stress);
    fputs(", \"start\": ", f);
    hp_put_vec(f, p->ns, p->seg[j].start);
    fputs(", \"target\": ", f);
    hp_put_vec(f, p->ns, p->seg[j].target);
    fprintf(f, ", \"steps\": %d}", p->seg[j].steps);
  }
  fputs("],\n", f);
  fputs("  \"path\": [", f);
  for (int k = 0; k <= p->done; ++k) {
    const hp_step *s = &p->step[k];
    fprintf(f,
            "%s\n    {\"step\": %d, \"load_factor\": %.17g, \"strain\": ", k ? "," : "",
            k, s->t);
    hp_put_vec(f, p->ns, s->strain);
    fputs(", \"stress\": ", f);
    hp_put_vec(f, p->ns, s->stress);
    fprintf(f, ", \"energy\": %.17g, \"newton_iterations\": %d, \"stable\": %s, ",
            s->energy, s->newton,
            s->stable == 1   ? "true"
            : s->stable == 0 ? "false"
                             : "null");
    fprintf(f, "\"segment\": %d, \"control\": ", s->seg);
    put_control(f, p->ns, p->seg[s->seg].stress);
    fprintf(f, ", \"mixed_iterations\": %d, \"tangent_min\": ", s->outer);
    put_num(f, s->tangent_min);
    fputs(", \"bloch_min\": ", f);
    put_num(f, s->local_min);
    fputs(", \"acoustic_min\": ", f);
    put_num(f, s->acoustic_min);
    fputc('}', f);
  }
  fputs("],\n", f);
  if (p->stopped) fprintf(f, "  \"path_stopped\": \"%s\",\n", p->stopped);
  if (p->limit_end == 1)
    fputs("  \"path_end\": \"limit point of the stress (no equilibrium beyond)\",\n", f);
  else if (p->limit_end == 2)
    fputs("  \"path_end\": \"past the instability the cell-periodic fluctuations are "
          "unstable: no tangent for the stress control\",\n",
          f);
  fputs("  \"instability\": ", f);
  if (!p->inst.found) {
    fputs("null,\n", f);
    put_pattern(f, p);
    return;
  }
  const hp_instability *in = &p->inst;
  fputs("{\"strain\": ", f);
  hp_put_vec(f, p->ns, in->strain);
  fputs(", \"stress\": ", f);
  hp_put_vec(f, p->ns, in->stress);
  fputs(", \"wave_vector\": ", f);
  hp_put_vec(f, p->dim, in->xi);
  if (!in->kind_macroscopic && in->nequiv > 0) {
    fputs(", \"equivalent_wave_vectors\": [", f);
    for (int e = 0; e < in->nequiv; ++e) {
      if (e) fputs(", ", f);
      hp_put_vec(f, p->dim, in->xi_equiv[e]);
    }
    fputc(']', f);
  }
  fprintf(f,
          ", \"kind\": \"%s\", \"criterion\": \"%s\", \"multiplicity\": %d, "
          "\"load_factor\": %.17g",
          in->kind_macroscopic ? "macroscopic" : "local",
          in->stress_limit       ? "stress_limit"
          : in->cell_periodic    ? "cell_periodic_fluctuations"
          : in->kind_macroscopic ? "rank_one_convexity"
                                 : "bloch",
          in->multiplicity, in->t);
  fputs(", \"bloch_eigenvalues\": ", f);
  hp_put_vec(f, in->neig, in->eig);
  if (in->stress_limit) {
    fputs(", \"strain_mode\": ", f);
    hp_put_vec(f, p->ns, in->mode);
  } else if (in->kind_macroscopic) {
    fputs(", \"direction\": ", f);
    hp_put_vec(f, 3, in->direction);
    fputs(", \"amplitude\": ", f);
    hp_put_vec(f, 3, in->amplitude);
  }
  fprintf(f, ", \"bisections\": %d},\n", in->bisections);
  put_pattern(f, p);
}

void hp_free(hp_path *p) {
  free(p->step);
  p->step = NULL;
  free(p->seg);
  p->seg = NULL;
  p->nseg = 0;
}
