/* bench_kernels.c - time per vertex of the energy kernels through the C API on a
 * single rod: energy, energy + gradient (rn_network_gradient), Hessian-vector
 * product (rn_network_hvp) and assembly of the CSR Hessian values
 * (rn_network_hessian_values), for straight and curved (helix) rods.
 *
 * Each row also gives the work per vertex: floating-point operations counted
 * by a counting build of the rod kernels (kernel_counts.cpp) plus the
 * additions of the assembly (one per scattered entry), the bytes the
 * evaluation must move at least with rodnet's data layout (bytes_model
 * below), and the achieved rates against one core's peak (clock from
 * /proc/cpuinfo, vector width from its flags, 2 FMA units: 4 x width flops
 * per cycle; the code uses no fused multiply-adds, so half of that is the
 * practical ceiling).
 *
 * Every timed evaluation is checked (status RN_OK, finite results) and the HVP is
 * compared with the assembled Hessian times the same vector, so a smoke run also
 * checks that the two share one source of truth.  Timings are never asserted.
 *
 *   bench_kernels [--sizes 100,1000,10000,100000] [--shapes straight,curved]
 *                 [--repeats N] [--min-time SECONDS] [--out FILE.csv]
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bench_util.h"
#include "kernel_counts.h"

#define MAX_LIST 32

typedef struct bench_opts {
  long sizes[MAX_LIST];
  int n_sizes;
  rn_bench_shape shapes[2];
  int n_shapes;
  int repeats;     /* timed batches per operation (>= 1) */
  double min_time; /* the repeats are raised until they take at least this long */
  const char *out;
} bench_opts;

/* The state the operations are evaluated at and their outputs. */
typedef struct bench_case {
  rn_network *net;
  size_t n, nnz;
  const int64_t *rowptr;
  const int32_t *col;
  double *x, *v, *g, *hv, *vals, E;
} bench_case;

typedef enum op_kind { OP_ENERGY, OP_GRADIENT, OP_HVP, OP_HESSIAN, OP_COUNT } op_kind;
static const char *const op_names[OP_COUNT] = {"energy", "gradient", "hvp",
                                               "hessian_values"};

static rn_status run_op(bench_case *c, op_kind op) {
  switch (op) {
  case OP_ENERGY:
    return rn_network_energy(c->net, c->x, &c->E);
  case OP_GRADIENT:
    return rn_network_gradient(c->net, c->x, &c->E, c->g);
  case OP_HVP:
    return rn_network_hvp(c->net, c->x, c->v, c->hv);
  default:
    return rn_network_hessian_values(c->net, c->x, c->vals);
  }
}

static int all_finite(const double *a, size_t n) {
  for (size_t i = 0; i < n; ++i)
    if (!isfinite(a[i])) return 0;
  return 1;
}

/* Checks the outputs of the last run of op. */
static int op_output_ok(const bench_case *c, op_kind op) {
  switch (op) {
  case OP_ENERGY:
    return isfinite(c->E);
  case OP_GRADIENT:
    return isfinite(c->E) && all_finite(c->g, c->n);
  case OP_HVP:
    return all_finite(c->hv, c->n);
  default:
    return all_finite(c->vals, c->nnz);
  }
}

/* |HVP - CSR * v| per row relative to sum_j |H_ij v_j| (round-off scale). */
static double hvp_vs_csr(const bench_case *c) {
  double worst = 0.0;
  for (size_t i = 0; i < c->n; ++i) {
    double y = 0.0, scale = 0.0;
    for (int64_t k = c->rowptr[i]; k < c->rowptr[i + 1]; ++k) {
      y += c->vals[k] * c->v[c->col[k]];
      scale += fabs(c->vals[k] * c->v[c->col[k]]);
    }
    double err = fabs(y - c->hv[i]) / (scale > 0.0 ? scale : 1.0);
    if (err > worst) worst = err;
  }
  return worst;
}

/* Peak double-precision flops per second of one core: clock x vector width x
 * 2 (FMA) x 2 units, from /proc/cpuinfo; 0 if unknown. */
static double core_peak(double *ghz, int *width) {
  FILE *f = fopen("/proc/cpuinfo", "r");
  char line[4096];
  double mhz = 0.0;
  *width = 2;
  if (!f) return 0.0;
  while (fgets(line, sizeof line, f)) {
    if (mhz == 0.0 && !strncmp(line, "cpu MHz", 7)) {
      const char *c = strchr(line, ':');
      if (c) mhz = atof(c + 1);
    }
    if (!strncmp(line, "flags", 5)) {
      if (strstr(line, " avx512f"))
        *width = 8;
      else if (strstr(line, " avx2") && *width < 4)
        *width = 4;
      break;
    }
  }
  fclose(f);
  *ghz = mhz * 1e-3;
  return mhz * 1e6 * (double)*width * 4.0;
}

/* Bytes an evaluation moves at least, per vertex, with rodnet's layout: each
 * array it touches counted once per read and once per write, at its size
 * (4 DOFs of 8 bytes and 4 entries of the 8-byte DOF map per vertex; per
 * edge the reference frame 48, stretch parameters 16; per interior vertex
 * bending 48, twisting 32 and stored twist 8 bytes; gradient and HVP zeroed,
 * accumulated (read + write) and checked; CSR values 8 bytes per entry,
 * stored once (rows next to clamps and joints are zeroed and accumulated:
 * not counted); the band-row descriptors 16 bytes per DOF). */
static double bytes_model(op_kind op, size_t n, size_t nnz, long nv) {
  double d = (double)n / (double)nv, e = (double)nnz / (double)nv;
  double state = 8.0 * d + 8.0 * d;                /* x and the map (gather) */
  double params = 48.0 + 16.0 + 48.0 + 32.0 + 8.0; /* per vertex ~ per edge */
  double b = state + params;
  switch (op) {
  case OP_ENERGY:
    return b;
  case OP_GRADIENT: /* g zeroed, accumulated, checked; map for the scatter */
    return b + 8.0 * d * 4.0 + 8.0 * d;
  case OP_HVP: /* v gathered (and its map), Hv as g */
    return b + 16.0 * d + 8.0 * d * 4.0 + 8.0 * d;
  default:
    return b + 8.0 * e + 16.0 * d;
  }
}

/* Batch size so that one timed batch takes about a millisecond. */
static int calibrate(bench_case *c, op_kind op) {
  double t0 = rn_bench_now();
  if (run_op(c, op)) return 1;
  double t = rn_bench_now() - t0;
  int batch = t > 0.0 ? (int)ceil(1e-3 / t) : 1000;
  return batch < 1 ? 1 : (batch > 100000 ? 100000 : batch);
}

/* Times op in `repeats` batches (more if they take less than min_time); per-call
 * median and min go to the CSV row.  Returns 0 or 1 on an evaluation failure. */
static int time_op(bench_case *c, op_kind op, const bench_opts *o, rn_bench_shape shape,
                   long nv, rn_context *ctx, FILE *out) {
  int batch = calibrate(c, op);
  int cap = o->repeats * 64, reps = 0;
  double *t = malloc((size_t)cap * sizeof *t), start = rn_bench_now();
  if (!t) return 1;
  while (reps < cap && (reps < o->repeats || rn_bench_now() - start < o->min_time)) {
    double t0 = rn_bench_now();
    for (int b = 0; b < batch; ++b) {
      rn_status s = run_op(c, op);
      if (s) {
        rn_bench_report_error(op_names[op], ctx, s);
        free(t);
        return 1;
      }
    }
    t[reps++] = (rn_bench_now() - t0) / batch;
  }
  if (!op_output_ok(c, op)) {
    fprintf(stderr, "bench: %s gives non-finite values at %ld vertices\n", op_names[op],
            nv);
    free(t);
    return 1;
  }
  double med, mn, addmul = 0.0, divsqrt = 0.0, ghz = 0.0;
  int width = 2;
  rn_bench_stats(t, reps, &med, &mn);
  free(t);
  if (nv >= 3 && rn_bench_kernel_counts((int)op, (int)nv, &addmul, &divsqrt)) {
    fprintf(stderr, "bench: the counting build failed at %ld vertices\n", nv);
    return 1;
  }
  /* plus one addition per entry the assembly scatters */
  addmul += op == OP_HESSIAN  ? (double)c->nnz / (double)nv
            : op == OP_ENERGY ? 0.0
                              : (double)c->n / (double)nv;
  double flops = addmul + divsqrt, bytes = bytes_model(op, c->n, c->nnz, nv);
  double tv = med / (double)nv, peak = core_peak(&ghz, &width);
  rn_bench_csv_begin(out, "kernels", rn_bench_shape_name(shape), nv, reps, med, mn);
  fprintf(out, ",%s,%zu,%zu,%d,%.6e,%.6e,%.1f,%.1f,%.1f,%.4g,%.4g,%.4g,%.4g\n",
          op_names[op], c->n, c->nnz, batch, tv, mn / (double)nv, flops, divsqrt, bytes,
          flops / tv * 1e-9, peak * 1e-9, peak > 0.0 ? flops / tv / peak : 0.0,
          bytes / tv * 1e-9);
  fflush(out);
  fprintf(stderr,
          "bench_kernels: %-8s %7ld vertices %-14s %8.1f ns/vertex (min %.1f)  %6.0f "
          "flops  %5.0f bytes  %5.2f Gflop/s = %.1f%% of peak\n",
          rn_bench_shape_name(shape), nv, op_names[op], tv * 1e9, mn / (double)nv * 1e9,
          flops, bytes, flops / tv * 1e-9, peak > 0.0 ? 100.0 * flops / tv / peak : 0.0);
  return 0;
}

static void case_free(bench_case *c) {
  free(c->x);
  free(c->v);
  free(c->g);
  free(c->hv);
  free(c->vals);
  rn_network_destroy(&c->net);
}

/* A loaded-free rod evaluated at a seeded random perturbation of its rest state
 * (relative size 1e-2 of an edge), so that no term is trivially zero. */
static int case_init(rn_context *ctx, rn_bench_shape shape, long nv, bench_case *c) {
  memset(c, 0, sizeof *c);
  if (rn_bench_cantilever(ctx, shape, (int)nv, 0.0, &c->net)) return 1;
  c->n = rn_network_num_dofs(c->net);
  rn_status s = rn_network_hessian_pattern(c->net, &c->nnz, &c->rowptr, &c->col);
  if (s) {
    rn_bench_report_error("hessian_pattern", ctx, s);
    return 1;
  }
  c->x = malloc(c->n * sizeof *c->x);
  c->v = malloc(c->n * sizeof *c->v);
  c->g = malloc(c->n * sizeof *c->g);
  c->hv = malloc(c->n * sizeof *c->hv);
  c->vals = malloc((c->nnz ? c->nnz : 1) * sizeof *c->vals);
  if (!c->x || !c->v || !c->g || !c->hv || !c->vals) return 1;
  s = rn_network_get_dofs(c->net, c->x);
  if (s) {
    rn_bench_report_error("get_dofs", ctx, s);
    return 1;
  }
  uint64_t seed = 0x9E3779B97F4A7C15ULL ^ (uint64_t)nv;
  double h = 1.0 / (double)(nv - 1);
  for (size_t i = 0; i < c->n; ++i) {
    c->x[i] += 1e-2 * h * rn_bench_rand(&seed);
    c->v[i] = rn_bench_rand(&seed);
  }
  return 0;
}

static int bench_one(rn_context *ctx, const bench_opts *o, rn_bench_shape shape, long nv,
                     FILE *out) {
  bench_case c;
  int rc = case_init(ctx, shape, nv, &c);
  for (int op = 0; op < OP_COUNT && !rc; ++op)
    rc = time_op(&c, (op_kind)op, o, shape, nv, ctx, out);
  if (!rc) {
    double err = hvp_vs_csr(&c);
    if (!(err <= 1e-12)) {
      fprintf(stderr, "bench: HVP and CSR Hessian disagree at %ld vertices: %.3e\n", nv,
              err);
      rc = 1;
    }
  }
  case_free(&c);
  return rc;
}

static int parse_shapes(void *opts, const char *s) {
  bench_opts *o = opts;
  char buf[64];
  o->n_shapes = 0;
  if (strlen(s) >= sizeof buf) return -1;
  strcpy(buf, s);
  for (char *tok = strtok(buf, ","); tok; tok = strtok(NULL, ",")) {
    if (o->n_shapes == 2 || rn_bench_shape_from_name(tok, &o->shapes[o->n_shapes]))
      return -1;
    o->n_shapes++;
  }
  return o->n_shapes > 0 ? 0 : -1;
}

static const rn_bench_cli cli = {
    "bench_kernels",
    "usage: bench_kernels [--sizes 100,1000,10000,100000] [--shapes straight,curved]\n"
    "                     [--repeats N] [--min-time SECONDS] [--out FILE.csv]\n",
    "kernel throughput"};

static int parse_args(int argc, char **argv, void *opts) {
  bench_opts *o = opts;
  o->n_sizes = rn_bench_parse_list("100,1000,10000,100000", o->sizes, MAX_LIST);
  o->shapes[0] = RN_BENCH_STRAIGHT;
  o->shapes[1] = RN_BENCH_CURVED;
  o->n_shapes = 2;
  o->repeats = 11;
  o->min_time = 0.2;
  o->out = NULL;
  const rn_bench_option opt[] = {
      {"--sizes", RN_BENCH_LIST, o->sizes, &o->n_sizes, MAX_LIST, NULL, NULL},
      {"--shapes", RN_BENCH_CALL, NULL, NULL, 0, parse_shapes, "bad --shapes"},
      {"--repeats", RN_BENCH_INT, &o->repeats, NULL, 0, NULL, NULL},
      {"--min-time", RN_BENCH_DOUBLE, &o->min_time, NULL, 0, NULL, NULL},
      {"--out", RN_BENCH_STRING, &o->out, NULL, 0, NULL, NULL}};
  int rc = rn_bench_parse_args(argc, argv, opt, sizeof opt / sizeof *opt, o, &cli);
  if (rc) return rc;
  if (o->n_sizes < 0) return rn_bench_bad_args(&cli, "bad --sizes");
  for (int k = 0; k < o->n_sizes; ++k)
    if (o->sizes[k] < 3 || o->sizes[k] > 100000000)
      return rn_bench_bad_args(&cli, "sizes in [3, 1e8]");
  if (o->repeats < 1 || !(o->min_time >= 0.0))
    return rn_bench_bad_args(&cli, "bad --repeats/--min-time");
  return 0;
}

/* Every shape of --shapes at every size of --sizes. */
static int run_all(rn_bench_run *run, const void *opts) {
  const bench_opts *o = opts;
  int rc = 0;
  for (int s = 0; s < o->n_shapes && !rc; ++s)
    for (int k = 0; k < o->n_sizes && !rc; ++k)
      rc = bench_one(run->ctx, o, o->shapes[s], o->sizes[k], run->out);
  return rc;
}

static const rn_bench_program program = {
    parse_args,
    "op,dofs,nnz,batch,median_per_vertex,min_per_vertex,flops_per_vertex,"
    "divsqrt_per_vertex,bytes_per_vertex,gflops,peak_gflops,peak_fraction,gbytes_per_s",
    run_all};

int main(int argc, char **argv) {
  bench_opts o = {0};
  return rn_bench_main(argc, argv, &program, &o, &o.out);
}
