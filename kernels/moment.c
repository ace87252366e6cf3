/* moment.c - a couple M acting on the material frame of one edge.
 * E = -|M| (angle0 + alpha), alpha = rotation about n = M / |M| of a vector
 * f fixed in the material frame since the last update (value f0): with u0
 * the projection of f0 onto the plane normal to n,
 * alpha = atan2((n x u0) . f, u0 . f). */
#include <math.h>

#include "rnk.h"
#include "stencil.h"

/* alpha for the frame vector f (jets) against the constant f0 about n. */
int rnk_projected_angle(const jvec *f, const double f0[3], const double n[3],
                        jet *alpha) {
  double fn = f0[0] * n[0] + f0[1] * n[1] + f0[2] * n[2], u0[3], c[3];
  for (int k = 0; k < 3; ++k) u0[k] = f0[k] - fn * n[k];
  double uu = u0[0] * u0[0] + u0[1] * u0[1] + u0[2] * u0[2];
  if (!(uu > 1e-12)) return RNK_DEGENERATE;
  c[0] = n[1] * u0[2] - n[2] * u0[1];
  c[1] = n[2] * u0[0] - n[0] * u0[2];
  c[2] = n[0] * u0[1] - n[1] * u0[0];
  jet num, den;
  jvec_dot_const(&num, f, c);
  jvec_dot_const(&den, f, u0);
  if (!(num.v * num.v + den.v * den.v > 1e-12 * uu)) return RNK_DEGENERATE;
  jet_atan2(alpha, &num, &den);
  return RNK_OK;
}

static int moment_eval(const double q[7], const rnk_frame *ref, const rnk_moment_param *p,
                       int ord, jet *alpha, double *mag) {
  double e[3] = {q[4] - q[0], q[5] - q[1], q[6] - q[2]};
  rnk_edge_jet f;
  int st = rnk_edge_jet_eval(e, q[3], ref, ord, &f);
  if (st) return st;
  double m = sqrt(p->M[0] * p->M[0] + p->M[1] * p->M[1] + p->M[2] * p->M[2]);
  *mag = m;
  if (!(m > 0.0)) {
    jet_const(alpha, 4, ord, 0.0);
    return RNK_OK;
  }
  double n[3] = {p->M[0] / m, p->M[1] / m, p->M[2] / m};
  /* f = b1 t + b2 d1 + b3 d2, and its value at the last update */
  jvec fv;
  double f0[3];
  for (int a = 0; a < 3; ++a) {
    jet t1;
    jet_lin(&t1, p->b[0], &f.t.c[a], p->b[1], &f.d1.c[a]);
    jet_lin(&fv.c[a], 1.0, &t1, p->b[2], &f.d2.c[a]);
    f0[a] = p->b[0] * p->f0[a] + p->b[1] * p->f0[3 + a] + p->b[2] * p->f0[6 + a];
  }
  return rnk_projected_angle(&fv, f0, n, alpha);
}

static int moment_energy_jet(const double q[7], const rnk_frame *ref,
                             const rnk_moment_param *p, int ord, jet *E) {
  double m;
  int st = moment_eval(q, ref, p, ord, E, &m);
  if (st) return st;
  jet_add_const(E, E, p->angle0);
  jet_scale(E, -m, E);
  return RNK_OK;
}

int rnk_moment_angle(const double q[7], const rnk_frame *ref, const rnk_moment_param *p,
                     double *alpha) {
  jet a;
  double m;
  int st = moment_eval(q, ref, p, 0, &a, &m);
  if (st) return st;
  *alpha = a.v;
  return RNK_OK;
}

int rnk_moment_energy(const double q[7], const rnk_frame *ref, const rnk_moment_param *p,
                      double *E) {
  jet e;
  int st = moment_energy_jet(q, ref, p, 0, &e);
  if (st) return st;
  *E = e.v;
  return RNK_OK;
}

int rnk_moment_grad(const double q[7], const rnk_frame *ref, const rnk_moment_param *p,
                    double *E, double g[7]) {
  jet e;
  int st = moment_energy_jet(q, ref, p, 1, &e);
  if (st) return st;
  if (E) *E = e.v;
  rnk_scatter_edge(&e, g, NULL);
  return RNK_OK;
}

int rnk_moment_hess(const double q[7], const rnk_frame *ref, const rnk_moment_param *p,
                    double H[49]) {
  jet e;
  int st = moment_energy_jet(q, ref, p, 2, &e);
  if (st) return st;
  rnk_scatter_edge(&e, NULL, H);
  return RNK_OK;
}

int rnk_moment_hvp(const double q[7], const rnk_frame *ref, const rnk_moment_param *p,
                   const double v[7], double Hv[7]) {
  double H[49];
  int st = rnk_moment_hess(q, ref, p, H);
  if (st) return st;
  rnk_block_mv(7, H, v, Hv);
  return RNK_OK;
}
