/* shim_newton_counts.c - Newton iteration counts of issue 8's problems with the
 * default solver (tr-minres) and tr-krylov, asserted as counts (never times):
 * the scenes of problems/scenes/ (argv[1] is that folder), each solved from its
 * initial state; the bound is the target where it is met (cantilever
 * alpha = 5: 12, arch P = 4: 15) and otherwise the count measured when the watchdog
 * went in, plus a margin of about 10 % (arch P = 8: 95 and 76; docs/solvers.md). */
#include <stdio.h>
#include <string.h>

#include "rodnet_solve.h"
#include "scene.h"
#include "testutil.h"

typedef struct count_case {
  const char *scene;
  rn_solver_kind solver;
  int max_iterations; /* the bound asserted */
} count_case;

static void run(rn_context *ctx, const char *dir, const count_case *c) {
  char path[1024];
  rn_scene *s = NULL;
  rn_solve_options opt;
  rn_solve_report rep;
  snprintf(path, sizeof path, "%s/%s", dir, c->scene);
  CHECK_STATUS(rn_scene_load(ctx, path, &s), RN_OK);
  if (!s) return;
  rn_solve_options_default(&opt);
  rn_scene_apply_solver(s, &opt);
  opt.solver = c->solver;
  CHECK_STATUS(rn_solve(rn_scene_network(s), &opt, &rep), RN_OK);
  printf("%-24s %-10s converged %d (stop %s), %3d Newton iterations (bound %d)\n",
         c->scene, rn_solver_name(c->solver), rep.converged, rn_solve_stop_name(rep.stop),
         rep.iterations, c->max_iterations);
  CHECK(rep.converged == 1);
  CHECK(rep.iterations <= c->max_iterations);
  rn_scene_destroy(&s);
}

int main(int argc, char **argv) {
  static const count_case cases[] = {
      {"cantilever.json", RN_SOLVER_TR_MINRES, 12},
      {"cantilever.json", RN_SOLVER_TR_KRYLOV, 12},
      {"cantilever_3201.json", RN_SOLVER_TR_MINRES, 12},
      {"end_moment_circle.json", RN_SOLVER_TR_MINRES, 16},
      {"end_moment_circle.json", RN_SOLVER_TR_KRYLOV, 16},
      {"arch_p4.json", RN_SOLVER_TR_MINRES, 15},
      {"arch_p4.json", RN_SOLVER_TR_KRYLOV, 15},
      {"arch_p8.json", RN_SOLVER_TR_MINRES, 105},
      {"arch_p8.json", RN_SOLVER_TR_KRYLOV, 85},
  };
  rn_context *ctx = NULL;
  if (argc < 2) {
    fprintf(stderr, "usage: %s SCENES_DIR\n", argv[0]);
    return 2;
  }
  CHECK_STATUS(rn_runtime_initialize(&argc, &argv), RN_OK);
  CHECK_STATUS(rn_context_create(&ctx), RN_OK);
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i)
    run(ctx, argv[1], &cases[i]);
  rn_context_destroy(&ctx);
  rn_runtime_finalize();
  return rn_test_finish("shim_newton_counts");
}
