/* section.c - cross-section constants (area, second moments, torsion). */
#include <math.h>

#include "rodnet.h"

static const double rn_pi = 3.14159265358979323846;

static int positive_finite(double v) { return isfinite(v) && v > 0.0; }

rn_status rn_section_circle(double r, rn_section *s) {
  return rn_section_hollow_circle(r, 0.0, s);
}

rn_status rn_section_hollow_circle(double ro, double ri, rn_section *s) {
  double r4;
  if (!s) return RN_ERR_ARG;
  if (!isfinite(ro) || !isfinite(ri)) return RN_ERR_NOT_FINITE;
  if (!(ro > 0.0) || !(ri >= 0.0) || !(ri < ro)) return RN_ERR_ARG;
  r4 = ro * ro * ro * ro - ri * ri * ri * ri;
  s->A = rn_pi * (ro * ro - ri * ri);
  s->I11 = rn_pi * r4 / 4.0;
  s->I22 = s->I11;
  s->I12 = 0.0;
  s->J = rn_pi * r4 / 2.0;
  return RN_OK;
}

rn_status rn_section_ellipse(double a, double b, rn_section *s) {
  if (!s) return RN_ERR_ARG;
  if (!isfinite(a) || !isfinite(b)) return RN_ERR_NOT_FINITE;
  if (!(a > 0.0) || !(b > 0.0)) return RN_ERR_ARG;
  s->A = rn_pi * a * b;
  s->I11 = rn_pi * a * a * a * b / 4.0; /* int (r . d1)^2 dA, a along d1 */
  s->I22 = rn_pi * a * b * b * b / 4.0;
  s->I12 = 0.0;
  s->J = rn_pi * a * a * a * b * b * b / (a * a + b * b);
  return RN_OK;
}

/* Saint-Venant torsion constant of an a x b rectangle (a >= b):
 * J = (a b^3 / 3) [1 - (192 b / (pi^5 a)) sum_{n odd} tanh(n pi a / (2 b)) / n^5],
 * summed until the terms no longer change the sum. */
static double rectangle_torsion(double a, double b) {
  double sum = 0.0;
  for (int n = 1; n < 200001; n += 2) {
    double dn = (double)n;
    double term = tanh(dn * rn_pi * a / (2.0 * b)) / (dn * dn * dn * dn * dn);
    sum += term;
    if (term < 1e-17 * sum) break;
  }
  return a * b * b * b / 3.0 * (1.0 - 192.0 * b / (pow(rn_pi, 5) * a) * sum);
}

rn_status rn_section_rectangle(double w, double h, rn_section *s) {
  if (!s) return RN_ERR_ARG;
  if (!isfinite(w) || !isfinite(h)) return RN_ERR_NOT_FINITE;
  if (!(w > 0.0) || !(h > 0.0)) return RN_ERR_ARG;
  s->A = w * h;
  s->I11 = h * w * w * w / 12.0; /* width along d1 */
  s->I22 = w * h * h * h / 12.0;
  s->I12 = 0.0;
  s->J = w >= h ? rectangle_torsion(w, h) : rectangle_torsion(h, w);
  return RN_OK;
}

rn_status rn_section_validate(const rn_section *s) {
  if (!s) return RN_ERR_ARG;
  if (!isfinite(s->A) || !isfinite(s->I11) || !isfinite(s->I22) || !isfinite(s->I12) ||
      !isfinite(s->J))
    return RN_ERR_NOT_FINITE;
  if (!positive_finite(s->A) || !positive_finite(s->I11) || !positive_finite(s->I22) ||
      !positive_finite(s->J))
    return RN_ERR_ARG;
  if (!(s->I11 * s->I22 - s->I12 * s->I12 > 0.0)) return RN_ERR_ARG;
  return RN_OK;
}
