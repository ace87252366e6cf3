/* reactions.c - what an equilibrium check needs: the kind of every reduced DOF
 * (force or moment units), the gradient on the full layout, the largest applied
 * load, and the reactions of every support (constraint) in the global frame. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "eval/eval.h"
#include "joints/joints.h"
#include "periodic/periodic.h"
#include "rnk_couple.h"
#include "rodnet_couple.h"

rn_status rn_network_dof_kinds(const rn_network *net, int *kind) {
  static const char *where = "rn_network_dof_kinds";
  rn_status st;
  if (!net) return RN_ERR_ARG;
  if ((st = rn_net_check_final(net, where))) return st;
  if (!kind && net->nred) return rn_fail(net->ctx, RN_ERR_ARG, where, "kind is NULL");
  for (int ir = 0; ir < net->nrods; ++ir) {
    const rn_rod *r = &net->rods[ir];
    for (int v = 0; v < r->nv; ++v)
      for (int k = 0; k < RN_DOFS_PER_VERTEX; ++k) {
        const int64_t m = net->map[rn_dof_vertex(r->off, v) + (size_t)k];
        if (m >= 0) kind[m] = RN_DOF_POSITION;
      }
    for (int j = 0; j < r->ne; ++j) {
      const int64_t m = net->map[rn_dof_theta(r->off, j)];
      if (m >= 0) kind[m] = RN_DOF_THETA;
    }
  }
  for (int ij = 0; ij < net->njoints; ++ij) {
    const rn_joint *J = &net->joints[ij];
    for (int k = 0; k < 3; ++k) {
      const int64_t m = net->map[rn_dof_joint_position(J->off) + (size_t)k];
      if (m >= 0) kind[m] = RN_DOF_POSITION;
    }
    if (!rn_joint_has_rotation(J)) continue;
    for (int k = 0; k < 3; ++k) {
      const int64_t m = net->map[rn_dof_joint_rotation(J->off) + (size_t)k];
      if (m >= 0) kind[m] = RN_DOF_ROTATION;
    }
  }
  for (size_t v = 0; v < rn_cell_full_count(net); ++v) {
    const int64_t m = net->map[net->cell->off + v];
    if (m >= 0) kind[m] = RN_DOF_STRAIN;
  }
  return RN_OK;
}

rn_status rn_network_dof_info(const rn_network *net, rn_dof_info *info) {
  static const char *where = "rn_network_dof_info";
  rn_status st;
  if (!net) return RN_ERR_ARG;
  if ((st = rn_net_check_final(net, where))) return st;
  if (!info && net->nred) return rn_fail(net->ctx, RN_ERR_ARG, where, "info is NULL");
  for (int ir = 0; ir < net->nrods; ++ir) { /* rods first: joints overwrite aliases */
    const rn_rod *r = &net->rods[ir];
    for (int v = 0; v < r->nv; ++v)
      for (int k = 0; k < RN_DOFS_PER_VERTEX; ++k) {
        const int64_t m = net->map[rn_dof_vertex(r->off, v) + (size_t)k];
        if (m >= 0) info[m] = (rn_dof_info){RN_DOF_POSITION, r->gid, -1, v, k};
      }
    for (int j = 0; j < r->ne; ++j) {
      const int64_t m = net->map[rn_dof_theta(r->off, j)];
      if (m >= 0) info[m] = (rn_dof_info){RN_DOF_THETA, r->gid, -1, j, 0};
    }
  }
  for (int ij = 0; ij < net->njoints; ++ij) {
    const rn_joint *J = &net->joints[ij];
    for (int k = 0; k < 3; ++k) {
      const int64_t m = net->map[rn_dof_joint_position(J->off) + (size_t)k];
      if (m >= 0) info[m] = (rn_dof_info){RN_DOF_POSITION, -1, J->gid, 0, k};
      const int64_t w = rn_joint_has_rotation(J)
                            ? net->map[rn_dof_joint_rotation(J->off) + (size_t)k]
                            : -1;
      if (w >= 0) info[w] = (rn_dof_info){RN_DOF_ROTATION, -1, J->gid, 0, k};
    }
  }
  for (size_t v = 0; v < rn_cell_full_count(net); ++v) {
    const int64_t m = net->map[net->cell->off + v];
    if (m >= 0) info[m] = (rn_dof_info){RN_DOF_STRAIN, -1, -1, 0, (int)v};
  }
  return RN_OK;
}

rn_status rn_network_gradient_full(const rn_network *net, const double *x,
                                   double *gfull) {
  static const char *where = "rn_network_gradient_full";
  rn_status st;
  if (!net) return RN_ERR_ARG;
  if ((st = rn_net_check_final(net, where))) return st;
  if ((!x && net->nred) || !gfull)
    return rn_fail(net->ctx, RN_ERR_ARG, where, "NULL array");
  if (!rn_all_finite(net->nred, x))
    return rn_fail(net->ctx, RN_ERR_NOT_FINITE, where, "x has NaN or infinite entries");
  return rn_eval_gradient_full(net, x, gfull, where);
}

rn_status rn_network_gradient_magnitude(const rn_network *net, const double *x,
                                        double *gabs) {
  static const char *where = "rn_network_gradient_magnitude";
  rn_status st;
  if (!net) return RN_ERR_ARG;
  if ((st = rn_net_check_final(net, where))) return st;
  if ((!x || !gabs) && net->nred)
    return rn_fail(net->ctx, RN_ERR_ARG, where, "NULL array");
  if (!rn_all_finite(net->nred, x))
    return rn_fail(net->ctx, RN_ERR_NOT_FINITE, where, "x has NaN or infinite entries");
  if ((st = rn_eval_gradient_magnitude(net, x, gabs, where))) return st;
  rn_cell_hold_zero(net, gabs);
  return RN_OK;
}

static double norm3(const double v[3]) {
  return sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}

rn_status rn_network_applied_load_max(const rn_network *net, double *force,
                                      double *moment) {
  static const char *where = "rn_network_applied_load_max";
  rn_status st;
  double fbig = 0.0, mbig = 0.0;
  if (!net) return RN_ERR_ARG;
  if ((st = rn_net_check_final(net, where))) return st;
  if (!force || !moment) return rn_fail(net->ctx, RN_ERR_ARG, where, "NULL output");
  for (int ir = 0; ir < net->nrods; ++ir) {
    const rn_rod *r = &net->rods[ir];
    for (int v = 0; v < r->nv; ++v) fbig = fmax(fbig, norm3(&r->fvert[3 * v]));
  }
  for (int im = 0; im < net->nmom; ++im) mbig = fmax(mbig, norm3(net->moments[im].M));
  for (int ij = 0; ij < net->njoints; ++ij) {
    fbig = fmax(fbig, norm3(net->joints[ij].force));
    mbig = fmax(mbig, norm3(net->joints[ij].M));
    mbig = fmax(mbig, norm3(net->joints[ij].Mfix));
  }
  *force = fabs(net->lambda) * fbig;
  *moment = fabs(net->lambda) * mbig;
  return RN_OK;
}

/* Calls visit(net, support, ctx) for every support in the documented order;
 * returns the number of supports. */
typedef void (*support_visitor)(const rn_network *net, const rn_reaction *proto,
                                void *ctx);

static int for_each_support(const rn_network *net, support_visitor visit, void *ctx) {
  int n = 0;
  rn_reaction p;
  for (int ir = 0; ir < net->nrods; ++ir) {
    const rn_rod *r = &net->rods[ir];
    memset(&p, 0, sizeof p);
    p.rod = ir;
    if (r->clamped[RN_START]) {
      p.kind = RN_SUPPORT_CLAMP, p.index = 0, p.fixed = RN_FIX_XYZ, p.fixed_rotation = 1;
      if (visit) visit(net, &p, ctx);
      ++n;
    }
    for (int v = 0; v < r->nv; ++v) {
      if (rn_rod_in_clamp(r, v) || !r->pinned[v]) continue;
      p.kind = RN_SUPPORT_VERTEX, p.index = v, p.fixed = r->pinned[v],
      p.fixed_rotation = 0;
      if (visit) visit(net, &p, ctx);
      ++n;
    }
    for (int j = 0; j < r->ne; ++j) {
      if (!r->theta_fixed[j] || (r->clamped[RN_START] && j == 0) ||
          (r->clamped[RN_END] && j == r->ne - 1))
        continue;
      p.kind = RN_SUPPORT_THETA, p.index = j, p.fixed = 0, p.fixed_rotation = 0;
      if (visit) visit(net, &p, ctx);
      ++n;
    }
    if (r->clamped[RN_END]) {
      p.kind = RN_SUPPORT_CLAMP, p.index = 1, p.fixed = RN_FIX_XYZ, p.fixed_rotation = 1;
      if (visit) visit(net, &p, ctx);
      ++n;
    }
  }
  for (int ij = 0; ij < net->njoints; ++ij) {
    const rn_joint *J = &net->joints[ij];
    const int mask = rn_joint_fixed_components(J);
    if (!mask) continue;
    memset(&p, 0, sizeof p);
    p.kind = RN_SUPPORT_JOINT, p.rod = -1, p.index = ij, p.fixed = mask;
    p.fixed_rotation = J->clamped;
    if (visit) visit(net, &p, ctx);
    ++n;
  }
  return n;
}

int rn_network_num_supports(const rn_network *net) {
  if (!net || !net->finalized) return 0;
  return for_each_support(net, NULL, NULL);
}

typedef struct reaction_ctx {
  const double *full, *gfull; /* state and gradient, full layout */
  rn_reaction *out;
  int n;
} reaction_ctx;

static void add_scaled(double a[3], double s, const double b[3]) {
  for (int k = 0; k < 3; ++k) a[k] += s * b[k];
}

/* Adds the force f applied at y to the reaction (force, and moment about point). */
static void add_point_force(rn_reaction *R, const double y[3], const double f[3]) {
  const double d[3] = {y[0] - R->point[0], y[1] - R->point[1], y[2] - R->point[2]};
  add_scaled(R->force, 1.0, f);
  R->moment[0] += d[1] * f[2] - d[2] * f[1];
  R->moment[1] += d[2] * f[0] - d[0] * f[2];
  R->moment[2] += d[0] * f[1] - d[1] * f[0];
}

/* The material angle of edge j is a rotation about its tangent: its gradient is
 * the moment component along it. */
static void add_theta_moment(const reaction_ctx *c, const rn_rod *r, int j,
                             rn_reaction *R) {
  const double *x0 = &c->full[rn_dof_vertex(r->off, j)];
  const double *x1 = &c->full[rn_dof_vertex(r->off, j + 1)];
  double t[3] = {x1[0] - x0[0], x1[1] - x0[1], x1[2] - x0[2]};
  const double l = norm3(t);
  if (l > 0.0) add_scaled(R->moment, c->gfull[rn_dof_theta(r->off, j)] / l, t);
}

static void reaction_visit(const rn_network *net, const rn_reaction *proto, void *vctx) {
  reaction_ctx *c = vctx;
  rn_reaction *R = &c->out[c->n++];
  *R = *proto;
  if (proto->kind == RN_SUPPORT_JOINT) {
    const rn_joint *J = &net->joints[proto->index];
    const size_t p = rn_dof_joint_position(J->off);
    memcpy(R->point, &c->full[p], sizeof R->point);
    add_scaled(R->force, 1.0, &c->gfull[p]);
    for (int k = 0; k < J->valence; ++k) { /* the rod end slots alias the joint */
      const rn_rod *r = &net->rods[J->rod[k]];
      add_scaled(R->force, 1.0,
                 &c->gfull[rn_dof_vertex(r->off, rn_end_vertex(r->nv, J->end[k]))]);
    }
    for (int k = 0; k < 3; ++k)
      if (!rn_component_fixed(proto->fixed, k)) R->force[k] = 0.0;
    if (J->clamped && rn_joint_has_rotation(J))
      add_scaled(R->moment, 1.0, &c->gfull[rn_dof_joint_rotation(J->off)]);
  } else {
    const rn_rod *r = &net->rods[proto->rod];
    if (proto->kind == RN_SUPPORT_VERTEX) {
      const size_t s = rn_dof_vertex(r->off, proto->index);
      memcpy(R->point, &c->full[s], sizeof R->point);
      for (int k = 0; k < 3; ++k)
        if (rn_component_fixed(proto->fixed, k)) R->force[k] = c->gfull[s + (size_t)k];
    } else {
      const int j = proto->kind == RN_SUPPORT_THETA ? proto->index
                                                    : rn_end_edge(r->nv, proto->index);
      const double *x0 = &c->full[rn_dof_vertex(r->off, j)];
      const double *x1 = &c->full[rn_dof_vertex(r->off, j + 1)];
      for (int k = 0; k < 3; ++k) R->point[k] = 0.5 * (x0[k] + x1[k]);
      if (proto->kind == RN_SUPPORT_CLAMP) {
        add_point_force(R, x0, &c->gfull[rn_dof_vertex(r->off, j)]);
        add_point_force(R, x1, &c->gfull[rn_dof_vertex(r->off, j + 1)]);
      }
      add_theta_moment(c, r, j, R);
    }
  }
  /* reported with whole-network indices (a part numbers its rods and joints
     locally; the same in a whole network) */
  if (proto->kind == RN_SUPPORT_JOINT)
    R->index = net->joints[proto->index].gid;
  else
    R->rod = net->rods[proto->rod].gid;
}

rn_status rn_network_reactions(const rn_network *net, const double *x, rn_reaction *out,
                               int n) {
  static const char *where = "rn_network_reactions";
  rn_status st;
  if (!net) return RN_ERR_ARG;
  if ((st = rn_net_check_final(net, where))) return st;
  const int ns = for_each_support(net, NULL, NULL);
  if (n != ns)
    return rn_fail(net->ctx, RN_ERR_ARG, where, "n = %d, but the network has %d supports",
                   n, ns);
  if (!ns) return RN_OK;
  if (!out || (!x && net->nred))
    return rn_fail(net->ctx, RN_ERR_ARG, where, "NULL array");
  if (!rn_all_finite(net->nred, x))
    return rn_fail(net->ctx, RN_ERR_NOT_FINITE, where, "x has NaN or infinite entries");
  double *full = malloc(2 * net->nfull * sizeof(double));
  if (!full) return rn_fail(net->ctx, RN_ERR_ALLOC, where, "out of memory");
  reaction_ctx c = {full, full + net->nfull, out, 0};
  rn_expand_state(net, x, full);
  st = rn_eval_gradient_full(net, x, full + net->nfull, where);
  if (!st) for_each_support(net, reaction_visit, &c);
  free(full);
  return st;
}

static void cross_add(const double a[3], const double b[3], double out[3]) {
  out[0] += a[1] * b[2] - a[2] * b[1];
  out[1] += a[2] * b[0] - a[0] * b[2];
  out[2] += a[0] * b[1] - a[1] * b[0];
}

/* The spatial moment couple mo applies at the current state, per unit load
 * factor: M for a couple fixed in space; f x (M x f) / |n x f|^2 for the
 * conservative one (rnk_moment_spatial, docs/model.md "Loads"), M where that
 * is degenerate (f along M: the state is degenerate for the couple too). */
static void applied_couple(const rn_network *net, const rn_moment *mo, double m[3]) {
  const rn_rod *r = &net->rods[mo->rod];
  const double *x = net->xfull + rn_dof_edge_stencil(r->off, mo->edge);
  double e[3], F[9];
  memcpy(m, mo->M, 3 * sizeof(double));
  if (mo->model != RN_COUPLE_CONSERVATIVE) return;
  for (int k = 0; k < 3; ++k) e[k] = x[RN_EDGE_LOCAL_X1 + k] - x[RN_EDGE_LOCAL_X0 + k];
  if (rnk_material_frame(e, &r->ref[mo->edge], x[RN_EDGE_LOCAL_THETA], F, F + 3, F + 6) !=
          RNK_OK ||
      rnk_moment_spatial(F, mo->b, mo->M, m) != RNK_OK)
    memcpy(m, mo->M, 3 * sizeof(double));
}

/* The same for the couples on joint ij: M for the one fixed in space plus,
 * for the conservative one, f x (M x f) / |n x f|^2 with f = Q couple_p, Q
 * the joint's current rotation (M where that is degenerate). */
static void applied_joint_couple(const rn_network *net, int ij, double m[3]) {
  const rn_joint *J = &net->joints[ij];
  double mc[3], Q[9], F[9];
  rn_joint_scratch s;
  rnk_joint kj;
  memcpy(mc, J->M, sizeof mc);
  if (norm3(J->M) > 0.0 && J->model != RN_JOINT_SMOOTH && !J->ghost &&
      rn_joint_scratch_init(J, &s) == RN_OK) {
    rn_joint_kernel(net, ij, 1.0, s.refs, &kj);
    rn_joint_gather_full(net, J, net->xfull, s.q);
    if (rnk_joint_rotation(s.q, &kj, Q) == RNK_OK) {
      for (int a = 0; a < 3; ++a) /* rows of F: the columns of Q */
        for (int k = 0; k < 3; ++k) F[3 * k + a] = Q[3 * a + k];
      if (rnk_moment_spatial(F, J->couple_p, J->M, mc) != RNK_OK)
        memcpy(mc, J->M, sizeof mc);
    }
    rn_joint_scratch_free(&s);
  }
  for (int k = 0; k < 3; ++k) m[k] = mc[k] + J->Mfix[k];
}

rn_status rn_network_applied_resultant(const rn_network *net, double force[3],
                                       double moment[3]) {
  static const char *where = "rn_network_applied_resultant";
  rn_status st;
  if (!net) return RN_ERR_ARG;
  if ((st = rn_net_check_final(net, where))) return st;
  if (!force || !moment) return rn_fail(net->ctx, RN_ERR_ARG, where, "NULL output");
  const double lam = net->lambda, *xf = net->xfull;
  double F[3] = {0, 0, 0}, M[3] = {0, 0, 0};
  for (int ir = 0; ir < net->nrods; ++ir) {
    const rn_rod *r = &net->rods[ir];
    for (int v = 0; v < r->nv; ++v) {
      const double f[3] = {lam * r->fvert[3 * v], lam * r->fvert[3 * v + 1],
                           lam * r->fvert[3 * v + 2]};
      add_scaled(F, 1.0, f);
      cross_add(&xf[rn_dof_vertex(r->off, v)], f, M);
    }
  }
  for (int im = 0; im < net->nmom; ++im) {
    double m[3];
    applied_couple(net, &net->moments[im], m);
    add_scaled(M, lam, m);
  }
  for (int ij = 0; ij < net->njoints; ++ij) {
    const rn_joint *J = &net->joints[ij];
    const double f[3] = {lam * J->force[0], lam * J->force[1], lam * J->force[2]};
    add_scaled(F, 1.0, f);
    cross_add(&xf[rn_dof_joint_position(J->off)], f, M);
    double m[3];
    applied_joint_couple(net, ij, m);
    add_scaled(M, lam, m);
  }
  memcpy(force, F, sizeof F);
  memcpy(moment, M, sizeof M);
  return RN_OK;
}

/* Internal forces of rod `rod` from the reduced state x; g: full-layout scratch,
 * zero on entry over the rod's DOFs and left zero there. */
static rn_status rod_internal(const rn_network *net, int rod, const double *x, double *g,
                              double *force, double *moment, const char *where) {
  const rn_rod *r = &net->rods[rod];
  rn_status st = rn_eval_rod_gradient_full(net, rod, x, g, where);
  /* F and the moment about the origin of the part before the cut, then moved
   * to the edge midpoint: M_c = M_0 - c x F (moments of the left part's
   * stencil forces, negated: what the right part exerts on it). */
  double F[3] = {0, 0, 0}, M0[3] = {0, 0, 0}, T[3] = {0, 0, 0};
  const double *xf = net->xfull;
  for (int j = 0; !st && j < r->ne; ++j) {
    const double *gv = &g[rn_dof_vertex(r->off, j)];
    const double *a = &xf[rn_dof_vertex(r->off, j)],
                 *b = &xf[rn_dof_vertex(r->off, j + 1)];
    double t[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, c[3], Mc[3];
    const double l = norm3(t), gt = g[rn_dof_theta(r->off, j)] / (l > 0.0 ? l : 1.0);
    add_scaled(F, -1.0, gv);
    double ga[3] = {-gv[0], -gv[1], -gv[2]};
    cross_add(a, ga, M0);
    for (int k = 0; k < 3; ++k) c[k] = 0.5 * (a[k] + b[k]);
    /* the twist moments of the edges before the cut; half of the cut edge's */
    for (int k = 0; k < 3; ++k) Mc[k] = M0[k] - T[k] - 0.5 * gt * t[k];
    double mF[3] = {-F[0], -F[1], -F[2]};
    cross_add(c, mF, Mc);
    add_scaled(T, gt, t);
    memcpy(&force[3 * j], F, sizeof F);
    memcpy(&moment[3 * j], Mc, sizeof Mc);
  }
  /* the rod's stencils wrote its vertices and angles only (and, in a periodic
   * cell, strain entries, which are not read here) */
  for (int v = 0; v < r->nv; ++v) memset(&g[rn_dof_vertex(r->off, v)], 0, 3 * sizeof *g);
  for (int j = 0; j < r->ne; ++j) g[rn_dof_theta(r->off, j)] = 0.0;
  return st;
}

/* x: the reduced state; g: a zeroed full-layout vector (both allocated here). */
static rn_status internal_scratch(const rn_network *net, double **x, double **g,
                                  const char *where) {
  *x = malloc((net->nred + 1) * sizeof(double));
  *g = calloc(net->nfull + 1, sizeof(double));
  if (!*x || !*g) {
    free(*x);
    free(*g);
    return rn_fail(net->ctx, RN_ERR_ALLOC, where, "out of memory");
  }
  rn_network_get_dofs(net, *x);
  return RN_OK;
}

rn_status rn_network_rod_internal_forces(const rn_network *net, int rod, double *force,
                                         double *moment) {
  static const char *where = "rn_network_rod_internal_forces";
  rn_status st;
  if (!net) return RN_ERR_ARG;
  if ((st = rn_net_check_final(net, where))) return st;
  if (rod < 0 || rod >= net->nrods)
    return rn_fail(net->ctx, RN_ERR_RANGE, where, "rod %d out of range (%d rods)", rod,
                   net->nrods);
  if (!force || !moment) return rn_fail(net->ctx, RN_ERR_ARG, where, "NULL output");
  double *x, *g;
  if ((st = internal_scratch(net, &x, &g, where))) return st;
  st = rod_internal(net, rod, x, g, force, moment, where);
  free(x);
  free(g);
  return st;
}

rn_status rn_network_internal_forces(const rn_network *net, double *force,
                                     double *moment) {
  static const char *where = "rn_network_internal_forces";
  rn_status st;
  if (!net) return RN_ERR_ARG;
  if ((st = rn_net_check_final(net, where))) return st;
  if (!force || !moment) return rn_fail(net->ctx, RN_ERR_ARG, where, "NULL output");
  double *x, *g;
  if ((st = internal_scratch(net, &x, &g, where))) return st;
  size_t e = 0;
  for (int ir = 0; !st && ir < net->nrods; ++ir) {
    st = rod_internal(net, ir, x, g, force + 3 * e, moment + 3 * e, where);
    e += (size_t)net->rods[ir].ne;
  }
  free(x);
  free(g);
  return st;
}
