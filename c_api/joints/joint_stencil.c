/* joint_stencil.c - joints at finalize and under the load factor: validation
 * (conflicting BCs, coincident joints, the fit at the initial state), the
 * kernel parameters of rnk.h's whole-joint stencil and its full index list,
 * fixed joint DOFs and the aliasing of rod end vertices, evaluation
 * scratch. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "joints/joints.h"
#include "periodic/periodic.h"

#define RN_PI 3.14159265358979323846

/* ---- validation ----------------------------------------------------------- */
/* A rod vertex that belongs to a joint cannot carry a BC of its own. */
static rn_status check_end_bcs(const rn_network *net, const char *where, int ij, int k) {
  const rn_joint *J = &net->joints[ij];
  const rn_rod *r = &net->rods[J->rod[k]];
  int v = rn_end_vertex(r->nv, J->end[k]);
  int in_clamp = rn_rod_in_clamp(r, v);
  if (r->pinned[v] || r->has_vdisp[v] || in_clamp)
    return rn_fail(net->ctx, RN_ERR_BC, where,
                   "rod %d ('%s') vertex %d belongs to joint %d ('%s') but is %s; "
                   "constrain the joint instead (rn_network_clamp_joint, "
                   "rn_network_pin_joint, rn_network_displace_joint)",
                   r->gid, r->name ? r->name : "", v, J->gid, J->name ? J->name : "",
                   in_clamp ? "in a clamped end"
                            : (r->pinned[v] ? "pinned" : "displaced"));
  return RN_OK;
}

static rn_status check_joint_motion(const rn_network *net, const char *where, int ij) {
  const rn_joint *J = &net->joints[ij];
  int rotates = J->rot[0] != 0.0 || J->rot[1] != 0.0 || J->rot[2] != 0.0;
  int fixed = rn_joint_fixed_components(J), k;
  char buf[4];
  if (!J->has_motion) return RN_OK;
  if (!fixed)
    return rn_fail(net->ctx, RN_ERR_BC, where,
                   "joint %d ('%s'): prescribed motion of a joint that is neither pinned "
                   "nor clamped",
                   J->gid, J->name ? J->name : "");
  if (rotates && !J->clamped)
    return rn_fail(net->ctx, RN_ERR_BC, where,
                   "joint %d ('%s'): prescribed rotation of a joint that is not clamped",
                   J->gid, J->name ? J->name : "");
  if ((k = rn_free_displaced_component(fixed, J->disp)) >= 0)
    return rn_fail(net->ctx, RN_ERR_BC, where,
                   "joint %d ('%s'): prescribed displacement %g along %c, which is free "
                   "(the joint is pinned in %s only); pin that component too or make "
                   "it 0",
                   J->gid, J->name ? J->name : "", J->disp[k], "xyz"[k],
                   rn_components_name(fixed, buf));
  return RN_OK;
}

typedef struct joint_key {
  double x;
  int j;
} joint_key;

static int key_cmp(const void *a, const void *b) {
  double xa = ((const joint_key *)a)->x, xb = ((const joint_key *)b)->x;
  return (xa > xb) - (xa < xb);
}

/* Two joints closer than 1e-9 of the shorter of their shortest incident
 * edges: sweep over the joints sorted by x. */
rn_status rn_joint_points_check(rn_context *ctx, const char *where, int n,
                                const rn_joint_point *p) {
  joint_key *keys;
  double lmax = 0.0;
  rn_status st = RN_OK;
  if (n < 2) return RN_OK;
  keys = malloc((size_t)n * sizeof(*keys));
  if (!keys) return rn_fail(ctx, RN_ERR_ALLOC, where, "out of memory");
  for (int i = 0; i < n; ++i) {
    keys[i].x = p[i].x0[0];
    keys[i].j = i;
    lmax = fmax(lmax, p[i].lmin);
  }
  qsort(keys, (size_t)n, sizeof(*keys), key_cmp);
  for (int a = 0; a < n && !st; ++a)
    for (int b = a + 1; b < n && !st; ++b) {
      const rn_joint_point *A = &p[keys[a].j], *B = &p[keys[b].j];
      double d0, d1, d2, tol;
      if (keys[b].x - keys[a].x > RN_JOINT_COINCIDE_TOL * lmax) break;
      d0 = A->x0[0] - B->x0[0];
      d1 = A->x0[1] - B->x0[1];
      d2 = A->x0[2] - B->x0[2];
      tol = RN_JOINT_COINCIDE_TOL * fmin(A->lmin, B->lmin);
      if (sqrt(d0 * d0 + d1 * d1 + d2 * d2) <= tol) {
        const rn_joint_point *I = A->gid < B->gid ? A : B, *J = A->gid < B->gid ? B : A;
        st = rn_fail(ctx, RN_ERR_GEOMETRY, where,
                     "joints %d ('%s') and %d ('%s') are coincident (at (%g, %g, %g)); "
                     "merge them into one joint",
                     I->gid, I->name ? I->name : "", J->gid, J->name ? J->name : "",
                     A->x0[0], A->x0[1], A->x0[2]);
      }
    }
  free(keys);
  return st;
}

static rn_status check_coincident(const rn_network *net, const char *where) {
  rn_joint_point *p;
  rn_status st;
  if (net->njoints < 2) return RN_OK;
  p = malloc((size_t)net->njoints * sizeof(*p));
  if (!p) return rn_fail(net->ctx, RN_ERR_ALLOC, where, "out of memory");
  for (int i = 0; i < net->njoints; ++i) {
    memcpy(p[i].x0, net->joints[i].x0, sizeof(p[i].x0));
    p[i].lmin = net->joints[i].lmin;
    p[i].gid = net->joints[i].gid;
    p[i].name = net->joints[i].name;
  }
  st = rn_joint_points_check(net->ctx, where, net->njoints, p);
  free(p);
  return st;
}

/* A smooth joint has no rotation: it cannot be clamped or carry a couple. */
static rn_status check_smooth(const rn_network *net, const char *where, int ij) {
  const rn_joint *J = &net->joints[ij];
  if (J->model != RN_JOINT_SMOOTH) return RN_OK;
  if (J->clamped || J->M[0] != 0.0 || J->M[1] != 0.0 || J->M[2] != 0.0 ||
      J->Mfix[0] != 0.0 || J->Mfix[1] != 0.0 || J->Mfix[2] != 0.0)
    return rn_fail(net->ctx, RN_ERR_BC, where,
                   "joint %d ('%s') is smooth (no rotation): it cannot be %s; pin it, or "
                   "clamp or load an edge of its rods",
                   J->gid, J->name ? J->name : "",
                   J->clamped ? "clamped" : "loaded by a couple");
  return RN_OK;
}

rn_status rn_joints_validate(const rn_network *net, const char *where) {
  rn_status st;
  for (int ij = 0; ij < net->njoints; ++ij) {
    if ((st = check_smooth(net, where, ij))) return st;
    for (int k = 0; k < net->joints[ij].valence; ++k)
      if ((st = check_end_bcs(net, where, ij, k))) return st;
    if ((st = check_joint_motion(net, where, ij))) return st;
  }
  return check_coincident(net, where);
}

/* ---- kernel parameters and index lists ------------------------------------ */
/* End k: side, rest frame of the terminal edge (its initial material frame),
 * stiffness of the terminal edge, half its rest length. */
static rn_status build_end(const rn_rod *r, int end, rnk_joint_end *e) {
  int j = rn_end_edge(r->nv, end);
  double ev[3];
  const rn_material *m = &r->mat[j];
  const rn_section *s = &r->sec[j];
  memset(e, 0, sizeof(*e));
  e->side = end == RN_END ? 0 : 1;
  for (int c = 0; c < 3; ++c) ev[c] = r->x0[3 * (j + 1) + c] - r->x0[3 * j + c];
  if (rnk_material_frame(ev, &r->ref_base[j], 0.0, e->cbar, e->cbar + 3, e->cbar + 6))
    return RN_ERR_GEOMETRY;
  e->bend.B[0] = m->E * s->I11;
  e->bend.B[1] = m->E * s->I12;
  e->bend.B[2] = m->E * s->I22;
  e->bend.vlen = 0.5 * r->lbar[j];
  e->twist.beta = m->G * s->J;
  e->twist.vlen = e->bend.vlen;
  return RN_OK;
}

/* Rest frames of the ends of a rigid or elastic joint other than the input
 * ones: straight (valence 2: end 1's is end 0's, turned by pi about d1 when
 * both ends have the same side) or given. */
static void rest_frames(rn_joint *J) {
  if (J->rest == RN_REST_FRAMES)
    for (int k = 0; k < J->valence; ++k)
      memcpy(J->ends[k].cbar, J->rest_frames + 9 * k, 9 * sizeof(double));
  if (J->rest != RN_REST_STRAIGHT || J->valence != 2) return;
  memcpy(J->ends[1].cbar, J->ends[0].cbar, 9 * sizeof(double));
  if (J->ends[0].side == J->ends[1].side)
    for (int c = 0; c < 3; ++c) { /* (t, d1, d2) -> (-t, d1, -d2) */
      J->ends[1].cbar[c] = -J->ends[1].cbar[c];
      J->ends[1].cbar[6 + c] = -J->ends[1].cbar[6 + c];
    }
}

/* A smooth joint's vertex parameters in ends[0]: stiffness averaged over the
 * two terminal edges, Voronoi length half their rest lengths, rest curvature
 * and twist (input shape, straight or given), reference twist h + 2 pi link
 * with h the input twist between the terminal edges' frames (a ring with a
 * total twist: the whole turns of it, the remainder spread over the ring's
 * rest twist). */
static rn_status build_smooth(const rn_network *net, rn_joint *J) {
  const rn_rod *r0 = &net->rods[J->rod[0]], *r1 = &net->rods[J->rod[1]];
  int j0 = rn_end_edge(r0->nv, RN_END), j1 = rn_end_edge(r1->nv, RN_START);
  rnk_joint_end *e0 = &J->ends[0], *e1 = &J->ends[1];
  rnk_frame refs[2] = {r0->ref_base[j0], r1->ref_base[j1]};
  double q[RN_VERTEX_STENCIL] = {0}, h, kappa[2], tau;
  for (int c = 0; c < 3; ++c) { /* input vertex stencil, theta = 0 */
    q[rn_stencil_x(0) + c] = r0->x0[3 * j0 + c];
    q[rn_stencil_x(1) + c] = r0->x0[3 * (j0 + 1) + c];
    q[rn_stencil_x(2) + c] = r0->x0[3 * (j0 + 1) + c] + r1->x0[3 + c] - r1->x0[c];
  }
  if (rnk_reference_twist(q, refs, 0.0, &h) != RNK_OK ||
      rnk_strains(q, refs, h, kappa, &tau) != RNK_OK)
    return RN_ERR_GEOMETRY;
  for (int c = 0; c < 3; ++c) e0->bend.B[c] = 0.5 * (e0->bend.B[c] + e1->bend.B[c]);
  e0->bend.vlen += e1->bend.vlen;
  e0->twist.beta = 0.5 * (e0->twist.beta + e1->twist.beta);
  e0->twist.vlen = e0->bend.vlen;
  e0->bend.kbar[0] = J->rest == RN_REST_INPUT ? kappa[0] : J->rest_kbar[0];
  e0->bend.kbar[1] = J->rest == RN_REST_INPUT ? kappa[1] : J->rest_kbar[1];
  e0->twist.taubar = J->rest == RN_REST_INPUT ? tau : J->rest_taubar;
  if (J->rest == RN_REST_STRAIGHT)
    e0->bend.kbar[0] = e0->bend.kbar[1] = e0->twist.taubar = 0;
  double turns = J->link;
  if (J->has_total_twist) {
    /* a ring with total twist T: the reference twist h + 2 pi k (it must stay
     * the geometric angle, mod 2 pi) with k the nearest whole turns of
     * T - h - s (s the input twist of the other vertices); the remainder
     * (within [-pi, pi]) lowers the rest twist of every vertex of the ring in
     * proportion to its Voronoi length, so the ring stores T - h - s evenly */
    double s = 0.0, len = e0->twist.vlen;
    for (int i = 0; i < r0->nv - 2; ++i) {
      s += r0->ref_twist[i];
      len += r0->tp[i].vlen;
    }
    turns = nearbyint((J->total_twist - h - s) / (2.0 * RN_PI));
    double rem = J->total_twist - h - s - 2.0 * RN_PI * turns;
    for (int i = 0; i < r0->nv - 2; ++i) r0->tp[i].taubar -= rem * r0->tp[i].vlen / len;
    e0->twist.taubar -= rem * e0->twist.vlen / len;
  }
  e0->twist.ref_twist = e1->twist.ref_twist = h + 2.0 * RN_PI * turns;
  J->turns = turns;
  return RN_OK;
}

/* A ring's stored whole turns start evenly spread: the closing vertex's
 * reference twist holds 2 pi k, so with every material angle at its input the
 * whole k turns would sit at that one vertex (a state far from any equilibrium
 * whose path may pass the ring through itself). Edge j's initial angle turns by
 * 2 pi k (s_j - s_o) / L (s_j the Voronoi length of the vertices between edge 0
 * and edge j, L the ring's, o the origin edge), which gives every vertex 2 pi k
 * times its share of L and leaves the total twist, the link and the energy's
 * minimisers unchanged. The origin is the ring's fixed angle if it has one (its
 * value stays the user's), edge 0 otherwise; with two or more fixed angles the
 * input angles are kept. */
static void spread_ring_turns(rn_network *net, const rn_joint *J) {
  const rn_rod *r = &net->rods[J->rod[0]];
  double len = J->ends[0].twist.vlen, s = 0.0, so = 0.0;
  int nfixed = 0;
  if (J->turns == 0.0 || J->rod[0] != J->rod[1] || !r->closed) return;
  for (int i = 0; i < r->nv - 2; ++i) len += r->tp[i].vlen;
  for (int j = 0; j < r->ne; ++j) {
    if (r->theta_fixed[j]) so = s, ++nfixed;
    if (j < r->nv - 2) s += r->tp[j].vlen;
  }
  if (nfixed > 1) return;
  s = 0.0;
  for (int j = 0; j < r->ne; ++j) {
    net->xfull[rn_dof_theta(r->off, j)] += 2.0 * RN_PI * J->turns * (s - so) / len;
    if (j < r->nv - 2) s += r->tp[j].vlen;
  }
}

static void build_indices(const rn_network *net, rn_joint *J) {
  int rigid = rn_joint_has_rotation(J);
  for (int c = 0; c < 3; ++c) {
    J->idx[RN_JOINT_LOCAL_X + c] = rn_dof_joint_position(J->off) + (size_t)c;
    if (rigid) J->idx[RN_JOINT_LOCAL_W + c] = rn_dof_joint_rotation(J->off) + (size_t)c;
  }
  for (int k = 0; k < J->valence; ++k) {
    const rn_rod *r = &net->rods[J->rod[k]];
    size_t *e = J->idx + rn_joint_local_end(rigid, k);
    size_t xv = rn_dof_vertex(r->off, rn_end_neighbor(r->nv, J->end[k]));
    for (int c = 0; c < 3; ++c) e[c] = xv + (size_t)c;
    e[3] = rn_dof_theta(r->off, rn_end_edge(r->nv, J->end[k]));
  }
}

rn_status rn_joints_build(rn_network *net) {
  for (int ij = 0; ij < net->njoints; ++ij) {
    rn_joint *J = &net->joints[ij];
    int n = rn_joint_stencil_count(rn_joint_has_rotation(J), J->valence);
    rn_couple_vector(J->f0, J->M, J->couple_p); /* f0 = identity: rest coordinates */
    J->ends = calloc((size_t)J->valence, sizeof(rnk_joint_end));
    J->idx = malloc((size_t)n * sizeof(size_t));
    if (!J->ends || !J->idx)
      return rn_fail(net->ctx, RN_ERR_ALLOC, "rn_network_finalize", "out of memory");
    for (int k = 0; k < J->valence; ++k)
      if (build_end(&net->rods[J->rod[k]], J->end[k], &J->ends[k]))
        return rn_fail(net->ctx, RN_ERR_GEOMETRY, "rn_network_finalize",
                       "joint %d ('%s'): degenerate terminal edge of rod %d", J->gid,
                       J->name ? J->name : "", net->rods[J->rod[k]].gid);
    if (J->model == RN_JOINT_SMOOTH && J->valence == 2 && build_smooth(net, J))
      return rn_fail(net->ctx, RN_ERR_GEOMETRY, "rn_network_finalize",
                     "joint %d ('%s'): the smooth joint's rods point in opposite "
                     "directions at the joint (a 180 degree kink)",
                     J->gid, J->name ? J->name : "");
    if (J->model == RN_JOINT_SMOOTH && J->valence == 2) spread_ring_turns(net, J);
    if (J->model != RN_JOINT_SMOOTH) rest_frames(J);
    build_indices(net, J);
  }
  return RN_OK;
}

void rn_joints_unbuild(rn_network *net) {
  for (int ij = 0; ij < net->njoints; ++ij) {
    rn_joint *J = &net->joints[ij];
    free(J->ends);
    free(J->idx);
    free(J->img);
    J->ends = NULL;
    J->idx = NULL;
    J->img = NULL;
  }
}

void rn_joint_kernel(const rn_network *net, int ij, double load_scale, rnk_frame *refs,
                     rnk_joint *kj) {
  const rn_joint *J = &net->joints[ij];
  memset(kj, 0, sizeof(*kj));
  kj->rigid = rn_joint_has_rotation(J);
  kj->smooth = J->model == RN_JOINT_SMOOTH;
  kj->valence = J->valence;
  kj->ends = J->ends;
  for (int k = 0; k < J->valence; ++k) {
    const rn_rod *r = &net->rods[J->rod[k]];
    refs[k] = r->ref[rn_end_edge(r->nv, J->end[k])];
  }
  kj->refs = refs;
  memcpy(kj->Qhat, J->Qhat, sizeof(kj->Qhat));
  memcpy(kj->f0, J->f0, sizeof(kj->f0));
  kj->angle0 = J->angle0;
  memcpy(kj->couple_p, J->couple_p, sizeof(kj->couple_p));
  for (int c = 0; c < 3; ++c) kj->M[c] = load_scale * J->M[c];
}

/* ---- scratch ----------------------------------------------------------------- */
rn_status rn_joint_scratch_init(const rn_joint *J, rn_joint_scratch *s) {
  rnk_joint kj;
  size_t n, need;
  memset(&kj, 0, sizeof(kj));
  kj.rigid = rn_joint_has_rotation(J);
  kj.valence = J->valence;
  n = rnk_joint_stencil_size(&kj);
  need = 2 * n + n * n + rnk_joint_work_size(&kj);
  int fixed = J->Mfix[0] != 0.0 || J->Mfix[1] != 0.0 || J->Mfix[2] != 0.0;
  if (fixed) need += n + n * n;
  s->n = (int)n;
  s->heap = NULL;
  s->heap_refs = NULL;
  s->refs = s->frames;
  s->q = s->buf;
  if (need > RN_JOINT_STACK) s->q = s->heap = malloc(need * sizeof(double));
  if (J->valence > RN_JOINT_STACK_ENDS)
    s->refs = s->heap_refs = malloc((size_t)J->valence * sizeof(rnk_frame));
  if ((need > RN_JOINT_STACK && !s->heap) ||
      (J->valence > RN_JOINT_STACK_ENDS && !s->heap_refs)) {
    rn_joint_scratch_free(s);
    return RN_ERR_ALLOC;
  }
  s->v = s->q + n;
  s->loc = s->v + n;
  s->work = s->loc + n * n;
  s->fix = fixed ? s->work + rnk_joint_work_size(&kj) : NULL;
  return RN_OK;
}

void rn_joint_scratch_free(rn_joint_scratch *s) {
  free(s->heap);
  free(s->heap_refs);
  s->heap = NULL;
  s->heap_refs = NULL;
}

/* ---- fixed DOFs and aliases ----------------------------------------------------- */
void rn_joints_sync(rn_network *net) {
  for (int ij = 0; ij < net->njoints; ++ij) {
    const rn_joint *J = &net->joints[ij];
    const double *xj = net->xfull + rn_dof_joint_position(J->off);
    for (int k = 0; k < J->valence; ++k) {
      const rn_rod *r = &net->rods[J->rod[k]];
      double *xv = net->xfull + rn_dof_vertex(r->off, rn_end_vertex(r->nv, J->end[k]));
      memcpy(xv, xj, 3 * sizeof(double));
      if (J->image) { /* periodic image: x_J + F s */
        double off[3];
        rn_cell_image_offset(net, J->image + 3 * k, net->xfull, off);
        for (int c = 0; c < 3; ++c) xv[c] += off[c];
      }
    }
  }
}

/* Continues the stored twists of a clamped joint whose rotation was moved
 * (keeps the 2 pi branch near the stored value), as for clamped rod ends. */
static void continue_joint_twists(rn_network *net, int ij) {
  rn_joint *J = &net->joints[ij];
  rn_joint_scratch s;
  rnk_joint kj;
  if (rn_joint_scratch_init(J, &s)) return;
  rn_joint_kernel(net, ij, net->lambda, s.refs, &kj);
  rn_joint_gather_full(net, J, net->xfull, s.q);
  if (rnk_joint_twists(s.q, &kj, s.v) == RNK_OK)
    for (int k = 0; k < J->valence; ++k) J->ends[k].twist.ref_twist = s.v[k];
  rn_joint_scratch_free(&s);
}

void rn_joints_place(rn_network *net) {
  for (int ij = 0; ij < net->njoints; ++ij) {
    rn_joint *J = &net->joints[ij];
    double *x = net->xfull + rn_dof_joint_position(J->off), w[3];
    int fixed = rn_joint_fixed_components(J);
    for (int c = 0; c < 3; ++c)
      if (rn_component_fixed(fixed, c)) x[c] = J->x0[c] + net->lambda * J->disp[c];
    if (!J->clamped) continue;
    for (int c = 0; c < 3; ++c) {
      w[c] = net->lambda * J->rot[c];
      net->xfull[rn_dof_joint_rotation(J->off) + (size_t)c] = 0.0;
    }
    rnk_rotation_exp(w, J->Qhat);
  }
  rn_joints_sync(net);
}

void rn_joints_continue_twists(rn_network *net) {
  for (int ij = 0; ij < net->njoints; ++ij)
    if (net->joints[ij].clamped && net->joints[ij].has_motion &&
        rn_joint_evaluated(&net->joints[ij]))
      continue_joint_twists(net, ij);
}

/* Rotation (for elastic joints the fit), energy and gradient at the initial
 * state: a degenerate joint there is bad input, not a trial point. */
rn_status rn_joints_check_initial(const rn_network *net, const char *where) {
  for (int ij = 0; ij < net->njoints; ++ij) {
    const rn_joint *J = &net->joints[ij];
    rn_joint_scratch s;
    rnk_joint kj;
    double E, R[9];
    int rc;
    if (!rn_joint_evaluated(J)) continue; /* its owner checks it */
    if (rn_joint_scratch_init(J, &s))
      return rn_fail(net->ctx, RN_ERR_ALLOC, where, "out of memory");
    rn_joint_kernel(net, ij, net->lambda, s.refs, &kj);
    rn_joint_gather_full(net, J, net->xfull, s.q);
    rc = rnk_joint_rotation(s.q, &kj, R);
    if (rc == RNK_OK) rc = rnk_joint_grad(s.q, &kj, s.work, &E, s.loc);
    rn_joint_scratch_free(&s);
    if (rc != RNK_OK)
      return rn_fail(net->ctx, RN_ERR_GEOMETRY, where,
                     "joint %d ('%s'): degenerate at the initial state (%s)", J->gid,
                     J->name ? J->name : "",
                     kj.rigid ? "opposite tangents at a connection edge"
                              : "the incident frames make the rotation fit singular, or "
                                "opposite tangents at a connection edge");
  }
  return RN_OK;
}
