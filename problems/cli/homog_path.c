/* homog_path.c - `rodnet homogenize --path`: runs rn_cell_path_run and writes
 * its result (homog_path.h). */
#define _POSIX_C_SOURCE 200809L
#include "cli/homog_path.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "io/num_format.h"

/* Progress line of a step on stderr (rn_cell_path_options.progress). */
static void print_step(void *user, const rn_cell_path_result *r) {
  const rn_cell_path_step *s = &r->step[r->done];
  (void)user;
  fprintf(stderr, "rodnet homogenize: step %d/%d  t %.4f  stress ", r->done, r->steps,
          s->t);
  hp_print_vec(stderr, r->ns, s->stress, 4, 1);
  fprintf(stderr, "  %d Newton  %s\n", s->newton,
          s->stable == 1   ? "stable"
          : s->stable == 0 ? "UNSTABLE"
                           : "-");
}

rn_status hp_run(rn_network *net, hp_path *p) {
  rn_cell_path_options o;
  rn_cell_path_options_default(&o);
  o.grid = p->grid;
  o.modes = p->modes;
  o.bloch_method = p->bloch_method;
  if (!p->quiet) o.progress = print_step;
  return rn_cell_path_run(net, p->nseg, p->seg, &o, &p->r);
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

/* The "path_segments" member: each segment's control, start, target and steps. */
static void put_segments(FILE *f, const hp_path *p) {
  fputs("  \"path_segments\": [", f);
  for (int j = 0; j < p->nseg; ++j) {
    fprintf(f, "%s\n    {\"control\": ", j ? "," : "");
    put_control(f, p->ns, p->r.seg[j].stress);
    fputs(", \"start\": ", f);
    hp_put_vec(f, p->ns, p->r.seg[j].start);
    fputs(", \"target\": ", f);
    hp_put_vec(f, p->ns, p->r.seg[j].target);
    fprintf(f, ", \"steps\": %d}", p->r.seg[j].steps);
  }
  fputs("],\n", f);
}

/* The "path" member: one record per step computed. */
static void put_steps(FILE *f, const hp_path *p) {
  fputs("  \"path\": [", f);
  for (int k = 0; k <= p->r.done; ++k) {
    const rn_cell_path_step *s = &p->r.step[k];
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
    put_control(f, p->ns, p->r.seg[s->seg].stress);
    fprintf(f, ", \"mixed_iterations\": %d, \"tangent_min\": ", s->outer);
    put_num(f, s->tangent_min);
    fputs(", \"bloch_min\": ", f);
    put_num(f, s->local_min);
    fputs(", \"acoustic_min\": ", f);
    put_num(f, s->acoustic_min);
    fputc('}', f);
  }
  fputs("],\n", f);
}

const char *hp_instability_kind(const rn_cell_path_instability *in) {
  return !in->found ? "none" : in->kind_macroscopic ? "macroscopic" : "local";
}

const char *hp_instability_criterion(const rn_cell_path_instability *in) {
  return !in->found             ? ""
         : in->stress_limit     ? "stress_limit"
         : in->cell_periodic    ? "cell_periodic_fluctuations"
         : in->kind_macroscopic ? "rank_one_convexity"
                                : "bloch";
}

/* The "instability" member's object (ends ",\n"). */
static void put_instability(FILE *f, const hp_path *p) {
  const rn_cell_path_instability *in = &p->r.inst;
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
          hp_instability_kind(in), hp_instability_criterion(in), in->multiplicity, in->t);
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
}

void hp_write_json(FILE *f, const hp_path *p) {
  static const char *const mode_names[] = {"all", "in-plane", "out-of-plane"};
  static const char *const method_names[] = {"auto", "dense", "sparse"};
  fputs("  \"path_target\": ", f);
  hp_put_vec(f, p->ns, p->target);
  fprintf(f, ",\n  \"path_steps\": %d,\n  \"bloch_modes\": \"%s\",\n", p->steps,
          mode_names[p->modes]);
  fprintf(f, "  \"bloch_method\": \"%s\",\n", method_names[p->bloch_method]);
  fprintf(f, "  \"path_kind\": \"%s\",\n", p->kind);
  put_segments(f, p);
  put_steps(f, p);
  if (p->r.stopped) fprintf(f, "  \"path_stopped\": \"%s\",\n", p->r.stopped);
  if (p->r.limit_end == 1)
    fputs("  \"path_end\": \"limit point of the stress (no equilibrium beyond)\",\n", f);
  else if (p->r.limit_end == 2)
    fputs("  \"path_end\": \"past the instability the cell-periodic fluctuations are "
          "unstable: no tangent for the stress control\",\n",
          f);
  else if (p->r.limit_end == 3)
    fputs("  \"path_end\": \"the step past the first instability (under mpirun the path "
          "ends there: the distributed Newton solver does not follow the unstable "
          "principal branch further)\",\n",
          f);
  fputs("  \"instability\": ", f);
  if (p->r.inst.found)
    put_instability(f, p);
  else
    fputs("null,\n", f);
  put_pattern(f, p);
}

void hp_free(hp_path *p) {
  rn_cell_path_result_free(&p->r);
  free(p->seg);
  p->seg = NULL;
  p->nseg = 0;
}
