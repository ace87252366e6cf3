/* val_end_moment.c - clamped rod under an end moment M (VALIDATION.md 2.2,
 * 2.3): every turning angle phi obeys the discrete-exact relation
 * tan(phi/2) + tan(phi/2)^3 = M h / (2 B) (checked to round-off), the rod is an
 * arc of radius EI/M, and M = 2 pi EI / L closes it into a circle with the
 * tip error converging at second order.
 *
 * A round rod bent by a tip couple is laterally unstable well below the
 * closing moment (lateral-torsional buckling, M_cr ~ pi sqrt(EI GJ) / (2L)
 * for a cantilever), and the trust region leaves saddles, so the planar
 * solutions are tested on a section that is 100 times stiffer out of plane
 * and in torsion (an explicit section); in-plane it is the round rod's. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "testutil.h"
#include "valutil.h"

/* turning angle at interior vertex i of rod 0 */
static double turning(const double *x, int i) {
  double a[3], b[3];
  for (int k = 0; k < 3; ++k) {
    a[k] = x[3 * i + k] - x[3 * (i - 1) + k];
    b[k] = x[3 * (i + 1) + k] - x[3 * i + k];
  }
  double c[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                 a[0] * b[1] - a[1] * b[0]};
  return atan2(sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]),
               a[0] * b[0] + a[1] * b[1] + a[2] * b[2]);
}

static double solve_u(double r) { /* u + u^3 = r */
  double u = r;
  for (int i = 0; i < 100; ++i) u -= (u + u * u * u - r) / (1 + 3 * u * u);
  return u;
}

int main(void) {
  rn_context *ctx;
  CHECK_STATUS(rn_context_create(&ctx), RN_OK);
  rn_material m;
  rn_section s;
  CHECK_STATUS(rn_material_from_E_nu(1e7, 0.5, 0.0, &m), RN_OK);
  CHECK_STATUS(rn_section_circle(0.01, &s), RN_OK);
  s.I22 *= 100.0;
  s.J *= 100.0;
  double EI = m.E * s.I11, L = 1.0;

  /* (1) discrete exactness, ML/EI = pi/2, moment about +z (bends towards +y) */
  {
    int n = 12;
    double M[3] = {0, 0, 0.5 * M_PI * EI / L}, h = L / (n - 0.5);
    rn_network *net = val_clamped_rod(ctx, n, L, &m, &s, NULL, M, 1);
    val_solve(net, 0);
    double *x = malloc(sizeof(double) * 3 * (size_t)(n + 1));
    rn_network_rod_vertices(net, 0, x);
    double phi = 2 * atan(solve_u(M[2] * h / (2 * EI)));
    for (int i = 1; i < n; ++i) CHECK_NEAR(turning(x, i), phi, 1e-9);
    /* no force resultant: edges keep their rest length */
    double strain[64];
    rn_network_rod_strains(net, 0, strain, NULL, NULL);
    for (int j = 0; j < n; ++j) CHECK_NEAR(strain[j], 0.0, 1e-10);
    printf("discrete-exact end moment: phi = %.15f (expected %.15f)\n", turning(x, n / 2),
           phi);
    free(x);
    rn_network_destroy(&net);
  }

  /* (2) closing into a circle: M = 2 pi EI / L; tip returns to the clamp
   * point (x = 0) with the tangent of the clamp. */
  int ns[4] = {10, 20, 40, 80};
  const double table[4] = {1.21e-1, 3.30e-2, 8.35e-3, 2.08e-3};
  double hs[4], err[4];
  for (int i = 0; i < 4; ++i) {
    double M[3] = {0, 0, 2 * M_PI * EI / L}, tip[3];
    rn_network *net = val_clamped_rod(ctx, ns[i], L, &m, &s, NULL, M, 1);
    val_solve(net, 0);
    val_vertex(net, -1, tip);
    /* the continuum tip is the clamp point (0, 0, 0) */
    err[i] = sqrt(tip[0] * tip[0] + tip[1] * tip[1] + tip[2] * tip[2]) / L;
    hs[i] = L / (ns[i] - 0.5);
    printf("circle closure n=%d: tip error/L %.4e (planar DER table %.3e)\n", ns[i],
           err[i], table[i]);
    CHECK_REL(err[i], table[i], 0.02);
    rn_network_destroy(&net);
  }
  double order = rn_test_loglog_slope(3, hs + 1, err + 1);
  printf("circle closure: convergence order %.3f\n", order);
  CHECK(order > 1.85 && order < 2.15);
  rn_context_destroy(&ctx);
  return rn_test_finish("val_end_moment");
}
