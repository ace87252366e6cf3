/* shim_dd_solve.c - the conformance suite of the preconditioners, driven by the
 * registries (rodnet_registry.h): every solver kind that takes a preconditioner
 * (tr-krylov, nox) with every preconditioner of the registry (auto = dd, factor,
 * local, gathered, dd, muelu, ifpack2, frosch, dd-amg) on lattices of `rodnet
 * generate` (honeycomb 4x4 with rigid and with elastic joints, octet 2x2x2 rigid,
 * uniaxial stretch 1e-3): converged, the preconditioner reported (an alias: the row
 * it stands for), and the same equilibrium as the exact trust region (tr-minres):
 * every vertex within 1e-7 of the largest displacement, energies within 1e-9
 * relative.  In the serial runtime the rows that need the MPI runtime (muelu,
 * ifpack2, frosch, dd-amg: RN_PC_MPI_RUNTIME) fail with a clear error (they need MPI
 * in Trilinos 13.2); run with the argument "mpi" and RODNET_MPI=1 they must work.
 * dd-amg (the DD with the multigrid coarse solve, which cannot prove H positive
 * definite) certifies the minimum by Lanczos on its coarse pencil (tr_krylov.cpp).
 * The same rows on 2 ranks: mpi_conformance (check_conformance_mpi.py). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rodnet.h"
#include "rodnet_registry.h"
#include "rodnet_solve.h"
#include "shim_lattices.h"

/* "mpi" as argument: the MPI runtime is in use (RODNET_MPI=1), MueLu must work. */
static int g_require_mpi = 0;
/* The solver kinds to run, by value: all, or the one a second argument names
 * (after "mpi" or "serial"). */
static int g_kinds[64];

static rn_scene *lattice(rn_context *ctx, rn_lattice_kind kind, int cells, int model) {
  return shim_lattice(ctx, kind, cells, model, 4, "shim_dd_solve_scene.json");
}

/* All vertices of all rods, concatenated. */
static double *vertices(const rn_network *net, size_t *count) {
  size_t n = 0, k = 0;
  for (int r = 0; r < rn_network_num_rods(net); ++r)
    n += 3 * (size_t)rn_network_rod_num_vertices(net, r);
  double *x = malloc(n * sizeof(double));
  for (int r = 0; r < rn_network_num_rods(net); ++r) {
    CHECK_STATUS(rn_network_rod_vertices(net, r, x + k), RN_OK);
    k += 3 * (size_t)rn_network_rod_num_vertices(net, r);
  }
  *count = n;
  return x;
}

/* The solve of kind with preconditioner row from the initial state against the
 * reference (x_ref, E_ref; umax the largest displacement). */
static void check_pair(rn_context *ctx, rn_network *net, const rn_state *initial,
                       const rn_solver_info *kind, const rn_preconditioner_info *row,
                       const double *x_ref, size_t n, double E_ref, double umax) {
  rn_solve_options opt;
  rn_solve_report rep;
  size_t m = 0;
  CHECK_STATUS(rn_network_state_restore(net, initial), RN_OK);
  rn_solve_options_default(&opt);
  opt.solver = kind->value;
  opt.preconditioner = row->value;
  const rn_status st = rn_solve(net, &opt, &rep);
  if ((row->flags & RN_PC_MPI_RUNTIME) && !g_require_mpi && st == RN_ERR_TRILINOS) {
    /* the serial runtime: MueLu, Ifpack2 and FROSch 13.2 cannot run there, a clear
     * error */
    printf("  %s %s: %s\n", kind->name, row->name, rn_context_last_error(ctx));
    CHECK(strstr(rn_context_last_error(ctx), "MPI runtime") != NULL);
    return;
  }
  CHECK_STATUS(st, RN_OK);
  double *x = vertices(net, &m), diff = 0.0;
  for (size_t i = 0; i < n; ++i) diff = fmax(diff, fabs(x[i] - x_ref[i]));
  printf("  %-9s %-8s -> %-8s its=%d krylov=%ld E=%.12e, max |x - x_ref| = %.2e\n",
         kind->name, row->name, rn_preconditioner_name(rep.preconditioner),
         rep.iterations, rep.krylov_iterations, rep.energy, diff);
  CHECK(rep.converged == 1);
  CHECK(rep.preconditioner == row->resolves_to);
  CHECK(diff <= 1e-7 * umax);
  CHECK_REL(rep.energy, E_ref, 1e-9);
  free(x);
}

static void check_case(rn_context *ctx, rn_lattice_kind kind, int cells, int model,
                       const char *name) {
  rn_scene *scene = lattice(ctx, kind, cells, model);
  rn_network *net = rn_scene_network(scene);
  rn_state *initial = NULL;
  rn_solve_options opt;
  rn_solve_report rep;
  size_t n = 0;
  CHECK_STATUS(rn_network_state_save(net, &initial), RN_OK);
  double *x0 = vertices(net, &n);
  rn_solve_options_default(&opt);
  CHECK_STATUS(rn_solve(net, &opt, &rep), RN_OK);
  CHECK(rep.converged == 1);
  const double E_ref = rep.energy;
  double *x_ref = vertices(net, &n), umax = 0.0;
  for (size_t i = 0; i < n; ++i) umax = fmax(umax, fabs(x_ref[i] - x0[i]));
  printf("%s: tr-minres its=%d krylov=%ld E=%.12e, largest displacement %.3e\n", name,
         rep.iterations, rep.krylov_iterations, rep.energy, umax);
  const rn_solver_info *k;
  for (size_t i = 0; (k = rn_solver_info_at(i)) != NULL; i++) {
    if (!(k->flags & RN_SOLVER_TAKES_PRECONDITIONER) || !g_kinds[i]) continue;
    const rn_preconditioner_info *row;
    for (size_t j = 0; (row = rn_preconditioner_info_at(j)) != NULL; j++)
      check_pair(ctx, net, initial, k, row, x_ref, n, E_ref, umax);
  }
  free(x0);
  free(x_ref);
  rn_state_destroy(&initial);
  rn_scene_destroy(&scene);
}

int main(int argc, char **argv) {
  rn_context *ctx = NULL;
  g_require_mpi = argc > 1 && strcmp(argv[1], "mpi") == 0;
  for (size_t i = 0; i < rn_solver_count() && i < 64; i++) g_kinds[i] = argc < 3;
  rn_solver_kind only = RN_SOLVER_TR_MINRES;
  if (argc > 2) {
    CHECK_STATUS(rn_solver_from_name(argv[2], &only), RN_OK);
    if ((size_t)only < 64) g_kinds[only] = 1;
  }
  CHECK_STATUS(rn_context_create(&ctx), RN_OK);
  check_case(ctx, RN_LATTICE_HONEYCOMB, 4, RN_JOINT_RIGID, "honeycomb 4x4 rigid");
  check_case(ctx, RN_LATTICE_HONEYCOMB, 4, RN_JOINT_ELASTIC, "honeycomb 4x4 elastic");
  check_case(ctx, RN_LATTICE_OCTET, 2, RN_JOINT_RIGID, "octet 2x2x2 rigid");
  rn_context_destroy(&ctx);
  return rn_test_finish("shim_dd_solve");
}
