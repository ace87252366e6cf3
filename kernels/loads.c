/* loads.c - dead forces: E = -f . x (linear, zero Hessian). */
#include "rnk.h"

double rnk_force_energy(const double x[3], const double f[3]) {
  return -(f[0] * x[0] + f[1] * x[1] + f[2] * x[2]);
}

void rnk_force_grad(const double f[3], double g[3]) {
  g[0] = -f[0];
  g[1] = -f[1];
  g[2] = -f[2];
}
