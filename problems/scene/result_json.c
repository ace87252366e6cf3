/* result_json.c - result JSON writer (streams the rods; %.17g numbers written by
 * rn_format_g17, a row at a time). */
#include "scene/result_json.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/atomic_file.h"
#include "rodnet_contact.h"
#include "rodnet_couple.h"
#include "io/num_format.h"

typedef struct json_out {
  FILE *f;
  int not_finite; /* a NaN/Inf was met: the file is discarded */
  const rn_scene *scene;
  const rn_result_info *info;
  const char *path;
  /* the field being written, for the message of a non-finite value: where,
   * or `KIND "NAME": where` (a rod's or joint's) */
  const char *where, *kind, *name;
  rn_num_check chk;
} json_out;

/* Appends x to buf ("null" if it is not finite: the field is recorded and the
 * file discarded); returns the characters written (at most RN_NUM_BUF - 1). */
static size_t num_text(json_out *o, double x, char *buf) {
  if (isfinite(x)) return rn_format_g17(x, buf);
  if (!o->not_finite) {
    char field[128];
    if (o->name)
      snprintf(field, sizeof field, "%s \"%s\": %s", o->kind, o->name, o->where);
    else
      snprintf(field, sizeof field, "%s", o->where ? o->where : "a number");
    rn_num_checked(&o->chk, field, x);
  }
  o->not_finite = 1;
  memcpy(buf, "null", 5);
  return 4;
}

static void put_num(json_out *o, double x) {
  char buf[RN_NUM_BUF];
  fwrite(buf, 1, num_text(o, x, buf), o->f);
}

/* Appends "[x, y, z]" of v to buf (at least 3 RN_NUM_BUF + 8 bytes). */
static size_t vec_text(json_out *o, const double *v, char *buf) {
  size_t n = 0;
  buf[n++] = '[';
  for (int k = 0; k < 3; k++) {
    if (k) {
      buf[n++] = ',';
      buf[n++] = ' ';
    }
    n += num_text(o, v[k], buf + n);
  }
  buf[n++] = ']';
  return n;
}

static void put_key_num(json_out *o, const char *key, double x) {
  fprintf(o->f, "  \"%s\": ", key);
  o->where = key;
  put_num(o, x);
  fputs(",\n", o->f);
}

static rn_status put_terms(json_out *o, rn_network *net) {
  static const char *const names[RN_TERM_COUNT] = {"stretch", "bend", "twist", "load"};
  size_t n = rn_network_num_dofs(net);
  double *x = malloc((n ? n : 1) * sizeof *x), E[RN_TERM_COUNT];
  if (!x) return RN_ERR_ALLOC;
  rn_status st = rn_network_get_dofs(net, x);
  if (!st) st = rn_network_energy_terms(net, x, E);
  free(x);
  if (st) return st;
  fputs("  \"energy_terms\": {", o->f);
  o->where = "energy_terms";
  for (int t = 0; t < RN_TERM_COUNT; t++) {
    fprintf(o->f, "%s\"%s\": ", t ? ", " : "", names[t]);
    put_num(o, E[t]);
  }
  fputs("},\n", o->f);
  return RN_OK;
}

/* "cell" of a periodic scene: area or volume, macroscopic strain and stress at the
 * result (docs/homogenization.md). */
static rn_status put_cell(json_out *o, rn_network *net) {
  int dim = 0, ns = 0;
  double measure = 0.0, eps[6], sig[6];
  rn_network_cell_info(net, &dim, &ns, &measure, NULL);
  if (dim == 0) return RN_OK;
  size_t n = rn_network_num_dofs(net);
  double *x = malloc((n ? n : 1) * sizeof *x);
  if (!x) return RN_ERR_ALLOC;
  rn_status st = rn_network_get_dofs(net, x);
  if (!st) st = rn_network_cell_strain(net, x, eps);
  if (!st) st = rn_network_cell_stress(net, x, sig);
  free(x);
  if (st) return st;
  fprintf(o->f, "  \"cell\": {\"dimension\": %d, \"%s\": ", dim,
          dim == 2 ? "area" : "volume");
  o->where = "cell";
  put_num(o, measure);
  for (int q = 0; q < 2; q++) {
    fprintf(o->f, ", \"%s\": [", q ? "stress" : "strain");
    for (int v = 0; v < ns; v++) {
      if (v) fputs(", ", o->f);
      put_num(o, q ? sig[v] : eps[v]);
    }
    fputc(']', o->f);
  }
  fputs("},\n", o->f);
  return RN_OK;
}

/* "where": {"KEY": value, ...} of six keys, not closed (the caller adds its
 * own members); the fourth written null when +inf (contact's min_gap: no pair
 * within reach, a valid result). */
static void put_fields(json_out *o, const char *where, const char *const keys[6],
                       const double vals[6]) {
  fprintf(o->f, "  \"%s\": {", where);
  o->where = where;
  for (int k = 0; k < 6; k++) {
    fprintf(o->f, "%s\"%s\": ", k ? ", " : "", keys[k]);
    if (k == 3 && isinf(vals[k]) && vals[k] > 0.0)
      fputs("null", o->f);
    else
      put_num(o, vals[k]);
  }
}

/* "contact" of a scene with contact (docs/contact.md): the settings and, at the
 * result, the smallest gap, the active pairs, the barrier energy and force. */
static rn_status put_contact(json_out *o, rn_network *net) {
  double dhat = 0.0, kappa = 0.0, r = 0.0;
  if (!rn_network_get_contact(net, &dhat, &kappa, &r)) return RN_OK;
  size_t n = rn_network_num_dofs(net);
  double *x = malloc((n ? n : 1) * sizeof *x);
  rn_contact_stats cs;
  if (!x) return RN_ERR_ALLOC;
  rn_status st = rn_network_get_dofs(net, x);
  if (!st) st = rn_network_contact_stats(net, x, &cs);
  free(x);
  if (st) return st;
  const char *keys[6] = {"distance", "stiffness", "radius", "min_gap", "energy", "force"};
  const double vals[6] = {dhat,       kappa,     r,
                          cs.min_gap, cs.energy, cs.force}; /* min_gap: null if inf */
  put_fields(o, "contact", keys, vals);
  fprintf(o->f, ", \"active_pairs\": %zu},\n", cs.active);
  return RN_OK;
}

/* "equilibrium": the residual on the physical scale that the gradient test used. */
static void put_equilibrium(json_out *o) {
  const rn_result_info *in = o->info;
  const char *keys[6] = {"force_residual",  "force_scale",  "force_tolerance",
                         "moment_residual", "moment_scale", "moment_tolerance"};
  const double vals[6] = {in->force_residual,  in->force_scale,  in->force_tolerance,
                          in->moment_residual, in->moment_scale, in->moment_tolerance};
  put_fields(o, "equilibrium", keys, vals);
  fputs(",\n    \"relative_force_residual\": ", o->f);
  put_num(o, in->force_scale > 0.0 ? in->force_residual / in->force_scale : 0.0);
  fputs(", \"relative_moment_residual\": ", o->f);
  put_num(o, in->moment_scale > 0.0 ? in->moment_residual / in->moment_scale : 0.0);
  fputs("},\n", o->f);
}

/* "stability": {...} of the returned state (rn_stability). */
static void put_stability(json_out *o) {
  const rn_stability *st = &o->info->stability;
  const char *note = o->info->stability_note ? o->info->stability_note : "not checked";
  if (rn_network_fixed_couples(rn_scene_network(o->scene), NULL, NULL) > 0)
    note = RN_NOTE_NONCONSERVATIVE;
  if (!st->checked) {
    fputs("  \"stability\": {\"checked\": false, \"verified_minimum\": false, "
          "\"note\": ",
          o->f);
    rn_put_json_string(o->f, note);
    fputs("},\n", o->f);
    return;
  }
  fputs("  \"stability\": {\"checked\": true, \"lowest_eigenvalue\": ", o->f);
  o->where = "stability";
  put_num(o, st->lowest_eigenvalue);
  fputs(", \"scale\": ", o->f);
  put_num(o, st->scale);
  fprintf(o->f, ", \"verified_minimum\": %s, \"zero_modes\": %d,\n",
          st->verified_minimum ? "true" : "false", st->zero_modes);
  if (st->symmetries >= 0)
    fprintf(o->f, "    \"symmetries\": %d, \"soft_modes\": %d, \"soft_positive\": %d,\n",
            st->symmetries, st->soft_modes, st->soft_positive);
  else /* LOBPCG on a distributed network: zero_modes holds both kinds */
    fputs("    \"symmetries\": null, \"soft_modes\": null, \"soft_positive\": null,\n",
          o->f);
  fprintf(o->f, "    \"factorizations\": %ld, \"time_s\": ", st->factorizations);
  put_num(o, st->time_s);
  fprintf(o->f, ", \"method\": \"%s\", \"iterations\": %d, \"cholesky_flops\": ",
          st->method == RN_STABILITY_LOBPCG ? "lobpcg" : "cholesky", st->iterations);
  put_num(o, st->cholesky_flops);
  fputs("},\n", o->f);
}

void rn_result_put_model(FILE *f, const rn_network *net) {
  const char *why = "";
  int ok = rn_network_planar(net, &why) == 1;
  fprintf(f, "  \"model\": {\"used\": \"%s\", \"planar\": %s",
          rn_network_is_planar(net) == 1 ? "planar" : "3d", ok ? "true" : "false");
  if (!ok) {
    fputs(", \"not_planar\": ", f);
    rn_put_json_string(f, why);
  }
  fputs("},\n", f);
}

const char *rn_result_model_line(const rn_network *net, char *buf, size_t n) {
  const char *why = "";
  int ok = rn_network_planar(net, &why) == 1;
  if (rn_network_is_planar(net) == 1)
    snprintf(buf, n, "planar (2 DOFs per vertex, no out-of-plane modes)");
  else if (ok)
    snprintf(buf, n, "3d (the scene qualifies for \"model\": \"planar\")");
  else
    snprintf(buf, n, "3d (not planar: %s)", why);
  return buf;
}

/* The solver, its factorisation and preconditioner, what it finds. */
static void put_solver(json_out *o, rn_network *net) {
  const rn_result_info *in = o->info;
  FILE *f = o->f;
  fputs(",\n  \"solver\": ", f);
  rn_put_json_string(f, in->solver);
  if (in->factorization) {
    fputs(",\n  \"factorization\": ", f);
    rn_put_json_string(f, in->factorization);
  }
  fprintf(f, ",\n  \"factorizations\": %ld", in->factorizations);
  if (in->preconditioner) {
    fputs(",\n  \"preconditioner\": ", f);
    rn_put_json_string(f, in->preconditioner);
  }
  int nfixed = rn_network_fixed_couples(net, NULL, NULL);
  if (in->finds) {
    fputs(",\n  \"finds\": ", f);
    rn_put_json_string(f, nfixed > 0 ? "stationary point" : in->finds);
  }
  if (nfixed > 0) /* rodnet_couple.h: the energy leaves out their work */
    fprintf(f, ",\n  \"nonconservative_loads\": %d", nfixed);
}

/* "timing" and "evaluations": where the solve spent its time and work. */
static void put_costs(json_out *o) {
  const rn_result_info *in = o->info;
  FILE *f = o->f;
  fputs("  \"timing\": {\"hessian_s\": ", f);
  o->where = "timing";
  put_num(o, in->hessian_s);
  fputs(", \"preconditioner_setup_s\": ", f);
  put_num(o, in->preconditioner_setup_s);
  fputs(", \"preconditioner_apply_s\": ", f);
  put_num(o, in->preconditioner_apply_s);
  fputs("},\n", f);
  fprintf(f,
          "  \"evaluations\": {\"energy\": %ld, \"gradient\": %ld, \"hvp\": %ld, "
          "\"hessian\": %ld, \"krylov_iterations\": %ld},\n",
          in->energy_evals, in->gradient_evals, in->hvp_evals, in->hessian_evals,
          in->krylov_iterations);
}

void rn_result_put_partition(FILE *f, int ranks, const long *dofs, const long *stencils,
                             long edge_cut, double imbalance) {
  fprintf(f, "  \"partition\": {\"ranks\": %d, \"owned_dofs\": [", ranks);
  for (int q = 0; q < ranks; q++) fprintf(f, "%s%ld", q ? ", " : "", dofs[q]);
  fputs("], \"owned_stencils\": [", f);
  for (int q = 0; q < ranks; q++) fprintf(f, "%s%ld", q ? ", " : "", stencils[q]);
  fprintf(f, "], \"edge_cut\": %ld, \"imbalance\": %.17g},\n", edge_cut,
          isfinite(imbalance) ? imbalance : 1.0);
}

/* "partition" of a distributed solve. */
static void put_partition(json_out *o) {
  const rn_result_info *in = o->info;
  if (in->part_ranks > 0)
    rn_result_put_partition(o->f, in->part_ranks, in->part_dofs, in->part_stencils,
                            in->edge_cut, in->imbalance);
}

static void put_summary(json_out *o, rn_network *net) {
  const rn_result_info *in = o->info;
  FILE *f = o->f;
  fprintf(f, "{\n  \"rodnet_version\": \"%s\",\n  \"scene\": ", rn_version_string());
  rn_put_json_string(f, rn_scene_label(o->scene));
  fputs(",\n  \"status\": ", f);
  rn_put_json_string(f, in->status);
  fprintf(f, ",\n  \"converged\": %s,\n  \"stop_reason\": ",
          in->converged ? "true" : "false");
  rn_put_json_string(f, in->stop);
  put_solver(o, net);
  fputs(",\n", f);
  put_key_num(o, "energy", in->energy);
  put_key_num(o, "gradient_norm", in->gradient_norm);
  put_key_num(o, "initial_gradient_norm", in->initial_gradient_norm);
  fprintf(f, "  \"iterations\": %d,\n  \"load_steps\": %d,\n  \"predictor_steps\": %d,\n",
          in->iterations, in->load_steps, in->predictor_steps);
  put_key_num(o, "load_factor", rn_network_load_factor(net));
  put_key_num(o, "time_s", in->time_s);
  put_costs(o);
  fprintf(f, "  \"num_dofs\": %zu,\n  \"num_vertices\": %ld,\n", rn_network_num_dofs(net),
          rn_scene_num_vertices(o->scene));
  rn_result_put_model(f, net);
  put_equilibrium(o);
  put_stability(o);
  put_partition(o);
}

static rn_status put_rod(json_out *o, rn_network *net, int rod, double *buf) {
  int nv = rn_network_rod_num_vertices(net, rod);
  FILE *f = o->f;
  rn_status st = rn_network_rod_vertices(net, rod, buf);
  if (st) return st;
  fputs("    {\"name\": ", f);
  rn_put_json_string(f, rn_network_rod_name(net, rod));
  o->kind = "rod";
  o->name = rn_network_rod_name(net, rod);
  o->where = "vertices";
  fprintf(f, ", \"num_vertices\": %d,\n     \"vertices\": [", nv);
  /* rows go through a 16 KiB chunk: one fwrite per chunk, not per row */
  enum { ROW = 3 * RN_NUM_BUF + 16, CHUNK = 1 << 14 };
  char chunk[CHUNK];
  size_t n = 0;
  static const char sep[] = ",\n       "; /* the first row has no comma */
  for (int i = 0; i < nv; i++) {
    if (n + ROW > CHUNK) {
      fwrite(chunk, 1, n, f);
      n = 0;
    }
    memcpy(chunk + n, i ? sep : sep + 1, i ? 9 : 8);
    n += i ? 9 : 8;
    n += vec_text(o, &buf[3 * i], chunk + n);
  }
  static const char theta_key[] = "],\n     \"theta\": [";
  if (n + sizeof theta_key > CHUNK) {
    fwrite(chunk, 1, n, f);
    n = 0;
  }
  memcpy(chunk + n, theta_key, sizeof theta_key - 1);
  n += sizeof theta_key - 1;
  if ((st = rn_network_rod_theta(net, rod, buf))) return st;
  o->where = "theta";
  for (int i = 0; i + 1 < nv; i++) {
    if (n + ROW > CHUNK) {
      fwrite(chunk, 1, n, f);
      n = 0;
    }
    if (i) { /* a line break after every 8 values */
      memcpy(chunk + n, ", \n       ", i % 8 ? 2 : 10);
      n += i % 8 ? 2 : 10;
    }
    n += num_text(o, buf[i], chunk + n);
  }
  fwrite(chunk, 1, n, f);
  fputs("]}", f);
  o->name = NULL;
  return RN_OK;
}

static void put_vec(json_out *o, const double *v) {
  char row[3 * RN_NUM_BUF + 8];
  fwrite(row, 1, vec_text(o, v, row), o->f);
}

/* {"name", "model", "valence", "position": [x, y, z], "rotation": 3 rows}. */
static rn_status put_joint(json_out *o, rn_network *net, int j) {
  double x[3], R[9];
  rn_status st = rn_network_joint_position(net, j, x);
  if (!st) st = rn_network_joint_rotation(net, j, R);
  if (st) return st;
  FILE *f = o->f;
  fputs("    {\"name\": ", f);
  rn_put_json_string(f, rn_network_joint_name(net, j));
  o->kind = "joint";
  o->name = rn_network_joint_name(net, j);
  o->where = "position";
  fprintf(
      f, ", \"model\": \"%s\", \"valence\": %d,\n     \"position\": ",
      rn_network_joint_model(net, j) == RN_JOINT_RIGID
          ? "rigid"
          : (rn_network_joint_model(net, j) == RN_JOINT_SMOOTH ? "smooth" : "elastic"),
      rn_network_joint_valence(net, j));
  put_vec(o, x);
  fputs(",\n     \"rotation\": [", f);
  o->where = "rotation";
  for (int r = 0; r < 3; r++) {
    fputs(r ? ", " : "", f);
    put_vec(o, &R[3 * r]);
  }
  fputs("]}", f);
  o->name = NULL;
  return RN_OK;
}

static rn_status put_joints(json_out *o, rn_network *net) {
  int n = rn_network_num_joints(net);
  rn_status st = RN_OK;
  fputs(n ? ",\n  \"joints\": [\n" : ",\n  \"joints\": [", o->f);
  for (int j = 0; j < n && !st; j++) {
    st = put_joint(o, net, j);
    fputs(j + 1 < n ? ",\n" : "\n  ", o->f);
  }
  fputs("]", o->f);
  return st;
}

/* One support of "reactions": what it is, where, and its force and moment. */
static void put_support(json_out *o, rn_network *net, const rn_reaction *r) {
  static const char *const kinds[] = {"clamp", "vertex", "angle", "joint"};
  FILE *f = o->f;
  fprintf(f, "    {\"kind\": \"%s\", ", kinds[r->kind]);
  if (r->kind == RN_SUPPORT_JOINT) {
    fputs("\"joint\": ", f);
    rn_put_json_string(f, rn_network_joint_name(net, r->index));
  } else {
    fputs("\"rod\": ", f);
    rn_put_json_string(f, rn_network_rod_name(net, r->rod));
    if (r->kind == RN_SUPPORT_CLAMP)
      fprintf(f, ", \"end\": \"%s\"", r->index ? "end" : "start");
    else
      fprintf(f, ", \"%s\": %d", r->kind == RN_SUPPORT_VERTEX ? "vertex" : "edge",
              r->index);
  }
  fputs(", \"components\": \"", f);
  for (int k = 0; k < 3; k++)
    if (r->fixed & (1 << k)) fputc("xyz"[k], f);
  fprintf(f, "\", \"fixes_rotation\": %s,\n     \"point\": ",
          r->fixed_rotation ? "true" : "false");
  put_vec(o, r->point);
  fputs(", \"force\": ", f);
  put_vec(o, r->force);
  fputs(", \"moment\": ", f);
  put_vec(o, r->moment);
  fputc('}', f);
}

static void put_force_moment(json_out *o, const char *key, const double F[3],
                             const double M[3], int last) {
  fprintf(o->f, "    \"%s\": {\"force\": ", key);
  put_vec(o, F);
  fputs(", \"moment\": ", o->f);
  put_vec(o, M);
  fputs(last ? "}\n" : "},\n", o->f);
}

/* "reactions": every support's reaction (rn_network_reactions) and the
 * resultants of the reactions and of the applied loads, moments about the
 * origin. */
static rn_status put_reactions(json_out *o, rn_network *net) {
  int ns = rn_network_num_supports(net);
  size_t n = rn_network_num_dofs(net);
  double *x = malloc((n ? n : 1) * sizeof *x);
  rn_reaction *r = malloc((size_t)(ns > 0 ? ns : 1) * sizeof *r);
  double F[3] = {0, 0, 0}, M[3] = {0, 0, 0}, AF[3], AM[3];
  rn_status st = x && r ? rn_network_get_dofs(net, x) : RN_ERR_ALLOC;
  if (!st) st = rn_network_reactions(net, x, r, ns);
  if (!st) st = rn_network_applied_resultant(net, AF, AM);
  free(x);
  if (st) {
    free(r);
    return st;
  }
  fputs(",\n  \"reactions\": {\n    \"supports\": [", o->f);
  o->where = "reactions";
  for (int i = 0; i < ns; i++) {
    fputs(i ? ",\n" : "\n", o->f);
    put_support(o, net, &r[i]);
    for (int k = 0; k < 3; k++) {
      F[k] += r[i].force[k];
      M[k] += r[i].moment[k];
    }
    M[0] += r[i].point[1] * r[i].force[2] - r[i].point[2] * r[i].force[1];
    M[1] += r[i].point[2] * r[i].force[0] - r[i].point[0] * r[i].force[2];
    M[2] += r[i].point[0] * r[i].force[1] - r[i].point[1] * r[i].force[0];
  }
  fputs("],\n", o->f);
  put_force_moment(o, "resultant", F, M, 0);
  put_force_moment(o, "applied", AF, AM, 1);
  fputs("  }", o->f);
  free(r);
  return RN_OK;
}

static rn_status write_result(FILE *f, void *user, rn_context *ctx) {
  json_out *o = user;
  rn_network *net = rn_scene_network(o->scene);
  o->f = f;
  put_summary(o, net);
  rn_status st = put_terms(o, net);
  if (!st) st = put_cell(o, net);
  if (!st) st = put_contact(o, net);
  int nrods = rn_network_num_rods(net), maxnv = 2;
  for (int r = 0; r < nrods; r++)
    if (rn_network_rod_num_vertices(net, r) > maxnv)
      maxnv = rn_network_rod_num_vertices(net, r);
  double *buf = st ? NULL : malloc(3 * (size_t)maxnv * sizeof *buf);
  if (!st && !buf) st = RN_ERR_ALLOC;
  fputs("  \"rods\": [\n", f);
  for (int r = 0; r < nrods && !st; r++) {
    st = put_rod(o, net, r, buf);
    fputs(r + 1 < nrods ? ",\n" : "\n", f);
  }
  fputs("  ]", f);
  if (!st) st = put_joints(o, net);
  if (!st) st = put_reactions(o, net);
  fputs("\n}\n", f);
  free(buf);
  if (st) {
    char msg[512];
    snprintf(msg, sizeof msg, "%s", rn_context_last_error(ctx));
    return rn_context_set_error(ctx, st, "result JSON: %s",
                                *msg ? msg : rn_status_message(st));
  }
  if (o->not_finite) {
    char msg[512];
    return rn_context_set_error(ctx, RN_ERR_NOT_FINITE, "result JSON %s",
                                rn_num_check_message(&o->chk, o->path, msg, sizeof msg));
  }
  return RN_OK;
}

rn_status rn_result_write_json(rn_context *ctx, const char *path, const rn_scene *scene,
                               const rn_result_info *info) {
  json_out o;
  memset(&o, 0, sizeof o);
  o.scene = scene;
  o.info = info;
  o.path = path;
  o.where = "summary";
  return rn_file_write_atomic(ctx, path, write_result, &o);
}
