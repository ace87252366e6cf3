/* planar.c - the planar model (docs/model.md "The planar model"): whether a
 * network qualifies, and the out-of-plane DOFs it holds fixed.
 *
 * A network qualifies when the reflection z -> 2 z0 - z maps its energy onto
 * itself and every load and prescribed motion onto itself: then the gradient
 * along the out-of-plane DOFs (z, the material angles, the joint rotations
 * about x and y) vanishes at every planar state, and the in-plane equilibria
 * of the 3D model are those of the in-plane DOFs alone.  With the material
 * directors at rest (d1, d2) and n = (d1 . e_z, d2 . e_z), the curvature of an
 * in-plane bend is perpendicular to n in the (kappa1, kappa2) plane (kappa1 =
 * kb . d2, kappa2 = -kb . d1 with kb along e_z), so the reflection flips the
 * component along n and the twist: the sections must have n as a principal
 * axis, the rest curvature no component along n and the rest twist its value
 * at the (planar) initial state.  The material angles are held, so no twist can
 * be stored (a ring's "link" or "total" twist, a smooth joint's rest twist), and
 * the rest frames of a joint's ends must differ from the initial ones by
 * rotations about the normal (a rigid joint's rotation turns about it only).
 * rn_planar_assess checks the input data before the DOF map,
 * rn_planar_assess_built the joints' rest parameters once they are built;
 * together they are the one predicate behind both the refusal of
 * RN_MODEL_PLANAR and rn_network_planar (the "qualifies" report). */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "bcs/bcs.h"

/* Relative tolerances: positions (of the network's extent), directions of
 * loads and motions (of their own size), sections and rest strains. */
#define PLANAR_TOL_X 1e-12
#define PLANAR_TOL_DIR 1e-12
#define PLANAR_TOL_SEC 1e-10
#define PLANAR_TOL_STRAIN 1e-10

static const char *rod_name(const rn_rod *r) { return r->name ? r->name : ""; }
static const char *joint_name(const rn_joint *J) { return J->name ? J->name : ""; }

/* 1 if the vector v[3] leaves the plane: a force or displacement with a z
 * component (inplane = 1), a moment or rotation with an x or y component
 * (inplane = 0). */
static int leaves(const double v[3], int inplane) {
  double n = fabs(v[0]) + fabs(v[1]) + fabs(v[2]);
  double off = inplane ? fabs(v[2]) : fabs(v[0]) + fabs(v[1]);
  return off > PLANAR_TOL_DIR * n;
}

/* Normal components n = (d1 . e_z, d2 . e_z) of the rest directors of edge j. */
static void edge_normal(const rn_rod *r, int j, double n[2]) {
  const rnk_frame *f = &r->ref_base[j];
  n[0] = f->a1[2];
  n[1] = f->t[0] * f->a1[1] - f->t[1] * f->a1[0]; /* (t x a1) . e_z */
}

static int why(rn_network *net, const char *fmt, ...)
    __attribute__((format(printf, 2, 3)));
static int why(rn_network *net, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(net->planar_why, sizeof net->planar_why, fmt, ap);
  va_end(ap);
  net->planar_ok = 0;
  return 1;
}

static int rod_geometry(rn_network *net, const rn_rod *r, double z0, double tol) {
  for (int v = 0; v < r->nv; ++v)
    if (fabs(r->x0[3 * v + 2] - z0) > tol)
      return why(net, "rod %d ('%s') vertex %d is at z = %.17g, off the plane z = %.17g",
                 r->gid, rod_name(r), v, r->x0[3 * v + 2], z0);
  return 0;
}

/* Sections and rest strains of a rod (see the file comment). */
static int rod_rest(rn_network *net, const rn_rod *r) {
  for (int j = 0; j < r->ne; ++j) {
    const rn_section *s = &r->sec[j];
    double n[2], cross, size = fabs(s->I11) + fabs(s->I22) + fabs(s->I12);
    edge_normal(r, j, n);
    cross = (s->I11 - s->I22) * n[0] * n[1] + s->I12 * (n[1] * n[1] - n[0] * n[0]);
    if (fabs(cross) > PLANAR_TOL_SEC * size)
      return why(net,
                 "rod %d ('%s') edge %d: no principal axis of its section is normal "
                 "to the plane (d1 . e_z = %.6g, I11 = %g, I22 = %g, I12 = %g)",
                 r->gid, rod_name(r), j, n[0], s->I11, s->I22, s->I12);
  }
  for (int i = 1; i < r->nv - 1; ++i) {
    const double *kb = r->kbar + 2 * (i - 1);
    double n[2], off;
    edge_normal(r, i - 1, n);
    off = kb[0] * n[0] + kb[1] * n[1];
    if (fabs(off) > PLANAR_TOL_STRAIN)
      return why(net, "rod %d ('%s') vertex %d: rest curvature out of the plane (%.6g)",
                 r->gid, rod_name(r), i, off);
    off = r->taubar[i - 1] - r->ref_twist[i - 1];
    if (fabs(off) > PLANAR_TOL_STRAIN)
      return why(net, "rod %d ('%s') vertex %d: rest twist %.6g (a planar rod has %.6g)",
                 r->gid, rod_name(r), i, r->taubar[i - 1], r->ref_twist[i - 1]);
  }
  return 0;
}

static int rod_loads_bcs(rn_network *net, const rn_rod *r) {
  for (int v = 0; v < r->nv; ++v) {
    if (leaves(r->fpoint + 3 * v, 1))
      return why(net, "rod %d ('%s') vertex %d: a point force out of the plane", r->gid,
                 rod_name(r), v);
    if (r->has_vdisp[v] && leaves(r->vdisp + 3 * v, 1))
      return why(net,
                 "rod %d ('%s') vertex %d: a prescribed displacement out of the plane",
                 r->gid, rod_name(r), v);
  }
  if (leaves(r->line_load, 1))
    return why(net, "rod %d ('%s'): a line load out of the plane", r->gid, rod_name(r));
  for (int end = RN_START; end <= RN_END; ++end) {
    if (!r->has_end_motion[end]) continue;
    if (leaves(r->end_disp[end], 1) || leaves(r->end_rot[end], 0))
      return why(net,
                 "rod %d ('%s'): the prescribed motion of its %s end leaves the plane",
                 r->gid, rod_name(r), end == RN_START ? "start" : "end");
  }
  return 0;
}

static int joint_checks(rn_network *net, const rn_joint *J, double z0, double tol) {
  if (fabs(J->x0[2] - z0) > tol)
    return why(net, "joint %d ('%s') is at z = %.17g, off the plane z = %.17g", J->gid,
               joint_name(J), J->x0[2], z0);
  if (leaves(J->force, 1))
    return why(net, "joint %d ('%s'): a force out of the plane", J->gid, joint_name(J));
  if (leaves(J->M, 0) || leaves(J->Mfix, 0))
    return why(net, "joint %d ('%s'): a couple about an in-plane axis", J->gid,
               joint_name(J));
  if (J->has_motion && (leaves(J->disp, 1) || leaves(J->rot, 0)))
    return why(net, "joint %d ('%s'): a prescribed motion out of the plane", J->gid,
               joint_name(J));
  return 0;
}

void rn_planar_assess(rn_network *net) {
  double z0 = 0.0, ext = 0.0, tol;
  int have = 0;
  net->planar_ok = 1;
  net->planar_why[0] = '\0';
  for (int ir = 0; ir < net->nrods; ++ir) {
    const rn_rod *r = &net->rods[ir];
    for (int k = 0; k < 3 * r->nv; ++k)
      if (fabs(r->x0[k]) > ext) ext = fabs(r->x0[k]);
    if (!have && r->nv > 0) {
      z0 = r->x0[2];
      have = 1;
    }
  }
  tol = PLANAR_TOL_X * (ext > 0.0 ? ext : 1.0);
  if (net->cell && net->cell->dim != 2) {
    why(net, "a %dD periodic cell", net->cell->dim);
    return;
  }
  if (leaves(net->gravity, 1)) {
    why(net, "gravity out of the plane");
    return;
  }
  for (int ir = 0; ir < net->nrods; ++ir) {
    const rn_rod *r = &net->rods[ir];
    if (rod_geometry(net, r, z0, tol) || rod_rest(net, r) || rod_loads_bcs(net, r))
      return;
  }
  for (int ij = 0; ij < net->njoints; ++ij)
    if (joint_checks(net, &net->joints[ij], z0, tol)) return;
  for (int im = 0; im < net->nmom; ++im)
    if (leaves(net->moments[im].M, 0)) {
      const rn_moment *mo = &net->moments[im];
      why(net, "rod %d ('%s') edge %d: a couple about an in-plane axis",
          net->rods[mo->rod].gid, rod_name(&net->rods[mo->rod]), mo->edge);
      return;
    }
}

/* Rest frame C (rows t, d1, d2) of a rigid or elastic joint end against the
 * initial material frame F of its terminal edge: the rotation P = C^T F taking
 * one to the other turns e_z into p = sum_i (F_i . e_z) C_i.  p = e_z: P is a
 * rotation about the normal (in-plane). */
static void end_normal_image(const rn_network *net, const rn_joint *J, int k,
                             double p[3]) {
  const rn_rod *r = &net->rods[J->rod[k]];
  const rnk_frame *f = &r->ref_base[rn_end_edge(r->nv, J->end[k])];
  const double *C = J->ends[k].cbar;
  double Fz[3];
  Fz[0] = f->t[2];
  Fz[1] = f->a1[2];
  Fz[2] = f->t[0] * f->a1[1] - f->t[1] * f->a1[0]; /* (t x a1) . e_z */
  for (int c = 0; c < 3; ++c) p[c] = Fz[0] * C[c] + Fz[1] * C[3 + c] + Fz[2] * C[6 + c];
}

static const char *rest_form(const rn_joint *J) {
  return J->rest == RN_REST_STRAIGHT ? "\"straight\"" : "\"frames\"";
}

/* Rest frames of a rigid joint (its rotation turns about the normal only) or an
 * elastic one (its fitted rotation is free: the frames relative to the first
 * end's) that the planar model cannot hold. */
static int joint_frames(rn_network *net, const rn_joint *J) {
  double p0[3] = {0.0, 0.0, 1.0};
  int rigid = rn_joint_has_rotation(J);
  if (J->rest == RN_REST_INPUT) return 0; /* the input frames: at rest as given */
  if (!rigid) end_normal_image(net, J, 0, p0);
  for (int k = rigid ? 0 : 1; k < J->valence; ++k) {
    double p[3], off = 0.0;
    end_normal_image(net, J, k, p);
    for (int c = 0; c < 3; ++c) off += fabs(p[c] - p0[c]);
    if (off > PLANAR_TOL_STRAIN)
      return why(
          net,
          "joint %d ('%s') end %d: its rest frame (rest shape %s) is turned out of "
          "the plane against the %s, a rotation the planar model cannot represent",
          J->gid, joint_name(J), k, rest_form(J),
          rigid ? "terminal edge's initial frame" : "first end's");
  }
  return 0;
}

/* The stored twist and rest strains of a smooth joint (the twist carried through
 * it: "link", a ring's "total", rest strains), after build_smooth. */
static int joint_smooth(rn_network *net, const rn_joint *J) {
  const rn_rod *r0 = &net->rods[J->rod[0]];
  const rnk_joint_end *e = &J->ends[0];
  double n[2], off;
  edge_normal(r0, rn_end_edge(r0->nv, RN_END), n);
  off = e->bend.kbar[0] * n[0] + e->bend.kbar[1] * n[1];
  if (fabs(off) > PLANAR_TOL_STRAIN)
    return why(net, "joint %d ('%s'): rest curvature out of the plane (%.6g)", J->gid,
               joint_name(J), off);
  off = e->twist.ref_twist - e->twist.taubar;
  if (fabs(off) <= PLANAR_TOL_STRAIN) return 0;
  if (J->has_total_twist)
    return why(net,
               "joint %d ('%s'): the ring stores the twist %.6g of its \"total\" %.6g; "
               "the planar model holds the material angles and cannot carry twist",
               J->gid, joint_name(J), off, J->total_twist);
  if (J->link)
    return why(net,
               "joint %d ('%s'): the ring stores %d full turn%s of twist (\"link\"); the "
               "planar model holds the material angles and cannot carry twist",
               J->gid, joint_name(J), J->link, J->link == 1 || J->link == -1 ? "" : "s");
  return why(net, "joint %d ('%s'): rest twist %.6g (a planar rod has %.6g)", J->gid,
             joint_name(J), e->twist.taubar, e->twist.ref_twist);
}

void rn_planar_assess_built(rn_network *net) {
  if (!net->planar_ok) return;
  for (int ij = 0; ij < net->njoints; ++ij) {
    const rn_joint *J = &net->joints[ij];
    if (!J->ends) continue;
    if (J->model == RN_JOINT_SMOOTH ? (J->valence == 2 && joint_smooth(net, J))
                                    : joint_frames(net, J))
      return;
  }
  for (int ir = 0; ir < net->nrods; ++ir) { /* a ring's total twist lowers tp */
    const rn_rod *r = &net->rods[ir];
    for (int i = 0; i < r->nv - 2; ++i) {
      double off = r->tp[i].taubar - r->ref_twist[i];
      if (fabs(off) > PLANAR_TOL_STRAIN) {
        why(net, "rod %d ('%s') vertex %d: rest twist %.6g (a planar rod has %.6g)",
            r->gid, rod_name(r), i + 1, r->tp[i].taubar, r->ref_twist[i]);
        return;
      }
    }
  }
}

void rn_planar_mark(rn_network *net) {
  if (!net->planar) return;
  for (int ir = 0; ir < net->nrods; ++ir) {
    const rn_rod *r = &net->rods[ir];
    for (int v = 0; v < r->nv; ++v) net->map[rn_dof_vertex(r->off, v) + 2] = -1;
    for (int j = 0; j < r->ne; ++j) net->map[rn_dof_theta(r->off, j)] = -1;
  }
  for (int ij = 0; ij < net->njoints; ++ij) {
    const rn_joint *J = &net->joints[ij];
    net->map[rn_dof_joint_position(J->off) + 2] = -1;
    if (!rn_joint_has_rotation(J)) continue;
    net->map[rn_dof_joint_rotation(J->off) + 0] = -1;
    net->map[rn_dof_joint_rotation(J->off) + 1] = -1;
  }
}

rn_status rn_network_set_model(rn_network *net, rn_model model) {
  static const char *where = "rn_network_set_model";
  if (!net) return RN_ERR_ARG;
  if (net->finalized)
    return rn_fail(net->ctx, RN_ERR_STATE, where, "the network is already finalized");
  if (model != RN_MODEL_AUTO && model != RN_MODEL_3D && model != RN_MODEL_PLANAR)
    return rn_fail(net->ctx, RN_ERR_ARG, where, "unknown model %d", (int)model);
  net->model = (int)model;
  return RN_OK;
}

int rn_network_is_planar(const rn_network *net) {
  return (net && net->finalized) ? net->planar : -1;
}

int rn_network_planar(const rn_network *net, const char **why_out) {
  if (!net || !net->finalized) return -1;
  if (why_out) *why_out = net->planar_ok ? "" : net->planar_why;
  return net->planar_ok;
}
