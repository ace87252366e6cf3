/* cli_solve.c - `rodnet solve SCENE.json -o RESULT.json [options]`. */
#define _XOPEN_SOURCE 700 /* realpath, stat */

#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "io/atomic_file.h"
#include "cli/cli.h"
#include "cli/cli_dist.h"
#include "cli/cli_registry.h"
#include "scene/result_json.h"
#include "rodnet_couple.h"
#include "rodnet_registry.h"
#include "rodnet_solve.h"
#include "scene/scene.h"
#include "scene/vtk.h"

static const char solve_help[] =
    "Usage: rodnet solve SCENE.json -o RESULT.json [options]\n"
    "\n"
    "Compute the static equilibrium of the scene (format: docs/scene-format.md)\n"
    "and write the result.  One progress line per Newton iteration goes to\n"
    "stderr (iteration, energy, gradient norm, trust radius, Krylov iterations,\n"
    "seconds, load factor); a summary goes to stdout at the end.\n"
    "\n"
    "Options:\n"
    "  -o, --output FILE   result JSON to write (required): status, energy,\n"
    "                      gradient norm, iterations, time, per rod its vertices\n"
    "                      and material angles, per joint its position and\n"
    "                      rotation matrix (docs/cli.md)\n"
    "      --vtk FILE      also write the solution as a VTK .vtu file (ParaView):\n"
    "                      displacement, curvature, twist, theta, strain, directors,\n"
    "                      moments, energy density; joints as points with their\n"
    "                      rotation\n";
/* then the --solver and --preconditioner rows (rn_cli_print_solver_help), then: */
static const char solve_help_mid[] =
    "      --factorization NAME  Cholesky factorisation of the shifted Hessian\n"
    "                      (also spelt --factorisation):\n"
    "                      auto (default: banded for rods, sparse for networks),\n"
    "                      banded (LAPACK), sparse (rodnet's supernodal, METIS\n"
    "                      ordering), cholmod (SuiteSparse CHOLMOD, the library\n"
    "                      reference for sparse)\n"
    "      --max-iter N    Newton iterations allowed per load step (default 200)\n"
    "      --gtol X        equilibrium test: stop when the largest force (moment)\n"
    "                      residual is below X times the force (moment) scale of\n"
    "                      the applied loads and support reactions, or at the\n"
    "                      round-off floor (default 1e-9; docs/solvers.md)\n"
    "      --load-steps N  apply the loads in N equal continuation steps (default:\n"
    "                      one step, split automatically when a full step fails)\n"
    "      --no-predictor  start each load step where the last one converged (default:\n"
    "                      from the linearised load-increment prediction, kept if\n"
    "                      it lowers the energy; docs/solvers.md)\n";
/* (two strings: one would exceed the 4095 characters C99 guarantees) */
static const char solve_help_tail[] =
    "      --no-stability  skip the stability check of the result (the lowest\n"
    "                      Hessian eigenvalues; docs/solvers.md)\n"
    "      --stability-method M  how the check computes them: auto (default:\n"
    "                      Cholesky when affordable, else LOBPCG), cholesky, lobpcg\n"
    "  -q, --quiet         no progress lines\n"
    "  -h, --help          show this help\n"
    "\n"
    "Options given here override the scene's \"solver\" block.  Output files are\n"
    "written completely or not at all.\n"
    "Exit status: 0 converged, 1 stopped without converging (the result is still\n"
    "written, with the reason as its status), 2 usage error, 3 bad scene or\n"
    "unwritable output path, 4 solver error or failed write.\n";

typedef struct solve_args {
  const char *scene, *output, *vtk, *solver, *factorization, *preconditioner;
  const char *stability_method;
  int quiet, max_iter, load_steps, has_max_iter, has_load_steps, has_gtol, no_predictor;
  int no_stability;
  double gtol;
} solve_args;

/* 0 to go on, otherwise an exit status (-1: help shown, exit 0). */
static int parse_value_option(int argc, char **argv, int *i, solve_args *a, int *rc) {
  const char *v = NULL;
  int m;
  *rc = 0;
  if ((m = rn_cli_option_value("solve", argc, argv, i, "--output", "-o", &v)) != 0)
    a->output = v;
  else if ((m = rn_cli_option_value("solve", argc, argv, i, "--vtk", NULL, &v)) != 0)
    a->vtk = v;
  else if ((m = rn_cli_option_value("solve", argc, argv, i, "--solver", NULL, &v)) != 0)
    a->solver = v;
  else if ((m = rn_cli_option_value("solve", argc, argv, i, "--factorization", NULL,
                                    &v)) != 0 ||
           (m = rn_cli_option_value("solve", argc, argv, i, "--factorisation", NULL,
                                    &v)) != 0) /* both spellings */
    a->factorization = v;
  else if ((m = rn_cli_option_value("solve", argc, argv, i, "--preconditioner", NULL,
                                    &v)) != 0)
    a->preconditioner = v;
  else if ((m = rn_cli_option_value("solve", argc, argv, i, "--stability-method", NULL,
                                    &v)) != 0)
    a->stability_method = v;
  else if ((m = rn_cli_option_value("solve", argc, argv, i, "--max-iter", NULL, &v)) !=
           0) {
    if (m > 0)
      *rc = rn_cli_parse_int("solve", "--max-iter", v, 1, 2147483647L, &a->max_iter);
    a->has_max_iter = 1;
  } else if ((m = rn_cli_option_value("solve", argc, argv, i, "--gtol", NULL, &v)) != 0) {
    if (m > 0) *rc = rn_cli_parse_double("solve", "--gtol", v, 0.0, &a->gtol);
    a->has_gtol = 1;
  } else if ((m = rn_cli_option_value("solve", argc, argv, i, "--load-steps", NULL,
                                      &v)) != 0) {
    if (m > 0)
      *rc = rn_cli_parse_int("solve", "--load-steps", v, 1, 2147483647L, &a->load_steps);
    a->has_load_steps = 1;
  }
  if (m < 0) *rc = RN_EXIT_USAGE;
  return m != 0;
}

/* 1 if path ends in ".vtu" (any case). */
static int has_vtu_extension(const char *path) {
  size_t n = strlen(path);
  if (n < 5 || path[n - 5] == '/') return 0;
  const char *e = path + n - 4;
  return e[0] == '.' && tolower((unsigned char)e[1]) == 'v' &&
         tolower((unsigned char)e[2]) == 't' && tolower((unsigned char)e[3]) == 'u';
}

/* The output paths: never the scene itself, never each other, and the VTK
 * file named for the format written (XML unstructured grid, .vtu). */
static int check_output_paths(const solve_args *a) {
  const rn_cli_file files[] = {{"the scene file", a->scene, NULL, RN_CLI_IN},
                               {"-o", a->output, NULL, RN_CLI_OUT},
                               {"--vtk", a->vtk, NULL, RN_CLI_OUT}};
  int rc = rn_cli_check_files("solve", files, 3);
  if (rc || !a->vtk) return rc;
  if (!has_vtu_extension(a->vtk))
    return rn_cli_usage_error("solve",
                              "--vtk %s: rodnet writes VTK XML unstructured grids, "
                              "name the file with the extension .vtu",
                              a->vtk);
  return 0;
}

static int parse_solve_args(int argc, char **argv, solve_args *a) {
  static const char *const valued[] = {
      "--output|-o",      "--vtk",
      "--solver",         "--factorization|--factorisation",
      "--preconditioner", "--stability-method",
      "--max-iter",       "--gtol",
      "--load-steps",     NULL};
  memset(a, 0, sizeof *a);
  for (int i = 1; i < argc; i++) {
    const char *s = argv[i];
    int rc = 0;
    if (strcmp(s, "-h") == 0 || strcmp(s, "--help") == 0) {
      fputs(solve_help, stdout);
      rn_cli_print_solver_help(stdout);
      fputs(solve_help_mid, stdout);
      fputs(solve_help_tail, stdout);
      return -1;
    }
    if (strcmp(s, "-q") == 0 || strcmp(s, "--quiet") == 0)
      a->quiet = 1;
    else if (strcmp(s, "--no-predictor") == 0)
      a->no_predictor = 1;
    else if (strcmp(s, "--no-stability") == 0)
      a->no_stability = 1;
    else if (parse_value_option(argc, argv, &i, a, &rc)) {
      if (rc) return rc;
    } else if (s[0] == '-' && s[1] != '\0')
      return rn_cli_usage_error("solve", "unknown option '%s'", s);
    else if (a->scene)
      return rn_cli_usage_error("solve", "more than one scene given ('%s' and '%s')",
                                a->scene, s);
    else
      a->scene = s;
  }
  int rc = rn_cli_check_repeats("solve", argc, argv, valued);
  if (rc) return rc;
  if (!a->scene) return rn_cli_usage_error("solve", "missing the scene file");
  if (!a->output) return rn_cli_usage_error("solve", "missing -o RESULT.json");
  if (a->stability_method && a->no_stability)
    return rn_cli_usage_error("solve", "--stability-method has no effect with "
                                       "--no-stability (no stability check is run)");
  return check_output_paths(a);
}

#ifdef RN_HAVE_SOLVER

typedef struct progress_state {
  int header_done;
} progress_state;

static void progress(void *user, const rn_iteration_info *it) {
  progress_state *p = user;
  if (!p->header_done) {
    fprintf(stderr, "%5s  %24s  %10s  %10s  %6s  %9s  %6s\n", "iter", "energy", "|grad|",
            "radius", "krylov", "time[s]", "load");
    p->header_done = 1;
  }
  fprintf(stderr, "%5d  %24.16e  %10.3e  %10.3e  %6d  %9.3f  %6.4f\n", it->iteration,
          it->energy, it->gradient_norm, it->radius, it->krylov_iterations, it->seconds,
          it->load_factor);
  fflush(stderr);
}

/* The solve options: defaults, the scene's solver block, the command line.  A
 * bad name is a usage error, printed only if loud (one rank of several). */
static int make_options(const solve_args *a, const rn_scene *scene, rn_solve_options *opt,
                        int loud) {
  rn_solve_options_default(opt);
  rn_scene_apply_solver(scene, opt);
  if (!loud &&
      ((a->solver && rn_solver_from_name(a->solver, &opt->solver) != RN_OK) ||
       (a->factorization &&
        rn_factorization_from_name(a->factorization, &opt->factorization) != RN_OK)))
    return RN_EXIT_USAGE;
  char known[256];
  if (a->solver && rn_solver_from_name(a->solver, &opt->solver) != RN_OK) {
    rn_cli_solver_names(known, sizeof known);
    return rn_cli_usage_error("solve", "unknown solver '%s' (known: %s)", a->solver,
                              known);
  }
  if (a->preconditioner &&
      rn_preconditioner_from_name(a->preconditioner, &opt->preconditioner) != RN_OK) {
    rn_cli_preconditioner_names(known, sizeof known);
    return rn_cli_usage_error("solve", "unknown preconditioner '%s' (known: %s)",
                              a->preconditioner, known);
  }
  if (a->factorization &&
      rn_factorization_from_name(a->factorization, &opt->factorization) != RN_OK)
    return rn_cli_usage_error("solve",
                              "unknown factorization '%s' (known: auto, banded, "
                              "sparse, cholmod)",
                              a->factorization);
  if (a->has_max_iter) opt->max_iterations = a->max_iter;
  if (a->has_gtol) opt->gtol_rel = a->gtol;
  if (a->has_load_steps) opt->load_steps = a->load_steps;
  if (a->no_predictor) opt->predictor = 0;
  if (a->no_stability) opt->stability = 0;
  if (a->stability_method) {
    static const char *const names[3] = {"auto", "cholesky", "lobpcg"};
    int k = 0;
    while (k < 3 && strcmp(a->stability_method, names[k]) != 0) ++k;
    if (k == 3)
      return rn_cli_usage_error("solve",
                                "unknown stability method '%s' (known: auto, "
                                "cholesky, lobpcg)",
                                a->stability_method);
    opt->stability_method = k;
  }
  return 0;
}

/* The partition block of one rank: everything owned by it. */
typedef struct part_block {
  long dofs1, stencils1; /* one rank */
  long *dofs, *stencils; /* [ranks], allocated (distributed) */
} part_block;

static void fill_serial_partition(rn_network *net, part_block *pb, rn_result_info *in) {
  rn_part_info pi;
  memset(&pi, 0, sizeof pi);
  rn_network_part_info(net, &pi);
  pb->dofs1 = (long)pi.owned_dofs;
  pb->stencils1 = pi.owned_stencils;
  in->part_ranks = 1;
  in->part_dofs = &pb->dofs1;
  in->part_stencils = &pb->stencils1;
  in->edge_cut = 0;
  in->imbalance = 1.0;
}

static void print_partition(const rn_result_info *in) {
  if (in->part_ranks < 2) return;
  printf("  partition    %d ranks, owned DOFs", in->part_ranks);
  for (int q = 0; q < in->part_ranks; q++) printf(" %ld", in->part_dofs[q]);
  printf(", owned stencils");
  for (int q = 0; q < in->part_ranks; q++) printf(" %ld", in->part_stencils[q]);
  printf(", edge cut %ld, imbalance %.3f\n", in->edge_cut, in->imbalance);
}

/* The modes the stability line names besides the verdict: symmetries (exact
 * zero modes, excluded) and soft modes (|lambda| <= 1e-12 scale outside them),
 * shown positive or not; e.g. "2 symmetries (rigid motions, frame spins), 4
 * soft modes, all positive". */
static void stability_modes(const rn_stability *st, char *buf, size_t n) {
  if (st->symmetries < 0) {
    snprintf(buf, n, "%d zero modes (symmetries and soft modes not separated)",
             st->zero_modes);
    return;
  }
  int k = snprintf(buf, n, "%d symmetr%s (rigid motions, frame spins), ", st->symmetries,
                   st->symmetries == 1 ? "y" : "ies");
  if (k < 0 || (size_t)k >= n) return;
  if (st->soft_modes == 0)
    snprintf(buf + k, n - (size_t)k, "no soft modes");
  else if (st->soft_positive == st->soft_modes)
    snprintf(buf + k, n - (size_t)k, "%d soft mode%s, all positive", st->soft_modes,
             st->soft_modes == 1 ? "" : "s");
  else
    snprintf(buf + k, n - (size_t)k, "%d soft mode%s of unresolved sign", st->soft_modes,
             st->soft_modes == 1 ? "" : "s");
}

static void print_stability(const rn_result_info *in) {
  const rn_stability *st = &in->stability;
  char modes[160];
  if (!st->checked) {
    printf("  stability    not checked: %s\n",
           in->stability_note ? in->stability_note : "not available");
    return;
  }
  stability_modes(st, modes, sizeof modes);
  printf("  stability    %s: lowest Hessian eigenvalue %.6e outside the symmetries "
         "(scale %.3e); %s; %s, %ld factorisations, %d iterations, %.3f s\n",
         st->verified_minimum ? "verified local minimum"
         : in->converged      ? "stationary, not a verified minimum"
                              : "not a verified minimum (not converged)",
         st->lowest_eigenvalue, st->scale, modes,
         st->method == RN_STABILITY_LOBPCG ? "lobpcg" : "cholesky", st->factorizations,
         st->iterations, st->time_s);
}

static void print_summary(const solve_args *a, const rn_scene *scene,
                          const rn_result_info *in) {
  rn_network *net = rn_scene_network(scene);
  char line[320];
  printf("rodnet solve: %s\n", a->scene);
  /* a converged stationary point that is not a verified minimum says so */
  printf("  status       %s%s (stopped by: %s)\n", in->status,
         in->converged && in->stability.checked && !in->stability.verified_minimum
             ? ": stationary, not a verified minimum"
             : "",
         in->stop);
  printf("  solver       %s (%s factorisation%s%s)\n", in->solver, in->factorization,
         in->preconditioner ? ", preconditioner " : "",
         in->preconditioner ? in->preconditioner : "");
  printf("  size         %d rods, %ld vertices, %zu free DOFs\n",
         rn_network_num_rods(net), rn_scene_num_vertices(scene),
         rn_network_num_dofs(net));
  printf("  model        %s\n", rn_result_model_line(net, line, sizeof line));
  printf("  iterations   %d Newton, %ld Krylov, %d load steps (load factor %g), %d "
         "predictor steps\n",
         in->iterations, in->krylov_iterations, in->load_steps,
         rn_network_load_factor(net), in->predictor_steps);
  printf("  evaluations  %ld energy, %ld gradient, %ld HVP, %ld Hessian, %ld "
         "factorisations\n",
         in->energy_evals, in->gradient_evals, in->hvp_evals, in->hessian_evals,
         in->factorizations);
  printf("  energy       %.17g\n", in->energy);
  printf("  |gradient|   %.3e (initial %.3e)\n", in->gradient_norm,
         in->initial_gradient_norm);
  printf("  residual     force %.3e (scale %.3e, tolerance %.3e), moment %.3e (scale "
         "%.3e, tolerance %.3e)\n",
         in->force_residual, in->force_scale, in->force_tolerance, in->moment_residual,
         in->moment_scale, in->moment_tolerance);
  print_stability(in);
  print_partition(in);
  printf("  time         %.3f s (Hessian assembly %.3f s, preconditioner setup %.3f s, "
         "apply %.3f s)\n",
         in->time_s, in->hessian_s, in->preconditioner_setup_s,
         in->preconditioner_apply_s);
  printf("  wrote        %s%s%s\n", a->output, a->vtk ? ", " : "", a->vtk ? a->vtk : "");
}

static int write_outputs(rn_context *ctx, const solve_args *a, const rn_scene *scene,
                         const rn_result_info *in) {
  rn_status st = rn_result_write_json(ctx, a->output, scene, in);
  if (!st && a->vtk) st = rn_vtk_write(ctx, a->vtk, scene);
  if (st) {
    fprintf(stderr, "rodnet solve: %s\n", rn_context_last_error(ctx));
    return RN_EXIT_INTERNAL;
  }
  return RN_EXIT_OK;
}

/* --preconditioner applies to tr-krylov and nox only (the solver chosen by the
 * command line, the scene or the default).  RN_EXIT_USAGE with a message. */
static int check_preconditioner(const solve_args *a, const rn_solve_options *opt) {
  const rn_solver_info *row = rn_solver_info_of(opt->solver);
  if (!a->preconditioner || (row && (row->flags & RN_SOLVER_TAKES_PRECONDITIONER)))
    return 0;
  char which[128];
  rn_cli_preconditioned_solvers(which, sizeof which);
  return rn_cli_usage_error("solve",
                            "--preconditioner %s: only the solvers %s "
                            "use a preconditioner choice, not '%s'",
                            a->preconditioner, which, rn_solver_name(opt->solver));
}

/* A couple fixed in space (rodnet_couple.h) has no energy: only NOX solves it.
 * RN_EXIT_USAGE with a message naming the load (printed if loud), else 0. */
static int refuse_fixed_couples(const solve_args *a, const rn_network *net,
                                const rn_solve_options *opt, int loud) {
  const rn_solver_info *row = rn_solver_info_of(opt->solver);
  if ((row && (row->flags & RN_SOLVER_FIXED_COUPLES)) ||
      rn_network_fixed_couples(net, NULL, NULL) == 0)
    return 0;
  char which[160]; /* the graph pass of a distributed solve has no names */
  if (loud)
    fprintf(
        stderr,
        "rodnet solve: %s: the moment on %s is a couple fixed in space (\"model\": "
        "\"fixed\"), a nonconservative load with no energy: the energy minimiser '%s' "
        "cannot solve it; use --solver nox (Newton on the residual)\n",
        a->scene, rn_network_fixed_couple_where(net, which, sizeof which),
        rn_solver_name(opt->solver));
  return RN_EXIT_USAGE;
}

static int run_solve(rn_context *ctx, const solve_args *a, rn_scene *scene) {
  rn_solve_options opt;
  int rc = make_options(a, scene, &opt, 1);
  if (rc) return rc;
  if ((rc = check_preconditioner(a, &opt))) return rc;
  if ((rc = refuse_fixed_couples(a, rn_scene_network(scene), &opt, 1))) return rc;
  progress_state ps = {0};
  if (!a->quiet) {
    opt.progress = progress;
    opt.progress_user = &ps;
  }
  rn_solve_report rep;
  memset(&rep, 0, sizeof rep);
  rn_status st = rn_solve(rn_scene_network(scene), &opt, &rep);
  if (st != RN_OK) {
    fprintf(stderr, "rodnet solve: %s: solver failed (%s): %s\n", a->scene,
            rn_status_name(st), rn_context_last_error(ctx));
    return RN_EXIT_INTERNAL;
  }
  rn_result_info in;
  part_block pb;
  rn_result_info_fill(&rep, &opt, &in);
  if (rn_network_fixed_couples(rn_scene_network(scene), NULL, NULL) > 0)
    in.stability_note = RN_NOTE_NONCONSERVATIVE;
  fill_serial_partition(rn_scene_network(scene), &pb, &in);
  if ((rc = write_outputs(ctx, a, scene, &in))) return rc;
  print_summary(a, scene, &in);
  return rep.converged ? RN_EXIT_OK : RN_EXIT_NOT_CONVERGED;
}

/* ---- under mpirun: one part of the network per rank (docs/parallel.md) ---- */

/* The partition block of RESULT.json from d (rn_cli_dist_partition, collective). */
static rn_status partition_info(rn_cli_dist *d, rn_result_info *in) {
  rn_status st = rn_cli_dist_partition(d);
  in->part_ranks = d->size;
  in->part_dofs = d->dofs;
  in->part_stencils = d->stencils;
  in->edge_cut = d->edge_cut;
  in->imbalance = d->imbalance;
  return st;
}

/* Graph pass (the scene's rod graph and options), and the output paths. */
static int load_graph(rn_cli_dist *d, const solve_args *a) {
  int rc = rn_cli_dist_load_graph(d, a->scene);
  if (rc) return rc;
  rn_status st = d->rank == 0 ? rn_file_probe_writable(d->ctx, a->output) : RN_OK;
  if (!st && d->rank == 0 && a->vtk) st = rn_file_probe_writable(d->ctx, a->vtk);
  if (rn_cli_dist_agree(d, st, "rodnet solve: ")) return RN_EXIT_INPUT;
  return 0;
}

/* Rank 0 reads the whole scene and receives every part's state; then writes. */
static int gather_and_write(rn_cli_dist *d, const solve_args *a, rn_result_info *in) {
  rn_network *part = rn_scene_network(d->part);
  rn_status st = RN_OK;
  if (d->rank == 0) {
    st = rn_scene_load(d->ctx, a->scene, &d->whole);
    if (!st)
      st = rn_network_set_load_factor(rn_scene_network(d->whole),
                                      rn_network_load_factor(part));
  }
  if (rn_cli_dist_agree(d, st, "rodnet solve: cannot gather the result: "))
    return RN_EXIT_INTERNAL;
  st = rn_dist_gather_state(part, d->whole ? rn_scene_network(d->whole) : NULL);
  if (rn_cli_dist_agree(d, st, "rodnet solve: cannot gather the result: "))
    return RN_EXIT_INTERNAL;
  st = partition_info(d, in);
  if (rn_cli_dist_agree(d, st, "rodnet solve: ")) return RN_EXIT_INTERNAL;
  /* the solve checks stability on the parts (LOBPCG, collective); if it did not,
   * the Cholesky check on rank 0 on the gathered state (serial; the other ranks
   * wait at the next agreement) */
  if (d->rank == 0 && !in->stability_note && !in->stability.checked) {
    if (rn_network_stability(rn_scene_network(d->whole), &in->stability) == RN_OK)
      in->stability.verified_minimum = in->stability.verified_minimum && in->converged;
    else
      in->stability_note = "failed on the gathered state";
  }
  int rc = d->rank == 0 ? write_outputs(d->ctx, a, d->whole, in) : RN_EXIT_OK;
  if (rn_cli_dist_agree(d, rc ? RN_ERR_IO : RN_OK, "")) return RN_EXIT_INTERNAL;
  if (d->rank == 0) print_summary(a, d->whole, in);
  return 0;
}

static int run_distributed(rn_cli_dist *d, const solve_args *a) {
  rn_solve_options opt;
  int rc = load_graph(d, a);
  if (rc) return rc;
  /* the scene's solver block is read in the graph pass too */
  rc = make_options(a, d->graph, &opt, d->rank == 0);
  if (rc) return rc; /* the same on every rank: its message printed by rank 0 */
  /* no solver asked for (command line or scene): the distributed default */
  if (!a->solver && !rn_scene_sets_solver_kind(d->graph))
    opt.solver = RN_SOLVER_TR_KRYLOV;
  if ((rc = check_preconditioner(a, &opt))) return rc; /* printed by rank 0 */
  if (!rn_solver_is_distributed(opt.solver)) {
    if (d->rank == 0)
      fprintf(stderr,
              "rodnet solve: solver '%s' factors the whole Hessian on one process and "
              "cannot run on %d MPI ranks; run it without mpirun (one process), or "
              "choose a distributed solver (docs/parallel.md)\n",
              rn_solver_name(opt.solver), d->size);
    return RN_EXIT_USAGE;
  }
  if ((rc = refuse_fixed_couples(a, rn_scene_network(d->graph), &opt, d->rank == 0)))
    return rc;
  if ((rc = rn_cli_dist_load_part(d, a->scene, "rodnet solve"))) return rc;
  progress_state ps = {0};
  if (!a->quiet && d->rank == 0) {
    opt.progress = progress;
    opt.progress_user = &ps;
  }
  rn_solve_report rep;
  memset(&rep, 0, sizeof rep);
  rn_status st = rn_solve(rn_scene_network(d->part), &opt, &rep);
  if (rn_cli_dist_agree(d, st, "rodnet solve: solver failed: ")) return RN_EXIT_INTERNAL;
  rn_result_info in;
  rn_result_info_fill(&rep, &opt, &in);
  if (rn_network_fixed_couples(rn_scene_network(d->part), NULL, NULL) > 0)
    in.stability_note = RN_NOTE_NONCONSERVATIVE;
  if ((rc = gather_and_write(d, a, &in))) return rc;
  return rep.converged ? RN_EXIT_OK : RN_EXIT_NOT_CONVERGED;
}

/* Every rank returns the same exit status; only rank 0 prints. */
static int solve_distributed(const solve_args *a, int rank, int size) {
  rn_cli_dist d;
  int rc = rn_cli_dist_begin(&d, rank, size, "rodnet solve");
  if (!rc) rc = run_distributed(&d, a);
  rn_cli_dist_end(&d);
  return rc;
}

static int solve_scene_serial(const solve_args *a);

static int solve_scene(const solve_args *a) {
  int rank, size, rc = rn_cli_mpi_start("rodnet solve", &rank, &size);
  if (rc) return rc;
  if (size > 1) return solve_distributed(a, rank, size);
  return solve_scene_serial(a);
}

static int solve_scene_serial(const solve_args *a) {
  rn_context *ctx = NULL;
  if (rn_context_create(&ctx) != RN_OK) {
    fprintf(stderr, "rodnet solve: out of memory\n");
    return RN_EXIT_INTERNAL;
  }
  rn_scene *scene = NULL;
  int rc = RN_EXIT_OK;
  rn_status st = rn_scene_load(ctx, a->scene, &scene);
  if (st) {
    fprintf(stderr, "%s\n", rn_context_last_error(ctx));
    rc = rn_cli_load_exit_code(st);
  }
  if (!rc && ((st = rn_file_probe_writable(ctx, a->output)) ||
              (a->vtk && (st = rn_file_probe_writable(ctx, a->vtk))))) {
    fprintf(stderr, "rodnet solve: %s\n", rn_context_last_error(ctx));
    rc = RN_EXIT_INPUT;
  }
  /* a scene whose loads push a free rigid motion has no equilibrium: say so
   * up front instead of running to max_iterations */
  if (!rc && (st = rn_network_check_supports(rn_scene_network(scene)))) {
    fprintf(stderr, "%s: %s\n", a->scene, rn_context_last_error(ctx));
    rc = rn_cli_load_exit_code(st);
  }
  if (!rc) {
    /* The solver's runtime (Kokkos, MPI) is needed only here. */
    st = rn_runtime_initialize(NULL, NULL);
    if (st) {
      fprintf(stderr, "rodnet solve: cannot start the solver runtime (%s)\n",
              rn_status_name(st));
      rc = RN_EXIT_INTERNAL;
    } else
      rc = run_solve(ctx, a, scene);
  }
  rn_scene_destroy(&scene);
  rn_context_destroy(&ctx);
  rn_runtime_finalize();
  return rc;
}

#endif /* RN_HAVE_SOLVER */

int rn_cli_solve(int argc, char **argv) {
  solve_args a;
  int rc = parse_solve_args(argc, argv, &a);
  if (rc) return rc < 0 ? RN_EXIT_OK : rc;
#ifdef RN_HAVE_SOLVER
  return solve_scene(&a);
#else
  return rn_cli_no_solver("solve");
#endif
}
