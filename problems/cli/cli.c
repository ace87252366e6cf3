/* cli.c - `rodnet` dispatch, top-level help and version, option helpers, the
 * plotting scripts' runner. */
#define _POSIX_C_SOURCE 200809L /* fork, waitpid, sigprocmask */
#include "cli/cli.h"
#include "cli/cli_registry.h"

#include <errno.h>
#include <signal.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <stdint.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

static const char main_help[] =
    "\n"
    "Usage: rodnet COMMAND [options]\n"
    "\n"
    "Commands:\n"
    "  solve SCENE.json -o RESULT.json   compute the equilibrium of a scene and write\n"
    "                                    the result as JSON (and VTK with --vtk)\n"
    "  check SCENE.json                  derivative self-test: gradient and Hessian of\n"
    "                                    the scene's energy against finite differences\n"
    "  generate KIND -o SCENE.json       write a lattice scene (square, triangular,\n"
    "                                    honeycomb, kagome, cubic, bcc, octet;\n"
    "                                    --periodic: a periodic cell)\n"
    "  homogenize SCENE.json -o RESULT.json  effective stiffness of a periodic cell\n"
    "  bench [--suite quick|full] -o DIR  optimiser benchmark: every problem of the\n"
    "                                    suite against every solver (runs.csv and\n"
    "                                    performance profiles)\n"
    "  path SCENE.json -o PATH.csv       follow the equilibrium path past limit points\n"
    "                                    (load or displacement control; --plot PNG)\n"
    "  sweep SWEEP.json -o DIR           homogenisation over a grid of parameters\n"
    "\n"
    "Options:\n"
    "  -h, --help       show this help; 'rodnet COMMAND --help' shows a command's "
    "options\n"
    "  -V, --version    print the version and whether the solver was built in\n"
    "\n"
    "Exit status: 0 success, 1 not converged (solve) or test failed (check),\n"
    "2 usage error, 3 bad scene or unusable input/output path, 4 solver or internal\n"
    "error, 5 the command needs the solver and this build has none (-V says).\n"
    "Scene format: docs/scene-format.md.  Commands: docs/cli.md.\n";

static void print_version(void) {
  printf("rodnet %s\n", rn_version_string());
#ifdef RN_HAVE_SOLVER
  char kinds[256];
  rn_cli_solver_names(kinds, sizeof kinds);
  printf("solver: built in (%s; Trilinos)\n", kinds);
#else
  printf("solver: not built (configured with RN_WITH_TRILINOS=OFF); 'check' and "
         "'generate' work, the other commands exit with status 5\n");
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
            "commands only 'rodnet solve' is distributed; docs/parallel.md)\n",
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
    printf("rodnet %s - static equilibria of discrete elastic rods\n",
           rn_version_string());
    fputs(main_help, stdout);
    return RN_EXIT_OK;
  }
  if (strcmp(cmd, "-V") == 0 || strcmp(cmd, "--version") == 0) {
    print_version();
    return RN_EXIT_OK;
  }
  if (strcmp(cmd, "solve") == 0) return rn_cli_solve(argc - 1, argv + 1);
  static const char *const one_process[] = {"check", "generate", "homogenize", "bench",
                                            "path",  "sweep",    NULL};
  for (int i = 0; one_process[i]; i++)
    if (strcmp(cmd, one_process[i]) == 0) {
      int rc = refuse_mpi(cmd);
      if (rc) return rc;
    }
  if (strcmp(cmd, "check") == 0) return rn_cli_check(argc - 1, argv + 1);
  if (strcmp(cmd, "generate") == 0) return rn_cli_generate(argc - 1, argv + 1);
  if (strcmp(cmd, "homogenize") == 0) return rn_cli_homogenize(argc - 1, argv + 1);
  if (strcmp(cmd, "bench") == 0) return rn_cli_bench(argc - 1, argv + 1);
  if (strcmp(cmd, "path") == 0) return rn_cli_path(argc - 1, argv + 1);
  if (strcmp(cmd, "sweep") == 0) return rn_cli_sweep(argc - 1, argv + 1);
  fprintf(stderr, "rodnet: unknown command '%s'\nTry 'rodnet --help'.\n", cmd);
  return RN_EXIT_USAGE;
}

int rn_cli_no_solver(const char *cmd) {
  fprintf(stderr,
          "rodnet %s: this rodnet was built without the solver (configured with "
          "-DRN_WITH_TRILINOS=OFF); rebuild with -DRN_WITH_TRILINOS=ON. 'rodnet check' "
          "and 'rodnet generate' work without it.\n",
          cmd);
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

#ifndef RN_PYTHON3
#define RN_PYTHON3 "python3"
#endif

int rn_cli_run_script(const char *script_env, const char *default_script,
                      const char *const *args) {
  const char *script = getenv(script_env), *python = getenv("RODNET_PYTHON");
  const char *argv[11];
  int n = 0;
  if (!script || !*script) script = default_script;
  if (!python || !*python) python = RN_PYTHON3;
  argv[n++] = python;
  argv[n++] = script;
  for (int i = 0; args[i] && n < 10; i++) argv[n++] = args[i];
  argv[n] = NULL;
  fflush(stdout);
  fflush(stderr);
  /* no signal between the fork and the child's registration: the handler
   * kills the script (cli_signals.c) */
  sigset_t block, old;
  sigemptyset(&block);
  sigaddset(&block, SIGINT);
  sigaddset(&block, SIGTERM);
  sigaddset(&block, SIGHUP);
  sigprocmask(SIG_BLOCK, &block, &old);
  pid_t pid = fork();
  if (pid == 0) {
    sigprocmask(SIG_SETMASK, &old, NULL);
    execvp(python, (char *const *)(uintptr_t)argv);
    _exit(127);
  }
  if (pid > 0) rn_cli_child((long)pid);
  sigprocmask(SIG_SETMASK, &old, NULL);
  if (pid < 0) return -1;
  int status = 0, rc = 0;
  while (waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) {
      rc = -1;
      break;
    }
  rn_cli_child(0);
  return !rc && WIFEXITED(status) && WEXITSTATUS(status) == 0 ? 0 : -1;
}

int rn_cli_run_script_to(const char *script_env, const char *default_script,
                         const char *const *args, const char *output) {
  struct stat sb;
  /* a device (/dev/null) or FIFO is written in place, as atomic_file.h does */
  if (stat(output, &sb) == 0 && !S_ISREG(sb.st_mode) && !S_ISDIR(sb.st_mode))
    return rn_cli_run_script(script_env, default_script, args);
  const char *slash = strrchr(output, '/'), *dot = strrchr(output, '.');
  const char *ext = dot && (!slash || dot > slash + 1) ? dot : "";
  size_t len = strlen(output) + strlen(ext) + 48;
  char *tmp = malloc(len);
  const char *targs[9];
  int n = 0, rc;
  if (!tmp) return -1;
  snprintf(tmp, len, "%s.tmp.%ld%s", output, (long)getpid(), ext);
  for (; args[n] && n < 8; n++) targs[n] = args[n] == output ? tmp : args[n];
  targs[n] = NULL;
  rn_cli_temp_file(tmp, 1);
  rc = rn_cli_run_script(script_env, default_script, targs);
  if (rc == 0 && rename(tmp, output) != 0) rc = -1;
  if (rc) remove(tmp);
  rn_cli_temp_file(tmp, 0);
  free(tmp);
  return rc;
}
