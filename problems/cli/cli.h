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

/* The table of the subcommands (cli.c): dispatch, the help's list and the
 * refusals come from it. */
enum {
  RN_CLI_NEEDS_SOLVER = 1, /* refused with RN_EXIT_NO_SOLVER by a build without
                              the solver (after parsing its options) */
  RN_CLI_DISTRIBUTED = 2   /* runs under mpirun on several ranks; the others
                              refuse there with RN_EXIT_USAGE */
};
typedef struct rn_cli_command {
  const char *name;     /* "solve" */
  const char *synopsis; /* "solve SCENE.json -o RESULT.json" */
  const char *help;     /* its lines in the help, '\n'-separated */
  int (*run)(int argc, char **argv);
  unsigned flags; /* RN_CLI_NEEDS_SOLVER | RN_CLI_DISTRIBUTED */
} rn_cli_command;
/* The rows in the order of the help; *n of them. */
const rn_cli_command *rn_cli_commands(int *n);

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
/* A usage error if one of the value options names (NULL-terminated; "--output|-o"
 * lists the spellings of one option) is given more than once: the last would
 * silently replace the others.  0 otherwise.  Flags may repeat. */
int rn_cli_check_repeats(const char *cmd, int argc, char **argv,
                         const char *const *names);
/* "rodnet CMD: this rodnet was built without the solver ..." on stderr (one
 * line); returns RN_EXIT_NO_SOLVER.  For the commands that need the solver
 * (solve, homogenize, path, sweep, bench) in a build without it. */
int rn_cli_no_solver(const char *cmd);
/* Exit status for a failed scene load. */
int rn_cli_load_exit_code(rn_status st);
/* ---- plotting scripts (cli_plot.c) -------------------------------------------
 * Run a plotting script with Python and wait for it: the interpreter is
 * $RODNET_PYTHON or the python3 found at configure time, the script
 * $script_env or default_script, then args (NULL-terminated, at most 8).
 * Flushes stdout and stderr first.  0 if the script exited with status 0,
 * -1 otherwise (fork, exec or the script failed). */
int rn_cli_run_script(const char *script_env, const char *default_script,
                      const char *const *args);
/* The same for a script that writes the file output (one of args): the script
 * writes "OUTPUT.tmp.PID.EXT" (the same extension, which names the format),
 * renamed to output when it succeeds, removed otherwise and on a signal; so
 * the plot, too, is written completely or not at all. */
int rn_cli_run_script_to(const char *script_env, const char *default_script,
                         const char *const *args, const char *output);
/* python3 SCRIPT INPUT PNG with rn_cli_run_script_to (the plot of one file:
 * path's CSV, sweep's CSV, homogenize's RESULT.json); 0 on success. */
int rn_cli_plot(const char *script_env, const char *default_script, const char *input,
                const char *png);

/* ---- input and output files (cli_paths.c) ----------------------------------
 * Every command lists the files it reads and writes; before any computation
 * no output may be one of the inputs or another output (the same file:
 * device and inode when both exist, else the resolved path; so "./a.json",
 * symbolic and hard links count), and every output must be writable. */
typedef enum rn_cli_role {
  RN_CLI_IN,     /* a file read */
  RN_CLI_OUT,    /* a file written */
  RN_CLI_OUT_DIR /* a folder written into (created if missing) */
} rn_cli_role;
typedef struct rn_cli_file {
  const char *what;   /* the option ("-o", "--plot") or, for an input, what it
                         is ("the scene file") */
  const char *path;   /* as given; NULL: not given, skipped */
  const char *suffix; /* NULL, or the file is path + suffix (--pattern P:
                         ".vtu"); a '*' in it makes a family of files
                         ("/point_*.json": the files of a folder); one
                         starting with '/' names a file in a folder output
                         (probed with the folder) */
  rn_cli_role role;
} rn_cli_file;
/* A usage error (RN_EXIT_USAGE, message printed) if an output is an input
 * ("-o X is the scene file itself") or another output ("--plot and -o name
 * the same file"); 0 otherwise. */
int rn_cli_check_files(const char *cmd, const rn_cli_file *files, int n);
/* RN_EXIT_INPUT (message printed) if an output cannot be written: its folder
 * is missing or not writable, it is a folder (a file output) or a file (a
 * folder output); 0 otherwise.  Writes nothing (atomic_file.h). */
int rn_cli_probe_outputs(const char *cmd, const rn_cli_file *files, int n);

/* ---- signals (cli_signals.c) -----------------------------------------------
 * On SIGINT, SIGTERM and SIGHUP the running script is killed and the
 * registered temporary files are removed; then the signal ends the process
 * as it would have.  rn_cli_main installs the handlers (and the temporary-file
 * hook of atomic_file.h) once. */
void rn_cli_signals_install(void);
/* Register (active 1) or forget (0) a temporary file; the name must stay valid
 * while registered. */
void rn_cli_temp_file(const char *tmp, int active);
/* The script running (0: none). */
void rn_cli_child(long pid);

/* ---- MPI (cli.c) -------------------------------------------------------------
 * 1 if this process is a rank other than 0 of an MPI job with several ranks
 * (from the launcher's environment, without starting MPI): it prints no
 * usage error. */
int rn_cli_quiet_rank(void);
/* The number of ranks of this process's MPI job from the launcher's
 * environment (1 without a launcher or with RODNET_MPI=0; -1 if the launcher
 * says the rank only), without starting MPI. */
long rn_cli_env_ranks(void);

#endif
