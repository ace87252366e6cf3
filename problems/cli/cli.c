/* cli.c - `rodnet` dispatch from the table of subcommands, top-level help and
 * version, the refusals (no solver, mpirun), option helpers. */
#include "cli/cli.h"
#include "cli/cli_registry.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The subcommands, in the order of the help: dispatch, the help's "Commands:"
 * list, the refusals without the solver and under mpirun all come from this
 * table (adding a subcommand: its file, its handler in cli.h, one row here).
 * help: the lines of its description, '\n'-separated. */
static const rn_cli_command commands[] = {
    {"solve", "solve SCENE.json -o RESULT.json",
     "compute the equilibrium of a scene and write\n"
     "the result as JSON (and VTK with --vtk)",
     rn_cli_solve, RN_CLI_NEEDS_SOLVER | RN_CLI_DISTRIBUTED},
    {"check", "check SCENE.json",
     "derivative self-test: gradient and Hessian of\n"
     "the scene's energy against finite differences",
     rn_cli_check, 0},
    {"generate", "generate KIND -o SCENE.json",
     "write a lattice scene (square, triangular,\n"
     "honeycomb, kagome, cubic, bcc, octet;\n"
     "--periodic: a periodic cell)",
     rn_cli_generate, 0},
    {"homogenize", "homogenize SCENE.json -o RESULT.json",
     "effective stiffness of a periodic cell", rn_cli_homogenize,
     RN_CLI_NEEDS_SOLVER | RN_CLI_DISTRIBUTED},
    {"bench", "bench [--suite quick|full] -o DIR",
     "optimiser benchmark: every problem of the\n"
     "suite against every solver (runs.csv and\n"
     "performance profiles)",
     rn_cli_bench, RN_CLI_NEEDS_SOLVER},
    {"path", "path SCENE.json -o PATH.csv",
     "follow the equilibrium path past limit points\n"
     "(load or displacement control; --plot PNG)",
     rn_cli_path, RN_CLI_NEEDS_SOLVER},
    {"sweep", "sweep SWEEP.json -o DIR", "homogenisation over a grid of parameters",
     rn_cli_sweep, RN_CLI_NEEDS_SOLVER | RN_CLI_DISTRIBUTED},
};
enum { n_commands = (int)(sizeof commands / sizeof commands[0]) };

const rn_cli_command *rn_cli_commands(int *n) {
  *n = n_commands;
  return commands;
}

static const rn_cli_command *find_command(const char *name) {
  for (int i = 0; i < n_commands; i++)
    if (strcmp(commands[i].name, name) == 0) return &commands[i];
  return NULL;
}

/* The synopsis padded to column 36 (two spaces at least), then the help, its
 * further lines indented to the same column. */
static void print_command_line(FILE *out, const rn_cli_command *c) {
  enum { column = 34 };
  int len = (int)strlen(c->synopsis);
  fprintf(out, "  %s%*s", c->synopsis, len + 2 > column ? 2 : column - len, "");
  for (const char *p = c->help; *p;) {
    size_t n = strcspn(p, "\n");
    fprintf(out, "%.*s\n", (int)n, p);
    p += n;
    if (*p == '\n') fprintf(out, "%*s", column + 2, "");
    p += *p == '\n';
  }
}

/* The names of the commands that work without the solver, each between
 * prefix and "'", joined by ", " and " and " into buf: "'check' and
 * 'generate'". */
static const char *solver_free(char *buf, size_t size, const char *prefix) {
  int k = 0, total = 0;
  size_t len = 0;
  buf[0] = '\0';
  for (int i = 0; i < n_commands; i++)
    total += !(commands[i].flags & RN_CLI_NEEDS_SOLVER);
  for (int i = 0; i < n_commands && len < size; i++) {
    if (commands[i].flags & RN_CLI_NEEDS_SOLVER) continue;
    k++;
    int w = snprintf(buf + len, size - len, "%s'%s%s'",
                     k == 1       ? ""
                     : k == total ? " and "
                                  : ", ",
                     prefix, commands[i].name);
    if (w < 0) break;
    len += (size_t)w;
  }
  return buf;
}

static void print_help(void) {
  printf("rodnet %s - static equilibria of discrete elastic rods\n", rn_version_string());
  fputs("\n"
        "Usage: rodnet COMMAND [options]\n"
        "\n"
        "Commands:\n",
        stdout);
  for (int i = 0; i < n_commands; i++) print_command_line(stdout, &commands[i]);
  fputs("\n"
        "Options:\n"
        "  -h, --help       show this help; 'rodnet COMMAND --help' shows a command's "
        "options\n"
        "  -V, --version    print the version and whether the solver was built in\n"
        "\n"
        "Exit status: 0 success, 1 not converged (solve) or test failed (check),\n"
        "2 usage error, 3 bad scene or unusable input/output path, 4 solver or internal\n"
        "error, 5 the command needs the solver and this build has none (-V says).\n"
        "Scene format: docs/scene-format.md.  Commands: docs/cli.md.\n",
        stdout);
}

static void print_version(void) {
  printf("rodnet %s\n", rn_version_string());
#ifdef RN_HAVE_SOLVER
  char kinds[256];
  rn_cli_solver_names(kinds, sizeof kinds);
  printf("solver: built in (%s; Trilinos)\n", kinds);
#else
  char names[256];
  printf("solver: not built (configured with RN_WITH_TRILINOS=OFF); %s work, the other "
         "commands exit with status 5\n",
         solver_free(names, sizeof names, ""));
#endif
}

/* The first of the environment variables names that is set, as an integer;
 * -1 if none is. */
static long env_long(const char *const *names) {
  for (int i = 0; names[i]; i++) {
    const char *v = getenv(names[i]);
    if (v && *v) return strtol(v, NULL, 10);
  }
  return -1;
}

/* This process's rank and the number of ranks of its MPI job, from the
 * launcher's environment (Open MPI, MPICH/Intel MPI hydra, PMIx: the
 * variables runtime.cpp reads; Slurm's own variables are set in batch
 * scripts too, outside any MPI job);
 * 0 of 1 without a launcher or with RODNET_MPI=0 (docs/cli.md); size -1 if
 * a launcher says the rank only. */
static void env_ranks(long *rank, long *size) {
  static const char *const ranks[] = {"OMPI_COMM_WORLD_RANK", "PMI_RANK", "PMIX_RANK",
                                      NULL};
  static const char *const sizes[] = {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", NULL};
  const char *force = getenv("RODNET_MPI");
  *rank = 0;
  *size = 1;
  if (force && strcmp(force, "0") == 0) return;
  long r = env_long(ranks), n = env_long(sizes);
  if (r < 0 && n < 0) return;
  *rank = r > 0 ? r : 0;
  *size = n > 0 ? n : -1;
}

long rn_cli_env_ranks(void) {
  long rank, size;
  env_ranks(&rank, &size);
  return size;
}

int rn_cli_quiet_rank(void) {
  long rank, size;
  env_ranks(&rank, &size);
  return rank > 0;
}

/* Under mpirun with several ranks, the commands other than solve refuse to
 * run (each rank would run the whole job and write the same files): rank 0
 * says so in one line, every rank returns RN_EXIT_USAGE; MPI is not started.
 * 0 to go on. */
static int refuse_mpi(const char *cmd) {
  long rank, size;
  env_ranks(&rank, &size);
  if (size == 1 || (size < 0 && rank == 0)) return 0;
  if (rank == 0)
    fprintf(stderr,
            "rodnet %s: runs on one process, not on %ld MPI ranks (each would run the "
            "whole job and write the same files); run it without mpirun (of the "
            "commands only 'rodnet solve', 'rodnet homogenize' and 'rodnet sweep' run on "
            "several ranks; "
            "docs/parallel.md)\n",
            cmd, size);
  return RN_EXIT_USAGE;
}

int rn_cli_main(int argc, char **argv) {
  rn_cli_signals_install();
  if (argc < 2) {
    fprintf(stderr, "rodnet: missing command\nTry 'rodnet --help'.\n");
    return RN_EXIT_USAGE;
  }
  const char *cmd = argv[1];
  if (strcmp(cmd, "-h") == 0 || strcmp(cmd, "--help") == 0 || strcmp(cmd, "help") == 0) {
    print_help();
    return RN_EXIT_OK;
  }
  if (strcmp(cmd, "-V") == 0 || strcmp(cmd, "--version") == 0) {
    print_version();
    return RN_EXIT_OK;
  }
  const rn_cli_command *c = find_command(cmd);
  if (!c) {
    fprintf(stderr, "rodnet: unknown command '%s'\nTry 'rodnet --help'.\n", cmd);
    return RN_EXIT_USAGE;
  }
  if (!(c->flags & RN_CLI_DISTRIBUTED)) {
    int rc = refuse_mpi(cmd);
    if (rc) return rc;
  }
  return c->run(argc - 1, argv + 1);
}

int rn_cli_no_solver(const char *cmd) {
  char names[256];
  fprintf(stderr,
          "rodnet %s: this rodnet was built without the solver (configured with "
          "-DRN_WITH_TRILINOS=OFF); rebuild with -DRN_WITH_TRILINOS=ON. %s work without "
          "it.\n",
          cmd, solver_free(names, sizeof names, "rodnet "));
  return RN_EXIT_NO_SOLVER;
}

int rn_cli_usage_error(const char *cmd, const char *fmt, ...) {
  va_list ap;
  if (rn_cli_quiet_rank()) return RN_EXIT_USAGE; /* rank 0 of the MPI job says it */
  fprintf(stderr, "rodnet %s: ", cmd);
  va_start(ap, fmt);
  vfprintf(stderr, fmt, ap);
  va_end(ap);
  fprintf(stderr, "\nTry 'rodnet %s --help'.\n", cmd);
  return RN_EXIT_USAGE;
}

int rn_cli_parse_int(const char *cmd, const char *opt, const char *s, long lo, long hi,
                     int *out) {
  char *end = NULL;
  errno = 0;
  long v = strtol(s, &end, 10);
  if (errno || end == s || *end || v < lo || v > hi) {
    if (hi >= 2147483647L)
      return rn_cli_usage_error(cmd, "%s expects an integer >= %ld, got '%s'", opt, lo,
                                s);
    return rn_cli_usage_error(cmd, "%s expects an integer in [%ld, %ld], got '%s'", opt,
                              lo, hi, s);
  }
  *out = (int)v;
  return 0;
}

int rn_cli_parse_double(const char *cmd, const char *opt, const char *s,
                        double lo_exclusive, double *out) {
  char *end = NULL;
  errno = 0;
  double v = strtod(s, &end);
  if (errno || end == s || *end || !isfinite(v) || !(v > lo_exclusive))
    return rn_cli_usage_error(cmd, "%s expects a finite number > %g, got '%s'", opt,
                              lo_exclusive, s);
  *out = v;
  return 0;
}

int rn_cli_option_value(const char *cmd, int argc, char **argv, int *i, const char *name,
                        const char *short_name, const char **value) {
  const char *a = argv[*i];
  size_t n = strlen(name);
  if (strncmp(a, name, n) == 0 && a[n] == '=') {
    *value = a + n + 1;
    return 1;
  }
  if (strcmp(a, name) != 0 && !(short_name && strcmp(a, short_name) == 0)) return 0;
  if (*i + 1 >= argc) {
    rn_cli_usage_error(cmd, "option %s needs a value", a);
    return -1;
  }
  *i += 1;
  *value = argv[*i];
  return 1;
}

/* 1 if a is the option spelt alias (alone, or "--name=value"). */
static int is_option(const char *a, const char *alias, size_t n, int *inline_value) {
  *inline_value = 0;
  if (strncmp(a, alias, n) != 0) return 0;
  if (a[n] == '\0') return 1;
  if (a[n] == '=' && alias[1] == '-') return *inline_value = 1;
  return 0;
}

int rn_cli_check_repeats(const char *cmd, int argc, char **argv,
                         const char *const *names) {
  int count[64] = {0};
  for (int i = 1; i < argc; i++) {
    for (int k = 0; names[k] && k < 64; k++) {
      int found = 0, inline_value = 0;
      for (const char *p = names[k]; *p && !found;) { /* "--output|-o" */
        size_t n = strcspn(p, "|");
        found = is_option(argv[i], p, n, &inline_value);
        p += n + (p[n] == '|');
      }
      if (!found) continue;
      if (++count[k] > 1)
        return rn_cli_usage_error(cmd,
                                  "%.*s given more than once: give it once (the last "
                                  "would silently replace the others)",
                                  (int)strcspn(argv[i], "="), argv[i]);
      if (!inline_value) i++; /* its value */
      break;
    }
  }
  return 0;
}

int rn_cli_load_exit_code(rn_status st) {
  return (st == RN_ERR_ALLOC || st == RN_ERR_INTERNAL) ? RN_EXIT_INTERNAL : RN_EXIT_INPUT;
}
