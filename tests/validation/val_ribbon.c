/* val_ribbon.c - anisotropic sections under small tip loads: the deflection
 * of a cantilever is (L^3 / 3E) I^{-1} P in the material frame, so a ribbon
 * (width along d1, I11 = h w^3 / 12 >> I22 = w h^3 / 12) loaded obliquely
 * bends about its soft axis; an explicit section with I12 != 0 couples the
 * two directions.  Small loads, second-order convergence to the beam value. */
#include <math.h>
#include <stdio.h>

#include "testutil.h"
#include "valutil.h"

/* tip deflection (along y = d1, along z = d2) for a tip force (0, Py, Pz) */
static void tip_deflection(rn_context *ctx, int n, const rn_section *s, double Py,
                           double Pz, double d[2]) {
  rn_material m;
  CHECK_STATUS(rn_material_from_E_nu(1e7, 0.3, 0.0, &m), RN_OK);
  double f[3] = {0, Py, Pz}, tip[3];
  rn_network *net = val_clamped_rod(ctx, n, 1.0, &m, s, f, NULL, 1);
  val_solve(net, 0);
  val_vertex(net, -1, tip);
  d[0] = tip[1];
  d[1] = tip[2];
  rn_network_destroy(&net);
}

int main(void) {
  rn_context *ctx;
  CHECK_STATUS(rn_context_create(&ctx), RN_OK);
  double E = 1e7, L = 1.0;
  rn_section rib, gen;
  CHECK_STATUS(rn_section_rectangle(0.02, 0.002, &rib), RN_OK); /* w along d1 = y */
  /* explicit coupled section */
  gen = (rn_section){.A = 3e-5, .I11 = 4e-10, .I22 = 1e-10, .I12 = 1.2e-10, .J = 2e-10};
  const rn_section *secs[2] = {&rib, &gen};
  const char *names[2] = {"ribbon", "coupled"};
  for (int c = 0; c < 2; ++c) {
    const rn_section *s = secs[c];
    /* small oblique load: alpha ~ 1e-5 on the soft axis */
    double Imin =
        0.5 * (s->I11 + s->I22) - sqrt(0.25 * pow(s->I11 - s->I22, 2) + s->I12 * s->I12);
    double P = 1e-5 * E * Imin / (L * L), Py = P, Pz = P;
    /* beam theory: d = L^3/(3E) I^{-1} P */
    double det = s->I11 * s->I22 - s->I12 * s->I12;
    double ey = L * L * L / (3 * E) * (s->I22 * Py - s->I12 * Pz) / det;
    double ez = L * L * L / (3 * E) * (-s->I12 * Py + s->I11 * Pz) / det;
    int ns[3] = {20, 40, 80};
    double hs[3], err[3], d[2];
    for (int i = 0; i < 3; ++i) {
      tip_deflection(ctx, ns[i], s, Py, Pz, d);
      hs[i] = L / (ns[i] - 0.5);
      err[i] = sqrt(pow(d[0] - ey, 2) + pow(d[1] - ez, 2)) / sqrt(ey * ey + ez * ez);
      printf("%s n=%d: tip (%.6e, %.6e) beam (%.6e, %.6e) rel err %.3e\n", names[c],
             ns[i], d[0], d[1], ey, ez, err[i]);
    }
    double order = rn_test_loglog_slope(3, hs, err);
    printf("%s: convergence order %.3f\n", names[c], order);
    CHECK(order > 1.9 && order < 2.1);
    CHECK(err[2] < 2e-4);
    if (c == 0) {
      /* the ribbon bends about its soft axis: deflection along d2 dominates
       * by I11 / I22 = (w / h)^2 = 100 */
      CHECK_REL(d[1] / d[0], rib.I11 / rib.I22, 1e-3);
    }
  }
  rn_context_destroy(&ctx);
  return rn_test_finish("val_ribbon");
}
