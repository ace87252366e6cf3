/* scene_check.c - the scene reader's contract on one input (scene_check.h). */
#include "scene_check.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cjson/cJSON.h>

#include "scene/scene.h"

typedef struct checker {
  const char *label;
  rn_network *net;
  rn_fuzz_result *res;
} checker;

#if defined(__GNUC__)
__attribute__((format(printf, 2, 3)))
#endif
static void
violation(checker *c, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  fprintf(stderr, "scene_check: %s: ", c->label);
  vfprintf(stderr, fmt, ap);
  fputc('\n', stderr);
  va_end(ap);
  c->res->violations++;
}

/* A "vertices" count above the limit anywhere in the tree. */
static int too_many_vertices(const cJSON *v) {
  for (const cJSON *c = v ? v->child : NULL; c; c = c->next) {
    if (c->string && strcmp(c->string, "vertices") == 0 && cJSON_IsNumber(c) &&
        !(c->valuedouble <= RN_FUZZ_MAX_LINE_VERTICES))
      return 1;
    if (too_many_vertices(c)) return 1;
  }
  return 0;
}

static int skip_input(const uint8_t *data, size_t size) {
  cJSON *root = cJSON_ParseWithLength((const char *)data, size);
  int skip = too_many_vertices(root);
  cJSON_Delete(root);
  return skip;
}

/* The message of a failed call: one non-empty line. */
static void check_message(checker *c, const char *call) {
  const char *msg = rn_context_last_error(rn_network_context(c->net));
  if (!*msg) violation(c, "%s failed without a message", call);
  if (strchr(msg, '\n')) violation(c, "%s: message of several lines: %s", call, msg);
}

/* Status st of call with output v[n]: RN_OK and finite, or RN_DEGENERATE
 * with a message.  Returns 1 if the values may be used. */
static int check_values(checker *c, const char *call, rn_status st, const double *v,
                        size_t n) {
  if (st > 0) {
    check_message(c, call);
    return 0;
  }
  if (st < 0) {
    violation(c, "%s returned %s on an accepted scene: %s", call, rn_status_name(st),
              rn_context_last_error(rn_network_context(c->net)));
    return 0;
  }
  for (size_t i = 0; i < n; ++i)
    if (!isfinite(v[i])) {
      violation(c, "%s returned RN_OK with a non-finite value at [%zu]: %g", call, i,
                v[i]);
      return 0;
    }
  return 1;
}

/* Like check_values for outputs a[na] and b[nb] of one call. */
static void check_pair(checker *c, const char *call, rn_status st, const double *a,
                       size_t na, const double *b, size_t nb) {
  if (check_values(c, call, st, a, na)) check_values(c, call, st, b, nb);
}

/* Per-rod results at the current state; buf holds 12 nv doubles. */
static void check_rod(checker *c, int rod, double *buf) {
  rn_network *net = c->net;
  size_t n = (size_t)rn_network_rod_num_vertices(net, rod), ne = n - 1, nin = n - 2;
  double *a = buf, *b = buf + 3 * n, *d = buf + 6 * n, *e = buf + 9 * n;
  rn_status st = rn_network_rod_vertices(net, rod, a);
  check_values(c, "rn_network_rod_vertices", st, a, 3 * n);
  st = rn_network_rod_theta(net, rod, a);
  check_values(c, "rn_network_rod_theta", st, a, ne);
  st = rn_network_rod_rest_lengths(net, rod, a);
  check_values(c, "rn_network_rod_rest_lengths", st, a, ne);
  st = rn_network_rod_frames(net, rod, a, b);
  check_pair(c, "rn_network_rod_frames", st, a, 3 * ne, b, 3 * ne);
  st = rn_network_rod_strains(net, rod, a, b, d);
  check_pair(c, "rn_network_rod_strains", st, a, ne, b, 2 * nin);
  check_values(c, "rn_network_rod_strains", st, d, nin);
  st = rn_network_rod_vertex_fields(net, rod, a, b, d, e);
  check_pair(c, "rn_network_rod_vertex_fields", st, a, 2 * nin, b, nin);
  check_pair(c, "rn_network_rod_vertex_fields", st, d, nin, e, nin);
  st = rn_network_rod_edge_fields(net, rod, a, b);
  check_pair(c, "rn_network_rod_edge_fields", st, a, ne, b, ne);
}

/* Evaluations at the state x[n] (the current one). */
static void check_evaluations(checker *c, const double *x, size_t n, double *g,
                              double *v) {
  double terms[RN_TERM_COUNT], E = 0;
  size_t nnz = 0;
  const int64_t *rowptr = NULL;
  const int32_t *col = NULL;
  check_values(c, "rn_network_energy_terms", rn_network_energy_terms(c->net, x, terms),
               terms, RN_TERM_COUNT);
  if (check_values(c, "rn_network_gradient", rn_network_gradient(c->net, x, &E, g), g, n))
    check_values(c, "rn_network_gradient (energy)", RN_OK, &E, 1);
  for (size_t i = 0; i < n; ++i) v[i] = 1.0 / (1.0 + (double)(i % 7));
  check_values(c, "rn_network_hvp", rn_network_hvp(c->net, x, v, g), g, n);
  if (rn_network_hessian_pattern(c->net, &nnz, &rowptr, &col) != RN_OK) {
    violation(c, "rn_network_hessian_pattern failed");
    return;
  }
  double *vals = malloc((nnz ? nnz : 1) * sizeof *vals);
  if (!vals) return;
  check_values(c, "rn_network_hessian_values", rn_network_hessian_values(c->net, x, vals),
               vals, nnz);
  free(vals);
}

/* A periodic cell (docs/homogenization.md) at the state x[n]: its description
 * is consistent (dimension 2 or 3, 3 or 6 strain components, a positive finite
 * measure and finite vectors, strain DOF indices in range or -1), and the cell's
 * strain, stress and relative density are finite or RN_DEGENERATE. */
static void check_cell(checker *c, const double *x, size_t n) {
  int dim = -1, ns = -1;
  double measure = 0.0, vec[9], eps[6], sig[6], rho = 0.0;
  int64_t idx[6];
  if (rn_network_cell_info(c->net, &dim, &ns, &measure, vec) != RN_OK) {
    violation(c, "rn_network_cell_info failed");
    return;
  }
  if (dim == 0) return;
  if (!((dim == 2 && ns == 3) || (dim == 3 && ns == 6))) {
    violation(c, "a periodic cell of dimension %d with %d strain components", dim, ns);
    return;
  }
  if (!(measure > 0.0) || !isfinite(measure))
    violation(c, "a periodic cell of measure %g", measure);
  check_values(c, "rn_network_cell_info (vectors)", RN_OK, vec, 9);
  if (rn_network_cell_strain_dofs(c->net, idx) != RN_OK)
    violation(c, "rn_network_cell_strain_dofs failed");
  else
    for (int v = 0; v < ns; ++v)
      if (idx[v] < -1 || idx[v] >= (int64_t)n)
        violation(c, "strain component %d has the DOF index %lld of %zu", v,
                  (long long)idx[v], n);
  check_values(c, "rn_network_cell_strain", rn_network_cell_strain(c->net, x, eps), eps,
               (size_t)ns);
  check_values(c, "rn_network_cell_stress", rn_network_cell_stress(c->net, x, sig), sig,
               (size_t)ns);
  check_values(c, "rn_network_cell_relative_density",
               rn_network_cell_relative_density(c->net, &rho), &rho, 1);
}

static void check_network(checker *c) {
  size_t n = rn_network_num_dofs(c->net);
  int nrods = rn_network_num_rods(c->net), maxnv = 2;
  for (int r = 0; r < nrods; ++r)
    if (rn_network_rod_num_vertices(c->net, r) > maxnv)
      maxnv = rn_network_rod_num_vertices(c->net, r);
  double *x = malloc((n + 1) * sizeof *x), *g = malloc((n + 1) * sizeof *g);
  double *v = malloc((n + 1) * sizeof *v),
         *buf = malloc(12 * (size_t)maxnv * sizeof *buf);
  if (x && g && v && buf) {
    if (rn_network_get_dofs(c->net, x) != RN_OK)
      violation(c, "rn_network_get_dofs failed");
    else if (check_values(c, "rn_network_get_dofs", RN_OK, x, n)) {
      check_evaluations(c, x, n, g, v);
      check_cell(c, x, n);
      for (int r = 0; r < nrods; ++r) check_rod(c, r, buf);
      /* half the loads and prescribed motions */
      if (rn_network_set_load_factor(c->net, 0.5) != RN_OK)
        violation(c, "rn_network_set_load_factor(0.5) failed");
      else
        check_evaluations(c, x, n, g, v);
    }
  }
  free(x);
  free(g);
  free(v);
  free(buf);
}

static void check_scene(checker *c, const rn_scene *s) {
  long nv = 0;
  int nrods = rn_network_num_rods(c->net);
  for (int r = 0; r < nrods; ++r) {
    int k = rn_network_rod_num_vertices(c->net, r);
    if (k < 2) violation(c, "rod %d has %d vertices", r, k);
    if (rn_scene_find_rod(s, rn_network_rod_name(c->net, r)) != r)
      violation(c, "rod %d is not found by its name", r);
    nv += k;
  }
  if (nrods < 1) violation(c, "an accepted scene without rods");
  if (nv != rn_scene_num_vertices(s)) violation(c, "vertex counts disagree");
  rn_solve_options opt;
  memset(&opt, 0, sizeof opt);
  rn_scene_apply_solver(s, &opt);
  check_network(c);
}

int rn_fuzz_scene_check(const uint8_t *data, size_t size, const char *label,
                        rn_fuzz_result *res) {
  memset(res, 0, sizeof *res);
  if (skip_input(data, size)) {
    res->skipped = 1;
    return 0;
  }
  rn_context *ctx = NULL;
  rn_scene *s = NULL;
  checker c = {label, NULL, res};
  if (rn_context_create(&ctx) != RN_OK) return 0;
  res->status = rn_scene_parse(ctx, label, (const char *)data, size, &s);
  snprintf(res->message, sizeof res->message, "%s", rn_context_last_error(ctx));
  if (res->status == RN_OK) {
    if (!s || !(c.net = rn_scene_network(s)))
      violation(&c, "RN_OK without a scene");
    else
      check_scene(&c, s);
  } else {
    size_t n = strlen(label);
    if (s) violation(&c, "a scene returned with status %s", rn_status_name(res->status));
    if (res->status > 0) violation(&c, "positive status %d", (int)res->status);
    if (strncmp(res->message, label, n) != 0 || res->message[n] != ':')
      violation(&c, "message does not start with \"%s:\": \"%s\"", label, res->message);
    if (strchr(res->message, '\n'))
      violation(&c, "message of several lines: %s", res->message);
  }
  rn_scene_destroy(&s);
  rn_context_destroy(&ctx);
  return res->violations;
}
