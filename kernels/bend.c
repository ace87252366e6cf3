/* bend.c - bending energy at an interior vertex,
 * E = 1/2 (kappa - kbar)^T B (kappa - kbar) / vlen, with the curvature
 * binormal kb = 2 t0 x t1 / (1 + t0 . t1) and the material curvature
 * kappa = (kb . (d2_0 + d2_1) / 2, -kb . (d1_0 + d1_1) / 2) (seed 000 (2.1),
 * (2.2)), divided by the Voronoi length as corrected in shared/seeds/README. */
#include "rnk.h"
#include "stencil.h"

static int bend_eval(const double q[11], const rnk_frame ref[2], const rnk_bend_param *p,
                     int ord, jet *E) {
  rnk_edge_jet f[2];
  int st = rnk_vertex_frames(q, ref, ord, f);
  if (st) return st;
  return rnk_bend_from_frames(f, p, E);
}

int rnk_bend_energy(const double q[11], const rnk_frame ref[2], const rnk_bend_param *p,
                    double *E) {
  jet e;
  int st = bend_eval(q, ref, p, 0, &e);
  if (st) return st;
  *E = e.v;
  return RNK_OK;
}

int rnk_bend_grad(const double q[11], const rnk_frame ref[2], const rnk_bend_param *p,
                  double *E, double g[11]) {
  jet e;
  int st = bend_eval(q, ref, p, 1, &e);
  if (st) return st;
  if (E) *E = e.v;
  rnk_scatter_vertex(&e, g, NULL);
  return RNK_OK;
}

int rnk_bend_hess(const double q[11], const rnk_frame ref[2], const rnk_bend_param *p,
                  double H[121]) {
  jet e;
  int st = bend_eval(q, ref, p, 2, &e);
  if (st) return st;
  rnk_scatter_vertex(&e, NULL, H);
  return RNK_OK;
}

int rnk_bend_hvp(const double q[11], const rnk_frame ref[2], const rnk_bend_param *p,
                 const double v[11], double Hv[11]) {
  double H[121];
  int st = rnk_bend_hess(q, ref, p, H);
  if (st) return st;
  rnk_block_mv(11, H, v, Hv);
  return RNK_OK;
}

int rnk_strains(const double q[11], const rnk_frame ref[2], double ref_twist_prev,
                double kappa[2], double *twist) {
  rnk_edge_jet f[2];
  jet k[2], tau;
  int st = rnk_vertex_frames(q, ref, 0, f);
  if (st) return st;
  st = rnk_curvature_jet(f, k);
  if (st) return st;
  if (kappa) {
    kappa[0] = k[0].v;
    kappa[1] = k[1].v;
  }
  if (twist) {
    rnk_twist_jet(f, q, ref_twist_prev, &tau);
    *twist = tau.v;
  }
  return RNK_OK;
}
