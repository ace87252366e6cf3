/* state.c - snapshots of a network's mutable state (rn_network_state_save /
 * _restore): everything that evaluation depends on and that solving, reference
 * updates or the load factor change.  Rods: the full state vector (with the
 * fixed entries at the saved load factor), the reference frames and reference
 * twists; moments: frame f0 and accumulated angle; joints: reference rotation
 * Qhat, couple frame f0 and angle, and the stored twist of every end.  What
 * finalize builds and nothing changes afterwards (rest quantities, parameters,
 * the DOF map, the couples' body vectors) is not copied. */
#include <stdlib.h>
#include <string.h>

#include "core/network_internal.h"

/* Per moment: f0[9], angle0.  Per joint: Qhat[9], f0[9], angle0. */
enum { MOMENT_DOUBLES = 10, JOINT_DOUBLES = 19 };

struct rn_state {
  const rn_network *net; /* the network it belongs to */
  size_t nfull, nedges, ninterior, nends;
  int nrods, nmom, njoints;
  double lambda, lambda_x;
  double *xfull;      /* [nfull] */
  rnk_frame *frames;  /* reference frames, rods concatenated [nedges] */
  double *twists;     /* reference twists, rods concatenated [ninterior] */
  double *moments;    /* [MOMENT_DOUBLES nmom] */
  double *joints;     /* [JOINT_DOUBLES njoints] */
  double *end_twists; /* joint end reference twists, joints concatenated [nends] */
};

static void count_sizes(const rn_network *net, rn_state *s) {
  s->net = net;
  s->nfull = net->nfull;
  s->nrods = net->nrods;
  s->nmom = net->nmom;
  s->njoints = net->njoints;
  s->nedges = s->ninterior = s->nends = 0;
  for (int ir = 0; ir < net->nrods; ++ir) {
    s->nedges += (size_t)net->rods[ir].ne;
    s->ninterior += (size_t)(net->rods[ir].nv - 2);
  }
  for (int ij = 0; ij < net->njoints; ++ij) s->nends += (size_t)net->joints[ij].valence;
}

/* 1 if s was saved from net (same object, same sizes). */
static int state_matches(const rn_network *net, const rn_state *s) {
  rn_state t;
  count_sizes(net, &t);
  return s->net == net && s->nfull == t.nfull && s->nrods == t.nrods &&
         s->nmom == t.nmom && s->njoints == t.njoints && s->nedges == t.nedges &&
         s->ninterior == t.ninterior && s->nends == t.nends;
}

static rn_status state_alloc(rn_state *s) {
  s->xfull = malloc((s->nfull + 1) * sizeof(double));
  s->frames = malloc((s->nedges + 1) * sizeof(rnk_frame));
  s->twists = malloc((s->ninterior + 1) * sizeof(double));
  s->moments = malloc(((size_t)MOMENT_DOUBLES * (size_t)s->nmom + 1) * sizeof(double));
  s->joints = malloc(((size_t)JOINT_DOUBLES * (size_t)s->njoints + 1) * sizeof(double));
  s->end_twists = malloc((s->nends + 1) * sizeof(double));
  return (s->xfull && s->frames && s->twists && s->moments && s->joints && s->end_twists)
             ? RN_OK
             : RN_ERR_ALLOC;
}

static void copy_rods_out(const rn_network *net, rn_state *s) {
  size_t fo = 0, to = 0;
  for (int ir = 0; ir < net->nrods; ++ir) {
    const rn_rod *r = &net->rods[ir];
    memcpy(s->frames + fo, r->ref, (size_t)r->ne * sizeof(rnk_frame));
    if (r->nv > 2)
      memcpy(s->twists + to, r->ref_twist, (size_t)(r->nv - 2) * sizeof(double));
    fo += (size_t)r->ne;
    to += (size_t)(r->nv - 2);
  }
}

static void copy_rods_in(rn_network *net, const rn_state *s) {
  size_t fo = 0, to = 0;
  for (int ir = 0; ir < net->nrods; ++ir) {
    rn_rod *r = &net->rods[ir];
    memcpy(r->ref, s->frames + fo, (size_t)r->ne * sizeof(rnk_frame));
    if (r->nv > 2)
      memcpy(r->ref_twist, s->twists + to, (size_t)(r->nv - 2) * sizeof(double));
    fo += (size_t)r->ne;
    to += (size_t)(r->nv - 2);
  }
}

static void copy_moments_out(const rn_network *net, rn_state *s) {
  for (int im = 0; im < net->nmom; ++im) {
    double *d = s->moments + (size_t)MOMENT_DOUBLES * (size_t)im;
    memcpy(d, net->moments[im].f0, 9 * sizeof(double));
    d[9] = net->moments[im].angle0;
  }
}

static void copy_moments_in(rn_network *net, const rn_state *s) {
  for (int im = 0; im < net->nmom; ++im) {
    const double *d = s->moments + (size_t)MOMENT_DOUBLES * (size_t)im;
    memcpy(net->moments[im].f0, d, 9 * sizeof(double));
    net->moments[im].angle0 = d[9];
  }
}

static void copy_joints_out(const rn_network *net, rn_state *s) {
  size_t eo = 0;
  for (int ij = 0; ij < net->njoints; ++ij) {
    const rn_joint *J = &net->joints[ij];
    double *d = s->joints + (size_t)JOINT_DOUBLES * (size_t)ij;
    memcpy(d, J->Qhat, 9 * sizeof(double));
    memcpy(d + 9, J->f0, 9 * sizeof(double));
    d[18] = J->angle0;
    for (int k = 0; k < J->valence; ++k) s->end_twists[eo++] = J->ends[k].twist.ref_twist;
  }
}

static void copy_joints_in(rn_network *net, const rn_state *s) {
  size_t eo = 0;
  for (int ij = 0; ij < net->njoints; ++ij) {
    rn_joint *J = &net->joints[ij];
    const double *d = s->joints + (size_t)JOINT_DOUBLES * (size_t)ij;
    memcpy(J->Qhat, d, 9 * sizeof(double));
    memcpy(J->f0, d + 9, 9 * sizeof(double));
    J->angle0 = d[18];
    for (int k = 0; k < J->valence; ++k) J->ends[k].twist.ref_twist = s->end_twists[eo++];
  }
}

rn_status rn_network_state_save(const rn_network *net, rn_state **out) {
  static const char *where = "rn_network_state_save";
  rn_status st;
  rn_state *s;
  if (out) *out = NULL;
  if (!net) return RN_ERR_ARG;
  if (!out) return rn_fail(net->ctx, RN_ERR_ARG, where, "output pointer is NULL");
  if ((st = rn_net_check_final(net, where))) return st;
  s = calloc(1, sizeof(*s));
  if (!s) return rn_fail(net->ctx, RN_ERR_ALLOC, where, "out of memory");
  count_sizes(net, s);
  if (state_alloc(s)) {
    rn_state_destroy(&s);
    return rn_fail(net->ctx, RN_ERR_ALLOC, where, "out of memory");
  }
  s->lambda = net->lambda;
  s->lambda_x = net->lambda_x;
  memcpy(s->xfull, net->xfull, net->nfull * sizeof(double));
  copy_rods_out(net, s);
  copy_moments_out(net, s);
  copy_joints_out(net, s);
  *out = s;
  return RN_OK;
}

rn_status rn_network_state_restore(rn_network *net, const rn_state *s) {
  static const char *where = "rn_network_state_restore";
  rn_status st;
  if (!net) return RN_ERR_ARG;
  if (!s) return rn_fail(net->ctx, RN_ERR_ARG, where, "state is NULL");
  if ((st = rn_net_check_final(net, where))) return st;
  if (!state_matches(net, s))
    return rn_fail(net->ctx, RN_ERR_ARG, where,
                   "the state was saved from another network");
  net->lambda = s->lambda;
  net->lambda_x = s->lambda_x;
  memcpy(net->xfull, s->xfull, net->nfull * sizeof(double));
  copy_rods_in(net, s);
  copy_moments_in(net, s);
  copy_joints_in(net, s);
  return rn_net_accept_state(net, where);
}

void rn_state_destroy(rn_state **s) {
  if (!s || !*s) return;
  free((*s)->xfull);
  free((*s)->frames);
  free((*s)->twists);
  free((*s)->moments);
  free((*s)->joints);
  free((*s)->end_twists);
  free(*s);
  *s = NULL;
}
