/* bench_util.c - timing, statistics, CSV and rod builders of the benchmarks. */
#define _POSIX_C_SOURCE 200809L
#include "bench_util.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "bench_config.h"

double rn_bench_now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static int cmp_double(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

void rn_bench_stats(double *t, int n, double *median, double *min) {
  qsort(t, (size_t)n, sizeof *t, cmp_double);
  *min = t[0];
  *median = (n % 2) ? t[n / 2] : 0.5 * (t[n / 2 - 1] + t[n / 2]);
}

int rn_bench_parse_list(const char *s, long *v, int max) {
  int n = 0;
  const char *p = s;
  while (*p) {
    char *end = NULL;
    errno = 0;
    long x = strtol(p, &end, 10);
    if (end == p || errno || x <= 0 || n == max) return -1;
    v[n++] = x;
    if (*end == ',')
      end++;
    else if (*end != '\0')
      return -1;
    p = end;
  }
  return n > 0 ? n : -1;
}

double rn_bench_rand(uint64_t *state) {
  /* xorshift64* */
  uint64_t x = *state;
  x ^= x >> 12;
  x ^= x << 25;
  x ^= x >> 27;
  *state = x;
  return (double)((x * 2685821657736338717ULL) >> 11) * (2.0 / 9007199254740992.0) - 1.0;
}

void rn_bench_csv_header(FILE *f, const char *extra) {
  fprintf(f, "commit,compiler,flags,ranks,bench,case,size,repeats,median,min%s%s\n",
          extra ? "," : "", extra ? extra : "");
}

void rn_bench_csv_begin_ranks(FILE *f, int ranks, const char *bench,
                              const char *case_name, long size, int repeats,
                              double median, double min) {
  fprintf(f, "\"%s\",\"%s\",\"%s\",%d,%s,%s,%ld,%d,%.6e,%.6e", RN_BENCH_COMMIT,
          RN_BENCH_COMPILER, RN_BENCH_FLAGS, ranks, bench, case_name, size, repeats,
          median, min);
}

void rn_bench_csv_begin(FILE *f, const char *bench, const char *case_name, long size,
                        int repeats, double median, double min) {
  rn_bench_csv_begin_ranks(f, 1, bench, case_name, size, repeats, median, min);
}

int rn_bench_begin(rn_bench_run *run, const char *path, const char *extra) {
  run->ctx = NULL;
  run->out = path ? fopen(path, "w") : stdout;
  if (!run->out) {
    perror(path);
    return 1;
  }
  if (rn_context_create(&run->ctx)) {
    if (run->out != stdout) fclose(run->out);
    run->out = NULL;
    return 1;
  }
  rn_bench_csv_header(run->out, extra);
  return 0;
}

int rn_bench_end(rn_bench_run *run, int rc) {
  rn_context_destroy(&run->ctx);
  if (run->out && run->out != stdout && fclose(run->out) != 0) rc = 1;
  run->out = NULL;
  return rc ? 1 : 0;
}

int rn_bench_main(int argc, char **argv, const rn_bench_program *p, void *opts,
                  const char *const *out) {
  rn_bench_run run;
  int rc = p->parse(argc, argv, opts);
  if (rc) return rc > 0 ? 0 : 2;
  if (rn_bench_begin(&run, *out, p->columns)) return 1;
  return rn_bench_end(&run, p->body(&run, opts));
}

int rn_bench_usage(const char *prog, const char *msg, const char *synopsis) {
  fprintf(stderr, "%s: %s\n%s", prog, msg, synopsis);
  return 2;
}

/* Stores value as o says; 0, or -1 after the usage if a CALL fails. */
static int set_option(const rn_bench_option *o, const char *value, void *opts,
                      const rn_bench_cli *cli) {
  switch (o->kind) {
  case RN_BENCH_FLAG:
    *(int *)o->dst = 1;
    break;
  case RN_BENCH_INT:
    *(int *)o->dst = atoi(value);
    break;
  case RN_BENCH_DOUBLE:
    *(double *)o->dst = atof(value);
    break;
  case RN_BENCH_STRING:
    *(const char **)o->dst = value;
    break;
  case RN_BENCH_LIST:
    *o->count = rn_bench_parse_list(value, (long *)o->dst, o->max);
    break;
  case RN_BENCH_CALL:
    if (o->call(opts, value)) return rn_bench_bad_args(cli, o->bad);
    break;
  }
  return 0;
}

int rn_bench_bad_args(const rn_bench_cli *cli, const char *msg) {
  rn_bench_usage(cli->prog, msg, cli->synopsis);
  return -1;
}

int rn_bench_parse_args(int argc, char **argv, const rn_bench_option *opt, int nopt,
                        void *opts, const rn_bench_cli *cli) {
  for (int i = 1; i < argc; ++i) {
    const char *a = argv[i], *val = i + 1 < argc ? argv[i + 1] : NULL;
    if (!strcmp(a, "--help") || !strcmp(a, "-h"))
      return rn_bench_usage(cli->prog, cli->help, cli->synopsis), 1;
    const rn_bench_option *o = NULL;
    for (int k = 0; k < nopt && !o; ++k)
      if (!strcmp(a, opt[k].name)) o = &opt[k];
    if (o && o->kind == RN_BENCH_FLAG) {
      *(int *)o->dst = 1;
      continue;
    }
    if (!val) return rn_bench_bad_args(cli, "missing value after an option");
    if (!o) return rn_bench_bad_args(cli, "unknown option");
    if (set_option(o, val, opts, cli)) return -1;
    ++i;
  }
  return 0;
}

int rn_bench_shape_from_name(const char *name, rn_bench_shape *shape) {
  if (strcmp(name, "straight") == 0)
    *shape = RN_BENCH_STRAIGHT;
  else if (strcmp(name, "curved") == 0)
    *shape = RN_BENCH_CURVED;
  else
    return -1;
  return 0;
}

const char *rn_bench_shape_name(rn_bench_shape shape) {
  return shape == RN_BENCH_CURVED ? "curved" : "straight";
}

/* Vertices of a rod of length 1: straight along x, or a helix of radius R = 0.05 with two
 * turns about z (arc length parameter s in [0, 1]). */
static void rod_vertices(rn_bench_shape shape, int nv, double *xyz) {
  const double pi = 3.14159265358979323846, R = 0.05, turns = 2.0;
  const double w = 2.0 * pi * turns;          /* angle per unit arc length */
  const double c = sqrt(1.0 - R * w * R * w); /* rise per unit arc length */
  for (int i = 0; i < nv; ++i) {
    double s = (double)i / (nv - 1);
    if (shape == RN_BENCH_STRAIGHT) {
      xyz[3 * i] = s;
      xyz[3 * i + 1] = 0.0;
      xyz[3 * i + 2] = 0.0;
    } else {
      xyz[3 * i] = R * cos(w * s);
      xyz[3 * i + 1] = R * sin(w * s);
      xyz[3 * i + 2] = c * s;
    }
  }
}

void rn_bench_report_error(const char *where, rn_context *ctx, rn_status s) {
  fprintf(stderr, "bench: %s: %s (%s)\n", where, rn_status_name(s),
          ctx ? rn_context_last_error(ctx) : "");
}

rn_status rn_bench_cantilever(rn_context *ctx, rn_bench_shape shape, int nv,
                              double tip_load, rn_network **net) {
  double *xyz = malloc(3 * (size_t)nv * sizeof *xyz);
  if (!xyz) return RN_ERR_ALLOC;
  rod_vertices(shape, nv, xyz);
  const double f[3] = {0.0, 0.0, -tip_load};
  rn_material mat;
  rn_section sec;
  int rod = -1;
  rn_status s = rn_network_create(ctx, net);
  /* d1 along y for the straight rod (as in the scene); derived by the library
   * for the helix. */
  const double d1[3] = {0.0, 1.0, 0.0};
  const double *d1p = shape == RN_BENCH_STRAIGHT ? d1 : NULL;
  if (!s) s = rn_network_add_rod(*net, "rod", nv, xyz, d1p, &rod);
  if (!s) s = rn_material_from_E_nu(1.0e7, 0.5, 0.0, &mat);
  if (!s) s = rn_section_circle(0.01, &sec);
  if (!s) s = rn_network_set_material(*net, rod, -1, &mat);
  if (!s) s = rn_network_set_section(*net, rod, -1, &sec);
  if (!s) s = rn_network_clamp(*net, rod, RN_START);
  if (!s && tip_load != 0.0) s = rn_network_add_force(*net, rod, -1, f);
  if (!s) s = rn_network_finalize(*net);
  free(xyz);
  if (s) {
    rn_bench_report_error("building the rod", ctx, s);
    rn_network_destroy(net);
  }
  return s;
}
