/* shim_runtime.c - the solver runtime uses MPI exactly when the process belongs to
 * an MPI job (rodnet_solve.h, "runtime"), and the solution does not depend on it.
 *
 *   shim_runtime serial       no MPI expected (plain run, or RODNET_MPI=0)
 *   shim_runtime mpi          MPI expected (under a launcher, or RODNET_MPI=1)
 *   shim_runtime program-mpi  the program initialises MPI itself first: rodnet
 *                             uses it and leaves it initialised at finalize
 *
 * Each mode solves the same cantilever and prints its tip deflection with all
 * digits and compares it with the linear value, and checks the runtime's life
 * cycle: rn_runtime_finalize finalises MPI only if rodnet initialised it, and
 * after it rn_runtime_initialize and rn_solve return RN_ERR_STATE. */
#include <mpi.h>
#include <stdio.h>
#include <string.h>

#include "shim_rods.h"

static int mpi_initialized(void) {
  int flag = 0;
  MPI_Initialized(&flag);
  return flag;
}

static int mpi_finalized(void) {
  int flag = 0;
  MPI_Finalized(&flag);
  return flag;
}

/* Solves the 21-vertex cantilever under a small load; returns the tip deflection. */
static double solve_cantilever(rn_context *ctx) {
  const double P = 1e-3 * 3.0 * shim_cantilever_EI();
  rn_network *net = shim_cantilever(ctx, P);
  rn_solve_report rep;
  double xyz[3 * 21] = {0};
  CHECK_STATUS(rn_solve(net, NULL, &rep), RN_OK);
  CHECK(rep.converged == 1);
  CHECK_STATUS(rn_network_rod_vertices(net, 0, xyz), RN_OK);
  rn_network_destroy(&net);
  return -xyz[3 * 21 - 1];
}

int main(int argc, char **argv) {
  const char *mode = argc > 1 ? argv[1] : "";
  const int program_mpi = strcmp(mode, "program-mpi") == 0;
  const int expect_mpi = program_mpi || strcmp(mode, "mpi") == 0;
  if (!program_mpi && !expect_mpi && strcmp(mode, "serial") != 0) {
    fprintf(stderr, "usage: shim_runtime serial|mpi|program-mpi\n");
    return 2;
  }
  if (program_mpi) MPI_Init(&argc, &argv);
  rn_context *ctx = NULL;
  CHECK_STATUS(rn_context_create(&ctx), RN_OK);
  CHECK_STATUS(rn_runtime_initialize(&argc, &argv), RN_OK);
  CHECK_STATUS(rn_runtime_initialize(&argc, &argv), RN_OK); /* idempotent */
  CHECK(mpi_initialized() == expect_mpi);

  const double Lc = 1.0 - 0.5 / 20.0, w = 1e-3 * Lc * Lc * Lc;
  const double tip = solve_cantilever(ctx);
  printf("%s: MPI %s, tip deflection %.17g (linear %.6e)\n", mode,
         mpi_initialized() ? "initialised" : "not initialised", tip, w);
  CHECK_REL(tip, w, 2e-3);

  rn_runtime_finalize();
  rn_runtime_finalize(); /* a second call is a no-op */
  /* MPI is finalised by rodnet only if rodnet initialised it */
  CHECK(mpi_finalized() == (expect_mpi && !program_mpi));
  /* what rodnet finalised cannot come back */
  rn_solve_report rep;
  rn_network *net = shim_cantilever(ctx, 1e-3);
  CHECK_STATUS(rn_runtime_initialize(&argc, &argv), RN_ERR_STATE);
  CHECK_STATUS(rn_solve(net, NULL, &rep), RN_ERR_STATE);
  CHECK(rep.status == RN_ERR_STATE && rep.converged == 0);
  rn_network_destroy(&net);
  if (program_mpi) MPI_Finalize();
  rn_context_destroy(&ctx);
  return rn_test_finish("shim_runtime");
}
