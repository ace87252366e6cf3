/* homog_path.c - `rodnet homogenize --path` (homog_path.h). */
#define _POSIX_C_SOURCE 200809L
#include "homog_path.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

int hp_parse_strain(const char *s, double *out, int *count) {
  int n = 0;
  const char *p = s;
  for (;;) {
    char *end = NULL;
    if (n == 6) return -1;
    double v = strtod(p, &end);
    if (end == p || !isfinite(v)) return -1;
    out[n++] = v;
    if (*end == '\0') break;
    if (*end != ',') return -1;
    p = end + 1;
  }
  *count = n;
  return 0;
}

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

/* Relax the cell at load factor t (strain t * target) from the current state and
 * record step s (strain, stress, energy). */
static rn_status relax_at(rn_network *net, const hp_path *p, double t, hp_step *s) {
  rn_cell_relax_report rep;
  double eps[6] = {0}, E[RN_TERM_COUNT];
  rn_status st;
  size_t n = rn_network_num_dofs(net);
  for (int v = 0; v < p->ns; ++v) eps[v] = t * p->target[v];
  if ((st = rn_cell_relax(net, eps, &rep))) return st;
  memset(s, 0, sizeof(*s));
  s->t = t;
  s->newton = rep.iterations;
  s->converged = rep.converged;
  double *x = malloc((n ? n : 1) * sizeof(double));
  if (!x)
    return rn_context_set_error(rn_network_context(net), RN_ERR_ALLOC, "out of memory");
  st = rn_network_get_dofs(net, x);
  if (!st) st = rn_network_cell_strain(net, x, s->strain);
  if (!st) st = rn_network_cell_stress(net, x, s->stress);
  if (!st) st = rn_network_energy_terms(net, x, E);
  free(x);
  if (!st) s->energy = E[RN_TERM_STRETCH] + E[RN_TERM_BEND] + E[RN_TERM_TWIST];
  return st;
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

/* Locate the first instability between the converged state lo (load factor
 * t_lo, its Bloch result rlo) and t_hi (result rhi) by bisection to 0.1 % of
 * the load factor, then a secant estimate inside the last bracket. */
static rn_status locate(rn_network *net, hp_path *p, const scales *sc, rn_state *lo,
                        double t_lo, rn_bloch_result rlo, double t_hi,
                        rn_bloch_result rhi) {
  rn_status st = RN_OK;
  hp_step s;
  hp_instability *in = &p->inst;
  int it = 0;
  while (t_hi - t_lo > 1e-3 * t_hi && it < 60) {
    double mid = 0.5 * (t_lo + t_hi);
    rn_bloch_result r;
    ++it;
    if ((st = rn_network_state_restore(net, lo)) || (st = relax_at(net, p, mid, &s)))
      goto done;
    if (!s.converged) break;
    if ((st = bloch_at(net, p, rhi.xi, &r))) goto done;
    if (unstable(&r, sc)) {
      t_hi = mid;
      rhi = r;
    } else {
      rn_state_destroy(&lo);
      if ((st = rn_network_state_save(net, &lo))) goto done;
      t_lo = mid;
      rlo = r;
    }
  }
  in->found = 1;
  in->bisections = it;
  in->kind_macroscopic = macro_unstable(&rhi, sc) && rhi.acoustic_valid;
  double flo = in->kind_macroscopic ? rlo.acoustic_min : rlo.local_min;
  double fhi = in->kind_macroscopic ? rhi.acoustic_min : rhi.local_min;
  double tc = t_hi;
  if (flo > 0.0 && fhi < 0.0) tc = t_lo + (t_hi - t_lo) * flo / (flo - fhi);
  in->t = tc;
  if (in->kind_macroscopic) {
    memset(in->xi, 0, sizeof(in->xi));
    in->multiplicity = 1;
    memcpy(in->direction, rhi.direction, sizeof(in->direction));
    memcpy(in->amplitude, rhi.amplitude, sizeof(in->amplitude));
  } else {
    memcpy(in->xi, rhi.xi, sizeof(in->xi));
    in->multiplicity = multiplicity(&rhi);
  }
  in->neig = rhi.neig;
  memcpy(in->eig, rhi.eig, sizeof(in->eig));
  if ((st = rn_network_state_restore(net, lo)) || (st = relax_at(net, p, tc, &s)))
    goto done;
  memcpy(in->strain, s.strain, sizeof(in->strain));
  memcpy(in->stress, s.stress, sizeof(in->stress));
done:
  rn_state_destroy(&lo); /* (owned here) */
  return st;
}

rn_status hp_run(rn_network *net, hp_path *p) {
  rn_status st;
  rn_bloch_result r, rprev;
  scales sc = {0.0, 0.0};
  rn_state *prev = NULL, *cur = NULL;
  double t0 = seconds_now();
  p->step = calloc((size_t)p->steps + 1, sizeof(hp_step));
  if (!p->step)
    return rn_context_set_error(rn_network_context(net), RN_ERR_ALLOC, "out of memory");
  memset(&p->inst, 0, sizeof(p->inst));
  if ((st = relax_at(net, p, 0.0, &p->step[0]))) goto done;
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
    p->inst.multiplicity = multiplicity(&r);
    memcpy(p->inst.stress, p->step[0].stress, sizeof(p->inst.stress));
  }
  rprev = r;
  if ((st = rn_network_state_save(net, &prev))) goto done;
  for (int k = 1; k <= p->steps; ++k) {
    hp_step *s = &p->step[k];
    double t = (double)k / p->steps;
    if ((st = relax_at(net, p, t, s))) goto done;
    if (!s->converged) {
      p->stopped = "the fluctuations did not converge";
      break;
    }
    s->local_min = s->acoustic_min = NAN;
    s->stable = -1; /* not examined (past the first instability) */
    if (!p->inst.found) {
      if ((st = bloch_at(net, p, rprev.xi, &r))) goto done;
      s->local_min = r.local_min;
      s->acoustic_min = r.acoustic_min;
      s->stable = !unstable(&r, &sc);
      if (!s->stable) {
        if ((st = rn_network_state_save(net, &cur))) goto done;
        st = locate(net, p, &sc, prev, p->step[k - 1].t, rprev, t, r);
        prev = NULL; /* locate owns it */
        if (st) goto done;
        if ((st = rn_network_state_restore(net, cur))) goto done;
        rn_state_destroy(&cur);
      }
      rprev = r;
    }
    rn_state_destroy(&prev);
    if ((st = rn_network_state_save(net, &prev))) goto done;
    p->done = k;
    if (!p->quiet)
      fprintf(
          stderr,
          "rodnet homogenize: step %d/%d  t %.4f  stress [%.4e %.4e %.4e%s]  %d Newton  "
          "%s\n",
          k, p->steps, t, s->stress[0], s->stress[1], s->stress[p->ns - 1],
          p->ns == 6 ? " ..." : "", s->newton,
          s->stable == 1   ? "stable"
          : s->stable == 0 ? "UNSTABLE"
                           : "-");
  }
done:
  rn_state_destroy(&prev);
  rn_state_destroy(&cur);
  p->seconds = seconds_now() - t0;
  return st;
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

void hp_write_json(FILE *f, const hp_path *p) {
  static const char *const mode_names[] = {"all", "in-plane", "out-of-plane"};
  fputs("  \"path_target\": ", f);
  hp_put_vec(f, p->ns, p->target);
  fprintf(f, ",\n  \"path_steps\": %d,\n  \"bloch_modes\": \"%s\",\n", p->steps,
          mode_names[p->modes]);
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
    fputs("\"bloch_min\": ", f);
    put_num(f, s->local_min);
    fputs(", \"acoustic_min\": ", f);
    put_num(f, s->acoustic_min);
    fputc('}', f);
  }
  fputs("],\n", f);
  if (p->stopped) fprintf(f, "  \"path_stopped\": \"%s\",\n", p->stopped);
  fputs("  \"instability\": ", f);
  if (!p->inst.found) {
    fputs("null,\n", f);
    return;
  }
  const hp_instability *in = &p->inst;
  fputs("{\"strain\": ", f);
  hp_put_vec(f, p->ns, in->strain);
  fputs(", \"stress\": ", f);
  hp_put_vec(f, p->ns, in->stress);
  fputs(", \"wave_vector\": ", f);
  hp_put_vec(f, p->dim, in->xi);
  fprintf(f, ", \"kind\": \"%s\", \"multiplicity\": %d, \"load_factor\": %.17g",
          in->kind_macroscopic ? "macroscopic" : "local", in->multiplicity, in->t);
  fputs(", \"bloch_eigenvalues\": ", f);
  hp_put_vec(f, in->neig, in->eig);
  if (in->kind_macroscopic) {
    fputs(", \"direction\": ", f);
    hp_put_vec(f, 3, in->direction);
    fputs(", \"amplitude\": ", f);
    hp_put_vec(f, 3, in->amplitude);
  }
  fprintf(f, ", \"bisections\": %d},\n", in->bisections);
  const hp_pattern *pt = &p->pattern;
  if (!pt->written) return;
  fputs("  \"pattern\": {\"supercell\": ", f);
  double rep[3] = {pt->rep[0], pt->rep[1], pt->rep[2]};
  hp_put_vec(f, p->dim, rep);
  fprintf(f,
          ", \"what\": \"principal branch at the critical strain plus the critical "
          "mode\", \"critical_mode_eigenvalue\": %.17g, \"amplitude\": %.17g, "
          "\"converged\": %s},\n",
          pt->eigenvalue, pt->amplitude, pt->converged ? "true" : "false");
}

void hp_free(hp_path *p) {
  free(p->step);
  p->step = NULL;
}
