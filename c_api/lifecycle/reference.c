/* reference.c - explicit update of the reference state on an accepted step:
 * reference twists continued with the old frames, frames moved by
 * time-parallel transport, moment angles accumulated; at joints the end
 * twists are continued, the couple angle accumulated and the rotation of a
 * rigid joint moved into its reference rotation (its rotation DOFs reset to
 * 0).  All new values are computed first, from the old reference state, and
 * committed only if every stencil succeeded. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "contact/contact.h"
#include "joints/joints.h"
#include "periodic/periodic.h"
#include "rodnet_couple.h"

static const char *where = "rn_network_update_reference";

typedef struct ref_update {
  double *full;      /* new full state [nfull] */
  rnk_frame *frames; /* new frames, all rods concatenated */
  double *twists;    /* new reference twists, all rods concatenated */
  double *angles;    /* new moment angles [nmom] */
  double *f0;        /* new moment frames [9 nmom] */
  double *jtw;       /* new joint end twists, all joints concatenated */
  double *jang;      /* new joint couple angles [njoints] */
  double *jQ;        /* joint rotations at x [9 njoints] */
} ref_update;

static void ref_update_free(ref_update *u) {
  free(u->full);
  free(u->frames);
  free(u->twists);
  free(u->angles);
  free(u->f0);
  free(u->jtw);
  free(u->jang);
  free(u->jQ);
}

static rn_status ref_update_alloc(const rn_network *net, ref_update *u) {
  size_t ne = 0, nin = 0, nm = (size_t)net->nmom + 1, nj = (size_t)net->njoints + 1;
  size_t nends = 1;
  for (int ij = 0; ij < net->njoints; ++ij) nends += (size_t)net->joints[ij].valence;
  for (int ir = 0; ir < net->nrods; ++ir) {
    ne += (size_t)net->rods[ir].ne;
    nin += (size_t)(net->rods[ir].nv - 2);
  }
  u->full = malloc((net->nfull + 1) * sizeof(double));
  u->frames = malloc((ne + 1) * sizeof(rnk_frame));
  u->twists = malloc((nin + 1) * sizeof(double));
  u->angles = malloc(nm * sizeof(double));
  u->f0 = malloc(9 * nm * sizeof(double));
  u->jtw = malloc(nends * sizeof(double));
  u->jang = malloc(nj * sizeof(double));
  u->jQ = malloc(9 * nj * sizeof(double));
  return (u->full && u->frames && u->twists && u->angles && u->f0 && u->jtw && u->jang &&
          u->jQ)
             ? RN_OK
             : RN_ERR_ALLOC;
}

/* New twists and frames of one rod into tw[nv-2] and fr[ne]. */
/* A ghost rod of a part updates only the frames of the terminal edges its
 * part's joints read (every DOF of the edge held), and keeps its twists. */
static int edge_held(const rn_network *net, const rn_rod *r, int j) {
  size_t s = rn_dof_edge_stencil(r->off, j);
  for (int k = 0; k < RN_EDGE_STENCIL; ++k)
    if (net->map[s + (size_t)k] == RN_DOF_ABSENT) return 0;
  return 1;
}

static rn_status update_rod(const rn_network *net, int ir, const double *full, double *tw,
                            rnk_frame *fr) {
  const rn_rod *r = &net->rods[ir];
  if (r->ghost) {
    if (r->nv > 2) memcpy(tw, r->ref_twist, (size_t)(r->nv - 2) * sizeof(double));
    for (int j = 0; j < r->ne; ++j) {
      const double *q = full + rn_dof_edge_stencil(r->off, j);
      double e[3];
      fr[j] = r->ref[j];
      if (!edge_held(net, r, j)) continue;
      for (int k = 0; k < 3; ++k)
        e[k] = q[RN_EDGE_LOCAL_X1 + k] - q[RN_EDGE_LOCAL_X0 + k];
      if (rnk_frame_update(e, &fr[j]) != RNK_OK)
        return rn_fail(net->ctx, RN_DEGENERATE, where, "rod %d edge %d: degenerate edge",
                       r->gid, j);
    }
    return RN_OK;
  }
  for (int i = 1; i < r->nv - 1; ++i) {
    const double *q = full + rn_dof_vertex_stencil(r->off, i);
    if (rnk_reference_twist(q, &r->ref[i - 1], r->ref_twist[i - 1], &tw[i - 1]) != RNK_OK)
      return rn_fail(net->ctx, RN_DEGENERATE, where,
                     "rod %d vertex %d: degenerate reference twist", r->gid, i);
  }
  for (int j = 0; j < r->ne; ++j) {
    const double *q = full + rn_dof_edge_stencil(r->off, j);
    double e[3];
    for (int k = 0; k < 3; ++k) e[k] = q[RN_EDGE_LOCAL_X1 + k] - q[RN_EDGE_LOCAL_X0 + k];
    fr[j] = r->ref[j];
    if (rnk_frame_update(e, &fr[j]) != RNK_OK)
      return rn_fail(net->ctx, RN_DEGENERATE, where, "rod %d edge %d: degenerate edge",
                     r->gid, j);
  }
  return RN_OK;
}

/* The conservative couple (rodnet_couple.h) turns the arm f about the fixed
 * axis n = M / |M|; its potential -|M| phi is singular where f reaches n (phi
 * undefined, the applied moment |M| / cos(beta) unbounded, beta the tilt of f
 * out of the plane normal to n) and not bounded below in 3D: each passage of f
 * around n adds 2 pi to phi at no elastic cost, which an energy minimiser
 * follows without end.  An accepted state with the tilt beyond
 * RN_COUPLE_TILT_MAX degrees is on that road (the couple then applies more
 * than 5.7 |M|): the update fails with RN_ERR_SOLVER naming the couple.  f
 * (unit) = sum_k b[k] F_k for a rod edge's frame rows F (t, d1, d2), Q p for a
 * joint; what names the couple. */
#define RN_COUPLE_TILT_MAX 80.0
int rn_network_set_couple_tilt_check(rn_network *net, int on) {
  int was;
  if (!net) return -1;
  was = !net->couple_tilt_off;
  net->couple_tilt_off = !on;
  return was;
}

static rn_status couple_tilt(const rn_network *net, const double M[3], const double f[3],
                             const char *what) {
  double mm = sqrt(M[0] * M[0] + M[1] * M[1] + M[2] * M[2]), ff, s, beta;
  ff = sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
  if (net->couple_tilt_off || !(mm > 0.0) || !(ff > 0.0)) return RN_OK;
  s = fabs(M[0] * f[0] + M[1] * f[1] + M[2] * f[2]) / (mm * ff);
  beta = asin(s < 1.0 ? s : 1.0) * 57.29577951308232; /* degrees */
  if (beta <= RN_COUPLE_TILT_MAX) return RN_OK;
  return rn_fail(
      net->ctx, RN_ERR_SOLVER, where,
      "the conservative couple on %s has turned its arm %.1f degrees out of "
      "the plane normal to M (it applies |m| = %.3g |M|, more than %g degrees "
      "is refused): past the couple's axis its potential is unbounded below in "
      "3D and the energy minimiser is following that; for a couple fixed in "
      "space give the moment \"model\": \"fixed\" and solve with --solver nox, "
      "for a couple about the normal of a planar structure use \"model\": "
      "\"planar\" (docs/model.md, Couples)",
      what, beta, 1.0 / sqrt(1.0 - s * s > 0.0 ? 1.0 - s * s : 0.0), RN_COUPLE_TILT_MAX);
}

/* New accumulated angle and frame of every moment (old reference frames). */
static rn_status update_moments(const rn_network *net, const double *full,
                                ref_update *u) {
  for (int im = 0; im < net->nmom; ++im) {
    const rn_moment *mo = &net->moments[im];
    const rn_rod *r = &net->rods[mo->rod];
    const double *q = full + rn_dof_edge_stencil(r->off, mo->edge);
    const rnk_frame *ref = &r->ref[mo->edge];
    rnk_moment_param p;
    double alpha = 0.0, e[3], *f0 = u->f0 + 9 * im;
    if (r->ghost) { /* its owner updates it */
      u->angles[im] = mo->angle0;
      memcpy(f0, mo->f0, sizeof(mo->f0));
      continue;
    }
    memcpy(p.M, mo->M, sizeof(p.M));
    memcpy(p.f0, mo->f0, sizeof(p.f0));
    memcpy(p.b, mo->b, sizeof(p.b));
    p.angle0 = mo->angle0;
    for (int k = 0; k < 3; ++k) e[k] = q[RN_EDGE_LOCAL_X1 + k] - q[RN_EDGE_LOCAL_X0 + k];
    if ((mo->M[0] != 0.0 || mo->M[1] != 0.0 || mo->M[2] != 0.0) &&
        mo->model == RN_COUPLE_CONSERVATIVE &&
        rnk_moment_angle(q, ref, &p, &alpha) != RNK_OK)
      return rn_fail(net->ctx, RN_DEGENERATE, where,
                     "rod %d vertex %d: degenerate moment angle", r->gid, mo->vertex);
    u->angles[im] = mo->angle0 + alpha;
    if (rnk_material_frame(e, ref, q[RN_EDGE_LOCAL_THETA], f0, f0 + 3, f0 + 6) != RNK_OK)
      return rn_fail(net->ctx, RN_DEGENERATE, where, "rod %d edge %d: degenerate edge",
                     r->gid, mo->edge);
    if (mo->model == RN_COUPLE_CONSERVATIVE) {
      double f[3];
      char what[200];
      rn_status st;
      for (int c = 0; c < 3; ++c)
        f[c] = mo->b[0] * f0[c] + mo->b[1] * f0[3 + c] + mo->b[2] * f0[6 + c];
      snprintf(what, sizeof what, "rod %d ('%s') vertex %d", r->gid,
               r->name ? r->name : "", mo->vertex);
      if ((st = couple_tilt(net, mo->M, f, what))) return st;
    }
  }
  return RN_OK;
}

/* Joint ij at the full state: end twists into tw[valence], couple angle and
 * rotation (old reference frames and rotations). */
static rn_status update_joint(const rn_network *net, int ij, const double *full,
                              double *tw, double *angle, double Q[9]) {
  const rn_joint *J = &net->joints[ij];
  rn_joint_scratch s;
  rnk_joint kj;
  double alpha = 0.0;
  int rc;
  if (J->ghost) { /* a ghost joint of a part: its owner updates it */
    for (int k = 0; k < J->valence; ++k) tw[k] = J->ends[k].twist.ref_twist;
    *angle = J->angle0;
    memcpy(Q, J->f0, sizeof(J->f0));
    return RN_OK;
  }
  if (rn_joint_scratch_init(J, &s))
    return rn_fail(net->ctx, RN_ERR_ALLOC, where, "out of memory");
  rn_joint_kernel(net, ij, net->lambda, s.refs, &kj);
  memcpy(kj.M, J->M, sizeof(kj.M)); /* its axis (unscaled: lambda may be 0) */
  rn_joint_gather_full(net, J, full, s.q);
  rc = rnk_joint_twists(s.q, &kj, tw);
  if (rc == RNK_OK) rc = rnk_joint_couple_angle(s.q, &kj, &alpha);
  if (rc == RNK_OK) rc = rnk_joint_rotation(s.q, &kj, Q);
  rn_joint_scratch_free(&s);
  if (rc != RNK_OK)
    return rn_fail(net->ctx, RN_DEGENERATE, where, "joint %d ('%s'): degenerate joint",
                   J->gid, J->name ? J->name : "");
  *angle = J->angle0 + alpha;
  return RN_OK;
}

/* A rigid joint whose rotation is free: its rotation moves into Qhat (by its
 * owner, in a part). */
static int rotation_moves(const rn_joint *J) {
  return J->model == RN_JOINT_RIGID && !J->clamped && !J->ghost;
}

static rn_status update_joints(const rn_network *net, ref_update *u) {
  size_t to = 0;
  rn_status st;
  for (int ij = 0; ij < net->njoints; ++ij) {
    const rn_joint *J = &net->joints[ij];
    if ((st = update_joint(net, ij, u->full, u->jtw + to, u->jang + ij, u->jQ + 9 * ij)))
      return st;
    if (!J->ghost) {
      const double *Q = u->jQ + 9 * ij;
      double f[3];
      char what[200];
      for (int a = 0; a < 3; ++a)
        f[a] = Q[3 * a] * J->couple_p[0] + Q[3 * a + 1] * J->couple_p[1] +
               Q[3 * a + 2] * J->couple_p[2];
      snprintf(what, sizeof what, "joint %d ('%s')", J->gid, J->name ? J->name : "");
      if ((st = couple_tilt(net, J->M, f, what))) return st;
    }
    to += (size_t)J->valence;
  }
  for (int ij = 0; ij < net->njoints; ++ij) /* after every joint used the old w */
    if (rotation_moves(&net->joints[ij]))
      for (int c = 0; c < 3; ++c)
        u->full[rn_dof_joint_rotation(net->joints[ij].off) + (size_t)c] = 0.0;
  return RN_OK;
}

static void commit_joints(rn_network *net, const ref_update *u, double *x) {
  size_t to = 0;
  for (int ij = 0; ij < net->njoints; ++ij) {
    rn_joint *J = &net->joints[ij];
    for (int k = 0; k < J->valence; ++k)
      J->ends[k].twist.ref_twist = u->jtw[to + (size_t)k];
    to += (size_t)J->valence;
    J->angle0 = u->jang[ij];
    memcpy(J->f0, u->jQ + 9 * ij, sizeof(J->f0));
    if (!rotation_moves(J)) continue;
    memcpy(J->Qhat, u->jQ + 9 * ij, sizeof(J->Qhat));
    for (int c = 0; c < 3; ++c) {
      int64_t m = net->map[rn_dof_joint_rotation(J->off) + (size_t)c];
      if (m >= 0) x[m] = 0.0;
    }
  }
}

static void commit(rn_network *net, const ref_update *u, double *x) {
  size_t fo = 0, to = 0;
  memcpy(net->xfull, u->full, net->nfull * sizeof(double));
  for (int ir = 0; ir < net->nrods; ++ir) {
    rn_rod *r = &net->rods[ir];
    memcpy(r->ref, u->frames + fo, (size_t)r->ne * sizeof(rnk_frame));
    if (r->nv > 2)
      memcpy(r->ref_twist, u->twists + to, (size_t)(r->nv - 2) * sizeof(double));
    fo += (size_t)r->ne;
    to += (size_t)(r->nv - 2);
  }
  for (int im = 0; im < net->nmom; ++im) {
    net->moments[im].angle0 = u->angles[im];
    memcpy(net->moments[im].f0, u->f0 + 9 * im, 9 * sizeof(double));
  }
  commit_joints(net, u, x);
}

rn_status rn_network_update_reference(rn_network *net, double *x) {
  ref_update u = {NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL};
  size_t fo = 0, to = 0;
  rn_status st;
  if (!net) return RN_ERR_ARG;
  if ((st = rn_net_check_final(net, where))) return st;
  if (!x && net->nred) return rn_fail(net->ctx, RN_ERR_ARG, where, "x is NULL");
  if (!rn_all_finite(net->nred, x))
    return rn_fail(net->ctx, RN_ERR_NOT_FINITE, where, "x has NaN or infinite entries");
  if (ref_update_alloc(net, &u)) {
    ref_update_free(&u);
    return rn_fail(net->ctx, RN_ERR_ALLOC, where, "out of memory");
  }
  rn_expand_state(net, x, u.full);
  for (int ir = 0; ir < net->nrods && !st; ++ir) {
    st = update_rod(net, ir, u.full, u.twists + to, u.frames + fo);
    fo += (size_t)net->rods[ir].ne;
    to += (size_t)(net->rods[ir].nv - 2);
  }
  if (!st) st = update_moments(net, u.full, &u);
  if (!st) st = update_joints(net, &u);
  if (!st) {
    commit(net, &u, x);
    net->lambda_x = net->lambda;
  }
  ref_update_free(&u);
  if (!st) st = rn_contact_pattern_update(net, 0, where);
  return st;
}
