/* homog_post.c - `rodnet homogenize --path ... --post-buckling P`: continuation
 * past the first (local) instability on the bifurcated branch in the supercell
 * the critical wave vector calls for (homog_path.h; docs/homogenization.md,
 * "Post-buckling"). */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cjson/cJSON.h>

#include "cli/cli.h"
#include "cli/homog_path.h"
#include "scene/scene.h"
#include "io/text_file.h"
#include "scene/vtk.h"

#ifndef RN_RENDER_VTU_SCRIPT
#define RN_RENDER_VTU_SCRIPT "render_vtu.py"
#endif

int hp_period_of(double xi) {
  for (int m = 1; m <= 12; ++m)
    if (fabs(m * xi - round(m * xi)) < 1e-3) return m;
  return 0;
}

static int gcd_int(int a, int b) { return b ? gcd_int(b, a % b) : a; }

int hp_instability_supercell(const rn_cell_path_instability *in, int dim, int rep[3]) {
  for (int i = 0; i < dim; ++i) {
    if (!(rep[i] = hp_period_of(in->xi[i]))) return 0;
    for (int e = 0; e < in->nequiv; ++e) {
      int m = hp_period_of(in->xi_equiv[e][i]);
      if (!m) return 0;
      rep[i] = rep[i] / gcd_int(rep[i], m) * m;
      if (rep[i] > 12) return 0;
    }
  }
  return 1;
}

/* Out-of-plane pins for an in-plane study of a 2D supercell: z of every joint
 * and interior rod vertex, every material angle, the first joint fully (the
 * anchor the periodic cell would otherwise add). */
static int add_pins(cJSON *root, const rn_network *net) {
  cJSON *cons = cJSON_GetObjectItemCaseSensitive(root, "constraints");
  if (!cons) {
    cons = cJSON_AddArrayToObject(root, "constraints");
    if (!cons) return -1;
  }
  for (int j = 0; j < rn_network_num_joints(net); ++j) {
    cJSON *c = cJSON_CreateObject();
    if (!c) return -1;
    cJSON_AddItemToArray(cons, c);
    cJSON_AddStringToObject(c, "type", "pin");
    cJSON_AddStringToObject(c, "joint", rn_network_joint_name(net, j));
    if (j > 0) {
      const char *z[] = {"z"};
      cJSON_AddItemToObject(c, "components", cJSON_CreateStringArray(z, 1));
    }
  }
  for (int r = 0; r < rn_network_num_rods(net); ++r) {
    int nv = rn_network_rod_num_vertices(net, r);
    const char *name = rn_network_rod_name(net, r);
    for (int v = 1; v + 1 < nv; ++v) {
      cJSON *c = cJSON_CreateObject();
      const char *z[] = {"z"};
      if (!c) return -1;
      cJSON_AddItemToArray(cons, c);
      cJSON_AddStringToObject(c, "type", "pin");
      cJSON_AddStringToObject(c, "rod", name);
      cJSON_AddNumberToObject(c, "vertex", v);
      cJSON_AddItemToObject(c, "components", cJSON_CreateStringArray(z, 1));
    }
    for (int e = 0; e + 1 < nv; ++e) {
      cJSON *c = cJSON_CreateObject();
      if (!c) return -1;
      cJSON_AddItemToArray(cons, c);
      cJSON_AddStringToObject(c, "type", "fix_theta");
      cJSON_AddStringToObject(c, "rod", name);
      cJSON_AddNumberToObject(c, "edge", e);
    }
  }
  return 0;
}

rn_status hp_supercell(rn_context *ctx, const char *scene, const int *rep, int dim,
                       int pin_out_of_plane, rn_scene **out) {
  char *text = NULL, *json = NULL;
  size_t len = 0;
  rn_status st;
  cJSON *root = NULL;
  rn_scene *sc = NULL;
  *out = NULL;
  if ((st = rn_text_file_read(ctx, scene, 1 << 28, &text, &len))) return st;
  root = cJSON_Parse(text);
  cJSON *per = cJSON_GetObjectItemCaseSensitive(root, "periodic");
  if (!cJSON_IsObject(per) || cJSON_GetObjectItemCaseSensitive(per, "repeat")) {
    st = rn_context_set_error(ctx, RN_ERR_ARG, "%s: needs a scene without \"repeat\"",
                              scene);
    goto done;
  }
  cJSON_DeleteItemFromObjectCaseSensitive(per, "stress");
  cJSON_DeleteItemFromObjectCaseSensitive(per, "strain");
  cJSON_AddItemToObject(per, "repeat", cJSON_CreateIntArray(rep, dim));
  if (!(json = cJSON_PrintUnformatted(root))) goto fail_alloc;
  if ((st = rn_scene_parse(ctx, scene, json, strlen(json), &sc))) goto done;
  if (pin_out_of_plane) {
    if (add_pins(root, rn_scene_network(sc))) goto fail_alloc;
    rn_scene_destroy(&sc);
    free(json);
    if (!(json = cJSON_PrintUnformatted(root))) goto fail_alloc;
    if ((st = rn_scene_parse(ctx, scene, json, strlen(json), &sc))) goto done;
  }
  *out = sc;
  sc = NULL;
  goto done;
fail_alloc:
  st = rn_context_set_error(ctx, RN_ERR_ALLOC, "out of memory");
done:
  rn_scene_destroy(&sc);
  free(json);
  free(text);
  cJSON_Delete(root);
  return st;
}

/* Strain of the cell path at parameter t (linear between the recorded steps). */
static void strain_at(const hp_path *p, double t, double *eps) {
  int k = 1;
  while (k < p->r.done && p->r.step[k].t < t) ++k;
  const rn_cell_path_step *a = &p->r.step[k - 1], *b = &p->r.step[k];
  double w = b->t > a->t ? (t - a->t) / (b->t - a->t) : 1.0;
  for (int v = 0; v < p->ns; ++v) eps[v] = (1.0 - w) * a->strain[v] + w * b->strain[v];
}

/* Stress, energy per cell and stability of the current state. */
static rn_status measure(rn_network *net, int copies, double *stress, double *energy,
                         int *verified, double *lowest) {
  double E[RN_TERM_COUNT];
  rn_status st;
  size_t n = rn_network_num_dofs(net);
  double *x = malloc((n ? n : 1) * sizeof(double));
  rn_stability stab;
  if (!x)
    return rn_context_set_error(rn_network_context(net), RN_ERR_ALLOC, "out of memory");
  st = rn_network_get_dofs(net, x);
  if (!st) st = rn_network_cell_stress(net, x, stress);
  if (!st) st = rn_network_energy_terms(net, x, E);
  free(x);
  if (st) return st;
  *energy = (E[RN_TERM_STRETCH] + E[RN_TERM_BEND] + E[RN_TERM_TWIST]) / copies;
  if ((st = rn_network_stability(net, &stab))) return st;
  *verified = stab.verified_minimum;
  *lowest = stab.lowest_eigenvalue;
  return RN_OK;
}

/* Positions of every rod vertex (3 per vertex, rods in order). */
static rn_status positions(const rn_network *net, double *xyz) {
  size_t at = 0;
  for (int r = 0; r < rn_network_num_rods(net); ++r) {
    rn_status st = rn_network_rod_vertices(net, r, xyz + at);
    if (st) return st;
    at += 3 * (size_t)rn_network_rod_num_vertices(net, r);
  }
  return RN_OK;
}

/* Harmonic content of the displacement d (bifurcated minus principal) over the
 * copies of the cell in the supercell: for each supercell harmonic xi = (p/m,
 * q/n(, s/k)) the share of sum |sum_c d_c exp(-2 pi i xi . c)|^2. */
static void harmonics(const rn_network *net, const hp_path *p, const double *d,
                      hp_post *po) {
  const int *rep = po->rep, dim = p->dim;
  int nh = rep[0] * rep[1] * (dim == 3 ? rep[2] : 1);
  double total = 0.0;
  po->nharm = nh > HP_MAX_HARMONICS ? 0 : nh;
  for (int h = 0; h < po->nharm; ++h) {
    int hc[3] = {h % rep[0], (h / rep[0]) % rep[1], dim == 3 ? h / (rep[0] * rep[1]) : 0};
    double power = 0.0;
    /* rods of copy (0,0) have names without '@'; their copies name@i,j */
    for (int r = 0; r < rn_network_num_rods(net); ++r) {
      const char *name = rn_network_rod_name(net, r);
      int nv = rn_network_rod_num_vertices(net, r);
      if (strchr(name, '@')) {
        continue;
      }
      for (int k = 0; k < 3 * nv; ++k) {
        double re = 0.0, im = 0.0;
        size_t at2 = 0;
        for (int r2 = 0; r2 < rn_network_num_rods(net); ++r2) {
          const char *n2 = rn_network_rod_name(net, r2);
          int nv2 = rn_network_rod_num_vertices(net, r2);
          size_t base = strlen(name);
          int c[3] = {0, 0, 0};
          int same = strcmp(n2, name) == 0 ||
                     (strncmp(n2, name, base) == 0 && n2[base] == '@' &&
                      sscanf(n2 + base + 1, "%d,%d,%d", &c[0], &c[1], &c[2]) >= 2);
          if (same && nv2 == nv) {
            double ph = 0.0;
            for (int m = 0; m < dim; ++m) ph += 6.283185307179586 * hc[m] * c[m] / rep[m];
            re += d[at2 + (size_t)k] * cos(ph);
            im -= d[at2 + (size_t)k] * sin(ph);
          }
          at2 += 3 * (size_t)nv2;
        }
        power += re * re + im * im;
      }
    }
    for (int m = 0; m < 3; ++m) po->harm_xi[h][m] = m < dim ? (double)hc[m] / rep[m] : 0;
    for (int m = 0; m < dim; ++m)
      if (po->harm_xi[h][m] > 0.5) po->harm_xi[h][m] -= 1.0;
    po->harm[h] = power;
    total += power;
  }
  for (int h = 0; h < po->nharm; ++h) po->harm[h] = total > 0.0 ? po->harm[h] / total : 0;
}

rn_status hp_write_pattern_files(rn_context *ctx, rn_scene *sc, const char *base,
                                 int quiet, int *vtu_written, int *png_written) {
  char vtu[4096], png[4096];
  snprintf(vtu, sizeof vtu, "%s.vtu", base);
  snprintf(png, sizeof png, "%s.png", base);
  rn_status st = rn_vtk_write(ctx, vtu, sc);
  if (st) return st;
  *vtu_written = 1;
  const char *const args[] = {
      vtu, png, "--view", "xy", "--field", "bending_moment", quiet ? "--quiet" : NULL,
      NULL};
  *png_written =
      rn_cli_run_script_to("RODNET_RENDER_VTU", RN_RENDER_VTU_SCRIPT, args, png) == 0;
  return RN_OK;
}

/* The post-buckling computation on the supercell network: the principal and
 * bifurcated states (owned), the critical mode (vec, its largest real entry
 * vmax over the nfl fluctuation DOFs), scratch for the DOFs and positions. */
typedef struct post_run {
  rn_network *net;
  int copies;
  rn_state *prin, *bif;
  double *x, *vec, *xp, *xb;
  size_t nd, nb, npos, nfl;
  double vmax;
} post_run;

/* The principal branch to the critical strain (through the path's steps) and
 * the critical mode there (the lowest Bloch mode at xi = 0 of the supercell). */
static rn_status post_start(rn_context *ctx, const hp_path *p, hp_post *po, post_run *q) {
  rn_network *net = q->net;
  const rn_cell_path_instability *in = &p->r.inst;
  rn_cell_relax_report rep;
  rn_status st;
  for (int k = 1; k <= p->r.done && p->r.step[k].t < in->t; ++k)
    if ((st = rn_cell_relax(net, p->r.step[k].strain, &rep))) return st;
  if ((st = rn_cell_relax(net, in->strain, &rep))) return st;
  q->nd = rn_network_num_dofs(net);
  for (int r = 0; r < rn_network_num_rods(net); ++r)
    q->npos += 3 * (size_t)rn_network_rod_num_vertices(net, r);
  if ((st = rn_network_bloch_dofs(net, &q->nb, NULL, NULL))) return st;
  q->x = malloc(q->nd * sizeof(double));
  q->vec = malloc(2 * q->nb * sizeof(double));
  q->xp = malloc(q->npos * sizeof(double));
  q->xb = malloc(q->npos * sizeof(double));
  if (!q->x || !q->vec || !q->xp || !q->xb)
    return rn_context_set_error(ctx, RN_ERR_ALLOC, "out of memory");
  const double zero[3] = {0.0, 0.0, 0.0};
  if ((st = rn_cell_bloch_eigen(net, zero, p->modes, 1, &po->mode_eigenvalue, q->vec)))
    return st;
  if ((st = rn_network_state_save(net, &q->prin))) return st;
  double measure_ = 0.0;
  rn_network_cell_info(net, NULL, NULL, &measure_, NULL);
  q->nfl = q->nd - (size_t)p->ns;
  for (size_t i = 0; i < q->nfl && i < q->nb; ++i)
    q->vmax = fmax(q->vmax, fabs(q->vec[2 * i]));
  if (!(q->vmax > 0.0))
    return rn_context_set_error(ctx, RN_ERR_SOLVER, "the critical mode has no real part");
  /* perturbation: 1e-3 of the cell size at the largest entry of the mode */
  po->perturbation = 1e-3 * pow(measure_ / q->copies, 1.0 / p->dim);
  return RN_OK;
}

/* Step s (strain s->strain) on both branches: principal from the previous
 * principal state by rn_cell_relax; bifurcated from the previous bifurcated
 * state, or the principal one plus the critical mode, by rn_cell_minimize; each
 * measured, and the amplitude of their difference. */
static rn_status post_step(hp_post *po, post_run *q, hp_post_step *s) {
  rn_network *net = q->net;
  rn_cell_relax_report rep;
  rn_status st;
  if ((st = rn_network_state_restore(net, q->prin)) ||
      (st = rn_cell_relax(net, s->strain, &rep)))
    return st;
  s->principal_converged = rep.converged;
  rn_state_destroy(&q->prin);
  if ((st = rn_network_state_save(net, &q->prin)) ||
      (st = measure(net, q->copies, s->principal_stress, &s->principal_energy,
                    &s->principal_verified, &s->principal_lowest)) ||
      (st = positions(net, q->xp)))
    return st;
  if (q->bif) {
    if ((st = rn_network_state_restore(net, q->bif))) return st;
  } else {
    if ((st = rn_network_get_dofs(net, q->x))) return st;
    for (size_t i = 0; i < q->nfl && i < q->nb; ++i)
      q->x[i] += po->perturbation * q->vec[2 * i] / q->vmax;
    if ((st = rn_network_set_dofs(net, q->x)) ||
        (st = rn_network_update_reference(net, q->x)))
      return st;
  }
  if ((st = rn_cell_minimize(net, s->strain, &rep))) return st;
  s->converged = rep.converged;
  s->iterations = rep.iterations;
  rn_state_destroy(&q->bif);
  if ((st = rn_network_state_save(net, &q->bif)) ||
      (st = measure(net, q->copies, s->stress, &s->energy, &s->verified, &s->lowest)) ||
      (st = positions(net, q->xb)))
    return st;
  s->amplitude = 0.0;
  for (size_t i = 0; i < q->npos; ++i) {
    q->xb[i] -= q->xp[i];
    s->amplitude = fmax(s->amplitude, fabs(q->xb[i]));
  }
  return RN_OK;
}

/* Progress line of post-buckling step j of n on stderr. */
static void print_post_step(const hp_path *p, const hp_post_step *s, int j, int n) {
  fprintf(stderr, "rodnet homogenize: post-buckling %d/%d  t %.4f  stress ", j, n, s->t);
  hp_print_vec(stderr, p->ns, s->stress, 4, 1);
  fputs(" (principal ", stderr);
  hp_print_vec(stderr, p->ns, s->principal_stress, 4, 1);
  fprintf(stderr, ")  amplitude %.3e  %s\n", s->amplitude,
          s->converged && s->verified ? "verified minimum" : "NOT a verified minimum");
}

rn_status hp_post_buckling(rn_context *ctx, const char *scene, const hp_path *p,
                           const char *out_base, hp_post *po) {
  rn_status st = RN_OK;
  rn_scene *sc = NULL;
  const rn_cell_path_instability *in = &p->r.inst;
  post_run q;
  memset(&q, 0, sizeof q);
  q.copies = 1;
  if (!in->found || in->kind_macroscopic) {
    po->failed = in->found ? "the instability is macroscopic (long wavelength): no "
                             "finite supercell"
                           : "the path stays stable: no post-buckling";
    return RN_OK;
  }
  if (!hp_instability_supercell(in, p->dim, po->rep)) {
    po->failed = "the wave vector is not commensurate with a supercell of at most 12 "
                 "cells per direction";
    return RN_OK;
  }
  for (int i = 0; i < p->dim; ++i) q.copies *= po->rep[i];
  po->pinned = p->dim == 2 && p->modes == RN_BLOCH_IN_PLANE;
  if ((st = hp_supercell(ctx, scene, po->rep, p->dim, po->pinned, &sc))) return st;
  q.net = rn_scene_network(sc);
  if ((st = post_start(ctx, p, po, &q))) goto done;
  const double t_end = p->r.step[p->r.done].t;
  int n = po->nsteps;
  po->step = calloc((size_t)n + 1, sizeof(hp_post_step));
  if (!po->step) {
    st = rn_context_set_error(ctx, RN_ERR_ALLOC, "out of memory");
    goto done;
  }
  for (int j = 1; j <= n; ++j) {
    hp_post_step *s = &po->step[j - 1];
    s->t = in->t + (t_end - in->t) * j / n;
    strain_at(p, s->t, s->strain);
    if ((st = post_step(po, &q, s))) goto done;
    po->done = j;
    if (!p->quiet) print_post_step(p, s, j, n);
    if (!s->converged) break;
  }
  harmonics(q.net, p, q.xb, po);
  /* the pattern: the last bifurcated state */
  st = hp_write_pattern_files(ctx, sc, out_base, p->quiet, &po->written, &po->png);
done:
  rn_state_destroy(&q.prin);
  rn_state_destroy(&q.bif);
  free(q.x);
  free(q.vec);
  free(q.xp);
  free(q.xb);
  rn_scene_destroy(&sc);
  return st;
}

void hp_post_write_json(FILE *f, const hp_path *p, const hp_post *po) {
  if (!po->requested) return;
  fputs("  \"post_buckling\": ", f);
  if (po->failed) {
    fprintf(f, "{\"error\": \"%s\"},\n", po->failed);
    return;
  }
  double rep[3] = {po->rep[0], po->rep[1], po->rep[2]};
  fputs("{\"supercell\": ", f);
  hp_put_vec(f, p->dim, rep);
  fprintf(f,
          ", \"out_of_plane_pinned\": %s, \"critical_mode_eigenvalue\": %.17g, "
          "\"perturbation\": %.17g, \"steps\": [",
          po->pinned ? "true" : "false", po->mode_eigenvalue, po->perturbation);
  for (int j = 0; j < po->done; ++j) {
    const hp_post_step *s = &po->step[j];
    fprintf(f, "%s\n    {\"load_factor\": %.17g, \"strain\": ", j ? "," : "", s->t);
    hp_put_vec(f, p->ns, s->strain);
    fputs(", \"stress\": ", f);
    hp_put_vec(f, p->ns, s->stress);
    fprintf(f,
            ", \"energy_per_cell\": %.17g, \"amplitude\": %.17g, \"converged\": %s, "
            "\"iterations\": %d, \"verified_minimum\": %s, \"lowest_eigenvalue\": %.17g, "
            "\"principal_stress\": ",
            s->energy, s->amplitude, s->converged ? "true" : "false", s->iterations,
            s->verified ? "true" : "false", s->lowest);
    hp_put_vec(f, p->ns, s->principal_stress);
    fprintf(f,
            ", \"principal_energy_per_cell\": %.17g, \"principal_verified_minimum\": %s, "
            "\"principal_lowest_eigenvalue\": %.17g}",
            s->principal_energy, s->principal_verified ? "true" : "false",
            s->principal_lowest);
  }
  fputs("],\n    \"harmonics\": [", f);
  for (int h = 0; h < po->nharm; ++h) {
    fprintf(f, "%s{\"wave_vector\": ", h ? ", " : "");
    hp_put_vec(f, p->dim, po->harm_xi[h]);
    fprintf(f, ", \"share\": %.6g}", po->harm[h]);
  }
  fprintf(f, "], \"pattern_written\": %s, \"png\": %s},\n",
          po->written ? "true" : "false", po->png ? "true" : "false");
}

void hp_post_free(hp_post *po) {
  free(po->step);
  po->step = NULL;
}
