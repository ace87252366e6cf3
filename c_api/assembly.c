/* assembly.c - energy, gradient, Hessian-vector product, energy split and
 * Hessian values: one loop over the stencils of every rod that calls the
 * kernels of rnk.h.  Evaluation is pure: nothing in the network changes and
 * all scratch lives on the stack (reentrant). */
#include <math.h>
#include <string.h>

#include "network_internal.h"

typedef enum { OP_ENERGY, OP_GRAD, OP_HVP, OP_HESS } eval_op;

typedef struct eval_args {
  eval_op op;
  const double *x; /* reduced state */
  const double *v; /* direction (OP_HVP) */
  double E[RN_TERM_COUNT];
  double *g;         /* OP_GRAD output, accumulated */
  double *Hv;        /* OP_HVP output, accumulated */
  double *vals;      /* OP_HESS output, accumulated */
  const char *where; /* public entry point, for messages */
} eval_args;

static rn_status degenerate(const rn_network *net, const eval_args *a, const char *term,
                            int rod, const char *what, int idx) {
  return rn_fail(net->ctx, RN_DEGENERATE, a->where,
                 "%s of rod %d ('%s') is degenerate at %s %d (zero-length edge or "
                 "opposite tangents)",
                 term, rod, rn_network_rod_name(net, rod), what, idx);
}

/* Accumulates a local gradient / HVP / Hessian block of a stencil. */
static void accumulate(const rn_network *net, eval_args *a, size_t s, int n,
                       const double *loc) {
  if (a->op == OP_GRAD) rn_scatter_add(net, loc, s, n, a->g);
  if (a->op == OP_HVP) rn_scatter_add(net, loc, s, n, a->Hv);
  if (a->op == OP_HESS) rn_csr_add_block(net, s, n, loc, a->vals);
}

static int stretch_eval(const rn_network *net, const rn_rod *r, int j, eval_args *a) {
  enum { N = RN_EDGE_STENCIL };
  size_t s = rn_dof_edge_stencil(r->off, j);
  const rnk_stretch_param *p = &r->sp[j];
  double q[N], vl[N], loc[N * N], E = 0.0;
  int rc = RNK_OK;
  rn_gather(net, a->x, s, N, q);
  switch (a->op) {
  case OP_ENERGY:
    rc = rnk_stretch_energy(q, p, &E);
    break;
  case OP_GRAD:
    rc = rnk_stretch_grad(q, p, &E, loc);
    break;
  case OP_HVP:
    rn_gather_dir(net, a->v, s, N, vl);
    rc = rnk_stretch_hvp(q, p, vl, loc);
    break;
  case OP_HESS:
    rc = rnk_stretch_hess(q, p, loc);
    break;
  }
  if (rc != RNK_OK) return rc;
  a->E[RN_TERM_STRETCH] += E;
  accumulate(net, a, s, N, loc);
  return RNK_OK;
}

/* Bending and twisting at interior vertex i share the edge frames: one
 * combined kernel (same values as rnk_bend_* + rnk_twist_*). */
static int bendtwist_eval(const rn_network *net, const rn_rod *r, int i, eval_args *a) {
  enum { N = RN_VERTEX_STENCIL };
  size_t s = rn_dof_vertex_stencil(r->off, i);
  const rnk_bend_param *bp = &r->bp[i - 1];
  rnk_twist_param tp = r->tp[i - 1];
  const rnk_frame *ref = &r->ref[i - 1];
  double q[N], vl[N], loc[N * N], Eb = 0.0, Et = 0.0;
  int rc = RNK_OK;
  tp.ref_twist = r->ref_twist[i - 1];
  rn_gather(net, a->x, s, N, q);
  switch (a->op) {
  case OP_ENERGY:
    rc = rnk_bendtwist_energy(q, ref, bp, &tp, &Eb, &Et);
    break;
  case OP_GRAD:
    rc = rnk_bendtwist_grad(q, ref, bp, &tp, &Eb, loc);
    break; /* sum */
  case OP_HVP:
    rn_gather_dir(net, a->v, s, N, vl);
    rc = rnk_bendtwist_hvp(q, ref, bp, &tp, vl, loc);
    break;
  case OP_HESS:
    rc = rnk_bendtwist_hess(q, ref, bp, &tp, loc);
    break;
  }
  if (rc != RNK_OK) return rc;
  a->E[RN_TERM_BEND] += Eb;
  a->E[RN_TERM_TWIST] += Et;
  accumulate(net, a, s, N, loc);
  return RNK_OK;
}

static int moment_eval(const rn_network *net, const rn_moment *mo, eval_args *a) {
  enum { N = RN_EDGE_STENCIL };
  const rn_rod *r = &net->rods[mo->rod];
  size_t s = rn_dof_edge_stencil(r->off, mo->edge);
  const rnk_frame *ref = &r->ref[mo->edge];
  rnk_moment_param p;
  double q[N], vl[N], loc[N * N], E = 0.0;
  int rc = RNK_OK;
  for (int k = 0; k < 3; ++k) p.M[k] = net->lambda * mo->M[k];
  if (p.M[0] == 0.0 && p.M[1] == 0.0 && p.M[2] == 0.0) return RNK_OK;
  memcpy(p.f0, mo->f0, sizeof(p.f0));
  p.angle0 = mo->angle0;
  rn_gather(net, a->x, s, N, q);
  switch (a->op) {
  case OP_ENERGY:
    rc = rnk_moment_energy(q, ref, &p, &E);
    break;
  case OP_GRAD:
    rc = rnk_moment_grad(q, ref, &p, &E, loc);
    break;
  case OP_HVP:
    rn_gather_dir(net, a->v, s, N, vl);
    rc = rnk_moment_hvp(q, ref, &p, vl, loc);
    break;
  case OP_HESS:
    rc = rnk_moment_hess(q, ref, &p, loc);
    break;
  }
  if (rc != RNK_OK) return rc;
  a->E[RN_TERM_LOAD] += E;
  accumulate(net, a, s, N, loc);
  return RNK_OK;
}

/* Dead vertex forces: E = -lambda f . x (Hessian zero). */
static void forces_eval(const rn_network *net, const rn_rod *r, eval_args *a) {
  for (int v = 0; v < r->nv; ++v) {
    size_t s = rn_dof_vertex(r->off, v);
    double f[3], xv[3], gl[3];
    for (int k = 0; k < 3; ++k) f[k] = net->lambda * r->fvert[3 * v + k];
    if (f[0] == 0.0 && f[1] == 0.0 && f[2] == 0.0) continue;
    rn_gather(net, a->x, s, RN_DOFS_PER_VERTEX, xv);
    a->E[RN_TERM_LOAD] += rnk_force_energy(xv, f);
    if (a->op == OP_GRAD) {
      rnk_force_grad(f, gl);
      rn_scatter_add(net, gl, s, RN_DOFS_PER_VERTEX, a->g);
    }
  }
}

static rn_status eval_rod(const rn_network *net, int ir, eval_args *a) {
  const rn_rod *r = &net->rods[ir];
  for (int j = 0; j < r->ne; ++j)
    if (stretch_eval(net, r, j, a) != RNK_OK)
      return degenerate(net, a, "stretching", ir, "edge", j);
  for (int i = 1; i < r->nv - 1; ++i)
    if (bendtwist_eval(net, r, i, a) != RNK_OK)
      return degenerate(net, a, "bending/twist", ir, "vertex", i);
  forces_eval(net, r, a);
  return RN_OK;
}

static rn_status eval_all(const rn_network *net, eval_args *a) {
  rn_status st;
  memset(a->E, 0, sizeof(a->E));
  for (int ir = 0; ir < net->nrods; ++ir)
    if ((st = eval_rod(net, ir, a))) return st;
  for (int im = 0; im < net->nmom; ++im)
    if (moment_eval(net, &net->moments[im], a) != RNK_OK)
      return degenerate(net, a, "moment", net->moments[im].rod, "vertex",
                        net->moments[im].vertex);
  return RN_OK;
}

static double sum_terms(const double E[RN_TERM_COUNT]) {
  double s = 0.0;
  for (int t = 0; t < RN_TERM_COUNT; ++t) s += E[t];
  return s;
}

static rn_status check_eval(const rn_network *net, const char *where, const double *x,
                            const void *out) {
  rn_status st;
  if ((st = rn_net_check_final(net, where))) return st;
  if ((!x || !out) && net->nred)
    return rn_fail(net->ctx, RN_ERR_ARG, where, "NULL array");
  if (!rn_all_finite(net->nred, x))
    return rn_fail(net->ctx, RN_ERR_NOT_FINITE, where, "x has NaN or infinite entries");
  return RN_OK;
}

rn_status rn_network_energy_terms(const rn_network *net, const double *x, double *E) {
  eval_args a;
  rn_status st;
  if (!net) return RN_ERR_ARG;
  if (!E) return rn_fail(net->ctx, RN_ERR_ARG, "rn_network_energy_terms", "E is NULL");
  if ((st = check_eval(net, "rn_network_energy_terms", x, E))) return st;
  memset(&a, 0, sizeof(a));
  a.where = "rn_network_energy";
  a.op = OP_ENERGY;
  a.x = x;
  if ((st = eval_all(net, &a))) return st;
  memcpy(E, a.E, sizeof(a.E));
  return RN_OK;
}

rn_status rn_network_energy(const rn_network *net, const double *x, double *E) {
  double terms[RN_TERM_COUNT];
  rn_status st;
  if (!net) return RN_ERR_ARG;
  if (!E) return rn_fail(net->ctx, RN_ERR_ARG, "rn_network_energy", "E is NULL");
  if ((st = rn_network_energy_terms(net, x, terms))) return st;
  *E = sum_terms(terms);
  return RN_OK;
}

rn_status rn_network_gradient(const rn_network *net, const double *x, double *E,
                              double *g) {
  eval_args a;
  rn_status st;
  if (!net) return RN_ERR_ARG;
  if ((st = check_eval(net, "rn_network_gradient", x, g))) return st;
  memset(&a, 0, sizeof(a));
  a.op = OP_GRAD;
  a.where = "rn_network_gradient";
  a.x = x;
  a.g = g;
  if (net->nred) memset(g, 0, net->nred * sizeof(double));
  if ((st = eval_all(net, &a))) return st;
  if (E) *E = sum_terms(a.E);
  return RN_OK;
}

rn_status rn_network_hvp(const rn_network *net, const double *x, const double *v,
                         double *Hv) {
  static const char *where = "rn_network_hvp";
  eval_args a;
  rn_status st;
  if (!net) return RN_ERR_ARG;
  if ((st = check_eval(net, where, x, Hv))) return st;
  if (!v && net->nred) return rn_fail(net->ctx, RN_ERR_ARG, where, "v is NULL");
  if (!rn_all_finite(net->nred, v))
    return rn_fail(net->ctx, RN_ERR_NOT_FINITE, where, "v has NaN or infinite entries");
  memset(&a, 0, sizeof(a));
  a.op = OP_HVP;
  a.where = where;
  a.x = x;
  a.v = v;
  a.Hv = Hv;
  if (net->nred) memset(Hv, 0, net->nred * sizeof(double));
  return eval_all(net, &a);
}

rn_status rn_network_hessian_values(const rn_network *net, const double *x,
                                    double *vals) {
  eval_args a;
  rn_status st;
  if (!net) return RN_ERR_ARG;
  if ((st = check_eval(net, "rn_network_hessian_values", x, vals))) return st;
  memset(&a, 0, sizeof(a));
  a.op = OP_HESS;
  a.where = "rn_network_hessian_values";
  a.x = x;
  a.vals = vals;
  if (net->nnz) memset(vals, 0, net->nnz * sizeof(double));
  return eval_all(net, &a);
}
