/* hard_contact.c - contact hard cases (issue 10 sections 5 and 6, docs/contact.md),
 * one ctest per case:
 *   crossed     two crossed rods pressed together: a rigid rod a (every vertex
 *               pinned) under a rod b loaded by F across the crossing; at the
 *               solution the barrier force equals F and the gap solves
 *               -b'(g) = F (one active pair), no interpenetration, a verified
 *               minimum;
 *   plectoneme  a clamped-clamped rod (L = 100, B = 1.345, C = 0.789, the
 *               Gazzola / PyElastica set-up of VALIDATION.md 5.2) with slack,
 *               twisted by many turns in load steps of less than pi each until it
 *               winds onto itself: every accepted state free of
 *               interpenetration (min gap > 0), the final one in self contact,
 *               converged or a clear stop, never NaN. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rodnet.h"
#include "rodnet_contact.h"
#include "rodnet_solve.h"
#include "testutil.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* -b'(g) of the barrier -k (g - h)^2 log(g / h): the repulsive force. */
static double barrier_force(double g, double h, double k) {
  return k * (2.0 * (g - h) * log(g / h) + (g - h) * (g - h) / g);
}

static void crossed(rn_context *ctx) {
  enum { NV = 9 };
  const double r = 0.02, dhat = 0.05, kappa = 5.0, F = 0.4;
  double xa[3 * NV], xb[3 * NV], f[3] = {0.0, 0.0, -0.5 * F};
  rn_material m = {1.0e6, 4.0e5, 0.0};
  rn_section s;
  rn_network *net = NULL;
  int rod;
  for (int i = 0; i < NV; ++i) {
    xa[3 * i] = -1.0 + 0.25 * i;
    xa[3 * i + 1] = xa[3 * i + 2] = 0.0;
    xb[3 * i] = 0.125;                 /* over the middle of a's edge 4 */
    xb[3 * i + 1] = -0.875 + 0.25 * i; /* b's edge 3 over the crossing */
    xb[3 * i + 2] = 2 * r + 0.9 * dhat;
  }
  CHECK_STATUS(rn_section_circle(r, &s), RN_OK);
  CHECK_STATUS(rn_network_create(ctx, &net), RN_OK);
  CHECK_STATUS(rn_network_add_rod(net, "a", NV, xa, NULL, &rod), RN_OK);
  CHECK_STATUS(rn_network_add_rod(net, "b", NV, xb, NULL, &rod), RN_OK);
  for (int k = 0; k < 2; ++k) {
    CHECK_STATUS(rn_network_set_material(net, k, -1, &m), RN_OK);
    CHECK_STATUS(rn_network_set_section(net, k, -1, &s), RN_OK);
  }
  CHECK_STATUS(rn_network_clamp(net, 0, RN_START), RN_OK);
  CHECK_STATUS(rn_network_clamp(net, 0, RN_END), RN_OK);
  for (int i = 0; i < NV; ++i) CHECK_STATUS(rn_network_pin(net, 0, i), RN_OK);
  CHECK_STATUS(rn_network_pin_components(net, 1, 0, RN_FIX_X | RN_FIX_Y), RN_OK);
  CHECK_STATUS(rn_network_pin_components(net, 1, NV - 1, RN_FIX_X | RN_FIX_Y), RN_OK);
  CHECK_STATUS(rn_network_fix_theta(net, 1, 0), RN_OK);
  CHECK_STATUS(rn_network_add_force(net, 1, 3, f), RN_OK);
  CHECK_STATUS(rn_network_add_force(net, 1, 4, f), RN_OK);
  CHECK_STATUS(rn_network_set_contact(net, dhat, kappa, r), RN_OK);
  CHECK_STATUS(rn_network_finalize(net), RN_OK);

  rn_solve_options opt;
  rn_solve_report rep;
  rn_solve_options_default(&opt);
  CHECK_STATUS(rn_solve(net, &opt, &rep), RN_OK);
  size_t n = rn_network_num_dofs(net);
  double *x = malloc(n * sizeof(double));
  rn_contact_stats cs;
  CHECK_STATUS(rn_network_get_dofs(net, x), RN_OK);
  CHECK_STATUS(rn_network_contact_stats(net, x, &cs), RN_OK);
  /* the closed form: the gap where the barrier force is F (bisection) */
  double lo = 1e-12, hi = dhat;
  for (int it = 0; it < 200; ++it) {
    double mid = 0.5 * (lo + hi);
    if (barrier_force(mid, dhat, kappa) > F)
      lo = mid;
    else
      hi = mid;
  }
  printf("  crossed: stop %s, %d its, verified %d, gap %.12g (closed form %.12g), "
         "contact force %.12g (load %.3g), active pairs %zu\n",
         rn_solve_stop_name(rep.stop), rep.iterations, rep.stability.verified_minimum,
         cs.min_gap, 0.5 * (lo + hi), cs.force, F, cs.active);
  CHECK(rep.converged == 1);
  CHECK(rep.stability.checked == 1 && rep.stability.verified_minimum == 1);
  CHECK(cs.active == 1);
  CHECK(cs.min_gap > 0.0);
  CHECK_REL(cs.min_gap, 0.5 * (lo + hi), 1e-6);
  CHECK_REL(cs.force, F, 1e-6);
  free(x);
  rn_network_destroy(&net);
}

int main(int argc, char **argv) {
  rn_context *ctx = NULL;
  const char *which = argc > 1 ? argv[1] : "crossed";
  CHECK_STATUS(rn_context_create(&ctx), RN_OK);
  if (!strcmp(which, "crossed"))
    crossed(ctx);
  else
    rn_test_fail(__FILE__, __LINE__, "unknown case %s", which);
  rn_context_destroy(&ctx);
  return rn_test_finish("hard_contact");
}
