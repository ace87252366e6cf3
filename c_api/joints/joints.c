/* joints.c - joints of a rod network: creation (rod ends that meet at one
 * vertex), boundary conditions, loads, names and sizes.  The kernel
 * parameters, validation at finalize and the load factor are in
 * joint_stencil.c; results in joint_results.c. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "joints/joints.h"
#include "periodic/periodic.h"
#include "rodnet_couple.h"
#include "rodnet_ring.h"

void rn_joint_free(rn_joint *J) {
  free(J->name);
  free(J->rod);
  free(J->end);
  free(J->ends);
  free(J->idx);
  free(J->image);
  free(J->img);
  free(J->rest_frames);
  memset(J, 0, sizeof(*J));
}

static const char *end_name(int end) { return end == RN_START ? "start" : "end"; }

/* Range and end value of end k of a new joint, and no end listed twice. */
static rn_status check_joint_end(const rn_network *net, const char *where,
                                 const int *rods, const int *ends, int k) {
  int rod = rods[k], end = ends[k];
  if (rod < 0 || rod >= rn_net_rods_added(net))
    return rn_fail(net->ctx, RN_ERR_RANGE, where, "rod %d does not exist (%d rods)", rod,
                   rn_net_rods_added(net));
  if (end != RN_START && end != RN_END)
    return rn_fail(net->ctx, RN_ERR_ARG, where,
                   "joint end %d: end must be RN_START or RN_END, got %d", k, end);
  for (int l = 0; l < k; ++l)
    if (rods[l] == rod && ends[l] == end)
      return rn_fail(net->ctx, RN_ERR_ARG, where,
                     "the %s of rod %d ('%s') is listed twice in the joint",
                     end_name(end), rod, rn_network_rod_name(net, rod));
  return RN_OK;
}

/* End (local rod lr, whole-network index g) must not belong to another joint. */
static rn_status check_end_free(const rn_network *net, const char *where, int lr, int g,
                                int end) {
  int o = net->rods[lr].joint[end];
  if (o < 0) return RN_OK;
  return rn_fail(net->ctx, RN_ERR_ARG, where,
                 "the %s of rod %d ('%s') already belongs to joint %d ('%s'); a rod "
                 "end belongs to at most one joint",
                 end_name(end), g, rn_network_rod_name(net, g), net->joints[o].gid,
                 net->joints[o].name ? net->joints[o].name : "");
}

static double dist3(const double a[3], const double b[3]) {
  double d0 = a[0] - b[0], d1 = a[1] - b[1], d2 = a[2] - b[2];
  return sqrt(d0 * d0 + d1 * d1 + d2 * d2);
}

/* The end vertices must coincide to RN_JOINT_COINCIDE_TOL of the shortest
 * incident terminal edge; sets J->x0 (first end's vertex) and J->lmin. */
static rn_status check_coincide(const rn_network *net, const char *where,
                                const char *name, rn_joint *J) {
  double lmin = INFINITY;
  for (int k = 0; k < J->valence; ++k) {
    const rn_rod *r = &net->rods[J->rod[k]];
    int j = rn_end_edge(r->nv, J->end[k]);
    double l = dist3(r->x0 + 3 * j, r->x0 + 3 * (j + 1)); /* input length */
    if (l < lmin) lmin = l;
  }
  J->lmin = lmin;
  for (int k = 0; k < J->valence; ++k) {
    const rn_rod *r = &net->rods[J->rod[k]];
    double p[3]; /* the end vertex shifted back from its image (periodic) */
    memcpy(p, r->x0 + 3 * rn_end_vertex(r->nv, J->end[k]), sizeof(p));
    if (J->image) {
      double off[3];
      rn_cell_image_offset(net, J->image + 3 * k, NULL, off);
      for (int c = 0; c < 3; ++c) p[c] -= off[c];
    }
    if (k == 0) {
      memcpy(J->x0, p, sizeof(J->x0));
      continue;
    }
    double d = dist3(J->x0, p);
    if (!(d <= RN_JOINT_COINCIDE_TOL * lmin))
      return rn_fail(net->ctx, RN_ERR_GEOMETRY, where,
                     "joint %d ('%s'): the %s of rod %d ('%s') is %g away from the "
                     "joint's first end (tolerance %g = 1e-9 of the shortest incident "
                     "edge); the end vertices of a joint must coincide",
                     J->gid, name ? name : "", end_name(J->end[k]), r->gid,
                     r->name ? r->name : "", d, RN_JOINT_COINCIDE_TOL * lmin);
  }
  return RN_OK;
}

static rn_status grow_joints(rn_network *net) {
  rn_joint *p;
  int cap;
  if (net->njoints < net->cap_joints) return RN_OK;
  cap = net->cap_joints ? 2 * net->cap_joints : 8;
  p = realloc(net->joints, (size_t)cap * sizeof(*p));
  if (!p) return RN_ERR_ALLOC;
  net->joints = p;
  net->cap_joints = cap;
  return RN_OK;
}

static rn_status joint_alloc(rn_joint *J, const char *name, int n, const int *rods,
                             const int *ends) {
  memset(J, 0, sizeof(*J));
  J->valence = n;
  J->rod = malloc((size_t)n * sizeof(int));
  J->end = malloc((size_t)n * sizeof(int));
  if (name) {
    J->name = malloc(strlen(name) + 1);
    if (J->name) strcpy(J->name, name);
  }
  if (!J->rod || !J->end || (name && !J->name)) return RN_ERR_ALLOC;
  memcpy(J->rod, rods, (size_t)n * sizeof(int));
  memcpy(J->end, ends, (size_t)n * sizeof(int));
  for (int i = 0; i < 9; ++i) J->Qhat[i] = J->f0[i] = (i % 4 == 0) ? 1.0 : 0.0;
  return RN_OK;
}

/* The ends of a new joint held here (keep_end[k]), as local rod indices. */
static int local_ends(const rn_network *net, int n, const int *rods, const int *ends,
                      const int *keep_end, int *lrods, int *lends) {
  int m = 0;
  for (int k = 0; k < n; ++k) {
    int lr = rods[k];
    if (!keep_end[k] || rn_net_rod(net, "", &lr) != RN_OK) continue;
    lrods[m] = lr;
    lends[m++] = ends[k];
  }
  return m;
}

/* Images of the ends of a new joint: all n checked, those of the ends kept here
 * (keep_end; a part's joint lists the ends at its rods) copied into J->image
 * (NULL when every kept shift is zero). */
static rn_status set_images(const rn_network *net, const char *where, const char *name,
                            int n, const int *images, const int *keep_end, rn_joint *J) {
  int any = 0, dim = net->cell ? net->cell->dim : 0;
  if (!images) return RN_OK;
  for (int k = 0; k < n; ++k)
    for (int c = 0; c < 3; ++c) {
      int v = images[3 * k + c];
      if (v == 0) continue;
      if (!net->cell)
        return rn_fail(net->ctx, RN_ERR_STATE, where,
                       "joint '%s' end %d: an image needs a periodic network "
                       "(rn_network_set_periodic)",
                       name ? name : "", k);
      if (c >= dim)
        return rn_fail(net->ctx, RN_ERR_ARG, where,
                       "joint '%s' end %d: image component %d of a %dD cell must be 0",
                       name ? name : "", k, c, dim);
      any |= keep_end[k];
    }
  if (!any) return RN_OK;
  J->image = malloc(3 * (size_t)n * sizeof(int));
  if (!J->image) return rn_fail(net->ctx, RN_ERR_ALLOC, where, "out of memory");
  for (int k = 0, m = 0; k < n; ++k)
    if (keep_end[k]) memcpy(J->image + 3 * m++, images + 3 * k, 3 * sizeof(int));
  return RN_OK;
}

static rn_status add_joint(rn_network *net, const char *where, const char *name,
                           rn_joint_model model, int n_ends, const int *rods,
                           const int *ends, const int *images, int *joint);

rn_status rn_network_add_joint(rn_network *net, const char *name, rn_joint_model model,
                               int n_ends, const int *rods, const int *ends, int *joint) {
  if (!net) return RN_ERR_ARG;
  return add_joint(net, "rn_network_add_joint", name, model, n_ends, rods, ends, NULL,
                   joint);
}

rn_status rn_network_add_joint_images(rn_network *net, const char *name,
                                      rn_joint_model model, int n_ends, const int *rods,
                                      const int *ends, const int *images, int *joint) {
  if (!net) return RN_ERR_ARG;
  return add_joint(net, "rn_network_add_joint_images", name, model, n_ends, rods, ends,
                   images, joint);
}

/* A smooth joint joins the end of one rod to the start of another (or of the
 * same rod: a closed rod); its ends are kept in that order (swapped into
 * sw_*). */
static rn_status smooth_ends(const rn_network *net, const char *where, const char *name,
                             int n_ends, const int **rods, const int **ends,
                             const int **images, int sw_rods[2], int sw_ends[2],
                             int sw_images[6]) {
  if (n_ends != 2 || !*rods || !*ends || (*ends)[0] == (*ends)[1])
    return rn_fail(net->ctx, RN_ERR_ARG, where,
                   "smooth joint '%s' needs valence 2, the end of one rod and the start "
                   "of another (reverse a rod to join two starts or two ends)",
                   name ? name : "");
  if ((*ends)[0] == RN_END) return RN_OK;
  for (int k = 0; k < 2; ++k) {
    sw_rods[k] = (*rods)[1 - k];
    sw_ends[k] = (*ends)[1 - k];
    for (int c = 0; c < 3 && *images; ++c)
      sw_images[3 * k + c] = (*images)[3 * (1 - k) + c];
  }
  *rods = sw_rods;
  *ends = sw_ends;
  if (*images) *images = sw_images;
  return RN_OK;
}

/* Stores the checked joint J (its m local ends lrods[k], lends[k]) as the next
 * joint: the rod ends point to it, a smooth joint of a rod's end to its own start
 * closes the rod; *joint (if given) its whole-network index. */
static void attach_joint(rn_network *net, const rn_joint *J, int m, const int *lrods,
                         const int *lends, int *joint) {
  for (int k = 0; k < m; ++k) net->rods[lrods[k]].joint[lends[k]] = net->njoints;
  if (J->model == RN_JOINT_SMOOTH && m == 2 && lrods[0] == lrods[1])
    net->rods[lrods[0]].closed = 1; /* its end joined to its start: a ring */
  net->joints[net->njoints] = *J;
  if (joint) *joint = J->gid;
  net->njoints++;
}

static rn_status add_joint(rn_network *net, const char *where, const char *name,
                           rn_joint_model model, int n_ends, const int *rods,
                           const int *ends, const int *images, int *joint) {
  rn_joint J;
  rn_status st;
  int keep, m, *buf, sw_rods[2], sw_ends[2], sw_images[6];
  if (!net) return RN_ERR_ARG;
  if ((st = rn_net_check_building(net, where))) return st;
  if (model != RN_JOINT_ELASTIC && model != RN_JOINT_RIGID && model != RN_JOINT_SMOOTH)
    return rn_fail(net->ctx, RN_ERR_ARG, where, "joint '%s': unknown model %d",
                   name ? name : "", (int)model);
  if (model == RN_JOINT_SMOOTH &&
      (st = smooth_ends(net, where, name, n_ends, &rods, &ends, &images, sw_rods, sw_ends,
                        sw_images)))
    return st;
  if (n_ends < 1)
    return rn_fail(net->ctx, RN_ERR_ARG, where,
                   "joint '%s' needs at least one rod end (valence %d)", name ? name : "",
                   n_ends);
  if (!rods || !ends) return rn_fail(net->ctx, RN_ERR_ARG, where, "rods or ends is NULL");
  for (int k = 0; k < n_ends; ++k)
    if ((st = check_joint_end(net, where, rods, ends, k))) return st;
  buf = malloc(3 * (size_t)n_ends * sizeof(int));
  if (!buf) return rn_fail(net->ctx, RN_ERR_ALLOC, where, "out of memory");
  st = rn_part_add_joint(net, name, n_ends, rods, ends, images, &keep, buf);
  if (st != RN_OK) {
    free(buf);
    if (st == RN_NOT_HERE && joint) *joint = rn_net_joints_added(net) - 1;
    return rn_not_here_ok(st);
  }
  m = local_ends(net, n_ends, rods, ends, buf, buf + n_ends, buf + 2 * n_ends);
  for (int k = 0; k < m && !st; ++k)
    st = check_end_free(net, where, buf[n_ends + k], net->rods[buf[n_ends + k]].gid,
                        buf[2 * n_ends + k]);
  if (!st && grow_joints(net))
    st = rn_fail(net->ctx, RN_ERR_ALLOC, where, "out of memory");
  if (!st && joint_alloc(&J, name, m, buf + n_ends, buf + 2 * n_ends)) {
    rn_joint_free(&J);
    st = rn_fail(net->ctx, RN_ERR_ALLOC, where, "out of memory");
  }
  if (st) {
    free(buf);
    return st;
  }
  J.model = (int)model;
  rn_part_tag_joint(net, &J);
  if ((st = set_images(net, where, name, n_ends, images, buf, &J)) ||
      (st = check_coincide(net, where, name, &J))) {
    rn_joint_free(&J);
    free(buf);
    return st;
  }
  attach_joint(net, &J, m, buf + n_ends, buf + 2 * n_ends, joint);
  free(buf);
  return RN_OK;
}

int rn_network_num_joints(const rn_network *net) {
  return net ? rn_net_num_joints_g(net) : 0;
}

/* The joint held here under whole-network index joint, NULL if none. */
static const rn_joint *local_joint(const rn_network *net, int joint) {
  if (!net || joint < 0 || joint >= rn_net_num_joints_g(net)) return NULL;
  if (net->part && rn_net_joint(net, "", &joint) != RN_OK) return NULL;
  return joint < net->njoints ? &net->joints[joint] : NULL;
}

const char *rn_network_joint_name(const rn_network *net, int joint) {
  const rn_joint *J = local_joint(net, joint);
  return (J && J->name) ? J->name : "";
}

int rn_network_joint_model(const rn_network *net, int joint) {
  const rn_joint *J = local_joint(net, joint);
  return J ? J->model : -1;
}

int rn_network_joint_valence(const rn_network *net, int joint) {
  const rn_joint *J = local_joint(net, joint);
  return J ? J->valence : -1;
}

/* ---- boundary conditions and loads ------------------------------------------ */
/* Checks a building call on joint g (whole-network index): *lj receives the
 * local index; RN_NOT_HERE if another part holds the joint (no effect here). */
static rn_status check_joint_arg(const rn_network *net, const char *where, int g,
                                 int *lj) {
  rn_status st;
  *lj = g;
  if ((st = rn_net_check_building(net, where))) return st;
  return rn_net_joint(net, where, lj);
}

rn_status rn_network_clamp_joint(rn_network *net, int joint) {
  rn_status st;
  int lj;
  if (!net) return RN_ERR_ARG;
  st = check_joint_arg(net, "rn_network_clamp_joint", joint, &lj);
  if (st == RN_OK || st == RN_NOT_HERE) net->positions_fixed = 1;
  if (st) return rn_not_here_ok(st);
  net->joints[lj].clamped = 1;
  return RN_OK;
}

/* Pins the components of a joint's position (union with earlier pins). */
static rn_status pin_joint(rn_network *net, const char *where, int joint,
                           int components) {
  rn_status st;
  int lj;
  st = check_joint_arg(net, where, joint, &lj);
  if (st && st != RN_NOT_HERE) return st;
  if (components < 1 || components > RN_FIX_XYZ)
    return rn_fail(net->ctx, RN_ERR_ARG, where,
                   "joint %d: components must be a non-empty RN_FIX_X | RN_FIX_Y | "
                   "RN_FIX_Z bitmask (1 .. 7), got %d",
                   joint, components);
  net->positions_fixed = 1;
  if (st == RN_NOT_HERE) return RN_OK;
  net->joints[lj].pinned |= components;
  return RN_OK;
}

rn_status rn_network_pin_joint(rn_network *net, int joint) {
  if (!net) return RN_ERR_ARG;
  return pin_joint(net, "rn_network_pin_joint", joint, RN_FIX_XYZ);
}

rn_status rn_network_pin_joint_components(rn_network *net, int joint, int components) {
  if (!net) return RN_ERR_ARG;
  return pin_joint(net, "rn_network_pin_joint_components", joint, components);
}

rn_status rn_network_displace_joint(rn_network *net, int joint, const double disp[3],
                                    const double rotvec[3]) {
  static const char *where = "rn_network_displace_joint";
  rn_status st;
  rn_joint *J;
  int lj;
  if (!net) return RN_ERR_ARG;
  st = check_joint_arg(net, where, joint, &lj);
  if (st && st != RN_NOT_HERE) return st;
  if ((disp && !rn_all_finite(3, disp)) || (rotvec && !rn_all_finite(3, rotvec)))
    return rn_fail(net->ctx, RN_ERR_NOT_FINITE, where, "joint %d: motion is not finite",
                   joint);
  if (st == RN_NOT_HERE) return RN_OK;
  J = &net->joints[lj];
  J->has_motion = 1;
  for (int k = 0; k < 3; ++k) {
    J->disp[k] = disp ? disp[k] : 0.0;
    J->rot[k] = rotvec ? rotvec[k] : 0.0;
  }
  return RN_OK;
}

/* Checks a load on joint g; *lj and RN_NOT_HERE as for check_joint_arg. */
static rn_status check_joint_load(const rn_network *net, const char *where, int g,
                                  const double *v, int *lj) {
  rn_status st = check_joint_arg(net, where, g, lj);
  if (st && st != RN_NOT_HERE) return st;
  if (!v) return rn_fail(net->ctx, RN_ERR_ARG, where, "value is NULL");
  if (!rn_all_finite(3, v))
    return rn_fail(net->ctx, RN_ERR_NOT_FINITE, where, "joint %d: load is not finite", g);
  return st;
}

rn_status rn_network_add_joint_force(rn_network *net, int joint, const double f[3]) {
  rn_status st;
  int lj;
  if (!net) return RN_ERR_ARG;
  if ((st = check_joint_load(net, "rn_network_add_joint_force", joint, f, &lj)))
    return rn_not_here_ok(st);
  for (int k = 0; k < 3; ++k) net->joints[lj].force[k] += f[k];
  return RN_OK;
}

rn_status rn_network_add_joint_moment(rn_network *net, int joint, const double m[3]) {
  return rn_network_add_joint_moment_model(net, joint, m, RN_COUPLE_CONSERVATIVE);
}

rn_status rn_network_add_joint_moment_model(rn_network *net, int joint, const double m[3],
                                            rn_couple_model model) {
  static const char *where = "rn_network_add_joint_moment";
  rn_status st;
  int lj;
  if (!net) return RN_ERR_ARG;
  if (model != RN_COUPLE_CONSERVATIVE && model != RN_COUPLE_FIXED)
    return rn_fail(net->ctx, RN_ERR_ARG, where, "joint %d: unknown couple model %d",
                   joint, (int)model);
  st = check_joint_load(net, where, joint, m, &lj);
  if (st && st != RN_NOT_HERE) return st;
  if (model == RN_COUPLE_FIXED && net->nfixed_couples++ == 0) {
    net->fixed_on_joint = 1;
    net->fixed_joint = joint;
    net->fixed_rod = net->fixed_vertex = -1;
  }
  if (st == RN_NOT_HERE) return RN_OK;
  double *dst = model == RN_COUPLE_FIXED ? net->joints[lj].Mfix : net->joints[lj].M;
  for (int k = 0; k < 3; ++k) dst[k] += m[k];
  return RN_OK;
}

/* ---- rest shapes and twist ----------------------------------------------------- */
/* Checks a building call on joint g that sets its rest shape: *lj as for
 * check_joint_arg; RN_ERR_ARG unless the joint's model is in models (bitmask
 * of 1 << model) and (need2) its valence is 2. */
static rn_status check_rest_joint(const rn_network *net, const char *where, int g,
                                  int models, int need2, int *lj) {
  rn_status st = check_joint_arg(net, where, g, lj);
  const rn_joint *J;
  if (st) return st;
  J = &net->joints[*lj];
  if (!((models >> J->model) & 1))
    return rn_fail(net->ctx, RN_ERR_ARG, where,
                   "joint %d ('%s'): this rest form does not apply to a %s joint", g,
                   J->name ? J->name : "",
                   J->model == RN_JOINT_SMOOTH
                       ? "smooth"
                       : (J->model == RN_JOINT_RIGID ? "rigid" : "elastic"));
  if (need2 && J->valence != 2)
    return rn_fail(net->ctx, RN_ERR_ARG, where,
                   "joint %d ('%s'): a straight rest shape needs valence 2, not %d", g,
                   J->name ? J->name : "", J->valence);
  return RN_OK;
}

rn_status rn_network_set_joint_rest_straight(rn_network *net, int joint) {
  rn_status st;
  int lj;
  if (!net) return RN_ERR_ARG;
  if ((st =
           check_rest_joint(net, "rn_network_set_joint_rest_straight", joint, 7, 1, &lj)))
    return rn_not_here_ok(st);
  net->joints[lj].rest = RN_REST_STRAIGHT;
  return RN_OK;
}

/* 1 if the rows of F (row-major) are orthonormal and right-handed to tol. */
static int is_rotation(const double F[9], double tol) {
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) {
      double d = F[3 * a] * F[3 * b] + F[3 * a + 1] * F[3 * b + 1] +
                 F[3 * a + 2] * F[3 * b + 2] - (a == b ? 1.0 : 0.0);
      if (!(fabs(d) <= tol)) return 0;
    }
  double det = F[0] * (F[4] * F[8] - F[5] * F[7]) - F[1] * (F[3] * F[8] - F[5] * F[6]) +
               F[2] * (F[3] * F[7] - F[4] * F[6]);
  return det > 0.0;
}

rn_status rn_network_set_joint_rest_frames(rn_network *net, int joint,
                                           const double *frames) {
  static const char *where = "rn_network_set_joint_rest_frames";
  rn_status st;
  rn_joint *J;
  int lj, models = (1 << RN_JOINT_ELASTIC) | (1 << RN_JOINT_RIGID);
  if (!net) return RN_ERR_ARG;
  if ((st = check_rest_joint(net, where, joint, models, 0, &lj)))
    return rn_not_here_ok(st);
  J = &net->joints[lj];
  if (!frames) return rn_fail(net->ctx, RN_ERR_ARG, where, "frames is NULL");
  for (int k = 0; k < J->valence; ++k)
    if (!rn_all_finite(9, frames + 9 * k) || !is_rotation(frames + 9 * k, 1e-9))
      return rn_fail(net->ctx, RN_ERR_ARG, where,
                     "joint %d ('%s') end %d: the rest frame (rows t, d1, d2) is not "
                     "orthonormal and right-handed to 1e-9",
                     joint, J->name ? J->name : "", k);
  if (!J->rest_frames &&
      !(J->rest_frames = malloc(9 * (size_t)J->valence * sizeof(double))))
    return rn_fail(net->ctx, RN_ERR_ALLOC, where, "out of memory");
  memcpy(J->rest_frames, frames, 9 * (size_t)J->valence * sizeof(double));
  J->rest = RN_REST_FRAMES;
  return RN_OK;
}

rn_status rn_network_set_joint_rest_strains(rn_network *net, int joint,
                                            const double kappa[2], double tau) {
  static const char *where = "rn_network_set_joint_rest_strains";
  rn_status st;
  rn_joint *J;
  int lj;
  if (!net) return RN_ERR_ARG;
  if ((st = check_rest_joint(net, where, joint, 1 << RN_JOINT_SMOOTH, 0, &lj)))
    return rn_not_here_ok(st);
  if (!kappa) return rn_fail(net->ctx, RN_ERR_ARG, where, "kappa is NULL");
  if (!rn_all_finite(2, kappa) || !isfinite(tau))
    return rn_fail(net->ctx, RN_ERR_NOT_FINITE, where,
                   "joint %d: rest strain is not finite", joint);
  J = &net->joints[lj];
  J->rest = RN_REST_STRAINS;
  memcpy(J->rest_kbar, kappa, sizeof(J->rest_kbar));
  J->rest_taubar = tau;
  return RN_OK;
}

rn_status rn_network_set_joint_link(rn_network *net, int joint, int link) {
  rn_status st;
  int lj;
  if (!net) return RN_ERR_ARG;
  if ((st = check_rest_joint(net, "rn_network_set_joint_link", joint,
                             1 << RN_JOINT_SMOOTH, 0, &lj)))
    return rn_not_here_ok(st);
  net->joints[lj].link = link;
  net->joints[lj].has_total_twist = 0;
  return RN_OK;
}

rn_status rn_network_set_ring_total_twist(rn_network *net, int joint, double total) {
  static const char *where = "rn_network_set_ring_total_twist";
  rn_status st;
  int lj;
  if (!net) return RN_ERR_ARG;
  if ((st = check_rest_joint(net, where, joint, 1 << RN_JOINT_SMOOTH, 0, &lj)))
    return rn_not_here_ok(st);
  rn_joint *J = &net->joints[lj];
  if (J->valence != 2 || J->rod[0] != J->rod[1] || !net->rods[J->rod[0]].closed)
    return rn_fail(net->ctx, RN_ERR_ARG, where,
                   "joint %d ('%s') does not close a ring (a total twist applies to "
                   "closed rods only)",
                   joint, J->name ? J->name : "");
  if (!isfinite(total))
    return rn_fail(net->ctx, RN_ERR_NOT_FINITE, where,
                   "joint %d ('%s'): total twist is not finite", joint,
                   J->name ? J->name : "");
  J->has_total_twist = 1;
  J->total_twist = total;
  J->link = 0;
  return RN_OK;
}

/* ---- closed rods ------------------------------------------------------------ */
rn_status rn_network_add_closed_rod(rn_network *net, const char *name, int nv,
                                    const double *xyz, const double *d1, int *rod,
                                    int *joint) {
  static const char *where = "rn_network_add_closed_rod";
  double *xc;
  rn_status st;
  int r = -1, rods[2], ends[2] = {RN_END, RN_START};
  if (!net) return RN_ERR_ARG;
  if ((st = rn_net_check_building(net, where))) return st;
  if (!xyz) return rn_fail(net->ctx, RN_ERR_ARG, where, "xyz is NULL");
  if (nv < 3)
    return rn_fail(net->ctx, RN_ERR_ARG, where,
                   "closed rod '%s' needs at least 3 vertices, got %d", name ? name : "",
                   nv);
  xc = malloc(3 * ((size_t)nv + 1) * sizeof(double));
  if (!xc) return rn_fail(net->ctx, RN_ERR_ALLOC, where, "out of memory");
  memcpy(xc, xyz, 3 * (size_t)nv * sizeof(double));
  memcpy(xc + 3 * (size_t)nv, xyz, 3 * sizeof(double)); /* the closing vertex */
  st = rn_network_add_rod(net, name, nv + 1, xc, d1, &r);
  free(xc);
  if (st) return st;
  rods[0] = rods[1] = r;
  if ((st = rn_network_add_joint(net, name, RN_JOINT_SMOOTH, 2, rods, ends, joint)))
    return st;
  if (rod) *rod = r;
  return RN_OK;
}
