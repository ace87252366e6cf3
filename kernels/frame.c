/* frame.c - parallel transport, edge frames as jets, reference twist, and
 * the scatter from jet variables to stencil DOFs. */
#include <math.h>

#include "rnk.h"
#include "rodq.h"
#include "stencil.h"

static void cross3(const double a[3], const double b[3], double r[3]) {
  double t[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                 a[0] * b[1] - a[1] * b[0]};
  r[0] = t[0];
  r[1] = t[1];
  r[2] = t[2];
}

int rnk_transport(const double ta[3], const double tb[3], const double v[3],
                  double out[3]) {
  /* R v = c v + n x v + n (n . v) / (1 + c), n = ta x tb, c = ta . tb:
   * no division by sin(angle), exact identity for ta == tb. */
  double c = rq_dot3(ta, tb), n[3], nv[3];
  if (!(1.0 + c >= RNK_OPPOSITE_TOL)) return RNK_DEGENERATE;
  cross3(ta, tb, n);
  cross3(n, v, nv);
  double s = rq_dot3(n, v) / (1.0 + c);
  for (int k = 0; k < 3; ++k) out[k] = c * v[k] + nv[k] + s * n[k];
  return RNK_OK;
}

int rnk_edge_jet_eval(const double e[3], double theta, const rnk_frame *ref, int ord,
                      rnk_edge_jet *f) {
  const int n = 4;
  double l2 = rq_dot3(e, e);
  if (!(l2 > 0.0) || !isfinite(l2)) return RNK_DEGENERATE;
  jvec ev;
  for (int k = 0; k < 3; ++k) jet_var(&ev.c[k], n, ord, e[k], k);
  jet len2, ilen;
  jvec_dot(&len2, &ev, &ev);
  jet_sqrt(&ilen, &len2);
  jet_inv(&ilen, &ilen);
  jvec_mul(&f->t, &ilen, &ev);

  /* a1 = c v - (t . v) t_hat + (t . w) (t_hat x t) / (1 + c), v = a1_hat,
   * w = a1_hat x t_hat, c = t_hat . t (constant vectors enter linearly) */
  const double *th = ref->t, *v = ref->a1;
  double w[3];
  cross3(v, th, w);
  jet c, tv, tw, q;
  jvec_dot_const(&c, &f->t, th);
  if (!(1.0 + c.v >= RNK_OPPOSITE_TOL)) return RNK_DEGENERATE;
  jvec_dot_const(&tv, &f->t, v);
  jvec_dot_const(&tw, &f->t, w);
  jet_add_const(&q, &c, 1.0);
  jet_div(&q, &tw, &q);
  jvec nrm;
  jvec_cross_const(&nrm, th, &f->t);
  for (int k = 0; k < 3; ++k) {
    jet_lin(&f->a1.c[k], v[k], &c, -th[k], &tv);
    jet_fma(&f->a1.c[k], &q, &nrm.c[k]);
  }
  jvec_cross(&f->a2, &f->t, &f->a1);

  jet th_j, cs, sn, msn;
  jet_var(&th_j, n, ord, theta, 3);
  jet_cos(&cs, &th_j);
  jet_sin(&sn, &th_j);
  jet_scale(&msn, -1.0, &sn);
  jvec_comb(&f->d1, &cs, &f->a1, &sn, &f->a2);
  jvec_comb(&f->d2, &msn, &f->a1, &cs, &f->a2);
  return RNK_OK;
}

int rnk_vertex_frames(const double q[11], const rnk_frame ref[2], int ord,
                      rnk_edge_jet f[2]) {
  for (int s = 0; s < 2; ++s) {
    const double *xa = q + 4 * s, *xb = q + 4 * s + 4;
    double e[3] = {xb[0] - xa[0], xb[1] - xa[1], xb[2] - xa[2]};
    int st = rnk_edge_jet_eval(e, q[4 * s + 3], &ref[s], ord, &f[s]);
    if (st) return st;
  }
  return RNK_OK;
}

/* Jet variable a of a stencil depends linearly on DOFs: edge vector
 * components are differences of vertex coordinates, angles are DOFs. */
typedef struct {
  int cnt;
  int idx[2];
  double c[2];
} rnk_dmap;

static void scatter(int nj, const rnk_dmap *m, int nq, const jet *E, double *g,
                    double *H) {
  if (g) {
    for (int i = 0; i < nq; ++i) g[i] = 0.0;
    for (int a = 0; a < nj; ++a)
      for (int r = 0; r < m[a].cnt; ++r) g[m[a].idx[r]] += m[a].c[r] * E->g[a];
  }
  if (H) {
    for (int i = 0; i < nq * nq; ++i) H[i] = 0.0;
    for (int a = 0; a < nj; ++a)
      for (int b = 0; b < nj; ++b) {
        double hab = a <= b ? E->h[a][b] : E->h[b][a];
        if (hab == 0.0) continue;
        for (int r = 0; r < m[a].cnt; ++r)
          for (int s = 0; s < m[b].cnt; ++s)
            H[m[a].idx[r] * nq + m[b].idx[s]] += m[a].c[r] * m[b].c[s] * hab;
      }
  }
}

void rnk_scatter_vertex(const jet *E, double *g, double *H) {
  static const rnk_dmap m[8] = {{2, {4, 0}, {1, -1}},  {2, {5, 1}, {1, -1}},
                                {2, {6, 2}, {1, -1}},  {1, {3, 0}, {1, 0}},
                                {2, {8, 4}, {1, -1}},  {2, {9, 5}, {1, -1}},
                                {2, {10, 6}, {1, -1}}, {1, {7, 0}, {1, 0}}};
  scatter(8, m, 11, E, g, H);
}

void rnk_scatter_edge(const jet *E, double *g, double *H) {
  static const rnk_dmap m[4] = {{2, {4, 0}, {1, -1}},
                                {2, {5, 1}, {1, -1}},
                                {2, {6, 2}, {1, -1}},
                                {1, {3, 0}, {1, 0}}};
  scatter(4, m, 7, E, g, H);
}

void rnk_twist_increment(const rnk_edge_jet f[2], double m_prev, jet *dm) {
  /* Rotate the second reference frame back by m_prev, then take the twist
   * angle of the relative rotation about the tangent (swing-twist):
   * tan(dm/2) = (a2_0 . b1 - a1_0 . b2) / (1 + t0.t1 + a1_0.b1 + a2_0.b2). */
  double cm = cos(m_prev), sm = sin(m_prev);
  jvec b1, b2;
  jvec_lin(&b1, cm, &f[1].a1, -sm, &f[1].a2);
  jvec_lin(&b2, sm, &f[1].a1, cm, &f[1].a2);
  jet num, den, p;
  jvec_dot_blocks(&num, &f[0].a2, &b1);
  jvec_dot_blocks(&p, &f[0].a1, &b2);
  jet_sub(&num, &num, &p);
  jvec_dot_blocks(&den, &f[0].t, &f[1].t);
  jvec_dot_blocks(&p, &f[0].a1, &b1);
  jet_add(&den, &den, &p);
  jvec_dot_blocks(&p, &f[0].a2, &b2);
  jet_add(&den, &den, &p);
  jet_add_const(&den, &den, 1.0);
  jet_atan2(dm, &num, &den);
  jet_scale(dm, 2.0, dm);
}

void rnk_twist_jet(const rnk_edge_jet f[2], const double q[11], double m_prev, jet *tau) {
  jet th;
  int ord = f[0].t.c[0].ord;
  rnk_twist_increment(f, m_prev, tau);
  jet_var(&th, 8, ord, q[7], 7);
  jet_add(tau, tau, &th);
  jet_var(&th, 8, ord, q[3], 3);
  jet_sub(tau, tau, &th);
  jet_add_const(tau, tau, m_prev);
}

/* Material curvature.  With kb = 2 t0 x t1 / (1 + t0 . t1) and right-handed
 * frames (t, d1, d2), seed 000 (2.2) kappa1 = kb . (d2_0 + d2_1) / 2 equals
 * (t1 . d1_0 - t0 . d1_1) / (1 + t0 . t1) and kappa2 = -kb . (d1_0 + d1_1) / 2
 * equals (t1 . d2_0 - t0 . d2_1) / (1 + t0 . t1): fewer operations. */
int rnk_curvature_jet(const rnk_edge_jet f[2], jet kappa[2]) {
  jet den, p;
  jvec_dot_blocks(&den, &f[0].t, &f[1].t);
  jet_add_const(&den, &den, 1.0);
  if (!(den.v >= RNK_OPPOSITE_TOL)) return RNK_DEGENERATE;
  jet_inv(&den, &den);
  jvec_dot_blocks(&kappa[0], &f[0].d1, &f[1].t);
  jvec_dot_blocks(&p, &f[0].t, &f[1].d1);
  jet_sub(&kappa[0], &kappa[0], &p);
  jet_mul(&kappa[0], &kappa[0], &den);
  jvec_dot_blocks(&kappa[1], &f[0].d2, &f[1].t);
  jvec_dot_blocks(&p, &f[0].t, &f[1].d2);
  jet_sub(&kappa[1], &kappa[1], &p);
  jet_mul(&kappa[1], &kappa[1], &den);
  return RNK_OK;
}

int rnk_material_frame(const double e[3], const rnk_frame *ref, double theta, double t[3],
                       double d1[3], double d2[3]) {
  rnk_edge_jet f;
  int st = rnk_edge_jet_eval(e, theta, ref, 0, &f);
  if (st) return st;
  for (int k = 0; k < 3; ++k) {
    if (t) t[k] = f.t.c[k].v;
    if (d1) d1[k] = f.d1.c[k].v;
    if (d2) d2[k] = f.d2.c[k].v;
  }
  return RNK_OK;
}

int rnk_frame_update(const double e[3], rnk_frame *ref) {
  rnk_edge_jet f;
  int st = rnk_edge_jet_eval(e, 0.0, ref, 0, &f);
  if (st) return st;
  double t[3], a[3];
  for (int k = 0; k < 3; ++k) {
    t[k] = f.t.c[k].v;
    a[k] = f.a1.c[k].v;
  }
  /* re-orthonormalise against round-off drift */
  double ta = rq_dot3(t, a);
  for (int k = 0; k < 3; ++k) a[k] -= ta * t[k];
  double na = sqrt(rq_dot3(a, a));
  if (!(na > 0.5)) return RNK_DEGENERATE;
  for (int k = 0; k < 3; ++k) {
    ref->t[k] = t[k];
    ref->a1[k] = a[k] / na;
  }
  return RNK_OK;
}

void rnk_block_mv(int n, const double *H, const double *v, double *y) {
  for (int i = 0; i < n; ++i) {
    double s = 0.0;
    for (int j = 0; j < n; ++j) s += H[i * n + j] * v[j];
    y[i] = s;
  }
}
