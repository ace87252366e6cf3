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
