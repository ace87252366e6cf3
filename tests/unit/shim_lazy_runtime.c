/* shim_lazy_runtime.c - rn_solve without rn_runtime_initialize: the first solve
 * initialises the runtime itself (Kokkos; MPI too under a launcher) and finalises
 * it at exit.  Also run under mpirun with one rank (ctest shim_lazy_runtime_mpirun;
 * which mode is chosen when is checked by shim_runtime).  A small-load
 * cantilever must converge twice in a row (second solve reuses the runtime) with
 * the tip deflection within 0.2 % of the linear value P Lc^3 / (3 E I), where
 * Lc = L - h/2 is the length from the clamp (the midpoint of the clamped edge,
 * see rodnet.h) to the tip. */
#include <math.h>
#include <stdio.h>

#include "shim_rods.h"

int main(void) {
  rn_context *ctx = NULL;
  rn_solve_report rep;
  const double P = 1e-3 * 3.0 * shim_cantilever_EI(); /* P L^3 / (3 E I) = 1e-3 */
  const double Lc = 1.0 - 0.5 / 20.0, w = 1e-3 * Lc * Lc * Lc;
  CHECK_STATUS(rn_context_create(&ctx), RN_OK);
  for (int k = 0; k < 2; ++k) {
    rn_network *net = shim_cantilever(ctx, P);
    double xyz[3 * 21];
    CHECK_STATUS(rn_solve(net, NULL, &rep), RN_OK);
    CHECK(rep.converged == 1);
    CHECK_STATUS(rn_network_rod_vertices(net, 0, xyz), RN_OK);
    printf("solve %d: its=%d, tip deflection %.6e (linear %.6e)\n", k, rep.iterations,
           -xyz[3 * 21 - 1], w);
    CHECK_REL(-xyz[3 * 21 - 1], w, 2e-3);
    rn_network_destroy(&net);
  }
  rn_context_destroy(&ctx);
  return rn_test_finish("shim_lazy_runtime");
}
