/* val_buckling.c - Euler buckling of a clamped-free column (VALIDATION.md
 * 3.1, 3.2): the lowest eigenvalue of the reduced Hessian at the compressed
 * straight equilibrium crosses zero at the discrete critical load, which
 * matches the table P_n / P_cr (mid-edge clamp) after the extensibility
 * correction P (1 - P / EA) = P_n, and converges to pi^2 EI / (4 L^2) at
 * second order. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "testutil.h"
#include "valutil.h"

/* lambda_min of the Hessian at the straight state compressed by P along x
 * (all edges shortened by P / EA: the exact straight equilibrium). */
static double lambda_min_at(rn_context *ctx, int n, double L, const rn_material *m,
                            const rn_section *s, double P) {
  double f[3] = {-P, 0, 0};
  rn_network *net = val_clamped_rod(ctx, n, L, m, s, f, NULL, 1);
  size_t nd = rn_network_num_dofs(net);
  double *x = malloc(sizeof(double) * nd), *g = malloc(sizeof(double) * nd);
  rn_network_get_dofs(net, x);
  /* Reduced layout (rodnet.h): free DOFs in full order, i.e. theta^1, x_2,
   * theta^2, x_3, ..., theta^{n-1}, x_n; set the x coordinates. */
  double h = L / (n - 0.5), eps = P / (m->E * s->A), x1 = 0.5 * h;
  size_t k = 1; /* skip theta^1 */
  for (int v = 2; v <= n; ++v) {
    x[k] = x1 + (v - 1) * h * (1 - eps);
    k += 3;
    if (v < n) k += 1;
  }
  CHECK(k == nd);
  rn_network_set_dofs(net, x);
  double E;
  rn_network_gradient(net, x, &E, g);
  double gn = 0;
  for (size_t i = 0; i < nd; ++i) gn += g[i] * g[i];
  CHECK(sqrt(gn) < 1e-9 * P + 1e-12);
  double lam = 0;
  CHECK_STATUS(rn_hessian_min_eigenvalue(net, &lam), RN_OK);
  free(x);
  free(g);
  rn_network_destroy(&net);
  return lam;
}

int main(void) {
  rn_context *ctx;
  CHECK_STATUS(rn_context_create(&ctx), RN_OK);
  rn_material m;
  rn_section s;
  CHECK_STATUS(rn_material_from_E_nu(1e7, 0.3, 0.0, &m), RN_OK);
  CHECK_STATUS(rn_section_circle(0.01, &s), RN_OK);
  double EI = m.E * s.I11, EA = m.E * s.A, L = 1.0, PE = M_PI * M_PI * EI / (4 * L * L);
  int ns[3] = {8, 16, 32};
  const double ratio[3] = {0.9963499316, 0.9991444479, 0.9997927944};
  double hs[3], err[3];
  for (int i = 0; i < 3; ++i) {
    int n = ns[i];
    double lo = 0.9 * PE, hi = 1.1 * PE;
    CHECK(lambda_min_at(ctx, n, L, &m, &s, lo) > 0);
    CHECK(lambda_min_at(ctx, n, L, &m, &s, hi) < 0);
    for (int it = 0; it < 50 && hi - lo > 1e-11 * PE; ++it) {
      double mid = 0.5 * (lo + hi);
      if (lambda_min_at(ctx, n, L, &m, &s, mid) > 0)
        lo = mid;
      else
        hi = mid;
    }
    double Pc = 0.5 * (lo + hi);
    double Pn = ratio[i] * PE;                                /* inextensible discrete */
    double expected = 0.5 * EA * (1 - sqrt(1 - 4 * Pn / EA)); /* P (1 - P/EA) = Pn */
    printf("clamped-free n=%d: P_cr/P_E = %.10f, inextensible table %.10f, with "
           "extensibility %.10f\n",
           n, Pc / PE, ratio[i], expected / PE);
    CHECK_REL(Pc, expected, 2e-9);
    hs[i] = L / (n - 0.5);
    err[i] = fabs(Pc * (1 - Pc / EA) - PE) / PE;
  }
  double order = rn_test_loglog_slope(3, hs, err);
  printf("buckling load convergence order %.3f\n", order);
  CHECK(order > 1.9 && order < 2.1);
  rn_context_destroy(&ctx);
  return rn_test_finish("val_buckling");
}
