/* finalize.c - validation, DOF map, per-stencil parameters, initial state. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "bcs/bcs.h"
#include "contact/contact.h"
#include "eval/eval.h"
#include "joints/joints.h"
#include "parts/parts.h"
#include "periodic/periodic.h"

static const char *where = "rn_network_finalize";

static rn_status validate_rod(const rn_network *net, int ir) {
  const rn_rod *r = &net->rods[ir];
  for (int j = 0; j < r->ne; ++j) {
    if (!r->has_mat[j])
      return rn_fail(net->ctx, RN_ERR_ARG, where, "rod %d ('%s') edge %d has no material",
                     r->gid, r->name ? r->name : "", j);
    if (!r->has_sec[j])
      return rn_fail(net->ctx, RN_ERR_ARG, where, "rod %d ('%s') edge %d has no section",
                     r->gid, r->name ? r->name : "", j);
  }
  for (int end = RN_START; end <= RN_END; ++end)
    if (r->has_end_motion[end] && !r->clamped[end])
      return rn_fail(
          net->ctx, RN_ERR_BC, where,
          "rod %d ('%s'): prescribed motion of the %s end, which is not clamped", r->gid,
          r->name ? r->name : "", end == RN_START ? "start" : "end");
  for (int v = 0; v < r->nv; ++v) {
    int fixed = rn_rod_fixed_components(r, v), k;
    char buf[4];
    if (!r->has_vdisp[v]) continue;
    if (!fixed)
      return rn_fail(
          net->ctx, RN_ERR_BC, where,
          "rod %d ('%s') vertex %d: prescribed displacement of a vertex that is "
          "neither pinned nor clamped",
          r->gid, r->name ? r->name : "", v);
    if ((k = rn_free_displaced_component(fixed, r->vdisp + 3 * v)) >= 0)
      return rn_fail(net->ctx, RN_ERR_BC, where,
                     "rod %d ('%s') vertex %d: prescribed displacement %g along %c, "
                     "which is free (the vertex is pinned in %s only); pin that "
                     "component too or make it 0",
                     r->gid, r->name ? r->name : "", v, r->vdisp[3 * v + k], "xyz"[k],
                     rn_components_name(fixed, buf));
  }
  return RN_OK;
}

static rn_status build_params(rn_rod *r) {
  int nin = r->nv - 2;
  r->fvert = calloc(3 * (size_t)r->nv, sizeof(double));
  r->sp = calloc((size_t)r->ne, sizeof(rnk_stretch_param));
  r->bp = calloc((size_t)(nin > 0 ? nin : 1), sizeof(rnk_bend_param));
  r->tp = calloc((size_t)(nin > 0 ? nin : 1), sizeof(rnk_twist_param));
  if (!r->fvert || !r->sp || !r->bp || !r->tp) return RN_ERR_ALLOC;
  for (int j = 0; j < r->ne; ++j) {
    r->sp[j].k = r->mat[j].E * r->sec[j].A;
    r->sp[j].lbar = r->lbar[j];
  }
  for (int i = 1; i <= nin; ++i) { /* averages of the two adjacent edges */
    const rn_material *ma = &r->mat[i - 1], *mb = &r->mat[i];
    const rn_section *sa = &r->sec[i - 1], *sb = &r->sec[i];
    rnk_bend_param *b = &r->bp[i - 1];
    rnk_twist_param *t = &r->tp[i - 1];
    b->B[0] = 0.5 * (ma->E * sa->I11 + mb->E * sb->I11);
    b->B[1] = 0.5 * (ma->E * sa->I12 + mb->E * sb->I12);
    b->B[2] = 0.5 * (ma->E * sa->I22 + mb->E * sb->I22);
    b->kbar[0] = r->kbar[2 * (i - 1)];
    b->kbar[1] = r->kbar[2 * (i - 1) + 1];
    b->vlen = 0.5 * (r->lbar[i - 1] + r->lbar[i]);
    t->beta = 0.5 * (ma->G * sa->J + mb->G * sb->J);
    t->taubar = r->taubar[i - 1];
    t->vlen = b->vlen;
  }
  return RN_OK;
}

/* Marks the fixed full DOFs of a rod with -1 in map (others 0). */
static void mark_fixed(rn_network *net, const rn_rod *r) {
  int64_t *m = net->map;
  for (int v = 0; v < r->nv; ++v) {
    int fixed = rn_rod_fixed_components(r, v);
    for (int k = 0; k < 3; ++k)
      m[rn_dof_vertex(r->off, v) + (size_t)k] = rn_component_fixed(fixed, k) ? -1 : 0;
  }
  for (int j = 0; j < r->ne; ++j) {
    int fixed = r->theta_fixed[j] || (r->clamped[RN_START] && j == 0) ||
                (r->clamped[RN_END] && j == r->ne - 1);
    m[rn_dof_theta(r->off, j)] = fixed ? -1 : 0;
  }
}

/* Joint DOFs: position components fixed if pinned or clamped, rotation
 * (present for rigid or clamped joints) fixed if clamped; initial position,
 * w = 0. */
static void mark_joint(rn_network *net, const rn_joint *J) {
  size_t p = rn_dof_joint_position(J->off), w = rn_dof_joint_rotation(J->off);
  int fixed = rn_joint_fixed_components(J);
  for (int k = 0; k < 3; ++k) {
    net->map[p + (size_t)k] = rn_component_fixed(fixed, k) ? -1 : 0;
    net->xfull[p + (size_t)k] = J->x0[k];
    if (!rn_joint_has_rotation(J)) continue;
    net->map[w + (size_t)k] = J->clamped ? -1 : 0;
  }
}

enum { ALIAS = -2 }; /* map marker of a rod end vertex attached to a joint */

/* Marks (alias = 1) or maps (alias = 0) the rod end vertices of every joint
 * to the joint position's entries. */
static void alias_joint_ends(rn_network *net, int alias) {
  for (int ij = 0; ij < net->njoints; ++ij) {
    const rn_joint *J = &net->joints[ij];
    size_t p = rn_dof_joint_position(J->off);
    for (int k = 0; k < J->valence; ++k) {
      const rn_rod *r = &net->rods[J->rod[k]];
      size_t v = rn_dof_vertex(r->off, rn_end_vertex(r->nv, J->end[k]));
      for (int c = 0; c < 3; ++c)
        net->map[v + (size_t)c] = alias ? ALIAS : net->map[p + (size_t)c];
    }
  }
}

/* Full vector: rods, then joints.  Free entries are numbered in full order;
 * aliased rod end vertices then take the numbers of their joint, which is
 * the canonical full index of those reduced DOFs in red2full. */
static rn_status build_dof_map(rn_network *net) {
  size_t off = 0, nred = 0;
  for (int ir = 0; ir < net->nrods; ++ir) {
    net->rods[ir].off = off;
    off += rn_dof_rod_count(net->rods[ir].nv);
  }
  for (int ij = 0; ij < net->njoints; ++ij) {
    net->joints[ij].off = off;
    off += rn_dof_joint_count(rn_joint_has_rotation(&net->joints[ij]));
  }
  if (net->cell) { /* periodic: the macroscopic strain follows the joints */
    net->cell->off = off;
    off += rn_cell_full_count(net);
  }
  net->nfull = off;
  net->map = malloc((off ? off : 1) * sizeof(int64_t)); /* a part may hold nothing */
  net->xfull = calloc(off ? off : 1, sizeof(double));
  if (!net->map || !net->xfull) return RN_ERR_ALLOC;
  for (int ir = 0; ir < net->nrods; ++ir) {
    const rn_rod *r = &net->rods[ir];
    mark_fixed(net, r);
    for (int v = 0; v < r->nv; ++v)
      memcpy(net->xfull + rn_dof_vertex(r->off, v), r->x0 + 3 * v, 3 * sizeof(double));
  }
  for (int ij = 0; ij < net->njoints; ++ij) mark_joint(net, &net->joints[ij]);
  rn_cell_mark(net);
  rn_planar_mark(net);
  alias_joint_ends(net, 1);
  if (net->part) { /* a part: what it does not read is absent, owned DOFs first */
    if (rn_part_begin_numbering(net)) return RN_ERR_ALLOC;
    rn_part_mark_absent(net);
  }
  for (size_t a = 0; a < off; ++a) nred += net->map[a] == 0;
  net->nred = nred;
  net->red2full = malloc((nred ? nred : 1) * sizeof(int64_t));
  if (!net->red2full) return RN_ERR_ALLOC;
  nred = 0;
  for (int pass = 0; pass < (net->part ? 2 : 1); ++pass)
    for (size_t a = 0; a < off; ++a)
      if (net->map[a] == 0 && (!net->part || rn_part_entry_owned(net, a) == !pass)) {
        net->red2full[nred] = (int64_t)a;
        net->map[a] = (int64_t)nred++;
      }
  alias_joint_ends(net, 0);
  rn_joints_sync(net);
  return net->part ? rn_part_build_keys(net) : RN_OK;
}

/* Material frame (t, d1, d2) of each moment's edge at the current state. */
static rn_status init_moments(rn_network *net) {
  for (int im = 0; im < net->nmom; ++im) {
    rn_moment *mo = &net->moments[im];
    const rn_rod *r = &net->rods[mo->rod];
    const double *x = net->xfull + rn_dof_edge_stencil(r->off, mo->edge);
    double e[3];
    for (int k = 0; k < 3; ++k) e[k] = x[RN_EDGE_LOCAL_X1 + k] - x[RN_EDGE_LOCAL_X0 + k];
    mo->angle0 = 0.0;
    if (rnk_material_frame(e, &r->ref[mo->edge], x[RN_EDGE_LOCAL_THETA], mo->f0,
                           mo->f0 + 3, mo->f0 + 6) != RNK_OK)
      return rn_fail(net->ctx, RN_ERR_GEOMETRY, where,
                     "rod %d edge %d: degenerate edge under a moment", mo->rod, mo->edge);
    rn_couple_vector(mo->f0, mo->M, mo->b);
  }
  return RN_OK;
}

static void undo_finalize(rn_network *net) {
  for (int ir = 0; ir < net->nrods; ++ir) {
    rn_rod *r = &net->rods[ir];
    free(r->fvert);
    free(r->sp);
    free(r->bp);
    free(r->tp);
    r->fvert = NULL;
    r->sp = NULL;
    r->bp = NULL;
    r->tp = NULL;
  }
  rn_joints_unbuild(net);
  rn_contact_unbuild(net);
  if (net->cell) {
    free(net->cell->slot);
    net->cell->slot = NULL;
    net->cell->nimg = 0;
  }
  free(net->map);
  free(net->red2full);
  free(net->xfull);
  rn_hessian_pattern_free(net);
  net->map = net->red2full = NULL;
  net->xfull = NULL;
  net->nfull = net->nred = net->nnz = net->bandwidth = 0;
}

/* The input before anything is built: rods, joints, the cell's anchor, the
 * planar model's condition. */
static rn_status check_input(rn_network *net) {
  rn_status st;
  if (rn_net_num_rods_g(net) == 0)
    return rn_fail(net->ctx, RN_ERR_ARG, where, "the network has no rods");
  rn_cell_anchor(net); /* periodic: one joint pinned unless a BC fixes a position */
  if ((st = rn_joints_validate(net, where))) return st;
  for (int ir = 0; ir < net->nrods; ++ir)
    if ((st = validate_rod(net, ir))) return st;
  rn_planar_assess(net);
  if (net->model == RN_MODEL_PLANAR && !net->planar_ok)
    return rn_fail(net->ctx, RN_ERR_ARG, where,
                   "the planar model needs a network in one plane z = const: %s",
                   net->planar_why);
  return RN_OK;
}

/* Kernel parameters and lumped forces, DOF map, joint stencils, cell images,
 * contact edges and Hessian pattern (the caller undoes them on failure). */
static rn_status build(rn_network *net) {
  rn_status st = RN_OK;
  for (int ir = 0; ir < net->nrods; ++ir) {
    if (build_params(&net->rods[ir]))
      return rn_fail(net->ctx, RN_ERR_ALLOC, where, "out of memory");
    rn_rod_lump_forces(net, &net->rods[ir]);
  }
  if (build_dof_map(net) || (st = rn_joints_build(net)) || rn_cell_build(net))
    return st ? st : rn_fail(net->ctx, RN_ERR_ALLOC, where, "out of memory");
  rn_planar_assess_built(net);
  if (net->planar && !net->planar_ok)
    return rn_fail(net->ctx, RN_ERR_ARG, where,
                   "the planar model needs a network in one plane z = const: %s",
                   net->planar_why);
  if ((st = rn_contact_build(net, where))) return st;
  if (net->nred > (size_t)INT32_MAX) /* CSR columns are int32 */
    return rn_fail(net->ctx, RN_ERR_RANGE, where,
                   "%zu free DOFs exceed the int32 CSR limit", net->nred);
  if (rn_build_hessian_pattern(net))
    return rn_fail(net->ctx, RN_ERR_ALLOC, where, "out of memory");
  return RN_OK;
}

/* The joints and contacts are checked on the initial geometry (load factor 0);
 * then the prescribed motions are ramped to the load factor (keeping twist
 * windings; the state there may be a degenerate trial point, which the solver
 * ramps through), the couples take their reference, and the contact pattern is
 * built at that state. */
static rn_status start(rn_network *net) {
  rn_status st;
  const double target = net->lambda;
  net->lambda = net->lambda_x = 0.0; /* the initial geometry is load factor 0's */
  rn_apply_load_factor(net);
  if (!(st = rn_joints_check_initial(net, where)) &&
      !(st = rn_contact_check_initial(net, where))) {
    rn_ramp_load_factor(net, target);
    st = init_moments(net);
  }
  if (!st) st = rn_contact_pattern_update(net, 1, where);
  return st;
}

rn_status rn_network_finalize(rn_network *net) {
  rn_status st;
  if (!net) return RN_ERR_ARG;
  if ((st = rn_net_check_building(net, where))) return st;
  if (rn_network_is_graph_only(net)) { /* only the rod graph: nothing to build */
    if ((st = rn_part_graph_validate(net, where))) return st;
    net->finalized = 1;
    return RN_OK;
  }
  if ((st = check_input(net))) return st;
  net->accept_state = rn_contact_pattern_update;
  net->rebuild_pattern = rn_rebuild_hessian_pattern;
  net->planar = net->model == RN_MODEL_PLANAR;
  if ((st = build(net)) || (st = start(net))) {
    undo_finalize(net);
    return st;
  }
  net->finalized = 1;
  return RN_OK;
}

/* ---- destroy ---------------------------------------------------------------- */
void rn_network_destroy(rn_network **net) {
  rn_network *n;
  if (!net || !*net) return;
  n = *net;
  for (int i = 0; i < n->nrods; ++i) rn_rod_free(&n->rods[i]);
  free(n->rods);
  free(n->moments);
  for (int i = 0; i < n->njoints; ++i) rn_joint_free(&n->joints[i]);
  free(n->joints);
  free(n->map);
  free(n->red2full);
  free(n->xfull);
  rn_hessian_pattern_free(n);
  rn_part_free(&n->part);
  rn_cell_free(&n->cell);
  rn_contact_free(n);
  free(n);
  *net = NULL;
}
