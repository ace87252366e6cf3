/* bench_util.h - shared helpers of rodnet's benchmarks: timing, statistics,
 * CSV output with provenance, option parsing and the rods the benchmarks use. */
#ifndef RN_BENCH_UTIL_H
#define RN_BENCH_UTIL_H
#include <stdint.h>
#include <stdio.h>

#include "rodnet.h"

/* Monotonic wall-clock time in seconds. */
double rn_bench_now(void);

/* Median and minimum of t[n] (n >= 1); t is sorted in place. */
void rn_bench_stats(double *t, int n, double *median, double *min);

/* Parse a comma-separated list of positive integers into v[max]; returns the
 * count, or -1 on a malformed list. */
int rn_bench_parse_list(const char *s, long *v, int max);

/* Deterministic uniform random number in [-1, 1). */
double rn_bench_rand(uint64_t *state);

/* CSV: the header starts with the common columns
 * commit,compiler,flags,ranks,bench,case,size,repeats,median,min
 * and continues with extra (a comma-separated list, may be NULL).  A row starts
 * with rn_bench_csv_begin (common columns up to min) and the caller appends the
 * extra columns and a newline. */
void rn_bench_csv_header(FILE *f, const char *extra);
void rn_bench_csv_begin(FILE *f, const char *bench, const char *case_name, long size,
                        int repeats, double median, double min);
/* As rn_bench_csv_begin, for a run on that many MPI ranks. */
void rn_bench_csv_begin_ranks(FILE *f, int ranks, const char *bench,
                              const char *case_name, long size, int repeats,
                              double median, double min);

/* What every benchmark's main opens and closes: the CSV output and a context. */
typedef struct rn_bench_run {
  FILE *out;       /* the CSV file, or stdout */
  rn_context *ctx; /* the context of the benchmark's networks */
} rn_bench_run;

/* Opens path for writing (stdout if NULL), creates a context and writes the CSV
 * header with the extra columns.  Returns 0, or 1 after printing why (perror) with
 * nothing left open. */
int rn_bench_begin(rn_bench_run *run, const char *path, const char *extra);

/* Destroys the context and closes the output (unless stdout).  Returns 1 if rc is
 * nonzero or the output cannot be closed, else 0: the exit status of the main. */
int rn_bench_end(rn_bench_run *run, int rc);

/* A benchmark program, for rn_bench_main. */
typedef struct rn_bench_program {
  /* Fills opts from the command line: 0 to run, 1 after --help, -1 after a usage
   * error (both print the usage: rn_bench_parse_args). */
  int (*parse)(int argc, char **argv, void *opts);
  /* The CSV columns after the common ones (rn_bench_csv_header). */
  const char *columns;
  /* Runs the benchmark with the options, writing its rows to run->out; 0 if ok. */
  int (*body)(rn_bench_run *run, const void *opts);
} rn_bench_program;

/* The main of a benchmark: p->parse, rn_bench_begin on the CSV path *out (which
 * parse stored in opts; NULL: stdout) with p->columns, p->body, rn_bench_end.
 * Returns the exit status: 0 after --help, 2 after a usage error, 1 if the output
 * cannot be opened or written or the body failed, else 0. */
int rn_bench_main(int argc, char **argv, const rn_bench_program *p, void *opts,
                  const char *const *out);

/* Prints "<prog>: <msg>\n<synopsis>" to stderr (the synopsis ends with a newline)
 * and returns 2, the exit status of a usage error. */
int rn_bench_usage(const char *prog, const char *msg, const char *synopsis);

/* Command lines: a table of options, each "--name VALUE" (or a flag without value). */
typedef enum rn_bench_opt_kind {
  RN_BENCH_FLAG,   /* no value: *(int *)dst = 1 */
  RN_BENCH_INT,    /* *(int *)dst = atoi(value) */
  RN_BENCH_DOUBLE, /* *(double *)dst = atof(value) */
  RN_BENCH_STRING, /* *(const char **)dst = value (borrowed from argv) */
  RN_BENCH_LIST,   /* rn_bench_parse_list(value, (long *)dst, max) into *count */
  RN_BENCH_CALL    /* call(opts, value); nonzero: a usage error with the message bad */
} rn_bench_opt_kind;

typedef struct rn_bench_option {
  const char *name; /* "--cells" */
  rn_bench_opt_kind kind;
  void *dst;                                  /* FLAG, INT, DOUBLE, STRING, LIST */
  int *count;                                 /* LIST */
  int max;                                    /* LIST */
  int (*call)(void *opts, const char *value); /* CALL */
  const char *bad;                            /* CALL */
} rn_bench_option;

/* A benchmark's name, usage synopsis (as rn_bench_usage) and what --help says. */
typedef struct rn_bench_cli {
  const char *prog, *synopsis, *help;
} rn_bench_cli;

/* Parses argv[1..argc-1] against the table opt[nopt] (opts: the caller's options,
 * passed to the CALL options).  --help or -h prints the usage with cli->help and
 * returns 1; a missing value, an unknown option or a failing CALL prints the usage
 * with "missing value after an option", "unknown option" or the option's bad and
 * returns -1; otherwise 0.  The values are not checked further. */
int rn_bench_parse_args(int argc, char **argv, const rn_bench_option *opt, int nopt,
                        void *opts, const rn_bench_cli *cli);

/* Prints the usage with msg (a value the benchmark refuses) and returns -1, what a
 * parse_args returns for a bad command line. */
int rn_bench_bad_args(const rn_bench_cli *cli, const char *msg);

/* Rod shapes of the benchmarks, all of total length 1 with nv vertices:
 * "straight" along x; "curved" a helix of radius 0.05 with two turns. */
typedef enum rn_bench_shape { RN_BENCH_STRAIGHT = 0, RN_BENCH_CURVED = 1 } rn_bench_shape;
int rn_bench_shape_from_name(const char *name, rn_bench_shape *shape);
const char *rn_bench_shape_name(rn_bench_shape shape);

/* Build and finalize the cantilever on a rod of that shape: E = 1e7,
 * nu = 0.5, circle r = 0.01, clamped at the start, dead force (0, 0, -tip_load)
 * at the last vertex.  On failure prints the context's error and returns it. */
rn_status rn_bench_cantilever(rn_context *ctx, rn_bench_shape shape, int nv,
                              double tip_load, rn_network **net);

/* Print "bench: where: status (context message)" to stderr. */
void rn_bench_report_error(const char *where, rn_context *ctx, rn_status s);

#endif
