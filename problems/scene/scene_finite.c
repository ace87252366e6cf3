/* scene_finite.c - the last check of the scene reader: the finalized network
 * is evaluated once at its initial state.  Every number of a scene is finite,
 * but their products need not be (E A, E I, G J, stiffness per rest length,
 * summed loads, a rest curvature times B, a rotation vector of 1e300 rad):
 * a scene whose initial energy, gradient, Hessian-vector product, vertex
 * positions or stencil fields overflow is rejected here with
 * RN_ERR_NOT_FINITE instead of handing NaN to the solver (found by
 * tests/fuzz).  A degenerate initial state (RN_DEGENERATE, e.g. prescribed
 * displacements that fold a rod at full load) is left to the solver, which
 * starts from small load factors. */
#include <math.h>
#include <stdlib.h>

#include "scene/scene_internal.h"

static int all_finite(const double *v, size_t n) {
  for (size_t i = 0; i < n; i++)
    if (!isfinite(v[i])) return 0;
  return 1;
}

static rn_status overflow(rn_scene_parser *p, const char *what) {
  return rn_jwalk_fail(&p->w, RN_ERR_NOT_FINITE,
                       "the %s at the initial state is not finite: a product of the "
                       "scene's numbers (stiffness E A, E I, G J per rest length, "
                       "summed loads, rest curvature or twist times stiffness, a "
                       "prescribed motion) overflows double precision",
                       what);
}

/* Status st of a call whose outputs v[n] are what: RN_OK and finite, or
 * degenerate (left to the solver), or an error. */
static rn_status judge(rn_scene_parser *p, rn_status st, const double *v, size_t n,
                       const char *what) {
  if (st == RN_OVERFLOW) return overflow(p, what);
  if (st > 0) return RN_OK;
  if (st < 0) return rn_jwalk_lib_error(&p->w, st);
  return all_finite(v, n) ? RN_OK : overflow(p, what);
}

/* Positions and stencil fields of every rod; buf holds 6 nv doubles. */
static rn_status check_rods(rn_scene_parser *p, rn_network *net, double *buf) {
  int nrods = rn_network_num_rods(net);
  rn_status st = RN_OK;
  for (int r = 0; r < nrods && !st; r++) {
    size_t nv = (size_t)rn_network_rod_num_vertices(net, r);
    if (!rn_network_rod_is_local(net, r)) continue; /* another part checks it */
    double *a = buf, *b = buf + 3 * nv;
    st = judge(p, rn_network_rod_vertices(net, r, a), a, 3 * nv, "position of a vertex");
    if (st) break;
    size_t nin = nv - 2;
    rn_status s2 = rn_network_rod_vertex_fields(net, r, a, b, b + nin, b + 2 * nin);
    st = judge(p, s2, a, 2 * nin, "bending moment");
    if (!st) st = judge(p, s2, b, 3 * nin, "twisting moment or energy");
    if (!st) s2 = rn_network_rod_edge_fields(net, r, a, b);
    if (!st) st = judge(p, s2, a, nv - 1, "axial force");
    if (!st) st = judge(p, s2, b, nv - 1, "stretching energy");
  }
  return st;
}

static rn_status check_evaluations(rn_scene_parser *p, rn_network *net, double *x,
                                   double *g, double *v) {
  size_t n = rn_network_num_dofs(net);
  double terms[RN_TERM_COUNT];
  rn_status st = rn_network_get_dofs(net, x);
  if (!st) st = judge(p, RN_OK, x, n, "state");
  if (!st) {
    rn_status s2 = rn_network_energy_terms(net, x, terms);
    st = judge(p, s2, terms, RN_TERM_COUNT, "energy");
  }
  if (!st) st = judge(p, rn_network_gradient(net, x, NULL, g), g, n, "gradient");
  for (size_t i = 0; i < n; i++) v[i] = 1.0;
  if (!st) st = judge(p, rn_network_hvp(net, x, v, g), g, n, "Hessian");
  return st;
}

rn_status rn_scene_check_finite(rn_scene_parser *p) {
  rn_network *net = p->scene->net;
  size_t n = rn_network_num_dofs(net) + 1, maxnv = 2;
  for (int r = 0; r < rn_network_num_rods(net); r++)
    if ((size_t)rn_network_rod_num_vertices(net, r) > maxnv)
      maxnv = (size_t)rn_network_rod_num_vertices(net, r);
  double *x = malloc(n * sizeof *x), *g = malloc(n * sizeof *g);
  double *v = malloc(n * sizeof *v), *buf = malloc(6 * maxnv * sizeof *buf);
  rn_status st = (x && g && v && buf)
                     ? check_evaluations(p, net, x, g, v)
                     : rn_jwalk_fail(&p->w, RN_ERR_ALLOC, "out of memory");
  if (!st) st = check_rods(p, net, buf);
  free(x);
  free(g);
  free(v);
  free(buf);
  return st;
}
