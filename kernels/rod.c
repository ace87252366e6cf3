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
    rq_edge_big_angle(&ref[s], &E[s]);
  }
  if (E[0].bad != 0.0 || E[1].bad != 0.0) return RNK_DEGENERATE;
  rq_vert_eval(&E[0], &E[1], bp, tp, tp->ref_twist, ord, V);
  return V->bad != 0.0 ? RNK_DEGENERATE : RNK_OK;
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
RQ_INLINE void stencil_hess_e(const rq_edge E[2], const rq_vert *V, double He[8][8]) {
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
    rq_edge_big_angle(&ref[s], &E[s]);
    if (E[s].bad != 0.0) return RNK_DEGENERATE;
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

/* ---- whole rod segments ----------------------------------------------------
 * Chunks of up to RQ_CHUNK edges, in phases whose loops have no calls and no
 * branches (they vectorise across stencils): (1) prepare every edge of the
 * chunk (structure of arrays); (2) every vertex stencil of the chunk reads
 * its two edges and writes its energy and its gradient / HVP in the edge
 * variables (e0, theta0, e1, theta1) or its Hessian block; (3) every edge
 * sums what its two vertices and its stretching give it, and the DOFs get
 * the differences.  Degeneracy is flagged, never an early exit. */
/* 65 edges per chunk: 64 vertex stencils, a whole number of vectors; the
 * arrays are padded to RQ_DIM. */
enum { RQ_CHUNK = 65, RQ_DIM = 72 };

/* Loops over stencils: no dependence between iterations.  With GCC, each
 * function holding one is also compiled for AVX2 and AVX-512 and picked at
 * run time (the build keeps the baseline architecture). */
#if defined(__GNUC__) && !defined(__clang__)
#define RQ_VECTOR_LOOP _Pragma("GCC ivdep")
#else
#define RQ_VECTOR_LOOP
#endif
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && \
    defined(__linux__) && !defined(RN_NO_TARGET_CLONES)
#define RQ_CLONES __attribute__((target_clones("avx512f", "avx2", "default")))
#else
#define RQ_CLONES
#endif

typedef enum { SEG_ENERGY, SEG_GRAD, SEG_HVP, SEG_HESS } seg_op;

/* Prepared edges of a chunk (rq_edge, structure of arrays). */
typedef struct rq_edges {
  double t[3][RQ_DIM], l[RQ_DIM], il[RQ_DIM], th[3][RQ_DIM];
  double g[4][RQ_DIM], q[4][RQ_DIM], h[4][RQ_DIM];
  double cs[RQ_DIM], sn[RQ_DIM], theta[RQ_DIM];
  double shrt[RQ_DIM], bad[RQ_DIM];
  /* HVP: the direction's edge vectors, tangent rates and angle rates */
  double de[3][RQ_DIM], dt[3][RQ_DIM], dth[RQ_DIM];
} rq_edges;

RQ_INLINE void edges_put(rq_edges *S, int j, const rq_edge *E) {
  RQ_UNROLL for (int k = 0; k < 3; ++k) {
    S->t[k][j] = E->t[k];
    S->th[k][j] = E->th[k];
  }
  RQ_UNROLL for (int k = 0; k < 4; ++k) {
    S->g[k][j] = E->g[k];
    S->q[k][j] = E->q[k];
    S->h[k][j] = E->h[k];
  }
  S->l[j] = E->l;
  S->il[j] = E->il;
  S->cs[j] = E->cs;
  S->sn[j] = E->sn;
  S->theta[j] = E->theta;
  S->shrt[j] = E->short_;
  S->bad[j] = E->bad;
}

RQ_INLINE void edges_get(const rq_edges *S, int j, rq_edge *E) {
  RQ_UNROLL for (int k = 0; k < 3; ++k) {
    E->t[k] = S->t[k][j];
    E->th[k] = S->th[k][j];
  }
  RQ_UNROLL for (int k = 0; k < 4; ++k) {
    E->g[k] = S->g[k][j];
    E->q[k] = S->q[k][j];
    E->h[k] = S->h[k][j];
  }
  E->l = S->l[j];
  E->il = S->il[j];
  E->cs = S->cs[j];
  E->sn = S->sn[j];
  E->theta = S->theta[j];
  E->short_ = S->shrt[j];
  E->bad = S->bad[j];
}

/* Phase 1: edges j0 .. j0 + n - 1 of the segment (and the direction's rates
 * for the HVP). */
/* Inputs of a chunk transposed to structure of arrays, so that the loops
 * over stencils read unit-stride arrays only. */
typedef struct rq_in {
  double e[3][RQ_DIM], theta[RQ_DIM], th[3][RQ_DIM], a1[3][RQ_DIM];
  double ve[3][RQ_DIM], vth[RQ_DIM]; /* HVP direction */
  /* vertex k of the chunk at index k - 1 */
  double B[3][RQ_DIM], kbar[2][RQ_DIM], vlen[RQ_DIM];
  double beta[RQ_DIM], taubar[RQ_DIM], tvlen[RQ_DIM], m[RQ_DIM];
} rq_in;

/* Phase 1: edges j0 .. j0 + n - 1 of the segment (and the direction's rates
 * for the HVP); the vertex parameters. */
RQ_CLONES static void chunk_edges(const rnk_rod_seg *s, int j0, int n, const double *v,
                                  rq_in *I, rq_edges *S) {
  const double *x = s->x + 4 * j0;
  const rnk_frame *ref = s->ref + j0;
  RQ_VECTOR_LOOP
  for (int j = 0; j < n; ++j) {
    const double *xa = x + 4 * j;
    RQ_UNROLL for (int k = 0; k < 3; ++k) I->e[k][j] = xa[4 + k] - xa[k];
    I->theta[j] = xa[3];
  }
  /* one member per loop: GCC vectorises strided copies of single members, not
   * of whole structs (groups of 6 or 4 doubles) */
#define RQ_COPY(dst, src, count) \
  RQ_VECTOR_LOOP for (int j = 0; j < (count); ++j) { (dst)[j] = src; }
  RQ_COPY(I->th[0], ref[j].t[0], n)
  RQ_COPY(I->th[1], ref[j].t[1], n)
  RQ_COPY(I->th[2], ref[j].t[2], n)
  RQ_COPY(I->a1[0], ref[j].a1[0], n)
  RQ_COPY(I->a1[1], ref[j].a1[1], n)
  RQ_COPY(I->a1[2], ref[j].a1[2], n)
  const rnk_bend_param *bp = s->bp + j0;
  const rnk_twist_param *tp = s->tp + j0;
  RQ_COPY(I->B[0], bp[j].B[0], n - 1)
  RQ_COPY(I->B[1], bp[j].B[1], n - 1)
  RQ_COPY(I->B[2], bp[j].B[2], n - 1)
  RQ_COPY(I->kbar[0], bp[j].kbar[0], n - 1)
  RQ_COPY(I->kbar[1], bp[j].kbar[1], n - 1)
  RQ_COPY(I->vlen, bp[j].vlen, n - 1)
  RQ_COPY(I->beta, tp[j].beta, n - 1)
  RQ_COPY(I->taubar, tp[j].taubar, n - 1)
  RQ_COPY(I->tvlen, tp[j].vlen, n - 1)
  RQ_COPY(I->m, s->ref_twist[j0 + j], n - 1)
#undef RQ_COPY
  RQ_VECTOR_LOOP
  for (int j = 0; j < n; ++j) {
    rq_edge E;
    rnk_frame f = {{I->th[0][j], I->th[1][j], I->th[2][j]},
                   {I->a1[0][j], I->a1[1][j], I->a1[2][j]}};
    double e[3] = {I->e[0][j], I->e[1][j], I->e[2][j]};
    rq_edge_init(e, I->theta[j], &f, &E);
    edges_put(S, j, &E);
  }
  for (int j = 0; j < n; ++j) /* rare: angles beyond the polynomial range */
    if (fabs(0.5 * S->theta[j]) > RQ_TRIG_MAX) {
      rq_edge E;
      edges_get(S, j, &E);
      rq_edge_big_angle(&ref[j], &E);
      edges_put(S, j, &E);
    }
  if (!v) return;
  v += 4 * j0;
  RQ_VECTOR_LOOP
  for (int j = 0; j < n; ++j) {
    const double *va = v + 4 * j;
    RQ_UNROLL for (int k = 0; k < 3; ++k) I->ve[k][j] = va[4 + k] - va[k];
    I->vth[j] = va[3];
  }
  RQ_VECTOR_LOOP
  for (int j = 0; j < n; ++j) {
    double de[3] = {I->ve[0][j], I->ve[1][j], I->ve[2][j]};
    double t[3] = {S->t[0][j], S->t[1][j], S->t[2][j]}, td = rq_dot3(t, de);
    RQ_UNROLL for (int k = 0; k < 3; ++k) {
      S->de[k][j] = de[k];
      S->dt[k][j] = (de[k] - td * t[k]) * S->il[j];
    }
    S->dth[j] = I->vth[j];
  }
}

/* Parameters of vertex k of the chunk (1 <= k < n). */
RQ_INLINE void vertex_params(const rq_in *I, int k, rnk_bend_param *bp,
                             rnk_twist_param *tp) {
  RQ_UNROLL for (int c = 0; c < 3; ++c) bp->B[c] = I->B[c][k - 1];
  bp->kbar[0] = I->kbar[0][k - 1];
  bp->kbar[1] = I->kbar[1][k - 1];
  bp->vlen = I->vlen[k - 1];
  tp->beta = I->beta[k - 1];
  tp->taubar = I->taubar[k - 1];
  tp->vlen = I->tvlen[k - 1];
  tp->ref_twist = I->m[k - 1];
}

/* Vertex k of the chunk: its two edges and its strains, energy and (ord >= 1)
 * dE/dr. */
RQ_INLINE void vertex_prepare(const rq_in *I, const rq_edges *S, int k, int ord,
                              rq_edge E[2], rq_vert *V) {
  rnk_bend_param bp;
  rnk_twist_param tp;
  vertex_params(I, k, &bp, &tp);
  edges_get(S, k - 1, &E[0]);
  edges_get(S, k, &E[1]);
  rq_vert_eval(&E[0], &E[1], &bp, &tp, tp.ref_twist, ord, V);
}

/* Per-vertex results of a chunk: vertex k (1 <= k < n) at index k; indices 0
 * and n stay zero so that every edge can read both neighbours. */
typedef struct rq_vout {
  double a[8][RQ_DIM];  /* gradient or HVP in (e0, theta0, e1, theta1) */
  double H[36][RQ_DIM]; /* Hessian in those variables, upper triangle */
} rq_vout;

/* Phase 2 (energy, gradient, HVP); specialised per op (chunk_* below) so
 * that the loop body has no branch. */
RQ_INLINE void chunk_vertices_op(const rq_in *I, int n, seg_op op, const rq_edges *S,
                                 rq_vout *O, double *Eb, double *Et, double *bad) {
  double eb = 0.0, et = 0.0, b = 0.0;
  int ord = op == SEG_ENERGY ? 0 : 1;
  RQ_VECTOR_LOOP
  for (int k = 1; k < n; ++k) {
    rq_edge E[2];
    rq_vert V;
    vertex_prepare(I, S, k, ord, E, &V);
    eb += V.Eb;
    et += V.Et;
    b += V.bad + E[0].bad + E[1].bad;
    if (op == SEG_GRAD) {
      double gy[8], ge[3];
      rq_grad_y(&E[0], &E[1], V.r, V.mu, gy);
      RQ_UNROLL for (int e = 0; e < 2; ++e) {
        rq_project(&E[e], gy + 4 * e, ge);
        RQ_UNROLL for (int c = 0; c < 3; ++c) O->a[4 * e + c][k] = ge[c];
        O->a[4 * e + 3][k] = gy[4 * e + 3];
      }
    } else if (op == SEG_HVP) {
      double gy[8], hy[8], dy[8], he[3];
      RQ_UNROLL for (int e = 0; e < 2; ++e) {
        RQ_UNROLL for (int c = 0; c < 3; ++c) dy[4 * e + c] = S->dt[c][k - 1 + e];
        dy[4 * e + 3] = S->dth[k - 1 + e];
      }
      rq_grad_y(&E[0], &E[1], V.r, V.mu, gy);
      rq_hvp_y(&E[0], &E[1], &V, dy, hy);
      RQ_UNROLL for (int e = 0; e < 2; ++e) {
        double de[3] = {S->de[0][k - 1 + e], S->de[1][k - 1 + e], S->de[2][k - 1 + e]};
        rq_project(&E[e], hy + 4 * e, he);
        rq_curv_add(&E[e], gy + 4 * e, de, he);
        RQ_UNROLL for (int c = 0; c < 3; ++c) O->a[4 * e + c][k] = he[c];
        O->a[4 * e + 3][k] = hy[4 * e + 3];
      }
    }
  }
  *Eb += eb;
  *Et += et;
  *bad += b;
}

RQ_CLONES static void chunk_vertices_energy(const rq_in *I, int n, const rq_edges *S,
                                            rq_vout *O, double *Eb, double *Et,
                                            double *bad) {
  chunk_vertices_op(I, n, SEG_ENERGY, S, O, Eb, Et, bad);
}
RQ_CLONES static void chunk_vertices_grad(const rq_in *I, int n, const rq_edges *S,
                                          rq_vout *O, double *Eb, double *Et,
                                          double *bad) {
  chunk_vertices_op(I, n, SEG_GRAD, S, O, Eb, Et, bad);
}
RQ_CLONES static void chunk_vertices_hvp(const rq_in *I, int n, const rq_edges *S,
                                         rq_vout *O, double *Eb, double *Et,
                                         double *bad) {
  chunk_vertices_op(I, n, SEG_HVP, S, O, Eb, Et, bad);
}

/* Phase 2 for the Hessian: the block of every vertex of the chunk. */
RQ_CLONES static void chunk_hess(const rq_in *I, int n, const rq_edges *S, rq_vout *O,
                                 double *bad) {
  double b = 0.0;
  RQ_VECTOR_LOOP
  for (int k = 1; k < n; ++k) {
    rq_edge E[2];
    rq_vert V;
    double He[8][8];
    vertex_prepare(I, S, k, 1, E, &V);
    b += V.bad + E[0].bad + E[1].bad;
    stencil_hess_e(E, &V, He);
    RQ_UNROLL for (int r = 0, m = 0; r < 8; ++r)
        RQ_UNROLL for (int c = r; c < 8; ++c, ++m) O->H[m][k] = He[r][c];
  }
  *bad += b;
}

/* Phase 3: stretching of the counted edges, and what the vertices gave each
 * edge, into the segment's DOFs: x_j gets -F_j, x_{j+1} gets +F_j. */
static void chunk_assemble(const rnk_rod_seg *s, int j0, int n, int lo, int hi, seg_op op,
                           const rq_edges *S, const rq_vout *O, double *Es, double *out,
                           double *bad) {
  double es = 0.0, b = 0.0;
  for (int j = 0; j < n; ++j) {
    const rnk_stretch_param *p = &s->sp[j0 + j];
    double w = (j0 + j >= lo && j0 + j < hi) ? 1.0 : 0.0; /* counted here */
    double d = S->l[j] - p->lbar, sk = w * p->k / p->lbar, F[3], th = 0.0;
    double t[3] = {S->t[0][j], S->t[1][j], S->t[2][j]};
    es += 0.5 * sk * d * d;
    b += w * S->shrt[j];
    if (op == SEG_GRAD) {
      RQ_UNROLL for (int c = 0; c < 3; ++c) F[c] =
          sk * d * t[c] + O->a[c][j + 1] + O->a[4 + c][j];
      th = O->a[3][j + 1] + O->a[7][j];
    } else if (op == SEG_HVP) {
      double de[3] = {S->de[0][j], S->de[1][j], S->de[2][j]};
      double r = 1.0 - p->lbar * S->il[j], td = (1.0 - r) * rq_dot3(t, de);
      RQ_UNROLL for (int c = 0; c < 3; ++c) F[c] =
          sk * (r * de[c] + td * t[c]) + O->a[c][j + 1] + O->a[4 + c][j];
      th = O->a[3][j + 1] + O->a[7][j];
    } else {
      continue;
    }
    double *o = out + 4 * (j0 + j);
    RQ_UNROLL for (int c = 0; c < 3; ++c) {
      o[c] -= F[c];
      o[4 + c] += F[c];
    }
    o[3] += th;
  }
  *Es += es;
  *bad += b;
}

/* The block of vertex k over its stencil q = (x0, theta0, x1, theta1, x2)
 * from the one in (e0, theta0, e1, theta1), e0 = x1 - x0, e1 = x2 - x1. */
static void vertex_block_q(const rq_vout *O, int k, double H[11][11]) {
  double He[8][8];
  RQ_UNROLL for (int r = 0, m = 0; r < 8; ++r) RQ_UNROLL for (int c = r; c < 8; ++c, ++m)
      He[r][c] = He[c][r] = O->H[m][k];
  RQ_UNROLL for (int a = 0; a < 3; ++a) {
    RQ_UNROLL for (int c = 0; c < 3; ++c) {
      double A = He[a][c], B = He[a][4 + c], Bt = He[4 + a][c], C = He[4 + a][4 + c];
      H[a][c] = A;
      H[a][4 + c] = B - A;
      H[a][8 + c] = -B;
      H[4 + a][c] = Bt - A;
      H[4 + a][4 + c] = A - B - Bt + C;
      H[4 + a][8 + c] = B - C;
      H[8 + a][c] = -Bt;
      H[8 + a][4 + c] = Bt - C;
      H[8 + a][8 + c] = C;
    }
    RQ_UNROLL for (int t = 0; t < 2; ++t) { /* angle columns 3, 7 */
      double u = He[a][4 * t + 3], w = He[4 + a][4 * t + 3];
      H[a][4 * t + 3] = H[4 * t + 3][a] = -u;
      H[4 + a][4 * t + 3] = H[4 * t + 3][4 + a] = u - w;
      H[8 + a][4 * t + 3] = H[4 * t + 3][8 + a] = w;
    }
  }
  H[3][3] = He[3][3];
  H[3][7] = He[3][7];
  H[7][3] = He[7][3];
  H[7][7] = He[7][7];
}

/* Phase 3 for the Hessian: stretching and vertex blocks into the band. */
static void chunk_band(const rnk_rod_seg *s, int j0, int n, int lo, int hi,
                       const rq_edges *S, const rq_vout *O, double *band) {
  const int ld = RNK_BAND - 1; /* M[a * ld + c]: entry (a, c) of a stencil */
  for (int j = 0; j < n; ++j) {
    if (j0 + j < lo || j0 + j >= hi) continue;
    const rnk_stretch_param *p = &s->sp[j0 + j];
    double r = 1.0 - p->lbar * S->il[j], sk = p->k / p->lbar;
    double t[3] = {S->t[0][j], S->t[1][j], S->t[2][j]};
    double *M = band + 4 * (j0 + j) * RNK_BAND + RNK_BAND_HALF;
    RQ_UNROLL for (int a = 0; a < 3; ++a) RQ_UNROLL for (int c = 0; c < 3; ++c) {
      double h = sk * ((1.0 - r) * t[a] * t[c] + (a == c ? r : 0.0));
      M[a * ld + c] += h;
      M[(4 + a) * ld + 4 + c] += h;
      M[a * ld + 4 + c] -= h;
      M[(4 + a) * ld + c] -= h;
    }
  }
  for (int k = 1; k < n; ++k) {
    double H[11][11];
    vertex_block_q(O, k, H);
    double *b = band + 4 * (j0 + k - 1) * RNK_BAND + RNK_BAND_HALF;
    for (int r = 0; r < 11; ++r) /* row r: columns 0..10 of the stencil */
      RQ_UNROLL for (int c = 0; c < 11; ++c) b[r * ld + c] += H[r][c];
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
  rq_in I;
  rq_edges S;
  rq_vout O;
  int ne = s->ne, j0 = 0;
  double anybad = 0.0, Es = 0.0, Eb = 0.0, Et = 0.0;
  bad[0] = bad[1] = -1;
  RQ_UNROLL for (int c = 0; c < 8; ++c) O.a[c][0] = 0.0;
  for (;;) {
    int j1 = j0 + RQ_CHUNK < ne ? j0 + RQ_CHUNK : ne, n = j1 - j0;
    /* stretching of the edges the previous chunk did not count */
    int lo = j0 == 0 ? 0 : j0 + 1, hi = j1;
    if (lo < s->stretch_lo) lo = s->stretch_lo;
    if (hi > s->stretch_hi) hi = s->stretch_hi;
    chunk_edges(s, j0, n, op == SEG_HVP ? v : NULL, &I, &S);
    RQ_UNROLL for (int c = 0; c < 8; ++c) O.a[c][n] = 0.0;
    if (op == SEG_HESS) {
      chunk_hess(&I, n, &S, &O, &anybad);
      chunk_band(s, j0, n, lo, hi, &S, &O, out);
      for (int j = 0; j < n; ++j)
        anybad += (j0 + j >= lo && j0 + j < hi) ? S.shrt[j] : 0.0;
    } else {
      if (op == SEG_ENERGY)
        chunk_vertices_energy(&I, n, &S, &O, &Eb, &Et, &anybad);
      else if (op == SEG_GRAD)
        chunk_vertices_grad(&I, n, &S, &O, &Eb, &Et, &anybad);
      else
        chunk_vertices_hvp(&I, n, &S, &O, &Eb, &Et, &anybad);
      chunk_assemble(s, j0, n, lo, hi, op, &S, &O, &Es, out, &anybad);
    }
    if (j1 == ne) break;
    j0 = j1 - 1;
  }
  if (E) {
    E[0] = Es;
    E[1] = Eb;
    E[2] = Et;
  }
  if (anybad == 0.0) return RNK_OK;
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
