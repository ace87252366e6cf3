/* rqmath.h - sine, cosine and arctangent as straight-line code (no calls, no
 * branches: loops that use them vectorise), accurate to a few units in the
 * last place; internal to kernels/.  The polynomials are the Taylor series,
 * truncated where the remainder is below 1e-19 on the reduced interval. */
#ifndef RODNET_RQMATH_H
#define RODNET_RQMATH_H

#include <math.h>

#if defined(__GNUC__)
#define RQM_INLINE static inline __attribute__((always_inline))
#else
#define RQM_INLINE static inline
#endif

/* Largest |x| for rq_sincos: the three-part reduction by pi/2 below is exact
 * in its first two products for |x / (pi/2)| < 2^20; beyond, callers use
 * libm (rod.c checks the angles outside the vectorised loops). */
#define RQ_TRIG_MAX 1.0e5

/* Nearest integer of |x| < 2^51 (ties to even) without a call: adding and
 * subtracting 1.5 2^52 rounds in the default rounding mode (IEEE double
 * arithmetic without -ffast-math, which would fold it away). */
RQM_INLINE double rq_rint(double x) {
  const double m = 6755399441055744.0;
  return (x + m) - m;
}

/* sin x and cos x for |x| <= RQ_TRIG_MAX. */
RQM_INLINE void rq_sincos(double x, double *s, double *c) {
  /* x = k pi/2 + r, |r| <= pi/4 (Cody-Waite: pi/2 = P1 + P2 + P3) */
  const double P1 = 1.57079632673412561417e+00, P2 = 6.07710050630396597660e-11,
               P3 = 2.02226624879595063154e-21;
  double k = rq_rint(x * 0.63661977236758134308);
  double r = ((x - k * P1) - k * P2) - k * P3, r2 = r * r;
  /* Taylor series to r^17 (sin) and r^16 (cos) */
  double ps = -1.0 / 355687428096000.0;
  ps = ps * r2 + 1.0 / 1307674368000.0;
  ps = ps * r2 - 1.0 / 6227020800.0;
  ps = ps * r2 + 1.0 / 39916800.0;
  ps = ps * r2 - 1.0 / 362880.0;
  ps = ps * r2 + 1.0 / 5040.0;
  ps = ps * r2 - 1.0 / 120.0;
  ps = ps * r2 + 1.0 / 6.0;
  double sr = r - r * r2 * ps;
  double pc = 1.0 / 20922789888000.0;
  pc = pc * r2 - 1.0 / 87178291200.0;
  pc = pc * r2 + 1.0 / 479001600.0;
  pc = pc * r2 - 1.0 / 3628800.0;
  pc = pc * r2 + 1.0 / 40320.0;
  pc = pc * r2 - 1.0 / 720.0;
  pc = pc * r2 + 1.0 / 24.0;
  double cr = 1.0 - 0.5 * r2 + r2 * r2 * pc;
  /* quadrant q = k mod 4: (sin, cos) = (s, c), (c, -s), (-s, -c), (-c, s) */
  double q = k - 4.0 * rq_rint(0.25 * k - 0.375); /* k mod 4 */
  *s = q == 0.0 ? sr : q == 1.0 ? cr : q == 2.0 ? -sr : -cr;
  *c = q == 0.0 ? cr : q == 1.0 ? -sr : q == 2.0 ? -cr : sr;
}

/* atan2(y, x) for (x, y) != (0, 0); 0 for (0, 0).  One division and one
 * square root: with t = min/max of |x|, |y| in [0, 1], atan t = pi/4 +
 * atan((t - 1)/(t + 1)) above tan(pi/8), and atan u = 2 atan v with
 * v = u / (1 + sqrt(1 + u^2)) = num / (den + sqrt(den^2 + num^2)) for
 * u = num / den, so |v| <= tan(pi/16). */
RQM_INLINE double rq_atan2(double y, double x) {
  const double pi = 3.14159265358979323846, tan_pi_8 = 0.41421356237309504880;
  double ax = fabs(x), ay = fabs(y);
  double mx = ax > ay ? ax : ay, mn = ax > ay ? ay : ax;
  double num = mn > tan_pi_8 * mx ? mn - mx : mn;
  double den = mn > tan_pi_8 * mx ? mn + mx : (mx > 0.0 ? mx : 1.0);
  double v = num / (den + sqrt(den * den + num * num)), v2 = v * v;
  double p = 1.0 / 25.0; /* Taylor series to v^25 */
  p = p * v2 - 1.0 / 23.0;
  p = p * v2 + 1.0 / 21.0;
  p = p * v2 - 1.0 / 19.0;
  p = p * v2 + 1.0 / 17.0;
  p = p * v2 - 1.0 / 15.0;
  p = p * v2 + 1.0 / 13.0;
  p = p * v2 - 1.0 / 11.0;
  p = p * v2 + 1.0 / 9.0;
  p = p * v2 - 1.0 / 7.0;
  p = p * v2 + 1.0 / 5.0;
  p = p * v2 - 1.0 / 3.0;
  double a = 2.0 * (v + v * v2 * p) + (mn > tan_pi_8 * mx ? 0.25 * pi : 0.0);
  a = ay > ax ? 0.5 * pi - a : a;
  a = x < 0.0 ? pi - a : a;
  return y < 0.0 ? -a : a;
}

#endif
