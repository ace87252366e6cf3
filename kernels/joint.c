/* joint.c - bending and twisting where a rod end meets a joint through a
 * connection edge rigidly attached to the joint's rotation
 * Q = exp([w]) Q_hat (seed 001 sections 2-4).  Jets over 7 variables: the
 * terminal edge (e[3], theta) and the rotation vector w[3].  The test oracle
 * of the closed forms (jointq.c): rnk_jet_joint_end_*. */
#include <math.h>

#include "rnk.h"
#include "stencil.h"

/* A(s) = sin(r)/r and B(s) = (1 - cos r)/r^2 with s = r^2, and their first
 * two derivatives in s: Taylor series for s <= 4 (no cancellation), closed
 * forms beyond. */
static void rodrigues_coeffs(double s, double A[3], double B[3]) {
  if (s <= 4.0) {
    enum { K = 20 };
    double ca[K + 2], cb[K + 2]; /* (-1)^k / (2k+1)!, (-1)^k / (2k+2)! */
    ca[0] = 1.0;
    cb[0] = 0.5;
    for (int k = 0; k + 1 < K + 2; ++k) {
      ca[k + 1] = -ca[k] / ((2.0 * k + 2) * (2.0 * k + 3));
      cb[k + 1] = -cb[k] / ((2.0 * k + 3) * (2.0 * k + 4));
    }
    for (int d = 0; d < 3; ++d) A[d] = B[d] = 0.0;
    double sk = 1.0; /* s^k */
    for (int k = 0; k + 2 < K + 2; ++k) {
      A[0] += ca[k] * sk;
      B[0] += cb[k] * sk;
      A[1] += (k + 1) * ca[k + 1] * sk;
      B[1] += (k + 1) * cb[k + 1] * sk;
      A[2] += (k + 2) * (k + 1) * ca[k + 2] * sk;
      B[2] += (k + 2) * (k + 1) * cb[k + 2] * sk;
      sk *= s;
    }
    return;
  }
  double r = sqrt(s), sn = sin(r), cs = cos(r);
  A[0] = sn / r;
  A[1] = (r * cs - sn) / (2 * r * r * r);
  A[2] = (-r * r * sn - 3 * r * cs + 3 * sn) / (4 * pow(r, 5));
  B[0] = (1 - cs) / s;
  B[1] = (r * sn - 2 * (1 - cs)) / (2 * s * s);
  B[2] = (r * r * cs - 5 * r * sn + 8 - 8 * cs) / (4 * pow(r, 6));
}

void rnk_rotation_exp(const double w[3], double R[9]) {
  double s = w[0] * w[0] + w[1] * w[1] + w[2] * w[2], A[3], B[3];
  rodrigues_coeffs(s, A, B);
  double K[9] = {0, -w[2], w[1], w[2], 0, -w[0], -w[1], w[0], 0};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      double k2 = 0;
      for (int l = 0; l < 3; ++l) k2 += K[3 * i + l] * K[3 * l + j];
      R[3 * i + j] = (i == j ? 1.0 : 0.0) + A[0] * K[3 * i + j] + B[0] * k2;
    }
}

/* exp([w]) v = v + A(s) w x v + B(s) (w (w . v) - s v), as 3-variable jets. */
static void rotate_jet(const jvec *w, const jet *A, const jet *B, const jet *s,
                       const double v[3], jvec *out) {
  jvec vv, wxv;
  jet wv, t;
  jvec_const(&vv, 3, w->c[0].ord, v);
  jvec_dot_const(&wv, w, v);
  jvec_cross(&wxv, w, &vv);
  for (int k = 0; k < 3; ++k) {
    jet_mul(&t, &w->c[k], &wv);
    jet_lin(&t, 1.0, &t, -v[k], s); /* w_k (w.v) - s v_k */
    jet_mul(&t, B, &t);
    jet_fma(&t, A, &wxv.c[k]);
    jet_add_const(&out->c[k], &t, v[k]);
  }
}

void rnk_rotate_jet(const double w[3], int ord, int nvec, const double *v, jvec *out) {
  jvec wj;
  jet s, A, B;
  double a[3], b[3];
  for (int k = 0; k < 3; ++k) jet_var(&wj.c[k], 3, ord, w[k], k);
  jvec_dot(&s, &wj, &wj);
  rodrigues_coeffs(s.v, a, b);
  jet_chain(&A, &s, a[0], a[1], a[2]);
  jet_chain(&B, &s, b[0], b[1], b[2]);
  for (int i = 0; i < nvec; ++i) rotate_jet(&wj, &A, &B, &s, v + 3 * i, &out[i]);
}

typedef struct joint_frames {
  rnk_edge_jet term; /* 4 variables */
  jvec t, d1, d2;    /* connection edge, 3 variables */
} joint_frames;

static int joint_frames_eval(const double q[10], const rnk_frame *ref,
                             const rnk_joint_end_param *p, int ord, joint_frames *f) {
  double e[3];
  for (int k = 0; k < 3; ++k) e[k] = p->side == 0 ? q[4 + k] - q[k] : q[k] - q[4 + k];
  int st = rnk_edge_jet_eval(e, q[3], ref, ord, &f->term);
  if (st) return st;
  jvec c[3];
  rnk_rotate_jet(q + 7, ord, 3, p->c, c);
  f->t = c[0];
  f->d1 = c[1];
  f->d2 = c[2];
  return RNK_OK;
}

/* x . y with x from the first edge of the vertex and y from the second; the
 * result's variables are always (terminal edge, rotation). */
static void edot(const rnk_joint_end_param *p, const jvec *x, const jvec *y, jet *r) {
  if (p->side == 0)
    jvec_dot_blocks(r, x, y); /* first edge = terminal */
  else
    jvec_dot_blocks(r, y, x); /* first edge = connection */
}

static int joint_strains_jet(const joint_frames *f, const rnk_joint_end_param *p,
                             jet kappa[2], jet *tau) {
  const jvec *t0, *t1, *d10, *d11, *d20, *d21;
  if (p->side == 0) {
    t0 = &f->term.t, d10 = &f->term.d1, d20 = &f->term.d2;
    t1 = &f->t, d11 = &f->d1, d21 = &f->d2;
  } else {
    t0 = &f->t, d10 = &f->d1, d20 = &f->d2;
    t1 = &f->term.t, d11 = &f->term.d1, d21 = &f->term.d2;
  }
  /* curvature: kappa1 = (t1.d1_0 - t0.d1_1)/(1 + t0.t1), kappa2 likewise */
  jet den, a, b;
  edot(p, t0, t1, &den);
  jet_add_const(&den, &den, 1.0);
  if (!(den.v >= RNK_OPPOSITE_TOL)) return RNK_DEGENERATE;
  jet_inv(&a, &den);
  edot(p, d10, t1, &kappa[0]);
  edot(p, t0, d11, &b);
  jet_sub(&kappa[0], &kappa[0], &b);
  jet_mul(&kappa[0], &kappa[0], &a);
  edot(p, d20, t1, &kappa[1]);
  edot(p, t0, d21, &b);
  jet_sub(&kappa[1], &kappa[1], &b);
  jet_mul(&kappa[1], &kappa[1], &a);
  /* twist between the material frames, continued from ref_twist:
   * tan(dt/2) = (d2_0.b1 - d1_0.b2) / (1 + t0.t1 + d1_0.b1 + d2_0.b2), with
   * (b1, b2) the second frame turned back by ref_twist */
  double m = p->twist.ref_twist, cm = cos(m), sm = sin(m);
  jvec b1, b2;
  jvec_lin(&b1, cm, d11, -sm, d21);
  jvec_lin(&b2, sm, d11, cm, d21);
  jet num, dn;
  edot(p, d20, &b1, &num);
  edot(p, d10, &b2, &b);
  jet_sub(&num, &num, &b);
  edot(p, d10, &b1, &b);
  jet_add(&dn, &den, &b);
  edot(p, d20, &b2, &b);
  jet_add(&dn, &dn, &b);
  jet_atan2(tau, &num, &dn);
  jet_scale(tau, 2.0, tau);
  jet_add_const(tau, tau, m);
  return RNK_OK;
}

static int joint_eval(const double q[10], const rnk_frame *ref,
                      const rnk_joint_end_param *p, int ord, jet *E) {
  joint_frames f;
  jet k[2], tau, a, b, c;
  int st = joint_frames_eval(q, ref, p, ord, &f);
  if (st) return st;
  st = joint_strains_jet(&f, p, k, &tau);
  if (st) return st;
  const rnk_bend_param *bp = &p->bend;
  jet_add_const(&k[0], &k[0], -bp->kbar[0]);
  jet_add_const(&k[1], &k[1], -bp->kbar[1]);
  jet_mul(&a, &k[0], &k[0]);
  jet_mul(&b, &k[0], &k[1]);
  jet_mul(&c, &k[1], &k[1]);
  double s = 0.5 / bp->vlen;
  jet_lin(E, s * bp->B[0], &a, 2.0 * s * bp->B[1], &b);
  jet_lin(E, 1.0, E, s * bp->B[2], &c);
  jet_add_const(&tau, &tau, -p->twist.taubar);
  jet_mul(&a, &tau, &tau);
  jet_lin(E, 1.0, E, 0.5 * p->twist.beta / p->twist.vlen, &a);
  return RNK_OK;
}

/* jet variables (e[3], theta, w[3]) -> stencil DOFs (x_n[3], theta, x_J[3], w[3]) */
static void scatter(const rnk_joint_end_param *p, const jet *E, double *g, double *H) {
  int idx[7][2], cnt[7];
  double c[7][2];
  double sg = p->side == 0 ? 1.0 : -1.0; /* e = sg (x_J - x_n) */
  for (int k = 0; k < 3; ++k) {
    cnt[k] = 2;
    idx[k][0] = 4 + k, c[k][0] = sg;
    idx[k][1] = k, c[k][1] = -sg;
    cnt[4 + k] = 1;
    idx[4 + k][0] = 7 + k, c[4 + k][0] = 1.0;
  }
  cnt[3] = 1;
  idx[3][0] = 3, c[3][0] = 1.0;
  if (g) {
    for (int i = 0; i < 10; ++i) g[i] = 0.0;
    for (int a = 0; a < 7; ++a)
      for (int r = 0; r < cnt[a]; ++r) g[idx[a][r]] += c[a][r] * E->g[a];
  }
  if (H) {
    for (int i = 0; i < 100; ++i) H[i] = 0.0;
    for (int a = 0; a < 7; ++a)
      for (int b = 0; b < 7; ++b) {
        double hab = a <= b ? E->h[a][b] : E->h[b][a];
        for (int r = 0; r < cnt[a]; ++r)
          for (int s = 0; s < cnt[b]; ++s)
            H[idx[a][r] * 10 + idx[b][s]] += c[a][r] * c[b][s] * hab;
      }
  }
}

int rnk_jet_joint_end_energy(const double q[10], const rnk_frame *ref,
                             const rnk_joint_end_param *p, double *E) {
  jet e;
  int st = joint_eval(q, ref, p, 0, &e);
  if (st) return st;
  *E = e.v;
  return RNK_OK;
}

int rnk_jet_joint_end_grad(const double q[10], const rnk_frame *ref,
                           const rnk_joint_end_param *p, double *E, double g[10]) {
  jet e;
  int st = joint_eval(q, ref, p, 1, &e);
  if (st) return st;
  if (E) *E = e.v;
  scatter(p, &e, g, NULL);
  return RNK_OK;
}

int rnk_jet_joint_end_hess(const double q[10], const rnk_frame *ref,
                           const rnk_joint_end_param *p, double H[100]) {
  jet e;
  int st = joint_eval(q, ref, p, 2, &e);
  if (st) return st;
  scatter(p, &e, NULL, H);
  return RNK_OK;
}

int rnk_jet_joint_end_hvp(const double q[10], const rnk_frame *ref,
                          const rnk_joint_end_param *p, const double v[10],
                          double Hv[10]) {
  double H[100];
  int st = rnk_jet_joint_end_hess(q, ref, p, H);
  if (st) return st;
  rnk_block_mv(10, H, v, Hv);
  return RNK_OK;
}

int rnk_jet_joint_end_strains(const double q[10], const rnk_frame *ref,
                              const rnk_joint_end_param *p, double kappa[2],
                              double *twist) {
  joint_frames f;
  jet k[2], tau;
  int st = joint_frames_eval(q, ref, p, 0, &f);
  if (st) return st;
  st = joint_strains_jet(&f, p, k, &tau);
  if (st) return st;
  if (kappa) kappa[0] = k[0].v, kappa[1] = k[1].v;
  if (twist) *twist = tau.v;
  return RNK_OK;
}
