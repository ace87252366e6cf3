/* twist.c - twisting energy at an interior vertex,
 * E = 1/2 beta (tau - taubar)^2 / vlen, tau = theta^i - theta^{i-1} + m,
 * with the reference twist m continued from the stored value (no aliasing
 * modulo 2 pi) and differentiated exactly through the reference frames. */
#include "rnk.h"
#include "stencil.h"

static int twist_eval(const double q[11], const rnk_frame ref[2],
                      const rnk_twist_param *p, int ord, jet *E) {
  rnk_edge_jet f[2];
  int st = rnk_vertex_frames(q, ref, ord, f);
  if (st) return st;
  rnk_twist_from_frames(f, q, p, E);
  return RNK_OK;
}

int rnk_twist_energy(const double q[11], const rnk_frame ref[2], const rnk_twist_param *p,
                     double *E) {
  jet e;
  int st = twist_eval(q, ref, p, 0, &e);
  if (st) return st;
  *E = e.v;
  return RNK_OK;
}

int rnk_twist_grad(const double q[11], const rnk_frame ref[2], const rnk_twist_param *p,
                   double *E, double g[11]) {
  jet e;
  int st = twist_eval(q, ref, p, 1, &e);
  if (st) return st;
  if (E) *E = e.v;
  rnk_scatter_vertex(&e, g, NULL);
  return RNK_OK;
}

int rnk_twist_hess(const double q[11], const rnk_frame ref[2], const rnk_twist_param *p,
                   double H[121]) {
  jet e;
  int st = twist_eval(q, ref, p, 2, &e);
  if (st) return st;
  rnk_scatter_vertex(&e, NULL, H);
  return RNK_OK;
}

int rnk_twist_hvp(const double q[11], const rnk_frame ref[2], const rnk_twist_param *p,
                  const double v[11], double Hv[11]) {
  double H[121];
  int st = rnk_twist_hess(q, ref, p, H);
  if (st) return st;
  rnk_block_mv(11, H, v, Hv);
  return RNK_OK;
}
