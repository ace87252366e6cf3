/* frames.c - reference frames, reference twists and rest quantities of a new
 * rod; rotation helpers. */
#include <math.h>
#include <string.h>

#include "core/network_internal.h"
#include "rodq.h"

static double norm3(const double a[3]) { return sqrt(rq_dot3(a, a)); }

void rn_mat_vec3(const double R[9], const double v[3], double out[3]) {
  for (int i = 0; i < 3; ++i)
    out[i] = R[3 * i] * v[0] + R[3 * i + 1] * v[1] + R[3 * i + 2] * v[2];
}

void rn_rotation_matrix(const double w[3], double R[9]) {
  double th2 = rq_dot3(w, w), th = sqrt(th2), s, c;
  double K[9] = {0, -w[2], w[1], w[2], 0, -w[0], -w[1], w[0], 0};
  if (th < 1e-4) { /* series of sin(th)/th and (1 - cos th)/th^2 */
    s = 1.0 - th2 / 6.0 + th2 * th2 / 120.0;
    c = 0.5 - th2 / 24.0 + th2 * th2 / 720.0;
  } else {
    s = sin(th) / th;
    c = (1.0 - cos(th)) / th2;
  }
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      double kk = 0.0;
      for (int l = 0; l < 3; ++l) kk += K[3 * i + l] * K[3 * l + j];
      R[3 * i + j] = (i == j ? 1.0 : 0.0) + s * K[3 * i + j] + c * kk;
    }
}

/* Edge vector of edge j of the input shape and its length. */
static double edge_vector(const rn_rod *r, int j, double e[3]) {
  for (int k = 0; k < 3; ++k) e[k] = r->x0[3 * (j + 1) + k] - r->x0[3 * j + k];
  return norm3(e);
}

/* Vertex stencil of interior vertex i of the input shape (all theta = 0). */
static void initial_stencil(const rn_rod *r, int i, double q[RN_VERTEX_STENCIL]) {
  memset(q, 0, RN_VERTEX_STENCIL * sizeof(double));
  for (int k = 0; k < 3; ++k)
    memcpy(q + rn_stencil_x(k), r->x0 + 3 * (i - 1 + k), 3 * sizeof(double));
}

/* First director of the first edge: the given d1 or the coordinate axis with
 * the smallest |t_k| (lowest index on ties), projected normal to t. */
static rn_status first_director(rn_context *ctx, int rod, const double t[3],
                                const double *d1, double a1[3]) {
  static const char *where = "rn_network_add_rod";
  double d[3] = {0.0, 0.0, 0.0}, dn, an;
  if (d1) {
    memcpy(d, d1, sizeof(d));
  } else {
    int kmin = 0;
    for (int k = 1; k < 3; ++k)
      if (fabs(t[k]) < fabs(t[kmin])) kmin = k;
    d[kmin] = 1.0;
  }
  dn = norm3(d);
  if (!(dn > 0.0))
    return rn_fail(ctx, RN_ERR_ARG, where, "rod %d: d1 is the zero vector", rod);
  for (int k = 0; k < 3; ++k) a1[k] = d[k] - rq_dot3(d, t) * t[k];
  an = norm3(a1);
  if (an < 1e-8 * dn)
    return rn_fail(ctx, RN_ERR_GEOMETRY, where,
                   "rod %d: d1 is parallel to the first edge's tangent", rod);
  for (int k = 0; k < 3; ++k) a1[k] /= an;
  return RN_OK;
}

static rn_status edge_frames(rn_context *ctx, rn_rod *r, int rod, const double *d1) {
  static const char *where = "rn_network_add_rod";
  rn_status st;
  for (int j = 0; j < r->ne; ++j) {
    double e[3], l = edge_vector(r, j, e);
    double scale = norm3(r->x0 + 3 * j) + norm3(r->x0 + 3 * (j + 1));
    rnk_frame *f = &r->ref_base[j];
    if (!(l > 1e-14 * scale) || l == 0.0)
      return rn_fail(ctx, RN_ERR_GEOMETRY, where, "rod %d edge %d: zero-length edge", rod,
                     j);
    for (int k = 0; k < 3; ++k) f->t[k] = e[k] / l;
    r->lbar[j] = l;
    if (j == 0) {
      if ((st = first_director(ctx, rod, f->t, d1, f->a1))) return st;
    } else {
      double a[3], an;
      if (rnk_transport(r->ref_base[j - 1].t, f->t, r->ref_base[j - 1].a1, a) != RNK_OK)
        return rn_fail(ctx, RN_ERR_GEOMETRY, where,
                       "rod %d vertex %d: consecutive edges point in opposite directions",
                       rod, j);
      for (int k = 0; k < 3; ++k) a[k] -= rq_dot3(a, f->t) * f->t[k];
      an = norm3(a);
      for (int k = 0; k < 3; ++k) f->a1[k] = a[k] / an;
    }
  }
  return RN_OK;
}

rn_status rn_rod_init_frames(rn_context *ctx, rn_rod *r, int rod, const double *d1) {
  static const char *where = "rn_network_add_rod";
  rn_status st;
  if ((st = edge_frames(ctx, r, rod, d1))) return st;
  memcpy(r->ref, r->ref_base, (size_t)r->ne * sizeof(rnk_frame));
  for (int i = 1; i < r->nv - 1; ++i) {
    double q[RN_VERTEX_STENCIL];
    initial_stencil(r, i, q);
    if (rnk_reference_twist(q, &r->ref[i - 1], 0.0, &r->ref_twist[i - 1]) != RNK_OK ||
        rnk_strains(q, &r->ref[i - 1], r->ref_twist[i - 1], &r->kbar[2 * (i - 1)],
                    &r->taubar[i - 1]) != RNK_OK)
      return rn_fail(ctx, RN_ERR_GEOMETRY, where, "rod %d vertex %d: degenerate kink",
                     rod, i);
  }
  return RN_OK;
}

void rn_couple_vector(const double f[9], const double m[3], double b[3]) {
  int best = 0;
  double bv = 2.0, mm = sqrt(m[0] * m[0] + m[1] * m[1] + m[2] * m[2]);
  b[0] = b[1] = b[2] = 0.0;
  if (!(mm > 0.0)) return;
  for (int k = 0; k < 3; ++k) {
    double c = fabs(f[3 * k] * m[0] + f[3 * k + 1] * m[1] + f[3 * k + 2] * m[2]) / mm;
    if (c < bv) bv = c, best = k;
  }
  /* u = f_best - (f_best . n) n in world coordinates, then b = F u / |u| */
  double n[3] = {m[0] / mm, m[1] / mm, m[2] / mm}, u[3];
  const double *fb = f + 3 * best;
  double fn = fb[0] * n[0] + fb[1] * n[1] + fb[2] * n[2];
  for (int a = 0; a < 3; ++a) u[a] = fb[a] - fn * n[a];
  double nu = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
  for (int k = 0; k < 3; ++k)
    b[k] = (f[3 * k] * u[0] + f[3 * k + 1] * u[1] + f[3 * k + 2] * u[2]) / nu;
}
