/* vec3.h - the small 3-vector helpers of the problems layer (scene reader,
 * writers, generators): one copy instead of one per file. */
#ifndef RN_PROBLEMS_VEC3_H
#define RN_PROBLEMS_VEC3_H

#include <math.h>

static inline double rn_dot3(const double *a, const double *b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* |q - p| */
static inline double rn_dist3(const double *p, const double *q) {
  double d[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]};
  return sqrt(rn_dot3(d, d));
}

#endif
