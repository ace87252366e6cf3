/* assembly.c - energy, gradient, Hessian-vector product, energy split and
 * Hessian values: one loop over the stencils of every rod and joint that
 * calls the kernels of rnk.h.  Evaluation is pure: nothing in the network changes and
 * all scratch lives on the stack (reentrant). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "contact/contact.h"
#include "eval/eval.h"
#include "joints/joints.h"
#include "periodic/periodic.h"
#include "rnk_couple.h"
#include "rodnet_couple.h"

typedef enum { OP_ENERGY, OP_GRAD, OP_HVP, OP_HESS } eval_op;

typedef struct eval_args {
  eval_op op;
  const double *x; /* reduced state */
  const double *v; /* direction (OP_HVP) */
  /* OP_HVP: if set, the direction is given on the full layout and only its
   * fixed entries count (free entries read as 0): H_{free,fixed} vfull */
  const double *vfull;
  double lambda;  /* scale of the loads (normally the network's load factor) */
  int loads_only; /* 1: only the load terms (forces, couples) */
  double E[RN_TERM_COUNT];
  double *g;           /* OP_GRAD output, accumulated */
  double *Hv;          /* OP_HVP output, accumulated */
  double *vals;        /* OP_HESS output, accumulated */
  rn_bloch_acc *bloch; /* OP_HESS: into this Bloch matrix instead of vals */
  int unbounded;       /* OP_HESS: a contribution exceeded RN_HESS_BOUND or was not
                          finite (then the sums may overflow) */
  const char *where;   /* public entry point, for messages */

  /* OP_GRAD variants (reactions.c): on the full layout instead of g
   * (rn_eval_gradient_full); |local gradient| into g (rn_eval_gradient_magnitude) */
  double *gfull;
  int magnitude;
} eval_args;

static rn_status degenerate(const rn_network *net, const eval_args *a, const char *term,
                            int rod, const char *what, int idx) {
  const rn_rod *r = &net->rods[rod];
  return rn_fail(net->ctx, RN_DEGENERATE, a->where,
                 "%s of rod %d ('%s') is degenerate at %s %d (zero-length edge or "
                 "opposite tangents)",
                 term, r->gid, r->name ? r->name : "", what, idx);
}

/* Local direction of a stencil starting at full index s (OP_HVP). */
static void gather_dir(const rn_network *net, const eval_args *a, size_t s, int n,
                       double *vl) {
  if (a->vfull)
    rn_gather_fixed_dir(net, a->vfull, s, n, vl);
  else
    rn_gather_dir(net, a->v, s, n, vl);
}

/* Accumulates a local gradient of n DOFs at full index s (or by index list idx). */
static void scatter_grad(const rn_network *net, eval_args *a, const double *gl, size_t s,
                         const size_t *idx, const int32_t *img, int n) {
  double mag[RN_VERTEX_STENCIL];
  if (a->magnitude) { /* stencils of rods and loads only (joints: by blocks below) */
    for (int b = 0; b < n; b += RN_VERTEX_STENCIL) {
      const int m = n - b < RN_VERTEX_STENCIL ? n - b : RN_VERTEX_STENCIL;
      for (int k = 0; k < m; ++k) mag[k] = fabs(gl[b + k]);
      if (idx) {
        rn_scatter_add_idx(net, mag, idx + b, m, a->g);
        if (img) rn_cell_scatter(net, mag, 0, idx + b, img + b, m, a->g);
      } else
        rn_scatter_add(net, mag, s + (size_t)b, m, a->g);
    }
    return;
  }
  if (a->gfull) {
    for (int k = 0; k < n; ++k) a->gfull[idx ? idx[k] : s + (size_t)k] += gl[k];
    if (net->cell) rn_cell_scatter_full(net, gl, s, idx, img, n, a->gfull);
  } else if (idx) {
    rn_scatter_add_idx(net, gl, idx, n, a->g);
    if (img) rn_cell_scatter(net, gl, 0, idx, img, n, a->g);
  } else
    rn_scatter_add(net, gl, s, n, a->g);
}

/* Accumulates a local gradient / HVP / Hessian block of a stencil. */
static void accumulate(const rn_network *net, eval_args *a, size_t s, int n,
                       const double *loc) {
  if (a->op == OP_GRAD) scatter_grad(net, a, loc, s, NULL, NULL, n);
  if (a->op == OP_HVP) rn_scatter_add(net, loc, s, n, a->Hv);
  if (a->op == OP_HESS) {
    a->unbounded |= !rn_all_bounded((size_t)n * (size_t)n, loc);
    if (a->bloch) {
      rn_bloch_add_block(net, a->bloch, s, NULL, NULL, n, loc, NULL);
      return;
    }
    rn_csr_add_block(net, s, n, loc, a->vals);
    if (net->cell) rn_cell_hess_block(net, s, NULL, NULL, n, loc, a->vals);
  }
}

/* Rods are evaluated by the whole-rod kernels (rnk_rod_*) in segments of up
 * to RN_ROD_SEGMENT edges: the segment's slice of the full state is gathered
 * onto the stack, the kernels compute each edge's frame once for both of its
 * vertices, and the result is scattered back (the Hessian as band rows, by
 * the positions computed at finalize).  Consecutive segments share one edge;
 * its stretching is counted by the first. */
enum { RN_ROD_SEGMENT_DOFS = 4 * RN_ROD_SEGMENT + 3 };

static rn_status rod_degenerate(const rn_network *net, const eval_args *a, int ir, int j0,
                                const int bad[2]) {
  if (bad[0] >= 0) return degenerate(net, a, "stretching", ir, "edge", j0 + bad[0]);
  return degenerate(net, a, "bending/twist", ir, "vertex", j0 + bad[1]);
}

/* The stretching, bending and twisting of edges [j0, j0 + ne) of rod r and of
 * the interior vertices between them, through a copy of the segment's DOFs
 * on the stack (ne <= RN_ROD_SEGMENT). */
static rn_status rod_segment_eval(const rn_network *net, int ir, int j0, int ne,
                                  eval_args *a) {
  const rn_rod *r = &net->rods[ir];
  size_t s = rn_dof_edge_stencil(r->off, j0);
  int n = 4 * ne + 3, bad[2], rc = RNK_OK;
  double x[RN_ROD_SEGMENT_DOFS], v[RN_ROD_SEGMENT_DOFS], out[RN_ROD_SEGMENT_DOFS];
  double band[RN_ROD_SEGMENT_DOFS * RNK_BAND], E[3] = {0.0, 0.0, 0.0};
  rnk_rod_seg seg = {ne, x,          r->ref + j0, r->sp + j0,       j0 ? 1 : 0,
                     ne, r->bp + j0, r->tp + j0,  r->ref_twist + j0};
  rn_gather(net, a->x, s, n, x);
  switch (a->op) {
  case OP_ENERGY:
    rc = rnk_rod_energy(&seg, E, bad);
    break;
  case OP_GRAD:
    memset(out, 0, (size_t)n * sizeof(double));
    if ((rc = rnk_rod_grad(&seg, E, out, bad)) == RNK_OK)
      rn_scatter_add(net, out, s, n, a->g);
    break;
  case OP_HVP:
    gather_dir(net, a, s, n, v);
    memset(out, 0, (size_t)n * sizeof(double));
    if ((rc = rnk_rod_hvp(&seg, v, out, bad)) == RNK_OK)
      rn_scatter_add(net, out, s, n, a->Hv);
    break;
  case OP_HESS:
    memset(band, 0, (size_t)n * RNK_BAND * sizeof(double));
    if ((rc = rnk_rod_hess(&seg, band, bad)) == RNK_OK && a->bloch) {
      a->unbounded |= !rn_all_bounded((size_t)n * RNK_BAND, band);
      rn_bloch_add_band(net, a->bloch, s, n, band);
    } else if (rc == RNK_OK) {
      a->unbounded |= !rn_csr_add_band(net, s, n, band, a->vals);
      if (net->cell) rn_cell_hess_band(net, s, n, band, a->vals);
    }
    break;
  }
  if (rc != RNK_OK) return rod_degenerate(net, a, ir, j0, bad);
  a->E[RN_TERM_STRETCH] += E[0];
  a->E[RN_TERM_BEND] += E[1];
  a->E[RN_TERM_TWIST] += E[2];
  return RN_OK;
}

/* The same for edges whose DOFs are free, distinct and consecutive in the
 * reduced vector (rn_rod_direct_edges): the kernels read x (and v) and
 * accumulate into g (Hv) in place, with no copy, however long the run. */
static rn_status rod_direct_eval(const rn_network *net, int ir, int j0, int ne,
                                 eval_args *a) {
  const rn_rod *r = &net->rods[ir];
  size_t m = (size_t)net->map[rn_dof_edge_stencil(r->off, j0)];
  int bad[2], rc = RNK_OK;
  double E[3] = {0.0, 0.0, 0.0};
  rnk_rod_seg seg = {ne, a->x + m,   r->ref + j0, r->sp + j0,       j0 ? 1 : 0,
                     ne, r->bp + j0, r->tp + j0,  r->ref_twist + j0};
  switch (a->op) {
  case OP_ENERGY:
    rc = rnk_rod_energy(&seg, E, bad);
    break;
  case OP_GRAD:
    rc = rnk_rod_grad(&seg, E, a->g + m, bad);
    break;
  case OP_HVP: /* (a direction on the fixed DOFs only is zero here) */
    if (!a->vfull) rc = rnk_rod_hvp(&seg, a->v + m, a->Hv + m, bad);
    break;
  case OP_HESS:
    return rod_segment_eval(net, ir, j0, ne, a); /* (not reached) */
  }
  if (rc != RNK_OK) return rod_degenerate(net, a, ir, j0, bad);
  a->E[RN_TERM_STRETCH] += E[0];
  a->E[RN_TERM_BEND] += E[1];
  a->E[RN_TERM_TWIST] += E[2];
  return RN_OK;
}

/* Rod ir's stretching, bending and twisting gradient stencil by stencil, for
 * the gradient variants that need each stencil's own contribution (on the full
 * layout, or its magnitude): the stencil kernels of rnk.h, same values as the
 * whole-rod kernels.  Off the hot path (reactions, round-off floors). */
static rn_status rod_stencils_grad_each(const rn_network *net, int ir, eval_args *a) {
  const rn_rod *r = &net->rods[ir];
  double q[RN_VERTEX_STENCIL], gl[RN_VERTEX_STENCIL], E = 0.0;
  for (int j = 0; j < r->ne; ++j) {
    size_t s = rn_dof_edge_stencil(r->off, j);
    rn_gather(net, a->x, s, RN_EDGE_STENCIL, q);
    if (rnk_stretch_grad(q, &r->sp[j], &E, gl) != RNK_OK)
      return degenerate(net, a, "stretching", ir, "edge", j);
    a->E[RN_TERM_STRETCH] += E;
    scatter_grad(net, a, gl, s, NULL, NULL, RN_EDGE_STENCIL);
  }
  for (int i = 1; i < r->nv - 1; ++i) {
    size_t s = rn_dof_vertex_stencil(r->off, i);
    rnk_twist_param tp = r->tp[i - 1];
    tp.ref_twist = r->ref_twist[i - 1];
    rn_gather(net, a->x, s, RN_VERTEX_STENCIL, q);
    if (rnk_bendtwist_grad(q, &r->ref[i - 1], &r->bp[i - 1], &tp, &E, gl) != RNK_OK)
      return degenerate(net, a, "bending/twist", ir, "vertex", i);
    a->E[RN_TERM_BEND] += E; /* the sum is what counts here */
    scatter_grad(net, a, gl, s, NULL, NULL, RN_VERTEX_STENCIL);
  }
  return RN_OK;
}

/* All of rod ir's stretching, bending and twisting: segments that share one
 * edge with the next (its stretching counted once), copied ones of at most
 * RN_ROD_SEGMENT edges and, for the energy, gradient and HVP, one in-place
 * segment over the rod's run of free consecutive DOFs. */
static rn_status rod_stencils_eval(const rn_network *net, int ir, eval_args *a) {
  const rn_rod *r = &net->rods[ir];
  if (a->op == OP_GRAD && (a->gfull || a->magnitude))
    return rod_stencils_grad_each(net, ir, a);
  int lo = a->op == OP_HESS ? 0 : net->rod_direct[2 * ir];
  int hi = a->op == OP_HESS ? 0 : net->rod_direct[2 * ir + 1];
  for (int j0 = 0;;) {
    int j1, direct = j0 >= lo && hi - j0 >= 2;
    if (direct)
      j1 = hi;
    else {
      j1 = j0 + RN_ROD_SEGMENT < r->ne ? j0 + RN_ROD_SEGMENT : r->ne;
      if (j0 < lo && j1 > lo + 1) j1 = lo + 1; /* the next starts the run */
    }
    rn_status st = direct ? rod_direct_eval(net, ir, j0, j1 - j0, a)
                          : rod_segment_eval(net, ir, j0, j1 - j0, a);
    if (st) return st;
    if (j1 == r->ne) return RN_OK;
    j0 = j1 - 1;
  }
}

/* A couple fixed in space (rodnet_couple.h): no energy; the gradient gets
 * -Q (the residual) and the Hessian -J (the residual's Jacobian,
 * nonsymmetric). */
static int fixed_couple_eval(const rn_network *net, const rn_moment *mo,
                             const double M[3], eval_args *a) {
  enum { N = RN_EDGE_STENCIL };
  const rn_rod *r = &net->rods[mo->rod];
  size_t s = rn_dof_edge_stencil(r->off, mo->edge);
  double q[N], Q[N], J[N * N], vl[N], loc[N * N];
  int rc;
  if (a->op == OP_ENERGY) return RNK_OK;
  rn_gather(net, a->x, s, N, q);
  rc = rnk_couple_fixed_force(q, &r->ref[mo->edge], M, Q, a->op == OP_GRAD ? NULL : J);
  if (rc != RNK_OK) return rc;
  if (a->op == OP_GRAD) {
    for (int i = 0; i < N; ++i) loc[i] = -Q[i];
  } else if (a->op == OP_HVP) {
    gather_dir(net, a, s, N, vl);
    for (int i = 0; i < N; ++i) {
      loc[i] = 0.0;
      for (int j = 0; j < N; ++j) loc[i] -= J[N * i + j] * vl[j];
    }
  } else {
    for (int i = 0; i < N * N; ++i) loc[i] = -J[i];
  }
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
  for (int k = 0; k < 3; ++k) p.M[k] = a->lambda * mo->M[k];
  if (p.M[0] == 0.0 && p.M[1] == 0.0 && p.M[2] == 0.0) return RNK_OK;
  if (mo->model == RN_COUPLE_FIXED) return fixed_couple_eval(net, mo, p.M, a);
  memcpy(p.f0, mo->f0, sizeof(p.f0));
  p.angle0 = mo->angle0;
  memcpy(p.b, mo->b, sizeof(p.b));
  rn_gather(net, a->x, s, N, q);
  switch (a->op) {
  case OP_ENERGY:
    rc = rnk_moment_energy(q, ref, &p, &E);
    break;
  case OP_GRAD:
    rc = rnk_moment_grad(q, ref, &p, &E, loc);
    break;
  case OP_HVP:
    gather_dir(net, a, s, N, vl);
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

/* Dead vertex forces: E = -lambda f . (x - x0), the potential measured from the
 * initial state x0 (so it does not depend on where the origin is); Hessian zero. */
static void forces_eval(const rn_network *net, const rn_rod *r, eval_args *a) {
  for (int v = 0; v < r->nv; ++v) {
    size_t s = rn_dof_vertex(r->off, v);
    double f[3], xv[3], gl[3];
    for (int k = 0; k < 3; ++k) f[k] = a->lambda * r->fvert[3 * v + k];
    if (f[0] == 0.0 && f[1] == 0.0 && f[2] == 0.0) continue;
    rn_gather(net, a->x, s, RN_DOFS_PER_VERTEX, xv);
    for (int k = 0; k < 3; ++k) xv[k] -= r->x0[3 * v + k];
    a->E[RN_TERM_LOAD] += rnk_force_energy(xv, f);
    if (a->op == OP_GRAD) {
      rnk_force_grad(f, gl);
      scatter_grad(net, a, gl, s, NULL, NULL, RN_DOFS_PER_VERTEX);
    }
  }
}

/* Energy of a joint split into its elastic part (RN_TERM_BEND) and the work
 * of its couple, -|M| (angle0 + alpha) (RN_TERM_LOAD). */
static int joint_energy_split(rn_joint_scratch *s, rnk_joint *kj, eval_args *a) {
  double M[3], Eb = 0.0, alpha = 0.0, m;
  int rc;
  if (kj->smooth) { /* a DER vertex: bending and twisting as in rods, no couple */
    double Et = 0.0;
    if ((rc = rnk_smooth_joint_energy(s->q, kj, &Eb, &Et)) != RNK_OK) return rc;
    a->E[RN_TERM_BEND] += Eb;
    a->E[RN_TERM_TWIST] += Et;
    return RNK_OK;
  }
  memcpy(M, kj->M, sizeof(M));
  memset(kj->M, 0, sizeof(kj->M));
  if ((rc = rnk_joint_energy(s->q, kj, s->work, &Eb)) != RNK_OK) return rc;
  a->E[RN_TERM_BEND] += Eb;
  m = sqrt(M[0] * M[0] + M[1] * M[1] + M[2] * M[2]);
  if (m == 0.0) return RNK_OK;
  memcpy(kj->M, M, sizeof(M));
  if ((rc = rnk_joint_couple_angle(s->q, kj, &alpha)) != RNK_OK) return rc;
  a->E[RN_TERM_LOAD] -= m * (kj->angle0 + alpha);
  return RNK_OK;
}

/* The direction on a joint stencil into s->v (OP_HVP). */
static void gather_joint_dir(const rn_network *net, const rn_joint *J,
                             rn_joint_scratch *s, const eval_args *a) {
  if (a->vfull) {
    rn_gather_fixed_dir_idx(net, a->vfull, J->idx, s->n, s->v);
    rn_cell_gather_fixed_dir(net, a->vfull, 0, J->idx, J->img, s->n, s->v);
  } else {
    rn_gather_dir_idx(net, a->v, J->idx, s->n, s->v);
    rn_cell_gather_dir(net, a->v, 0, J->idx, J->img, s->n, s->v);
  }
}

/* s->loc, a product (OP_HVP) or a block (OP_HESS) of a joint stencil, into
 * the outputs. */
static void scatter_joint_hv(const rn_network *net, const rn_joint *J,
                             const rn_joint_scratch *s, eval_args *a) {
  rn_scatter_add_idx(net, s->loc, J->idx, s->n, a->Hv);
  rn_cell_scatter(net, s->loc, 0, J->idx, J->img, s->n, a->Hv);
}

static void scatter_joint_hess(const rn_network *net, const rn_joint *J,
                               const rn_joint_scratch *s, eval_args *a) {
  a->unbounded |= !rn_all_bounded((size_t)s->n * (size_t)s->n, s->loc);
  if (a->bloch) {
    rn_bloch_add_block(net, a->bloch, 0, J->idx, J->img, s->n, s->loc, J);
    return;
  }
  rn_csr_add_block_idx(net, J->idx, s->n, s->loc, a->vals);
  rn_cell_hess_block(net, 0, J->idx, J->img, s->n, s->loc, a->vals);
}

static int joint_kernel_op(const rn_network *net, const rn_joint *J, rn_joint_scratch *s,
                           rnk_joint *kj, eval_args *a) {
  double E = 0.0;
  int rc = RNK_OK;
  switch (a->op) {
  case OP_ENERGY:
    return joint_energy_split(s, kj, a);
  case OP_GRAD:
    if ((rc = rnk_joint_grad(s->q, kj, s->work, &E, s->loc)) != RNK_OK) return rc;
    a->E[RN_TERM_BEND] += E; /* the sum is what counts here */
    scatter_grad(net, a, s->loc, 0, J->idx, J->img, s->n);
    break;
  case OP_HVP: /* matrix-free: the kernel never forms the block */
    gather_joint_dir(net, J, s, a);
    if ((rc = rnk_joint_hvp(s->q, kj, s->work, s->v, s->loc)) != RNK_OK) return rc;
    scatter_joint_hv(net, J, s, a);
    break;
  case OP_HESS:
    if ((rc = rnk_joint_hess(s->q, kj, s->work, s->loc)) != RNK_OK) return rc;
    scatter_joint_hess(net, J, s, a);
    break;
  }
  return rc;
}

/* Gradient of the joint's couple alone (loads_only): the gradient with the
 * couple minus the one without (the couple term is linear in M). */
static int joint_couple_grad(const rn_network *net, const rn_joint *J,
                             rn_joint_scratch *s, rnk_joint *kj, eval_args *a) {
  double E = 0.0, *g0 = s->loc + s->n; /* loc holds n * n >= 2 n doubles */
  int rc;
  if (kj->M[0] == 0.0 && kj->M[1] == 0.0 && kj->M[2] == 0.0) return RNK_OK;
  if ((rc = rnk_joint_grad(s->q, kj, s->work, &E, s->loc)) != RNK_OK) return rc;
  memset(kj->M, 0, sizeof(kj->M));
  if ((rc = rnk_joint_grad(s->q, kj, s->work, &E, g0)) != RNK_OK) return rc;
  for (int k = 0; k < s->n; ++k) s->loc[k] -= g0[k];
  rn_scatter_add_idx(net, s->loc, J->idx, s->n, a->g);
  rn_cell_scatter(net, s->loc, 0, J->idx, J->img, s->n, a->g);
  return RNK_OK;
}

/* A couple fixed in space on the joint rotation (rodnet_couple.h): no energy;
 * the gradient gets -Q, the Hessian -J (nonsymmetric), scattered like the
 * joint's own terms; also in the loads-only gradient. */
static int joint_fixed_couple(const rn_network *net, const rn_joint *J,
                              rn_joint_scratch *s, const rnk_joint *kj, eval_args *a) {
  const int n = s->n;
  double M[3], *Q = s->fix, *Jm = s->fix ? s->fix + n : NULL;
  int rc;
  if (!s->fix || a->op == OP_ENERGY) return RNK_OK;
  for (int k = 0; k < 3; ++k) M[k] = a->lambda * J->Mfix[k];
  rc =
      rnk_joint_couple_fixed_force(s->q, kj, M, s->work, Q, a->op == OP_GRAD ? NULL : Jm);
  if (rc != RNK_OK) return rc;
  if (a->op == OP_GRAD) {
    for (int i = 0; i < n; ++i) s->loc[i] = -Q[i];
    scatter_grad(net, a, s->loc, 0, J->idx, J->img, n);
  } else if (a->op == OP_HVP) {
    gather_joint_dir(net, J, s, a);
    for (int i = 0; i < n; ++i) {
      s->loc[i] = 0.0;
      for (int j = 0; j < n; ++j) s->loc[i] -= Jm[n * i + j] * s->v[j];
    }
    scatter_joint_hv(net, J, s, a);
  } else {
    for (int i = 0; i < n * n; ++i) s->loc[i] = -Jm[i];
    scatter_joint_hess(net, J, s, a);
  }
  return RNK_OK;
}

/* The whole-joint stencil, gathered and scattered by its index list; the
 * dead force on the joint position, E = -lambda F . (x_J - x_J0) (from the initial
 * position, as forces_eval). */
static rn_status joint_eval(const rn_network *net, int ij, eval_args *a) {
  const rn_joint *J = &net->joints[ij];
  rn_joint_scratch s;
  rnk_joint kj;
  double f[3], xj[3], gl[3];
  size_t p = rn_dof_joint_position(J->off);
  int rc;
  if (rn_joint_scratch_init(J, &s))
    return rn_fail(net->ctx, RN_ERR_ALLOC, a->where, "out of memory");
  rn_joint_kernel(net, ij, a->lambda, s.refs, &kj);
  rn_gather_idx(net, a->x, J->idx, s.n, s.q);
  rn_cell_gather(net, a->x, 0, J->idx, J->img, s.n, s.q);
  rc = a->loads_only ? joint_couple_grad(net, J, &s, &kj, a)
                     : joint_kernel_op(net, J, &s, &kj, a);
  if (rc == RNK_OK) rc = joint_fixed_couple(net, J, &s, &kj, a);
  rn_joint_scratch_free(&s);
  if (rc != RNK_OK)
    return rn_fail(
        net->ctx, RN_DEGENERATE, a->where,
        "joint %d ('%s') is degenerate (opposite tangents at a connection edge, "
        "a zero-length terminal edge or a singular rotation fit)",
        J->gid, J->name ? J->name : "");
  for (int k = 0; k < 3; ++k) f[k] = a->lambda * J->force[k];
  if (f[0] == 0.0 && f[1] == 0.0 && f[2] == 0.0) return RN_OK;
  rn_gather(net, a->x, p, RN_DOFS_PER_VERTEX, xj);
  for (int k = 0; k < 3; ++k) xj[k] -= J->x0[k];
  a->E[RN_TERM_LOAD] += rnk_force_energy(xj, f);
  if (a->op == OP_GRAD) {
    rnk_force_grad(f, gl);
    scatter_grad(net, a, gl, p, NULL, NULL, RN_DOFS_PER_VERTEX);
  }
  return RN_OK;
}

/* Contact (contact.c): the pairs within the barrier's reach at x, each a
 * 12-DOF stencil of the ends of two edges gathered and scattered by index.
 * The energy and gradient first check the motion from the accepted state
 * (continuous collision check): a step that would cross is a degenerate
 * trial point.  A pair outside the Hessian pattern (built at the accepted
 * state) that comes within the activation distance makes x a degenerate trial
 * point too: the pattern holds every pair the Hessian can couple. */
static rn_status contact_eval(const rn_network *net, eval_args *a) {
  rn_contact_list L;
  rn_status st = rn_contact_candidates(net, a->x, a->op == OP_ENERGY || a->op == OP_GRAD,
                                       a->where, &L);
  if (st) return st;
  for (size_t i = 0; i < L.n && !st; ++i) {
    const int pa = L.pair[2 * i], pb = L.pair[2 * i + 1];
    const rnk_contact_param pp = rn_contact_pair_param(net, pa, pb);
    const rnk_contact_param *p = &pp;
    size_t idx[12];
    double q[12], vl[12], loc[144], E = 0.0, gap = 0.0;
    int rc = RNK_OK;
    rn_contact_pair_idx(net, pa, pb, idx);
    rn_gather_idx(net, a->x, idx, 12, q);
    if (!rn_contact_in_pattern(net, pa, pb)) {
      if (rnk_contact_gap(q, p->radius, &gap) == RNK_OK && gap >= p->dhat)
        continue; /* no force, no Hessian block */
      st = rn_contact_pair_fail(
          net, RN_DEGENERATE, a->where, pa, pb,
          gap > 0.0 ? "two edges outside the Hessian pattern of the accepted state "
                      "come within the activation distance (a shorter step brings "
                      "them into the pattern)"
                    : "interpenetrating edges (or a zero-length edge)");
      break;
    }
    switch (a->op) {
    case OP_ENERGY:
      rc = rnk_contact_energy(q, p, &E);
      break;
    case OP_GRAD:
      if ((rc = rnk_contact_grad(q, p, &E, loc)) == RNK_OK)
        scatter_grad(net, a, loc, 0, idx, NULL, 12);
      break;
    case OP_HVP:
      if (a->vfull)
        rn_gather_fixed_dir_idx(net, a->vfull, idx, 12, vl);
      else
        rn_gather_dir_idx(net, a->v, idx, 12, vl);
      if ((rc = rnk_contact_hess(q, p, loc)) == RNK_OK) {
        double hv[12];
        rnk_block_mv(12, loc, vl, hv);
        rn_scatter_add_idx(net, hv, idx, 12, a->Hv);
      }
      break;
    case OP_HESS:
      if ((rc = rnk_contact_hess(q, p, loc)) == RNK_OK) {
        a->unbounded |= !rn_all_bounded(144, loc);
        rn_csr_add_block_idx(net, idx, 12, loc, a->vals);
      }
      break;
    }
    if (rc != RNK_OK)
      st = rn_contact_pair_fail(net, RN_DEGENERATE, a->where, pa, pb,
                                "interpenetrating edges (or a zero-length edge)");
    a->E[RN_TERM_LOAD] += E; /* (rodnet_contact.h) */
  }
  rn_contact_list_free(&L);
  return st;
}

static rn_status eval_rod(const rn_network *net, int ir, eval_args *a) {
  const rn_rod *r = &net->rods[ir];
  if (a->loads_only) {
    forces_eval(net, r, a);
    return RN_OK;
  }
  rn_status st = rod_stencils_eval(net, ir, a);
  if (st) return st;
  forces_eval(net, r, a);
  return RN_OK;
}

static rn_status eval_all(const rn_network *net, eval_args *a) {
  rn_status st;
  memset(a->E, 0, sizeof(a->E));
  /* In a part, the stencils of ghost rods and joints belong to other parts. */
  for (int ir = 0; ir < net->nrods; ++ir)
    if (rn_rod_evaluated(&net->rods[ir]) && (st = eval_rod(net, ir, a))) return st;
  for (int im = 0; im < net->nmom; ++im)
    if (rn_rod_evaluated(&net->rods[net->moments[im].rod]) &&
        moment_eval(net, &net->moments[im], a) != RNK_OK)
      return degenerate(net, a, "moment", net->moments[im].rod, "vertex",
                        net->moments[im].vertex);
  for (int ij = 0; ij < net->njoints; ++ij)
    if (rn_joint_evaluated(&net->joints[ij]) && (st = joint_eval(net, ij, a))) return st;
  if (net->contact && !a->loads_only && (st = contact_eval(net, a))) return st;
  if (net->cell && a->op != OP_HVP && a->op != OP_HESS && !a->magnitude)
    a->E[RN_TERM_LOAD] +=
        rn_cell_load(net, a->x, a->lambda, a->op == OP_GRAD && !a->gfull ? a->g : NULL,
                     a->op == OP_GRAD ? a->gfull : NULL);
  /* Finite inputs can still overflow (huge stiffness times strain, huge
   * loads): never hand back NaN or inf with RN_OK.  Recoverable, so a solver
   * rejects such a trial point. */
  int finite = rn_all_finite(RN_TERM_COUNT, a->E);
  if (finite && a->op == OP_GRAD)
    finite =
        a->gfull ? rn_all_finite(net->nfull, a->gfull) : rn_all_finite(net->nred, a->g);
  if (finite && a->op == OP_HVP) finite = rn_all_finite(net->nred, a->Hv);
  /* Hessian: every contribution was checked against RN_HESS_BOUND, so the
   * sums cannot overflow (fewer than 1e7 contributions per entry), without
   * another pass over the values */
  if (finite && a->op == OP_HESS) finite = !a->unbounded;
  if (!finite)
    return rn_fail(net->ctx, RN_OVERFLOW, a->where,
                   "the energy or its derivatives overflow (not finite) at this state");
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

/* Arguments of one evaluation of op at x, loads at the network's load factor. */
static void args_init(eval_args *a, const rn_network *net, eval_op op, const char *where,
                      const double *x) {
  memset(a, 0, sizeof(*a));
  a->lambda = net->lambda;
  a->op = op;
  a->where = where;
  a->x = x;
}

/* Runs an evaluation that accumulates into out[nred] (gradient or HVP). */
static rn_status eval_into(const rn_network *net, eval_args *a, double *out) {
  if (a->op == OP_GRAD) a->g = out;
  if (a->op == OP_HVP) a->Hv = out;
  if (net->nred) memset(out, 0, net->nred * sizeof(double));
  return eval_all(net, a);
}

rn_status rn_network_energy_terms(const rn_network *net, const double *x, double *E) {
  eval_args a;
  rn_status st;
  if (!net) return RN_ERR_ARG;
  if (!E) return rn_fail(net->ctx, RN_ERR_ARG, "rn_network_energy_terms", "E is NULL");
  if ((st = check_eval(net, "rn_network_energy_terms", x, E))) return st;
  args_init(&a, net, OP_ENERGY, "rn_network_energy", x);
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
  args_init(&a, net, OP_GRAD, "rn_network_gradient", x);
  if ((st = eval_into(net, &a, g))) return st;
  rn_cell_hold_zero(net, g);
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
  args_init(&a, net, OP_HVP, where, x);
  if (!rn_cell_held(net)) {
    a.v = v;
    return eval_into(net, &a, Hv);
  }
  /* held strain: H v = [H_uu v_u; v_e] (the v_e term once, on part 0) */
  double *vu = malloc((net->nred ? net->nred : 1) * sizeof(double));
  if (!vu) return rn_fail(net->ctx, RN_ERR_ALLOC, where, "out of memory");
  memcpy(vu, v, net->nred * sizeof(double));
  rn_cell_hold_zero(net, vu);
  a.v = vu;
  st = eval_into(net, &a, Hv);
  if (!st) rn_cell_hold_hvp(net, v, Hv);
  free(vu);
  return st;
}

rn_status rn_network_hessian_values(const rn_network *net, const double *x,
                                    double *vals) {
  eval_args a;
  rn_status st;
  if (!net) return RN_ERR_ARG;
  if ((st = check_eval(net, "rn_network_hessian_values", x, vals))) return st;
  args_init(&a, net, OP_HESS, "rn_network_hessian_values", x);
  a.vals = vals;
  rn_hessian_zero(net, vals); /* the rest is stored by the rods first */
  if ((st = eval_all(net, &a))) return st;
  rn_cell_hold_hessian(net, vals);
  return RN_OK;
}

rn_status rn_eval_fixed_hvp(const rn_network *net, const double *x, const double *vfull,
                            double *Hv, const char *where) {
  eval_args a;
  args_init(&a, net, OP_HVP, where, x);
  a.vfull = vfull;
  return eval_into(net, &a, Hv);
}

rn_status rn_eval_load_rate(const rn_network *net, const double *x, double *g,
                            const char *where) {
  eval_args a;
  args_init(&a, net, OP_GRAD, where, x);
  a.lambda = 1.0; /* the loads' rate: they are linear in the load factor */
  a.loads_only = 1;
  return eval_into(net, &a, g);
}

rn_status rn_eval_gradient_full(const rn_network *net, const double *x, double *gfull,
                                const char *where) {
  eval_args a;
  args_init(&a, net, OP_GRAD, where, x);
  a.gfull = gfull;
  if (net->nfull) memset(gfull, 0, net->nfull * sizeof(double));
  return eval_all(net, &a);
}

rn_status rn_eval_rod_gradient_full(const rn_network *net, int ir, const double *x,
                                    double *gfull, const char *where) {
  eval_args a;
  args_init(&a, net, OP_GRAD, where, x);
  a.gfull = gfull;
  return rod_stencils_grad_each(net, ir, &a);
}

rn_status rn_eval_gradient_magnitude(const rn_network *net, const double *x, double *gabs,
                                     const char *where) {
  eval_args a;
  args_init(&a, net, OP_GRAD, where, x);
  a.magnitude = 1;
  return eval_into(net, &a, gabs);
}

rn_status rn_eval_bloch(const rn_network *net, const double *x, rn_bloch_acc *b,
                        const char *where) {
  eval_args a;
  args_init(&a, net, OP_HESS, where, x);
  a.bloch = b;
  return eval_all(net, &a);
}
