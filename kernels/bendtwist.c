/* bendtwist.c - bending and twisting at one vertex from second-order jets of
 * the two edge frames: the helpers the joint kernels use, and the jet
 * evaluation of the vertex stencil that the tests take as the oracle of the
 * closed forms (rod.c). */
#include "rnk.h"
#include "stencil.h"

static void bend_from_kappa(jet k[2], const rnk_bend_param *p, jet *E) {
  jet a, b, c;
  jet_add_const(&k[0], &k[0], -p->kbar[0]);
  jet_add_const(&k[1], &k[1], -p->kbar[1]);
  jet_mul(&a, &k[0], &k[0]);
  jet_mul(&b, &k[0], &k[1]);
  jet_mul(&c, &k[1], &k[1]);
  double s = 0.5 / p->vlen;
  jet_lin(E, s * p->B[0], &a, 2.0 * s * p->B[1], &b);
  jet_lin(E, 1.0, E, s * p->B[2], &c);
}

/* The bending energy of the vertex (bendtwist_eval). */
int rnk_bend_from_frames(const rnk_edge_jet f[2], const rnk_bend_param *p, jet *E) {
  jet k[2];
  int st = rnk_curvature_jet(f, k);
  if (st) return st;
  bend_from_kappa(k, p, E);
  return RNK_OK;
}

void rnk_twist_from_frames(const rnk_edge_jet f[2], const double q[11],
                           const rnk_twist_param *p, jet *E) {
  jet tau;
  rnk_twist_jet(f, q, p->ref_twist, &tau);
  jet_add_const(&tau, &tau, -p->taubar);
  jet_mul(E, &tau, &tau);
  jet_scale(E, 0.5 * p->beta / p->vlen, E);
}

static int bendtwist_eval(const double q[11], const rnk_frame ref[2],
                          const rnk_bend_param *bp, const rnk_twist_param *tp, int ord,
                          jet *Eb, jet *Et) {
  rnk_edge_jet f[2];
  int st = rnk_vertex_frames(q, ref, ord, f);
  if (st) return st;
  st = rnk_bend_from_frames(f, bp, Eb);
  if (st) return st;
  rnk_twist_from_frames(f, q, tp, Et);
  return RNK_OK;
}

int rnk_jet_bendtwist_energy(const double q[11], const rnk_frame ref[2],
                             const rnk_bend_param *bp, const rnk_twist_param *tp,
                             double *Eb, double *Et) {
  jet eb, et;
  int st = bendtwist_eval(q, ref, bp, tp, 0, &eb, &et);
  if (st) return st;
  *Eb = eb.v;
  *Et = et.v;
  return RNK_OK;
}

int rnk_jet_bendtwist_grad(const double q[11], const rnk_frame ref[2],
                           const rnk_bend_param *bp, const rnk_twist_param *tp, double *E,
                           double g[11]) {
  jet eb, et;
  int st = bendtwist_eval(q, ref, bp, tp, 1, &eb, &et);
  if (st) return st;
  jet_add(&eb, &eb, &et);
  if (E) *E = eb.v;
  rnk_scatter_vertex(&eb, g, NULL);
  return RNK_OK;
}

int rnk_jet_bendtwist_hess(const double q[11], const rnk_frame ref[2],
                           const rnk_bend_param *bp, const rnk_twist_param *tp,
                           double H[121]) {
  jet eb, et;
  int st = bendtwist_eval(q, ref, bp, tp, 2, &eb, &et);
  if (st) return st;
  jet_add(&eb, &eb, &et);
  rnk_scatter_vertex(&eb, NULL, H);
  return RNK_OK;
}

int rnk_jet_bendtwist_hvp(const double q[11], const rnk_frame ref[2],
                          const rnk_bend_param *bp, const rnk_twist_param *tp,
                          const double v[11], double Hv[11]) {
  double H[121];
  int st = rnk_jet_bendtwist_hess(q, ref, bp, tp, H);
  if (st) return st;
  rnk_block_mv(11, H, v, Hv);
  return RNK_OK;
}
