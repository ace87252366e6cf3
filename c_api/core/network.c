/* network.c - rn_network creation, rods, properties, rest shape, sizes and
 * state access. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/network_internal.h"

/* ---- shared checks ------------------------------------------------------- */
int rn_all_finite(size_t n, const double *v) {
  /* x * 0 is NaN exactly for infinite or NaN x: one test per 8 entries */
  size_t i = 0;
  for (; i + 8 <= n; i += 8) {
    double s = (v[i] * 0.0 + v[i + 1] * 0.0) + (v[i + 2] * 0.0 + v[i + 3] * 0.0) +
               (v[i + 4] * 0.0 + v[i + 5] * 0.0) + (v[i + 6] * 0.0 + v[i + 7] * 0.0);
    if (s != s) return 0;
  }
  for (; i < n; ++i)
    if (!isfinite(v[i])) return 0;
  return 1;
}

int rn_all_bounded(size_t n, const double *v) {
  double m = 0.0; /* the largest magnitude; NaN makes it fail below */
  int nan = 0;
  for (size_t i = 0; i < n; ++i) {
    double a = fabs(v[i]);
    m = a > m ? a : m;
    nan |= a != a;
  }
  return !nan && m <= RN_HESS_BOUND;
}

int rn_wrap_index(int i, int n) {
  if (i < 0) i += n;
  return (i >= 0 && i < n) ? i : -1;
}

rn_status rn_net_check_rod(const rn_network *net, const char *where, int *rod) {
  int g = *rod;
  rn_status st = rn_net_rod(net, where, rod);
  if (st == RN_NOT_HERE)
    return rn_fail(net->ctx, RN_ERR_RANGE, where,
                   "rod %d is held by another part of the network", g);
  return st;
}

rn_status rn_net_check_building(const rn_network *net, const char *where) {
  if (net->finalized)
    return rn_fail(net->ctx, RN_ERR_STATE, where,
                   "the network is finalized; its model can no longer change");
  return RN_OK;
}

rn_status rn_net_check_final(const rn_network *net, const char *where) {
  if (!net->finalized)
    return rn_fail(net->ctx, RN_ERR_STATE, where,
                   "the network is not finalized (call rn_network_finalize)");
  return RN_OK;
}

/* ---- lifecycle ------------------------------------------------------------ */
rn_status rn_network_create(rn_context *ctx, rn_network **net) {
  if (!net) return rn_fail(ctx, RN_ERR_ARG, __func__, "net is NULL");
  *net = calloc(1, sizeof(**net));
  if (!*net) return rn_fail(ctx, RN_ERR_ALLOC, __func__, "out of memory");
  (*net)->ctx = ctx;
  (*net)->lambda = 1.0;
  return RN_OK;
}

void rn_rod_free(rn_rod *r) {
  free(r->name);
  free(r->x0);
  free(r->mat);
  free(r->sec);
  free(r->has_mat);
  free(r->has_sec);
  free(r->lbar);
  free(r->kbar);
  free(r->taubar);
  free(r->ref_base);
  free(r->ref);
  free(r->ref_twist);
  free(r->pinned);
  free(r->has_vdisp);
  free(r->vdisp);
  free(r->theta_fixed);
  free(r->fpoint);
  free(r->fvert);
  free(r->sp);
  free(r->bp);
  free(r->tp);
  memset(r, 0, sizeof(*r));
}

/* ---- rods ------------------------------------------------------------------ */
static rn_status rod_alloc(rn_rod *r, int nv, const char *name) {
  size_t v = (size_t)nv, e = v - 1, in = v - 2;
  r->nv = nv;
  r->ne = nv - 1;
  r->joint[0] = r->joint[1] = -1;
  if (name) {
    r->name = malloc(strlen(name) + 1);
    if (r->name) strcpy(r->name, name);
  }
  r->x0 = calloc(3 * v, sizeof(double));
  r->mat = calloc(e, sizeof(rn_material));
  r->sec = calloc(e, sizeof(rn_section));
  r->has_mat = calloc(e, 1);
  r->has_sec = calloc(e, 1);
  r->lbar = calloc(e, sizeof(double));
  r->kbar = calloc(2 * in + 1, sizeof(double));
  r->taubar = calloc(in + 1, sizeof(double));
  r->ref_base = calloc(e, sizeof(rnk_frame));
  r->ref = calloc(e, sizeof(rnk_frame));
  r->ref_twist = calloc(in + 1, sizeof(double));
  r->pinned = calloc(v, 1);
  r->has_vdisp = calloc(v, 1);
  r->vdisp = calloc(3 * v, sizeof(double));
  r->theta_fixed = calloc(e, 1);
  r->fpoint = calloc(3 * v, sizeof(double));
  if ((name && !r->name) || !r->x0 || !r->mat || !r->sec || !r->has_mat || !r->has_sec ||
      !r->lbar || !r->kbar || !r->taubar || !r->ref_base || !r->ref || !r->ref_twist ||
      !r->pinned || !r->has_vdisp || !r->vdisp || !r->theta_fixed || !r->fpoint)
    return RN_ERR_ALLOC;
  return RN_OK;
}

static rn_status grow_rods(rn_network *net) {
  rn_rod *p;
  int cap;
  if (net->nrods < net->cap_rods) return RN_OK;
  cap = net->cap_rods ? 2 * net->cap_rods : 8;
  p = realloc(net->rods, (size_t)cap * sizeof(*p));
  if (!p) return RN_ERR_ALLOC;
  net->rods = p;
  net->cap_rods = cap;
  return RN_OK;
}

rn_status rn_network_add_rod(rn_network *net, const char *name, int nv, const double *xyz,
                             const double *d1, int *rod) {
  static const char *where = "rn_network_add_rod";
  rn_rod r;
  rn_status st;
  int keep;
  if (!net) return RN_ERR_ARG;
  if ((st = rn_net_check_building(net, where))) return st;
  if (!xyz) return rn_fail(net->ctx, RN_ERR_ARG, where, "xyz is NULL");
  if (nv < 2)
    return rn_fail(net->ctx, RN_ERR_ARG, where,
                   "rod '%s' needs at least 2 vertices, got %d", name ? name : "", nv);
  if (!rn_all_finite(3 * (size_t)nv, xyz))
    return rn_fail(net->ctx, RN_ERR_NOT_FINITE, where,
                   "rod '%s': a vertex coordinate is NaN or infinite", name ? name : "");
  if (d1 && !rn_all_finite(3, d1))
    return rn_fail(net->ctx, RN_ERR_NOT_FINITE, where, "rod '%s': d1 is not finite",
                   name ? name : "");
  if ((st = rn_part_add_rod(net, nv, xyz, &keep)) != RN_OK) {
    if (st == RN_NOT_HERE && rod) *rod = rn_net_rods_added(net) - 1;
    return rn_not_here_ok(st);
  }
  if (grow_rods(net)) return rn_fail(net->ctx, RN_ERR_ALLOC, where, "out of memory");
  memset(&r, 0, sizeof(r));
  rn_part_tag_rod(net, &r);
  if (rod_alloc(&r, nv, name)) {
    rn_rod_free(&r);
    return rn_fail(net->ctx, RN_ERR_ALLOC, where, "out of memory");
  }
  memcpy(r.x0, xyz, 3 * (size_t)nv * sizeof(double));
  st = rn_rod_init_frames(net->ctx, &r, net->nrods, d1);
  if (st) {
    rn_rod_free(&r);
    return st;
  }
  net->rods[net->nrods] = r;
  if (rod) *rod = r.gid;
  net->nrods++;
  return RN_OK;
}

int rn_network_rod_is_closed(const rn_network *net, int rod) {
  if (!net || rod < 0 || rod >= rn_net_num_rods_g(net)) return 0;
  if (rn_net_rod(net, "", &rod) != RN_OK) return 0;
  return net->rods[rod].closed;
}

/* Checks a building call on rod g (whole-network index) and edge (-1: all):
 * *lr receives the local index; RN_NOT_HERE if another part holds the rod
 * (the call then has no effect here). */
static rn_status check_edge_arg(const rn_network *net, const char *where, int g, int edge,
                                int *lr) {
  rn_status st;
  int ne;
  *lr = g;
  if ((st = rn_net_check_building(net, where))) return st;
  st = rn_net_rod(net, where, lr);
  if (st && st != RN_NOT_HERE) return st;
  ne = rn_net_rod_nv(net, g) - 1;
  if (edge < -1 || edge >= ne)
    return rn_fail(net->ctx, RN_ERR_RANGE, where,
                   "rod %d: edge %d out of range (-1 = all, %d edges)", g, edge, ne);
  return st;
}

rn_status rn_network_set_material(rn_network *net, int rod, int edge,
                                  const rn_material *m) {
  static const char *where = "rn_network_set_material";
  rn_status st;
  rn_rod *r;
  int lr;
  if (!net) return RN_ERR_ARG;
  st = check_edge_arg(net, where, rod, edge, &lr);
  if (st && st != RN_NOT_HERE) return st;
  if (!m) return rn_fail(net->ctx, RN_ERR_ARG, where, "material is NULL");
  if (!isfinite(m->E) || !isfinite(m->G) || !isfinite(m->density))
    return rn_fail(net->ctx, RN_ERR_NOT_FINITE, where, "rod %d: material is not finite",
                   rod);
  if (!(m->E > 0.0) || !(m->G > 0.0) || !(m->density >= 0.0))
    return rn_fail(
        net->ctx, RN_ERR_ARG, where,
        "rod %d: need E > 0, G > 0, density >= 0 (E = %g, G = %g, density = %g)", rod,
        m->E, m->G, m->density);
  if (st == RN_NOT_HERE) return RN_OK;
  r = &net->rods[lr];
  for (int j = 0; j < r->ne; ++j) {
    if (edge != -1 && j != edge) continue;
    r->mat[j] = *m;
    r->has_mat[j] = 1;
  }
  return RN_OK;
}

rn_status rn_network_set_section(rn_network *net, int rod, int edge,
                                 const rn_section *s) {
  static const char *where = "rn_network_set_section";
  rn_status st, here;
  rn_rod *r;
  int lr;
  if (!net) return RN_ERR_ARG;
  here = check_edge_arg(net, where, rod, edge, &lr);
  if (here && here != RN_NOT_HERE) return here;
  if (!s) return rn_fail(net->ctx, RN_ERR_ARG, where, "section is NULL");
  st = rn_section_validate(s);
  if (st)
    return rn_fail(
        net->ctx, st, where,
        "rod %d: invalid section (need finite A, I11, I22, J > 0 and "
        "I11 I22 - I12^2 > 0; got A = %g, I11 = %g, I22 = %g, I12 = %g, J = %g)",
        rod, s->A, s->I11, s->I22, s->I12, s->J);
  if (here == RN_NOT_HERE) return RN_OK;
  r = &net->rods[lr];
  for (int j = 0; j < r->ne; ++j) {
    if (edge != -1 && j != edge) continue;
    r->sec[j] = *s;
    r->has_sec[j] = 1;
  }
  return RN_OK;
}

/* ---- rest shape overrides ---------------------------------------------------- */
/* Checks a rest-shape call on rod g with n values v (finite unless what is
 * NULL); *lr as for check_edge_arg. */
static rn_status check_rest_arg(const rn_network *net, const char *where, int g,
                                const double *v, size_t n, const char *what, int *lr) {
  rn_status st, here;
  *lr = g;
  if ((st = rn_net_check_building(net, where))) return st;
  here = rn_net_rod(net, where, lr);
  if (here && here != RN_NOT_HERE) return here;
  if (!v) return rn_fail(net->ctx, RN_ERR_ARG, where, "rod %d: array is NULL", g);
  if (what && !rn_all_finite(n, v))
    return rn_fail(net->ctx, RN_ERR_NOT_FINITE, where, "rod %d: %s is not finite", g,
                   what);
  return here;
}

rn_status rn_network_set_rest_curvature(rn_network *net, int rod, const double *kappa) {
  static const char *where = "rn_network_set_rest_curvature";
  rn_status st;
  size_t n;
  int lr;
  if (!net) return RN_ERR_ARG;
  n = 2 * (size_t)(rn_net_rod_nv(net, rod) > 2 ? rn_net_rod_nv(net, rod) - 2 : 0);
  if ((st = check_rest_arg(net, where, rod, kappa, n, "curvature", &lr)))
    return rn_not_here_ok(st);
  if (n) memcpy(net->rods[lr].kbar, kappa, n * sizeof(double));
  return RN_OK;
}

rn_status rn_network_set_rest_twist(rn_network *net, int rod, const double *tau) {
  static const char *where = "rn_network_set_rest_twist";
  rn_status st;
  size_t n;
  int lr;
  if (!net) return RN_ERR_ARG;
  n = (size_t)(rn_net_rod_nv(net, rod) > 2 ? rn_net_rod_nv(net, rod) - 2 : 0);
  if ((st = check_rest_arg(net, where, rod, tau, n, "twist", &lr)))
    return rn_not_here_ok(st);
  if (n) memcpy(net->rods[lr].taubar, tau, n * sizeof(double));
  return RN_OK;
}

rn_status rn_network_set_rest_lengths(rn_network *net, int rod, const double *len) {
  static const char *where = "rn_network_set_rest_lengths";
  rn_status st;
  int lr, ne;
  if (!net) return RN_ERR_ARG;
  st = check_rest_arg(net, where, rod, len, 0, NULL, &lr);
  if (st && st != RN_NOT_HERE) return st;
  ne = rn_net_rod_nv(net, rod) - 1;
  for (int j = 0; j < ne; ++j) {
    if (!isfinite(len[j]))
      return rn_fail(net->ctx, RN_ERR_NOT_FINITE, where,
                     "rod %d edge %d: rest length is not finite", rod, j);
    if (!(len[j] > 0.0))
      return rn_fail(net->ctx, RN_ERR_GEOMETRY, where,
                     "rod %d edge %d: rest length must be > 0, got %g", rod, j, len[j]);
  }
  if (st == RN_NOT_HERE) return RN_OK;
  memcpy(net->rods[lr].lbar, len, (size_t)ne * sizeof(double));
  return RN_OK;
}

/* ---- sizes and state -------------------------------------------------------- */
size_t rn_joints_full_count(const rn_network *net) {
  size_t n = 0;
  for (int i = 0; i < net->njoints; ++i)
    n += rn_dof_joint_count(rn_joint_has_rotation(&net->joints[i]));
  return n;
}

size_t rn_network_num_dofs(const rn_network *net) {
  return (net && net->finalized) ? net->nred : 0;
}

size_t rn_network_num_full_dofs(const rn_network *net) {
  size_t n = 0;
  if (!net) return 0;
  for (int i = 0; i < net->nrods; ++i) n += rn_dof_rod_count(net->rods[i].nv);
  return n + rn_joints_full_count(net);
}

int rn_network_num_rods(const rn_network *net) {
  return net ? rn_net_num_rods_g(net) : 0;
}

int rn_network_rod_num_vertices(const rn_network *net, int rod) {
  return net ? rn_net_rod_nv(net, rod) : 0;
}

const char *rn_network_rod_name(const rn_network *net, int rod) {
  if (!net || !rn_network_rod_is_local(net, rod)) return "";
  if (net->part && rn_net_rod(net, "", &rod)) return "";
  return net->rods[rod].name ? net->rods[rod].name : "";
}

rn_context *rn_network_context(const rn_network *net) { return net ? net->ctx : NULL; }

rn_status rn_network_get_dofs(const rn_network *net, double *x) {
  static const char *where = "rn_network_get_dofs";
  rn_status st;
  if (!net) return RN_ERR_ARG;
  if ((st = rn_net_check_final(net, where))) return st;
  if (!x && net->nred) return rn_fail(net->ctx, RN_ERR_ARG, where, "x is NULL");
  for (size_t r = 0; r < net->nred; ++r) x[r] = net->xfull[net->red2full[r]];
  return RN_OK;
}

rn_status rn_network_set_dofs(rn_network *net, const double *x) {
  static const char *where = "rn_network_set_dofs";
  rn_status st;
  if (!net) return RN_ERR_ARG;
  if ((st = rn_net_check_final(net, where))) return st;
  if (!x && net->nred) return rn_fail(net->ctx, RN_ERR_ARG, where, "x is NULL");
  if (!rn_all_finite(net->nred, x))
    return rn_fail(net->ctx, RN_ERR_NOT_FINITE, where, "x has NaN or infinite entries");
  rn_expand_state(net, x, net->xfull); /* every alias of a reduced DOF */
  net->lambda_x = net->lambda;
  return rn_net_accept_state(net, where);
}
