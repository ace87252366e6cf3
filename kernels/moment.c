/* moment.c - a couple M acting on the material frame of one edge.
 * E = -|M| (angle0 + alpha), alpha the rotation of the frame (t, d1, d2) about
 * the fixed axis n = M / |M| since the reference frame f0 (swing-twist
 * decomposition of the incremental rotation R = sum_k f_k f0_k^T):
 * tan(alpha / 2) = n . sum_k (f0_k x f_k) / (1 + sum_k f0_k . f_k). */
#include <math.h>

#include "rnk.h"
#include "stencil.h"

static int moment_eval(const double q[7], const rnk_frame *ref, const rnk_moment_param *p,
                       int ord, jet *alpha, double *mag) {
  double e[3] = {q[4] - q[0], q[5] - q[1], q[6] - q[2]};
  rnk_edge_jet f;
  int st = rnk_edge_jet_eval(e, q[3], ref, ord, &f);
  if (st) return st;
  double m = sqrt(p->M[0] * p->M[0] + p->M[1] * p->M[1] + p->M[2] * p->M[2]);
  double n[3] = {0.0, 0.0, 0.0};
  if (m > 0.0)
    for (int k = 0; k < 3; ++k) n[k] = p->M[k] / m;
  *mag = m;
  const jvec *fr[3] = {&f.t, &f.d1, &f.d2};
  jet num, den, tmp;
  jet_const(&num, 4, ord, 0.0);
  jet_const(&den, 4, ord, 1.0);
  for (int k = 0; k < 3; ++k) {
    const double *f0 = p->f0 + 3 * k;
    double c[3] = {n[1] * f0[2] - n[2] * f0[1], n[2] * f0[0] - n[0] * f0[2],
                   n[0] * f0[1] - n[1] * f0[0]};
    /* n . (f0 x f) = (n x f0) . f */
    for (int a = 0; a < 3; ++a) {
      jet_scale(&tmp, c[a], &fr[k]->c[a]);
      jet_add(&num, &num, &tmp);
      jet_scale(&tmp, f0[a], &fr[k]->c[a]);
      jet_add(&den, &den, &tmp);
    }
  }
  if (!(den.v > RNK_OPPOSITE_TOL)) return RNK_DEGENERATE;
  jet_atan2(alpha, &num, &den);
  jet_scale(alpha, 2.0, alpha);
  return RNK_OK;
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
