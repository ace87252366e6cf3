/* boundary.c - boundary conditions (clamp, pin, fixed angle, prescribed
 * motions) and the load factor that moves the fixed DOFs. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bcs/bcs.h"
#include "contact/contact.h"
#include "joints/joints.h"
#include "periodic/periodic.h"
#include "rodnet_ramp.h"

/* Checks a call on end `end` of rod g (whole-network index); *lr receives the
 * local index, RN_NOT_HERE if another part holds the rod. */
static rn_status check_end(const rn_network *net, const char *where, int g, int end,
                           int *lr) {
  rn_status st;
  *lr = g;
  if ((st = rn_net_check_building(net, where))) return st;
  st = rn_net_rod(net, where, lr);
  if (st && st != RN_NOT_HERE) return st;
  if (end != RN_START && end != RN_END)
    return rn_fail(net->ctx, RN_ERR_ARG, where,
                   "rod %d: end must be RN_START or RN_END, got %d", g, end);
  return st;
}

/* Resolves a vertex of rod g (negative = from the end) or records an error;
 * *lr as for check_end. */
static rn_status resolve_vertex(const rn_network *net, const char *where, int g,
                                int vertex, int *v, int *lr) {
  rn_status st;
  int nv = rn_net_rod_nv(net, g);
  *lr = g;
  if ((st = rn_net_check_building(net, where))) return st;
  st = rn_net_rod(net, where, lr);
  if (st && st != RN_NOT_HERE) return st;
  *v = rn_wrap_index(vertex, nv);
  if (*v < 0)
    return rn_fail(net->ctx, RN_ERR_RANGE, where,
                   "rod %d: vertex %d out of range (%d vertices)", g, vertex, nv);
  return st;
}

rn_status rn_network_clamp(rn_network *net, int rod, int end) {
  rn_status st;
  int lr;
  if (!net) return RN_ERR_ARG;
  st = check_end(net, "rn_network_clamp", rod, end, &lr);
  if (st == RN_OK || st == RN_NOT_HERE) net->positions_fixed = 1;
  if (st) return rn_not_here_ok(st);
  net->rods[lr].clamped[end] = 1;
  return RN_OK;
}

/* Pins the components of vertex (union with earlier pins). */
static rn_status pin_vertex(rn_network *net, const char *where, int rod, int vertex,
                            int components) {
  rn_status st;
  int v, lr;
  st = resolve_vertex(net, where, rod, vertex, &v, &lr);
  if (st && st != RN_NOT_HERE) return st;
  if (components < 1 || components > RN_FIX_XYZ)
    return rn_fail(net->ctx, RN_ERR_ARG, where,
                   "rod %d vertex %d: components must be a non-empty RN_FIX_X | "
                   "RN_FIX_Y | RN_FIX_Z bitmask (1 .. 7), got %d",
                   rod, v, components);
  net->positions_fixed = 1;
  if (st == RN_NOT_HERE) return RN_OK;
  net->rods[lr].pinned[v] |= (unsigned char)components;
  return RN_OK;
}

rn_status rn_network_pin(rn_network *net, int rod, int vertex) {
  if (!net) return RN_ERR_ARG;
  return pin_vertex(net, "rn_network_pin", rod, vertex, RN_FIX_XYZ);
}

rn_status rn_network_pin_components(rn_network *net, int rod, int vertex,
                                    int components) {
  if (!net) return RN_ERR_ARG;
  return pin_vertex(net, "rn_network_pin_components", rod, vertex, components);
}

rn_status rn_network_fix_theta(rn_network *net, int rod, int edge) {
  static const char *where = "rn_network_fix_theta";
  rn_status st;
  int j, lr = rod, ne;
  if (!net) return RN_ERR_ARG;
  if ((st = rn_net_check_building(net, where))) return st;
  st = rn_net_rod(net, where, &lr);
  if (st && st != RN_NOT_HERE) return st;
  ne = rn_net_rod_nv(net, rod) - 1;
  j = rn_wrap_index(edge, ne);
  if (j < 0)
    return rn_fail(net->ctx, RN_ERR_RANGE, where,
                   "rod %d: edge %d out of range (%d edges)", rod, edge, ne);
  if (st == RN_NOT_HERE) return RN_OK;
  net->rods[lr].theta_fixed[j] = 1;
  return RN_OK;
}

rn_status rn_network_displace_end(rn_network *net, int rod, int end, const double disp[3],
                                  const double rotvec[3]) {
  static const char *where = "rn_network_displace_end";
  rn_status st;
  rn_rod *r;
  int lr;
  if (!net) return RN_ERR_ARG;
  st = check_end(net, where, rod, end, &lr);
  if (st && st != RN_NOT_HERE) return st;
  if ((disp && !rn_all_finite(3, disp)) || (rotvec && !rn_all_finite(3, rotvec)))
    return rn_fail(net->ctx, RN_ERR_NOT_FINITE, where, "rod %d: motion is not finite",
                   rod);
  if (st == RN_NOT_HERE) return RN_OK;
  r = &net->rods[lr];
  r->has_end_motion[end] = 1;
  for (int k = 0; k < 3; ++k) {
    r->end_disp[end][k] = disp ? disp[k] : 0.0;
    r->end_rot[end][k] = rotvec ? rotvec[k] : 0.0;
  }
  return RN_OK;
}

rn_status rn_network_displace_vertex(rn_network *net, int rod, int vertex,
                                     const double disp[3]) {
  static const char *where = "rn_network_displace_vertex";
  rn_status st;
  int v, lr;
  if (!net) return RN_ERR_ARG;
  st = resolve_vertex(net, where, rod, vertex, &v, &lr);
  if (st && st != RN_NOT_HERE) return st;
  if (!disp) return rn_fail(net->ctx, RN_ERR_ARG, where, "disp is NULL");
  if (!rn_all_finite(3, disp))
    return rn_fail(net->ctx, RN_ERR_NOT_FINITE, where,
                   "rod %d vertex %d: displacement is not finite", rod, v);
  if (st == RN_NOT_HERE) return RN_OK;
  net->rods[lr].has_vdisp[v] = 1;
  memcpy(net->rods[lr].vdisp + 3 * v, disp, 3 * sizeof(double));
  return RN_OK;
}

/* ---- load factor -------------------------------------------------------------- */
/* The clamped edge and its first vertex at an end. */
static int clamp_edge(const rn_rod *r, int end) {
  return end == RN_START ? 0 : r->ne - 1;
}

/* The fixed components of pinned vertices (free ones keep the state). */
static void place_pins(rn_network *net, rn_rod *r) {
  for (int v = 0; v < r->nv; ++v) {
    double *x = net->xfull + rn_dof_vertex(r->off, v);
    for (int k = 0; k < 3; ++k)
      if (rn_component_fixed(r->pinned[v], k))
        x[k] = r->x0[3 * v + k] + net->lambda * r->vdisp[3 * v + k];
  }
}

/* Clamped end: x = c0 + lambda d + R(lambda w)(x0 - c0) (+ lambda vertex
 * displacement), c0 the midpoint of the clamped edge; its reference frame
 * rotates with R. */
static void place_clamp(rn_network *net, rn_rod *r, int end) {
  int j = clamp_edge(r, end);
  double w[3], R[9], c0[3];
  for (int k = 0; k < 3; ++k) {
    w[k] = net->lambda * r->end_rot[end][k];
    c0[k] = 0.5 * (r->x0[3 * j + k] + r->x0[3 * (j + 1) + k]);
  }
  rn_rotation_matrix(w, R);
  for (int v = j; v <= j + 1; ++v) {
    double rel[3], rot[3], *x = net->xfull + rn_dof_vertex(r->off, v);
    for (int k = 0; k < 3; ++k) rel[k] = r->x0[3 * v + k] - c0[k];
    rn_mat_vec3(R, rel, rot);
    for (int k = 0; k < 3; ++k)
      x[k] = c0[k] + net->lambda * r->end_disp[end][k] + rot[k] +
             net->lambda * r->vdisp[3 * v + k];
  }
  if (r->has_end_motion[end]) {
    rn_mat_vec3(R, r->ref_base[j].t, r->ref[j].t);
    rn_mat_vec3(R, r->ref_base[j].a1, r->ref[j].a1);
  }
}

/* Continues the reference twist of the interior vertices next to a clamped
 * edge whose frame was moved (keeps the 2 pi branch near the stored value). */
static void continue_twist_near(rn_network *net, rn_rod *r, int j) {
  for (int i = j; i <= j + 1; ++i) {
    double q[RN_VERTEX_STENCIL], m;
    if (i < 1 || i > r->nv - 2) continue;
    memcpy(q, net->xfull + rn_dof_vertex_stencil(r->off, i), sizeof(q));
    if (rnk_reference_twist(q, &r->ref[i - 1], r->ref_twist[i - 1], &m) == RNK_OK)
      r->ref_twist[i - 1] = m;
  }
}

rn_status rn_apply_load_factor(rn_network *net) {
  rn_cell_place(net);   /* first: image ends are placed from the strain */
  rn_joints_place(net); /* first: rod stencils near joints read their position */
  for (int ir = 0; ir < net->nrods; ++ir) {
    rn_rod *r = &net->rods[ir];
    place_pins(net, r);
    for (int end = RN_START; end <= RN_END; ++end) {
      if (!r->clamped[end]) continue;
      place_clamp(net, r, end);
      if (r->has_end_motion[end]) continue_twist_near(net, r, clamp_edge(r, end));
    }
  }
  rn_joints_continue_twists(net);
  return RN_OK;
}

double rn_prescribed_rotation_rate(const rn_network *net) {
  double w = 0.0;
  for (int ir = 0; ir < net->nrods; ++ir)
    for (int end = RN_START; end <= RN_END; ++end) {
      const double *v = net->rods[ir].end_rot[end];
      if (net->rods[ir].clamped[end] && net->rods[ir].has_end_motion[end])
        w = fmax(w, sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]));
    }
  for (int ij = 0; ij < net->njoints; ++ij) {
    const double *v = net->joints[ij].rot;
    if (net->joints[ij].clamped)
      w = fmax(w, sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]));
  }
  return w;
}

int rn_ramp_steps(double turn) {
  if (!(turn > RN_RAMP_ANGLE) || !(turn <= RN_RAMP_ANGLE * RN_RAMP_MAX_STEPS)) return 1;
  return (int)ceil(turn / RN_RAMP_ANGLE);
}

void rn_ramp_load_factor(rn_network *net, double lambda) {
  const double from = net->lambda;
  const int n = rn_ramp_steps(fabs(lambda - from) * rn_prescribed_rotation_rate(net));
  for (int k = 1; k <= n; ++k) {
    net->lambda = k == n ? lambda : from + (lambda - from) * (double)k / (double)n;
    rn_apply_load_factor(net);
  }
}

rn_status rn_network_set_load_factor(rn_network *net, double lambda) {
  static const char *where = "rn_network_set_load_factor";
  if (!net) return RN_ERR_ARG;
  if (!isfinite(lambda))
    return rn_fail(net->ctx, RN_ERR_NOT_FINITE, where, "load factor is not finite");
  if (lambda < 0.0 || lambda > 1.0)
    return rn_fail(net->ctx, RN_ERR_ARG, where, "load factor %g is outside [0, 1]",
                   lambda);
  if (!net->finalized) {
    net->lambda = lambda;
    return RN_OK;
  }
  rn_ramp_load_factor(net, lambda);
  return rn_contact_pattern_update(net, 0, where); /* prescribed positions moved */
}

/* Largest |change of an edge vector| / |edge| over the rod edges, between the
 * fixed entries of xa and xb (free entries equal). */
static double edge_stretch(const rn_network *net, const double *xa, const double *xb) {
  double ratio = 0.0;
  for (int ir = 0; ir < net->nrods; ++ir) {
    const rn_rod *r = &net->rods[ir];
    for (int j = 0; j + 1 < r->nv; ++j) {
      const size_t a = rn_dof_vertex(r->off, j), b = rn_dof_vertex(r->off, j + 1);
      double e2 = 0.0, d2 = 0.0;
      for (int k = 0; k < 3; ++k) {
        const double e = xa[b + k] - xa[a + k];
        const double d = (xb[b + k] - xb[a + k]) - e;
        e2 += e * e;
        d2 += d * d;
      }
      if (d2 == 0.0) continue;
      ratio = e2 > 0.0 ? fmax(ratio, sqrt(d2 / e2)) : HUGE_VAL;
    }
  }
  return ratio;
}

rn_status rn_network_load_step_size(rn_network *net, double t0, double t1,
                                    double *stretch, double *angle) {
  static const char *where = "rn_network_load_step_size";
  rn_state *saved = NULL;
  double *xa = NULL;
  rn_status st;
  if (!net) return RN_ERR_ARG;
  if ((st = rn_net_check_final(net, where))) return st;
  if (!stretch || !angle) return rn_fail(net->ctx, RN_ERR_ARG, where, "NULL output");
  if (!isfinite(t0) || !isfinite(t1))
    return rn_fail(net->ctx, RN_ERR_NOT_FINITE, where, "load factor is not finite");
  if (t0 < 0.0 || t0 > 1.0 || t1 < 0.0 || t1 > 1.0)
    return rn_fail(net->ctx, RN_ERR_ARG, where, "load factors %g, %g: outside [0, 1]", t0,
                   t1);
  *angle = fabs(t1 - t0) * rn_prescribed_rotation_rate(net);
  *stretch = 0.0;
  if (!net->nfull) return RN_OK;
  if ((st = rn_network_state_save(net, &saved))) return st;
  xa = malloc(net->nfull * sizeof(double));
  if (!xa) {
    st = rn_fail(net->ctx, RN_ERR_ALLOC, where, "out of memory");
  } else {
    rn_ramp_load_factor(net, t0);
    memcpy(xa, net->xfull, net->nfull * sizeof(double));
    rn_ramp_load_factor(net, t1);
    *stretch = edge_stretch(net, xa, net->xfull);
  }
  free(xa);
  {
    rn_status st2 = rn_network_state_restore(net, saved);
    rn_state_destroy(&saved);
    if (!st) st = st2;
  }
  return st;
}

double rn_network_load_factor(const rn_network *net) { return net ? net->lambda : 0.0; }

double rn_network_dofs_load_factor(const rn_network *net) {
  return net && net->finalized ? net->lambda_x : NAN;
}
