/* load_increment.c - rn_network_load_increment: the first-order change of the
 * reduced gradient at fixed free DOFs when the load factor goes from t_prev to
 * t (the linearised load-increment predictor of a load step).  Evaluated at
 * t_prev; the network's whole mutable state is saved before and restored after
 * (rn_network_state_save / _restore), so the call leaves it as it found it. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bcs/bcs.h"
#include "eval/eval.h"
#include "rodq.h"

static const char *const where = "rn_network_load_increment";

static rn_status check_args(const rn_network *net, const double *x, double t_prev,
                            double t, const double *dg) {
  rn_status st;
  if ((st = rn_net_check_final(net, where))) return st;
  if ((!x || !dg) && net->nred) return rn_fail(net->ctx, RN_ERR_ARG, where, "NULL array");
  if (!rn_all_finite(net->nred, x))
    return rn_fail(net->ctx, RN_ERR_NOT_FINITE, where, "x has NaN or infinite entries");
  if (!isfinite(t_prev) || !isfinite(t))
    return rn_fail(net->ctx, RN_ERR_NOT_FINITE, where, "load factor is not finite");
  if (t_prev < 0.0 || t_prev > 1.0 || t < 0.0 || t > 1.0)
    return rn_fail(net->ctx, RN_ERR_ARG, where, "load factors %g, %g: outside [0, 1]",
                   t_prev, t);
  return RN_OK;
}

/* Angle about the clamped edge's tangent at t (positions in full_t) from the
 * director of the reference frame ref_prev (at t_prev) to that of ref_t, both
 * transported to that tangent: the material angle that gives, with the
 * reference frame at t_prev, the material frame the clamp prescribes at t. */
static int clamp_angle(const double *full_t, size_t s, const rnk_frame *ref_prev,
                       const rnk_frame *ref_t, double *phi) {
  const double *xa = full_t + s, *xb = full_t + s + 4;
  double e[3], n, tt[3], a[3], b[3], c[3];
  int rc;
  for (int k = 0; k < 3; ++k) e[k] = xb[k] - xa[k];
  n = sqrt(rq_dot3(e, e));
  if (!(n > 0.0)) return RNK_DEGENERATE;
  for (int k = 0; k < 3; ++k) tt[k] = e[k] / n;
  if ((rc = rnk_transport(ref_prev->t, tt, ref_prev->a1, a)) != RNK_OK) return rc;
  if ((rc = rnk_transport(ref_t->t, tt, ref_t->a1, b)) != RNK_OK) return rc;
  c[0] = a[1] * b[2] - a[2] * b[1];
  c[1] = a[2] * b[0] - a[0] * b[2];
  c[2] = a[0] * b[1] - a[1] * b[0];
  *phi = atan2(rq_dot3(tt, c), rq_dot3(a, b));
  return RNK_OK;
}

/* Reference frames of the clamped edges with prescribed motion, at the current
 * load factor: frames[2 ir + end]. */
static void save_clamp_frames(const rn_network *net, rnk_frame *frames) {
  for (int ir = 0; ir < net->nrods; ++ir) {
    const rn_rod *r = &net->rods[ir];
    for (int end = RN_START; end <= RN_END; ++end)
      if (r->clamped[end] && r->has_end_motion[end])
        frames[2 * ir + end] = r->ref[rn_end_edge(r->nv, end)];
  }
}

/* dfull = the increment of the fixed entries of the full state from t_prev to
 * t (free entries 0) with the network at t_prev on return.  The material angles
 * of turned clamped edges are summed over sub-steps of at most RN_RAMP_ANGLE of
 * turn (phi[2 nrods]), so a turn of any size keeps its winding.  Joint rotations
 * of clamped joints: Q = exp(w) Qhat with Qhat = exp(lambda rot), so the
 * increment of w is (t - t_prev) rot. */
static rn_status fixed_increment(rn_network *net, double t_prev, double t, double *dfull,
                                 rnk_frame *frames, double *phi) {
  const int n = rn_ramp_steps(fabs(t - t_prev) * rn_prescribed_rotation_rate(net));
  rnk_frame *prev = frames, *cur = frames + 2 * (size_t)net->nrods, *tmp;
  double *full_t = dfull;
  memset(phi, 0, 2 * (size_t)net->nrods * sizeof(double));
  rn_ramp_load_factor(net, t_prev);
  save_clamp_frames(net, prev);
  for (int k = 1; k <= n; ++k) {
    rn_ramp_load_factor(net, k == n ? t : t_prev + (t - t_prev) * (double)k / (double)n);
    save_clamp_frames(net, cur);
    for (int ir = 0; ir < net->nrods; ++ir) {
      const rn_rod *r = &net->rods[ir];
      for (int end = RN_START; end <= RN_END; ++end) {
        int j = rn_end_edge(r->nv, end);
        double p = 0.0;
        if (!r->clamped[end] || !r->has_end_motion[end] ||
            net->map[rn_dof_theta(r->off, j)] >= 0)
          continue;
        if (clamp_angle(net->xfull, rn_dof_edge_stencil(r->off, j), &prev[2 * ir + end],
                        &cur[2 * ir + end], &p) != RNK_OK)
          return rn_fail(net->ctx, RN_DEGENERATE, where,
                         "clamped edge %d of rod %d ('%s') is degenerate", j, r->gid,
                         r->name ? r->name : "");
        phi[2 * ir + end] += p;
      }
    }
    tmp = prev;
    prev = cur;
    cur = tmp;
  }
  memcpy(full_t, net->xfull, net->nfull * sizeof(double));
  rn_ramp_load_factor(net, t_prev);
  for (int ir = 0; ir < net->nrods; ++ir) {
    const rn_rod *r = &net->rods[ir];
    for (int end = RN_START; end <= RN_END; ++end) {
      size_t th = rn_dof_theta(r->off, rn_end_edge(r->nv, end));
      if (!r->clamped[end] || !r->has_end_motion[end] || net->map[th] >= 0) continue;
      full_t[th] = net->xfull[th] + phi[2 * ir + end]; /* the difference below */
    }
  }
  for (size_t i = 0; i < net->nfull; ++i)
    dfull[i] = net->map[i] >= 0 ? 0.0 : full_t[i] - net->xfull[i];
  for (int ij = 0; ij < net->njoints; ++ij) {
    const rn_joint *J = &net->joints[ij];
    if (!J->clamped) continue;
    for (int c = 0; c < 3; ++c)
      dfull[rn_dof_joint_rotation(J->off) + (size_t)c] = (t - t_prev) * J->rot[c];
  }
  return RN_OK;
}

static rn_status increment_at(rn_network *net, const double *x, double t_prev, double t,
                              double *dg) {
  double *dfull = malloc((net->nfull + 1) * sizeof(double));
  double *rate = malloc((net->nred + 1) * sizeof(double));
  double *phi = malloc((2 * (size_t)net->nrods + 1) * sizeof(double));
  rnk_frame *frames = malloc((4 * (size_t)net->nrods + 1) * sizeof(rnk_frame));
  rn_status st = RN_ERR_ALLOC;
  if (!dfull || !rate || !frames || !phi) {
    rn_fail(net->ctx, st, where, "out of memory");
  } else if (!(st = fixed_increment(net, t_prev, t, dfull, frames, phi)) &&
             !(st = rn_eval_fixed_hvp(net, x, dfull, dg, where)) &&
             !(st = rn_eval_load_rate(net, x, rate, where))) {
    for (size_t i = 0; i < net->nred; ++i) dg[i] += (t - t_prev) * rate[i];
  }
  free(dfull);
  free(rate);
  free(phi);
  free(frames);
  return st;
}

rn_status rn_network_load_increment(rn_network *net, const double *x, double t_prev,
                                    double t, double *dg) {
  rn_state *saved = NULL;
  rn_status st, st2;
  if (!net) return RN_ERR_ARG;
  if ((st = check_args(net, x, t_prev, t, dg))) return st;
  if (!net->nred) return RN_OK;
  if ((st = rn_network_state_save(net, &saved))) return st;
  st = increment_at(net, x, t_prev, t, dg);
  if (!st) rn_cell_hold_zero(net, dg);
  st2 = rn_network_state_restore(net, saved);
  rn_state_destroy(&saved);
  return st ? st : st2;
}
