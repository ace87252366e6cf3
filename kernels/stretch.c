/* stretch.c - stretching energy of an edge, E = 1/2 k (l - lbar)^2 / lbar
 * (seed 000 (2.7)).  Closed-form gradient and Hessian. */
#include <math.h>

#include "rnk.h"

static int edge_geometry(const double q[7], double e[3], double *l) {
  for (int k = 0; k < 3; ++k) e[k] = q[4 + k] - q[k];
  double l2 = e[0] * e[0] + e[1] * e[1] + e[2] * e[2];
  if (!(l2 > 0.0) || !isfinite(l2)) return RNK_DEGENERATE;
  *l = sqrt(l2);
  return RNK_OK;
}

int rnk_stretch_energy(const double q[7], const rnk_stretch_param *p, double *E) {
  double e[3], l;
  int st = edge_geometry(q, e, &l);
  if (st) return st;
  double d = l - p->lbar;
  *E = 0.5 * p->k * d * d / p->lbar;
  return RNK_OK;
}

int rnk_stretch_grad(const double q[7], const rnk_stretch_param *p, double *E,
                     double g[7]) {
  double e[3], l;
  int st = edge_geometry(q, e, &l);
  if (st) return st;
  double d = l - p->lbar, f = p->k * d / p->lbar;
  if (E) *E = 0.5 * p->k * d * d / p->lbar;
  for (int k = 0; k < 3; ++k) {
    double gk = f * e[k] / l; /* dE/de = f t */
    g[k] = -gk;
    g[4 + k] = gk;
  }
  g[3] = 0.0;
  return RNK_OK;
}

int rnk_stretch_hess(const double q[7], const rnk_stretch_param *p, double H[49]) {
  double e[3], l;
  int st = edge_geometry(q, e, &l);
  if (st) return st;
  /* d2E/de2 = (k / lbar) [ t t^T + (1 - lbar / l) (I - t t^T) ] */
  double s = p->k / p->lbar, r = 1.0 - p->lbar / l, t[3] = {e[0] / l, e[1] / l, e[2] / l};
  for (int i = 0; i < 49; ++i) H[i] = 0.0;
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) {
      double hab = s * ((1.0 - r) * t[a] * t[b] + (a == b ? r : 0.0));
      H[a * 7 + b] = hab;
      H[(4 + a) * 7 + (4 + b)] = hab;
      H[a * 7 + (4 + b)] = -hab;
      H[(4 + a) * 7 + b] = -hab;
    }
  return RNK_OK;
}

int rnk_stretch_hvp(const double q[7], const rnk_stretch_param *p, const double v[7],
                    double Hv[7]) {
  double e[3], l;
  int st = edge_geometry(q, e, &l);
  if (st) return st;
  /* (k / lbar) [ r de + (1 - r) t (t . de) ], r = 1 - lbar / l, de = v1 - v0 */
  double s = p->k / p->lbar, r = 1.0 - p->lbar / l, de[3], td = 0.0;
  for (int k = 0; k < 3; ++k) {
    de[k] = v[4 + k] - v[k];
    td += e[k] * de[k];
  }
  td *= (1.0 - r) / (l * l);
  for (int k = 0; k < 3; ++k) {
    double hk = s * (r * de[k] + td * e[k]);
    Hv[k] = -hk;
    Hv[4 + k] = hk;
  }
  Hv[3] = 0.0;
  return RNK_OK;
}
