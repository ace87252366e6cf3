/* cli_check.c - `rodnet check SCENE.json`: the derivative self-test. */
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "cli/cli.h"
#include "scene/scene.h"

static const char check_help[] =
    "Usage: rodnet check SCENE.json [options]\n"
    "\n"
    "Derivative self-test of the scene's energy: the gradient and the\n"
    "Hessian-vector product are compared with central differences over a sweep\n"
    "of step sizes (reporting the worst relative error and the observed order,\n"
    "2 for a correct derivative), the assembled Hessian is checked for symmetry\n"
    "and against the Hessian-vector product.  Tested at the scene's initial\n"
    "state and at random perturbations of it.\n"
    "\n"
    "Options:\n"
    "      --random N    number of random perturbed states besides the initial\n"
    "                    one (default 3)\n"
    "      --perturb P   relative size of the random perturbations (default 1e-2)\n"
    "      --seed S      seed of the random perturbations (default 1)\n"
    "      --tol X       largest accepted relative error (default 1e-5; the\n"
    "                    round-off floor of the differences grows with the\n"
    "                    scene size: long rods may need more).  A finite-\n"
    "                    difference test also passes when its error, extrapolated\n"
    "                    to h -> 0 (Richardson), is within X: second-order\n"
    "                    truncation, not a wrong derivative\n"
    "  -h, --help        show this help\n"
    "\n"
    "Exit status: 0 all errors within the tolerance, 1 some error above it,\n"
    "2 usage error, 3 bad scene, 4 internal error.\n";

typedef struct check_args {
  const char *scene;
  int random, seed;
  double perturb, tol;
  int has_seed, has_perturb; /* given */
} check_args;

/* 1 if argv[*i] was a value option (rc: 0 or an exit status). */
static int parse_value_option(int argc, char **argv, int *i, check_args *a, int *rc) {
  const char *v = NULL;
  int m;
  *rc = 0;
  if ((m = rn_cli_option_value("check", argc, argv, i, "--random", NULL, &v)) > 0)
    *rc = rn_cli_parse_int("check", "--random", v, 0, 1000000L, &a->random);
  else if (!m &&
           (m = rn_cli_option_value("check", argc, argv, i, "--seed", NULL, &v)) > 0) {
    *rc = rn_cli_parse_int("check", "--seed", v, 0, 2147483647L, &a->seed);
    a->has_seed = 1;
  } else if (!m && (m = rn_cli_option_value("check", argc, argv, i, "--perturb", NULL,
                                            &v)) > 0) {
    *rc = rn_cli_parse_double("check", "--perturb", v, 0.0, &a->perturb);
    a->has_perturb = 1;
  } else if (!m &&
             (m = rn_cli_option_value("check", argc, argv, i, "--tol", NULL, &v)) > 0)
    *rc = rn_cli_parse_double("check", "--tol", v, 0.0, &a->tol);
  if (m < 0) *rc = RN_EXIT_USAGE;
  return m != 0;
}

/* 0 to go on, -1 help shown, otherwise an exit status. */
static int parse_check_args(int argc, char **argv, check_args *a) {
  memset(a, 0, sizeof *a);
  a->random = 3;
  a->seed = 1;
  a->perturb = 1e-2;
  a->tol = 1e-5;
  for (int i = 1; i < argc; i++) {
    const char *s = argv[i];
    int rc = 0;
    if (strcmp(s, "-h") == 0 || strcmp(s, "--help") == 0) {
      fputs(check_help, stdout);
      return -1;
    }
    if (parse_value_option(argc, argv, &i, a, &rc)) {
      if (rc) return rc;
    } else if (s[0] == '-' && s[1] != '\0')
      return rn_cli_usage_error("check", "unknown option '%s'", s);
    else if (a->scene)
      return rn_cli_usage_error("check", "more than one scene given ('%s' and '%s')",
                                a->scene, s);
    else
      a->scene = s;
  }
  static const char *const valued[] = {"--random", "--seed", "--perturb", "--tol", NULL};
  int rc = rn_cli_check_repeats("check", argc, argv, valued);
  if (rc) return rc;
  if (!a->scene) return rn_cli_usage_error("check", "missing the scene file");
  /* check writes no file; the random states' options need random states */
  if (a->random == 0 && (a->has_seed || a->has_perturb))
    return rn_cli_usage_error("check",
                              "%s applies to the random states: with --random 0 "
                              "only the initial state is tested",
                              a->has_seed ? "--seed" : "--perturb");
  return 0;
}

static int report(const check_args *a, const rn_check_report *r) {
  struct {
    const char *what;
    double err, order, extrapolated;
    int fd;
  } rows[] = {{"gradient vs central differences", r->grad_rel_err, r->grad_order,
               r->grad_extrapolated_err, 1},
              {"HVP vs central differences", r->hvp_rel_err, r->hvp_order,
               r->hvp_extrapolated_err, 1},
              {"Hessian symmetry", r->hess_sym_err, 0, 0, 0},
              {"assembled Hessian vs HVP", r->hess_hvp_err, 0, 0, 0}};
  int ok = 1, truncation = 0;
  for (size_t i = 0; i < sizeof rows / sizeof rows[0]; i++) {
    int pass = rows[i].fd ? rn_check_fd_passes(rows[i].err, rows[i].extrapolated, a->tol)
                          : rows[i].err <= a->tol; /* NaN fails */
    int trunc = pass && !(rows[i].err <= a->tol);
    ok &= pass;
    truncation |= trunc;
    printf("  %-33s rel. error %10.3e", rows[i].what, rows[i].err);
    if (rows[i].fd)
      printf("   order %5.2f   extrapolated %9.3e", rows[i].order, rows[i].extrapolated);
    else
      printf("              %23s", "");
    printf("   %s\n", pass ? (trunc ? "ok (truncation)" : "ok") : "FAILED");
  }
  printf("%s: worst relative error %s the tolerance %g\n", ok ? "PASS" : "FAIL",
         ok ? (truncation ? "within (or truncation that extrapolates within)" : "within")
            : "above",
         a->tol);
  return ok ? RN_EXIT_OK : RN_EXIT_NOT_CONVERGED;
}

int rn_cli_check(int argc, char **argv) {
  check_args a;
  int rc = parse_check_args(argc, argv, &a);
  if (rc) return rc < 0 ? RN_EXIT_OK : rc;
  rn_context *ctx = NULL;
  if (rn_context_create(&ctx) != RN_OK) {
    fprintf(stderr, "rodnet check: out of memory\n");
    return RN_EXIT_INTERNAL;
  }
  rn_scene *scene = NULL;
  rn_status st = rn_scene_load(ctx, a.scene, &scene);
  if (st) {
    fprintf(stderr, "%s\n", rn_context_last_error(ctx));
    rc = rn_cli_load_exit_code(st);
  } else {
    rn_network *net = rn_scene_network(scene);
    rn_check_report r;
    memset(&r, 0, sizeof r);
    st = rn_network_check_derivatives(net, NULL, a.random, a.perturb, (uint64_t)a.seed,
                                      &r);
    if (st) {
      fprintf(stderr, "rodnet check: %s: %s\n", a.scene, rn_context_last_error(ctx));
      rc = RN_EXIT_INTERNAL;
    } else {
      printf("rodnet check: %s (%d rods, %ld vertices, %zu free DOFs, %d states)\n",
             a.scene, rn_network_num_rods(net), rn_scene_num_vertices(scene),
             rn_network_num_dofs(net), r.n_points);
      rc = report(&a, &r);
    }
  }
  rn_scene_destroy(&scene);
  rn_context_destroy(&ctx);
  return rc;
}
