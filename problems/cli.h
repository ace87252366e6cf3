/* cli.h - the `rodnet` command (docs/cli.md).  The command prints; nothing
 * below it does. */
#ifndef RN_CLI_H
#define RN_CLI_H

#include "rodnet.h"

/* Exit status of the command. */
enum {
  RN_EXIT_OK = 0,            /* success */
  RN_EXIT_NOT_CONVERGED = 1, /* solve stopped without converging; check failed */
  RN_EXIT_USAGE = 2,         /* bad command line */
  RN_EXIT_INPUT = 3,         /* bad scene, unreadable input, unwritable output path */
  RN_EXIT_INTERNAL = 4,      /* solver or internal error, failed output write */
  RN_EXIT_NO_SOLVER = 5      /* the command needs the solver, which this build lacks
                                (configured with -DRN_WITH_TRILINOS=OFF) */
};

/* Entry point: argv[0] is the program name. */
int rn_cli_main(int argc, char **argv);

/* Subcommands: argv[0] is the subcommand name. */
int rn_cli_solve(int argc, char **argv);
int rn_cli_check(int argc, char **argv);
int rn_cli_generate(int argc, char **argv);
int rn_cli_homogenize(int argc, char **argv);
int rn_cli_bench(int argc, char **argv);
int rn_cli_path(int argc, char **argv);
int rn_cli_sweep(int argc, char **argv);

/* ---- helpers shared by the subcommands ---------------------------------- */
/* Print "rodnet CMD: message" and a hint to stderr; returns RN_EXIT_USAGE. */
int rn_cli_usage_error(const char *cmd, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;
/* Option argument parsing; 0 on success, else prints a usage error. */
int rn_cli_parse_int(const char *cmd, const char *opt, const char *s, long lo, long hi,
                     int *out);
int rn_cli_parse_double(const char *cmd, const char *opt, const char *s,
                        double lo_exclusive, double *out);
/* Option matching: argv[*i] is "--name" (value in argv[*i + 1]) or
 * "--name=value".  Returns 1 and sets *value (advancing *i) on a match, 0 if
 * argv[*i] is another option, -1 (usage error printed) if the value is
 * missing.  short_name may be NULL. */
int rn_cli_option_value(const char *cmd, int argc, char **argv, int *i, const char *name,
                        const char *short_name, const char **value);
/* "rodnet CMD: this rodnet was built without the solver ..." on stderr (one
 * line); returns RN_EXIT_NO_SOLVER.  For the commands that need the solver
 * (solve, homogenize, path, sweep, bench) in a build without it. */
int rn_cli_no_solver(const char *cmd);
/* Exit status for a failed scene load. */
int rn_cli_load_exit_code(rn_status st);
/* Run a plotting script with Python and wait for it: the interpreter is
 * $RODNET_PYTHON or the python3 found at configure time, the script
 * $script_env or default_script, then args (NULL-terminated, at most 8).
 * Flushes stdout and stderr first.  0 if the script exited with status 0,
 * -1 otherwise (fork, exec or the script failed). */
int rn_cli_run_script(const char *script_env, const char *default_script,
                      const char *const *args);

#endif
