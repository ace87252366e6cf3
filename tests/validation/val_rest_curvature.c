/* val_rest_curvature.c - a free rod with rest curvature taken from a
 * discrete arc (VALIDATION.md 4, 7.1): starting straight, it relaxes to the
 * polygon arc exactly (zero energy, every turning angle equal to the rest
 * one), whatever the (anisotropic) stiffness and whichever axis the rest
 * curvature is about; with rest twist too it becomes a discrete helix of
 * constant curvature and torsion. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "testutil.h"
#include "valutil.h"

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

static void run(rn_context *ctx, double k1, double k2, double tw, const rn_section *s) {
  int n = 30, nv = n + 1;
  double h = 1.0 / n;
  double *xyz = malloc(sizeof(double) * 3 * (size_t)nv);
  double *kap = malloc(sizeof(double) * 2 * (size_t)(nv - 2));
  double *tau = malloc(sizeof(double) * (size_t)(nv - 2));
  for (int i = 0; i < nv; ++i) {
    xyz[3 * i] = i * h;
    xyz[3 * i + 1] = 0;
    xyz[3 * i + 2] = 0;
  }
  for (int i = 0; i < nv - 2; ++i) {
    kap[2 * i] = k1;
    kap[2 * i + 1] = k2;
    tau[i] = tw;
  }
  rn_material m;
  CHECK_STATUS(rn_material_from_E_nu(1e6, 0.4, 0.0, &m), RN_OK);
  rn_network *net;
  int rod;
  double d1[3] = {0, 0.6, 0.8};
  CHECK_STATUS(rn_network_create(ctx, &net), RN_OK);
  CHECK_STATUS(rn_network_add_rod(net, "r", nv, xyz, d1, &rod), RN_OK);
  CHECK_STATUS(rn_network_set_material(net, rod, -1, &m), RN_OK);
  CHECK_STATUS(rn_network_set_section(net, rod, -1, s), RN_OK);
  CHECK_STATUS(rn_network_set_rest_curvature(net, rod, kap), RN_OK);
  CHECK_STATUS(rn_network_set_rest_twist(net, rod, tau), RN_OK);
  CHECK_STATUS(rn_network_finalize(net), RN_OK);
  double E0;
  size_t nd = rn_network_num_dofs(net);
  double *x = malloc(sizeof(double) * nd);
  rn_network_get_dofs(net, x);
  rn_network_energy(net, x, &E0);
  val_solve(net, 0);
  rn_network_get_dofs(net, x);
  double E;
  rn_network_energy(net, x, &E);
  rn_network_rod_vertices(net, rod, xyz);
  /* Planar arc: every turning angle is the rest one, |kb| = 2 tan(phi/2) =
   * |kappa|.  With rest twist the material curvature is measured in the
   * averaged (twisted) frames, so only uniformity is asserted. */
  double kk = sqrt(k1 * k1 + k2 * k2), phi = 2 * atan(kk / 2);
  if (tw != 0.0) phi = turning(xyz, nv / 2);
  double worst = 0;
  for (int i = 1; i < nv - 1; ++i) worst = fmax(worst, fabs(turning(xyz, i) - phi));
  double kap_out[2 * 64], tau_out[64];
  rn_network_rod_strains(net, rod, NULL, kap_out, tau_out);
  double wk = 0, wt = 0;
  for (int i = 0; i < nv - 2; ++i) {
    wk = fmax(wk, fmax(fabs(kap_out[2 * i] - k1), fabs(kap_out[2 * i + 1] - k2)));
    wt = fmax(wt, fabs(tau_out[i] - tw));
  }
  printf("rest curvature (%.3f, %.3f), twist %.3f: E0 = %.3e -> E = %.3e, worst "
         "turning-angle "
         "error %.2e, curvature %.2e, twist %.2e\n",
         k1, k2, tw, E0, E, worst, wk, wt);
  CHECK(E <= 1e-18 * E0);
  CHECK(worst < 1e-8);
  CHECK(wk < 1e-8);
  CHECK(wt < 1e-8);
  free(x);
  free(xyz);
  free(kap);
  free(tau);
  rn_network_destroy(&net);
}

int main(void) {
  rn_context *ctx;
  CHECK_STATUS(rn_context_create(&ctx), RN_OK);
  rn_section ribbon, round;
  CHECK_STATUS(rn_section_rectangle(0.02, 0.004, &ribbon), RN_OK);
  CHECK_STATUS(rn_section_circle(0.005, &round), RN_OK);
  run(ctx, 0.1, 0.0, 0.0, &ribbon); /* about the stiff axis */
  run(ctx, 0.0, 0.1, 0.0, &ribbon); /* about the soft axis */
  run(ctx, 0.06, -0.08, 0.0, &round);
  run(ctx, 0.08, 0.0, 0.03, &ribbon); /* helix */
  rn_context_destroy(&ctx);
  return rn_test_finish("val_rest_curvature");
}
