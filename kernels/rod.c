/* rod.c - closed-form bending + twisting kernels of a vertex stencil q[11]
 * (rodq.h: quaternions of the material frames), and the bending-only and
 * twisting-only kernels as the same code with the other stiffness zero.
 * The jet implementation (bendtwist.c) is the test oracle. */
#include <string.h>

#include "rnk.h"
#include "rodq.h"

/* Edges and vertex of a stencil; RNK_DEGENERATE as the jets report it. */
static int stencil_init(const double q[11], const rnk_frame ref[2],
                        const rnk_bend_param *bp, const rnk_twist_param *tp, int ord,
                        rq_edge E[2], rq_vert *V) {
  for (int s = 0; s < 2; ++s) {
    const double *xa = q + 4 * s, *xb = q + 4 * s + 4;
    double e[3] = {xb[0] - xa[0], xb[1] - xa[1], xb[2] - xa[2]};
    rq_edge_init(e, q[4 * s + 3], &ref[s], &E[s]);
  }
  if (E[0].bad || E[1].bad) return RNK_DEGENERATE;
  rq_vert_eval(&E[0], &E[1], bp, tp, tp->ref_twist, ord, V);
  return V->bad ? RNK_DEGENERATE : RNK_OK;
}

/* Gradient over y = (t0, theta0, t1, theta1) to the stencil q[11]. */
static void grad_to_q(const rq_edge E[2], const double gy[8], double g[11]) {
  double ge0[3], ge1[3];
  rq_project(&E[0], gy, ge0);
  rq_project(&E[1], gy + 4, ge1);
  for (int k = 0; k < 3; ++k) {
    g[k] = -ge0[k];
    g[4 + k] = ge0[k] - ge1[k];
    g[8 + k] = ge1[k];
  }
  g[3] = gy[3];
  g[7] = gy[7];
}

int rnk_bendtwist_energy(const double q[11], const rnk_frame ref[2],
                         const rnk_bend_param *bp, const rnk_twist_param *tp, double *Eb,
                         double *Et) {
  rq_edge E[2];
  rq_vert V;
  int st = stencil_init(q, ref, bp, tp, 0, E, &V);
  if (st) return st;
  *Eb = V.Eb;
  *Et = V.Et;
  return RNK_OK;
}

int rnk_bendtwist_grad(const double q[11], const rnk_frame ref[2],
                       const rnk_bend_param *bp, const rnk_twist_param *tp, double *E,
                       double g[11]) {
  rq_edge Ed[2];
  rq_vert V;
  double gy[8];
  int st = stencil_init(q, ref, bp, tp, 1, Ed, &V);
  if (st) return st;
  if (E) *E = V.Eb + V.Et;
  rq_grad_y(&Ed[0], &Ed[1], V.r, V.mu, gy);
  grad_to_q(Ed, gy, g);
  return RNK_OK;
}

/* Hessian-vector product of a prepared stencil. */
static void stencil_hvp(const rq_edge E[2], const rq_vert *V, const double v[11],
                        double Hv[11]) {
  double de[2][3], dy[8], gy[8], hy[8], he[2][3];
  for (int k = 0; k < 3; ++k) {
    de[0][k] = v[4 + k] - v[k];
    de[1][k] = v[8 + k] - v[4 + k];
  }
  for (int s = 0; s < 2; ++s) {
    double td = rq_dot3(E[s].t, de[s]);
    for (int k = 0; k < 3; ++k) dy[4 * s + k] = (de[s][k] - td * E[s].t[k]) * E[s].il;
  }
  dy[3] = v[3];
  dy[7] = v[7];
  rq_grad_y(&E[0], &E[1], V->r, V->mu, gy);
  rq_hvp_y(&E[0], &E[1], V, dy, hy);
  for (int s = 0; s < 2; ++s) {
    rq_project(&E[s], hy + 4 * s, he[s]);
    rq_curv_add(&E[s], gy + 4 * s, de[s], he[s]);
  }
  for (int k = 0; k < 3; ++k) {
    Hv[k] = -he[0][k];
    Hv[4 + k] = he[0][k] - he[1][k];
    Hv[8 + k] = he[1][k];
  }
  Hv[3] = hy[3];
  Hv[7] = hy[7];
}

int rnk_bendtwist_hvp(const double q[11], const rnk_frame ref[2],
                      const rnk_bend_param *bp, const rnk_twist_param *tp,
                      const double v[11], double Hv[11]) {
  rq_edge E[2];
  rq_vert V;
  int st = stencil_init(q, ref, bp, tp, 1, E, &V);
  if (st) return st;
  stencil_hvp(E, &V, v, Hv);
  return RNK_OK;
}

/* Hessian of a prepared stencil in the edge variables (e0, theta0, e1,
 * theta1). */
static void stencil_hess_e(const rq_edge E[2], const rq_vert *V, double He[8][8]) {
  double gy[8];
  rq_grad_y(&E[0], &E[1], V->r, V->mu, gy);
  rq_hess_y(&E[0], &E[1], V, He);
  rq_hess_e(&E[0], &E[1], gy, He);
}

/* Adds the block of a vertex stencil, given in the edge variables, to
 * M[row * ld + col] over the stencil's q = (x0, theta0, x1, theta1, x2):
 * e0 = x1 - x0, e1 = x2 - x1. */
static void add_vertex_block(double He[8][8], double *M, int ld) {
  for (int a = 0; a < 8; ++a) {
    int sa = a >> 2, ka = a & 3; /* edge, component (3: angle) */
    for (int b = 0; b < 8; ++b) {
      int sb = b >> 2, kb = b & 3;
      double h = He[a][b];
      if (ka == 3 && kb == 3) {
        M[(4 * sa + 3) * ld + 4 * sb + 3] += h;
      } else if (ka == 3) {
        M[(4 * sa + 3) * ld + 4 * sb + 4 + kb] += h;
        M[(4 * sa + 3) * ld + 4 * sb + kb] -= h;
      } else if (kb == 3) {
        M[(4 * sa + 4 + ka) * ld + 4 * sb + 3] += h;
        M[(4 * sa + ka) * ld + 4 * sb + 3] -= h;
      } else {
        M[(4 * sa + 4 + ka) * ld + 4 * sb + 4 + kb] += h;
        M[(4 * sa + 4 + ka) * ld + 4 * sb + kb] -= h;
        M[(4 * sa + ka) * ld + 4 * sb + 4 + kb] -= h;
        M[(4 * sa + ka) * ld + 4 * sb + kb] += h;
      }
    }
  }
}

static void stencil_hess(const rq_edge E[2], const rq_vert *V, double H[121]) {
  double He[8][8];
  stencil_hess_e(E, V, He);
  memset(H, 0, 121 * sizeof(double));
  add_vertex_block(He, H, 11);
}

int rnk_bendtwist_hess(const double q[11], const rnk_frame ref[2],
                       const rnk_bend_param *bp, const rnk_twist_param *tp,
                       double H[121]) {
  rq_edge E[2];
  rq_vert V;
  int st = stencil_init(q, ref, bp, tp, 1, E, &V);
  if (st) return st;
  stencil_hess(E, &V, H);
  return RNK_OK;
}

/* ---- strains (values) --------------------------------------------------------
 * The same code as the energy, so that rest strains taken from a state give
 * exactly zero energy there. */
static const rnk_bend_param unit_bend = {{0.0, 0.0, 0.0}, {0.0, 0.0}, 1.0};

int rnk_strains(const double q[11], const rnk_frame ref[2], double ref_twist_prev,
                double kappa[2], double *twist) {
  rq_edge E[2];
  rq_vert V;
  rnk_twist_param tp = {0.0, 0.0, 1.0, ref_twist_prev};
  int st = stencil_init(q, ref, &unit_bend, &tp, 0, E, &V);
  if (st) return st;
  if (kappa) {
    kappa[0] = V.kappa[0];
    kappa[1] = V.kappa[1];
  }
  if (twist) *twist = V.tau;
  return RNK_OK;
}

int rnk_reference_twist(const double q[11], const rnk_frame ref[2], double ref_twist_prev,
                        double *m) {
  rq_edge E[2];
  rq_vert V;
  rnk_twist_param tp = {0.0, 0.0, 1.0, ref_twist_prev};
  for (int s = 0; s < 2; ++s) { /* the twist needs no curvature: no kink test */
    const double *xa = q + 4 * s, *xb = q + 4 * s + 4;
    double e[3] = {xb[0] - xa[0], xb[1] - xa[1], xb[2] - xa[2]};
    rq_edge_init(e, q[4 * s + 3], &ref[s], &E[s]);
    if (E[s].bad) return RNK_DEGENERATE;
  }
  rq_vert_eval(&E[0], &E[1], &unit_bend, &tp, ref_twist_prev, 0, &V);
  *m = V.ref_twist;
  return RNK_OK;
}

/* ---- bending alone and twisting alone: the other stiffness zero ---------- */
static const rnk_twist_param no_twist = {0.0, 0.0, 1.0, 0.0};

static rnk_bend_param no_bend(double vlen) {
  rnk_bend_param p = {{0.0, 0.0, 0.0}, {0.0, 0.0}, vlen};
  return p;
}

int rnk_bend_energy(const double q[11], const rnk_frame ref[2], const rnk_bend_param *p,
                    double *E) {
  double Et;
  return rnk_bendtwist_energy(q, ref, p, &no_twist, E, &Et);
}
int rnk_bend_grad(const double q[11], const rnk_frame ref[2], const rnk_bend_param *p,
                  double *E, double g[11]) {
  return rnk_bendtwist_grad(q, ref, p, &no_twist, E, g);
}
int rnk_bend_hess(const double q[11], const rnk_frame ref[2], const rnk_bend_param *p,
                  double H[121]) {
  return rnk_bendtwist_hess(q, ref, p, &no_twist, H);
}
int rnk_bend_hvp(const double q[11], const rnk_frame ref[2], const rnk_bend_param *p,
                 const double v[11], double Hv[11]) {
  return rnk_bendtwist_hvp(q, ref, p, &no_twist, v, Hv);
}

int rnk_twist_energy(const double q[11], const rnk_frame ref[2], const rnk_twist_param *p,
                     double *E) {
  double Eb;
  rnk_bend_param b = no_bend(p->vlen);
  return rnk_bendtwist_energy(q, ref, &b, p, &Eb, E);
}
int rnk_twist_grad(const double q[11], const rnk_frame ref[2], const rnk_twist_param *p,
                   double *E, double g[11]) {
  rnk_bend_param b = no_bend(p->vlen);
  return rnk_bendtwist_grad(q, ref, &b, p, E, g);
}
int rnk_twist_hess(const double q[11], const rnk_frame ref[2], const rnk_twist_param *p,
                   double H[121]) {
  rnk_bend_param b = no_bend(p->vlen);
  return rnk_bendtwist_hess(q, ref, &b, p, H);
}
int rnk_twist_hvp(const double q[11], const rnk_frame ref[2], const rnk_twist_param *p,
                  const double v[11], double Hv[11]) {
  rnk_bend_param b = no_bend(p->vlen);
  return rnk_bendtwist_hvp(q, ref, &b, p, v, Hv);
}

/* ---- whole rod segments ---------------------------------------------------- */
enum { RQ_CHUNK = 64 }; /* edges prepared at a time (on the stack) */

typedef enum { SEG_ENERGY, SEG_GRAD, SEG_HVP, SEG_HESS } seg_op;

/* Stretching of edge j (prepared frame E) for op; same values as stretch.c. */
static void seg_stretch(const rnk_rod_seg *s, int j, const rq_edge *E, seg_op op,
                        const double *v, double *Es, double *out) {
  const rnk_stretch_param *p = &s->sp[j];
  double d = E->l - p->lbar, sk = p->k / p->lbar, *o = out + 4 * j;
  if (op == SEG_ENERGY || op == SEG_GRAD) *Es += 0.5 * sk * d * d;
  if (op == SEG_GRAD) {
    double f = sk * d;
    for (int k = 0; k < 3; ++k) {
      o[k] -= f * E->t[k];
      o[4 + k] += f * E->t[k];
    }
  } else if (op == SEG_HVP) {
    const double *vj = v + 4 * j;
    double de[3] = {vj[4] - vj[0], vj[5] - vj[1], vj[6] - vj[2]};
    double r = 1.0 - p->lbar * E->il, td = (1.0 - r) * rq_dot3(E->t, de);
    for (int k = 0; k < 3; ++k) {
      double hk = sk * (r * de[k] + td * E->t[k]);
      o[k] -= hk;
      o[4 + k] += hk;
    }
  } else if (op == SEG_HESS) {
    double r = 1.0 - p->lbar * E->il, *M = out + 4 * j * RNK_BAND + RNK_BAND_HALF;
    const int ld = RNK_BAND - 1; /* M[a * ld + c]: entry (4j + a, 4j + c) */
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) {
        double h = sk * ((1.0 - r) * E->t[a] * E->t[b] + (a == b ? r : 0.0));
        M[a * ld + b] += h;
        M[(4 + a) * ld + 4 + b] += h;
        M[a * ld + 4 + b] -= h;
        M[(4 + a) * ld + b] -= h;
      }
  }
}

/* Interior vertex k (edges k-1, k prepared in E[0], E[1]) for op. */
static void seg_vertex(const rnk_rod_seg *s, int k, const rq_edge E[2], seg_op op,
                       const double *v, double *Eb, double *Et, double *out, int *bad) {
  rq_vert V;
  int o = 4 * (k - 1);
  rq_vert_eval(&E[0], &E[1], &s->bp[k - 1], &s->tp[k - 1], s->ref_twist[k - 1],
               op == SEG_ENERGY ? 0 : 1, &V);
  *bad |= V.bad | E[0].bad | E[1].bad;
  *Eb += V.Eb;
  *Et += V.Et;
  if (op == SEG_GRAD) {
    double gy[8], g[11];
    rq_grad_y(&E[0], &E[1], V.r, V.mu, gy);
    grad_to_q(E, gy, g);
    for (int i = 0; i < 11; ++i) out[o + i] += g[i];
  } else if (op == SEG_HVP) {
    double hv[11];
    stencil_hvp(E, &V, v + o, hv);
    for (int i = 0; i < 11; ++i) out[o + i] += hv[i];
  } else if (op == SEG_HESS) {
    double He[8][8];
    stencil_hess_e(E, &V, He);
    add_vertex_block(He, out + o * RNK_BAND + RNK_BAND_HALF, RNK_BAND - 1);
  }
}

/* First degenerate stretched edge and interior vertex, by the stencil
 * kernels (only called when the pass found one). */
static void seg_find_bad(const rnk_rod_seg *s, int bad[2]) {
  double E1, E2;
  for (int j = s->stretch_lo; j < s->stretch_hi && bad[0] < 0; ++j)
    if (rnk_stretch_energy(s->x + 4 * j, &s->sp[j], &E1)) bad[0] = j;
  for (int k = 1; k < s->ne && bad[1] < 0; ++k) {
    rnk_twist_param tp = s->tp[k - 1];
    tp.ref_twist = s->ref_twist[k - 1];
    if (rnk_bendtwist_energy(s->x + 4 * (k - 1), &s->ref[k - 1], &s->bp[k - 1], &tp, &E1,
                             &E2))
      bad[1] = k;
  }
}

static int seg_eval(const rnk_rod_seg *s, seg_op op, const double *v, double E[3],
                    double *out, int bad[2]) {
  rq_edge Ed[RQ_CHUNK];
  int ne = s->ne, j0 = 0, anybad = 0;
  double Es = 0.0, Eb = 0.0, Et = 0.0;
  bad[0] = bad[1] = -1;
  for (;;) {
    int j1 = j0 + RQ_CHUNK < ne ? j0 + RQ_CHUNK : ne;
    for (int j = j0; j < j1; ++j) {
      const double *xa = s->x + 4 * j;
      double e[3] = {xa[4] - xa[0], xa[5] - xa[1], xa[6] - xa[2]};
      rq_edge_init(e, xa[3], &s->ref[j], &Ed[j - j0]);
    }
    /* stretching of the edges not counted by the previous chunk */
    int lo = j0 == 0 ? 0 : j0 + 1, hi = j1;
    if (lo < s->stretch_lo) lo = s->stretch_lo;
    if (hi > s->stretch_hi) hi = s->stretch_hi;
    for (int j = lo; j < hi; ++j) {
      anybad |= Ed[j - j0].short_;
      seg_stretch(s, j, &Ed[j - j0], op, v, &Es, out);
    }
    for (int k = j0 + 1; k < j1; ++k)
      seg_vertex(s, k, &Ed[k - 1 - j0], op, v, &Eb, &Et, out, &anybad);
    if (j1 == ne) break;
    j0 = j1 - 1;
  }
  if (E) {
    E[0] = Es;
    E[1] = Eb;
    E[2] = Et;
  }
  if (!anybad) return RNK_OK;
  seg_find_bad(s, bad);
  return RNK_DEGENERATE;
}

int rnk_rod_energy(const rnk_rod_seg *s, double E[3], int bad[2]) {
  return seg_eval(s, SEG_ENERGY, NULL, E, NULL, bad);
}
int rnk_rod_grad(const rnk_rod_seg *s, double E[3], double *g, int bad[2]) {
  return seg_eval(s, SEG_GRAD, NULL, E, g, bad);
}
int rnk_rod_hvp(const rnk_rod_seg *s, const double *v, double *Hv, int bad[2]) {
  return seg_eval(s, SEG_HVP, v, NULL, Hv, bad);
}
int rnk_rod_hess(const rnk_rod_seg *s, double *band, int bad[2]) {
  return seg_eval(s, SEG_HESS, NULL, NULL, band, bad);
}
