/* cli_bench.c - `rodnet bench [--suite quick|full] [--solvers A,B,...] -o DIR`: the
 * optimiser benchmark (docs/benchmarking.md).  Every problem of the suite's
 * manifest (benchmarks/suite/suite.json) is solved by every solver selected
 * (the default selection below, or --solvers); one CSV row per problem and solver goes to
 * DIR/runs.csv, and benchmarks/bench_profiles.py draws the performance and data profiles
 * from it. */
#define _GNU_SOURCE /* dl_iterate_phdr, gethostname */
#include <cjson/cJSON.h>
#include <errno.h>
#include <link.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "io/atomic_file.h"
#include "cli/cli.h"
#include "cli/cli_registry.h"
#include "io/num_format.h"
#include "rodnet_solve.h"
#include "rodnet_registry.h"
#include "scene/scene.h"
#include "io/text_file.h"

#ifndef RN_BENCH_SUITE
#define RN_BENCH_SUITE "benchmarks/suite/suite.json"
#endif
#ifndef RN_PLOT_BENCH_SCRIPT
#define RN_PLOT_BENCH_SCRIPT "benchmarks/bench_profiles.py"
#endif
#ifndef RN_BUILD_COMMIT
#define RN_BUILD_COMMIT "unknown"
#endif
#ifndef RN_BUILD_COMPILER
#define RN_BUILD_COMPILER "unknown"
#endif
#ifndef RN_BUILD_FLAGS
#define RN_BUILD_FLAGS ""
#endif

/* ---- the solvers -------------------------------------------------------------
 * A solver of the benchmark: a solver kind of the library's registry
 * (rodnet_registry.h) and, for the kinds that take one, a preconditioner, named
 * KIND or KIND-PRECONDITIONER (the CSV's solver column, e.g. tr-krylov-dd); and its
 * iteration limit (0: the rn_solve default, or the scene's).  --solvers picks any of
 * them; without it the default selection below runs (docs/benchmarking.md). */
typedef struct bench_solver {
  char name[48];
  rn_solver_kind kind;
  rn_preconditioner precond;
  int max_iterations;
  int max_load_cuts; /* -1: default */
} bench_solver;

/* The default selection, in this order (first in the table). */
static const struct {
  rn_solver_kind kind;
  rn_preconditioner precond;
} default_solvers[] = {
    {RN_SOLVER_TR_MINRES, RN_PRECOND_AUTO},     {RN_SOLVER_TR_KRYLOV, RN_PRECOND_DD},
    {RN_SOLVER_TR_KRYLOV, RN_PRECOND_FACTOR},   {RN_SOLVER_ROL_TR_TCG, RN_PRECOND_AUTO},
    {RN_SOLVER_ROL_LS_NEWTON, RN_PRECOND_AUTO}, {RN_SOLVER_NOX, RN_PRECOND_DD},
    {RN_SOLVER_ROL_LBFGS, RN_PRECOND_AUTO}};
enum {
  N_DEFAULT_SOLVERS = (int)(sizeof default_solvers / sizeof default_solvers[0]),
  NSOLVERS = 64 /* room for every pair of the registry (the runs' stride) */
};
static bench_solver solvers[NSOLVERS];
static int n_solvers; /* filled by bench_solvers_make */

/* Appends the pair (kind, precond) to solvers[] unless it is there. */
static void add_solver(const rn_solver_info *k, const rn_preconditioner_info *p) {
  for (int i = 0; i < n_solvers; i++)
    if (solvers[i].kind == k->value && solvers[i].precond == (p ? p->value : 0)) return;
  if (n_solvers == NSOLVERS) return;
  bench_solver *s = &solvers[n_solvers++];
  snprintf(s->name, sizeof s->name, "%s%s%s", k->name, p ? "-" : "", p ? p->name : "");
  s->kind = k->value;
  s->precond = p ? p->value : RN_PRECOND_AUTO;
  /* first order: more iterations, and a failed attempt is final (no load cuts,
   * each of which would cost as much again) */
  s->max_iterations = k->value == RN_SOLVER_ROL_LBFGS ? 3000 : 0;
  s->max_load_cuts = k->value == RN_SOLVER_ROL_LBFGS ? 0 : -1;
}

/* solvers[]: the default selection, then every other pair of the registry (the
 * preconditioners that stand for another, auto, not as a name of their own). */
static void bench_solvers_make(void) {
  if (n_solvers) return;
  for (int i = 0; i < N_DEFAULT_SOLVERS; i++) {
    const rn_solver_info *k = rn_solver_info_of(default_solvers[i].kind);
    add_solver(k, k->flags & RN_SOLVER_TAKES_PRECONDITIONER
                      ? rn_preconditioner_info_of(default_solvers[i].precond)
                      : NULL);
  }
  const rn_solver_info *k;
  for (size_t i = 0; (k = rn_solver_info_at(i)) != NULL; i++) {
    if (!(k->flags & RN_SOLVER_TAKES_PRECONDITIONER)) {
      add_solver(k, NULL);
      continue;
    }
    const rn_preconditioner_info *p;
    for (size_t j = 0; (p = rn_preconditioner_info_at(j)) != NULL; j++)
      if (!(p->flags & RN_PC_ALIAS)) add_solver(k, p);
  }
}

/* The names of solvers[first, last) into buf[n], comma-separated. */
static void solver_names(int first, int last, char *buf, size_t n) {
  size_t len = 0;
  buf[0] = '\0';
  for (int k = first; k < last; k++) {
    const char *sep = k > first ? ", " : "";
    const size_t a = strlen(sep), b = strlen(solvers[k].name);
    if (len + a + b >= n) break;
    memcpy(buf + len, sep, a);
    memcpy(buf + len + a, solvers[k].name, b + 1);
    len += a + b;
  }
}

static const char bench_help[] =
    "Usage: rodnet bench [--suite smoke|quick|full] [--solvers A,B,...] -o DIR\n"
    "\n"
    "Run the optimiser benchmark: every problem of the suite against every\n"
    "solver; write DIR/runs.csv (one row per problem and solver: converged,\n"
    "verified minimum, iterations, gradients, HVPs, Krylov iterations, final\n"
    "gradient norm, error against the stored reference, time, and the machine,\n"
    "commit, compiler and flags) and, by python3 with matplotlib, the\n"
    "Dolan-More performance profiles DIR/profile_time.png, DIR/profile_hvp.png,\n"
    "the data profile DIR/data_profile.png and DIR/profile_summary.csv\n"
    "(docs/benchmarking.md).\n"
    "\n"
    "Options:\n"
    "  -o, --output DIR    directory to write (created if missing; required)\n"
    "      --suite NAME    smoke (3 small problems), quick (default: under two\n"
    "                      minutes) or full\n";
/* then the --solvers rows (print_bench_help), then: */
static const char bench_help_tail[] =
    "      --problems LIST only these problems of the manifest (comma-separated;\n"
    "                      whatever suites they belong to)\n"
    "      --manifest FILE the suite's manifest (default: the source tree's\n"
    "                      benchmarks/suite/suite.json; RODNET_BENCH_SUITE)\n"
    "      --repeats N     solve each pair N times, report the median time\n"
    "                      (default 1)\n"
    "      --no-plot       write runs.csv only\n"
    "      --write-references  solve every problem of the suite with tr-minres\n"
    "                      to gtol 1e-11 and write its reference answer (the\n"
    "                      vertex positions) to the manifest's reference path\n"
    "  -q, --quiet         no line per run on stderr\n"
    "  -h, --help          show this help\n"
    "\n"
    "Exit status: 0 done (whatever the solvers did), 2 usage error, 3 bad\n"
    "manifest, scene or output path, 4 internal error or failed plot.\n";

/* The names of solvers[first, last) after a label, wrapped at 80 columns from
 * column 22. */
static void print_solver_list(const char *label, int first, int last) {
  int col = printf("%22s%s", "", label);
  for (int k = first; k < last; k++) {
    const int len = (int)strlen(solvers[k].name) + (k + 1 < last ? 1 : 0);
    if (col + 1 + len > 80) col = printf("\n%21s", "") - 1;
    col += printf(" %s%s", solvers[k].name, k + 1 < last ? "," : "");
  }
  fputc('\n', stdout);
}

static void print_bench_help(void) {
  char which[128];
  rn_cli_preconditioned_solvers(which, sizeof which);
  fputs(bench_help, stdout);
  printf("      --solvers LIST  comma-separated solvers: a solver kind of `rodnet solve\n"
         "                      --help`, for %s KIND-PRECONDITIONER\n",
         which);
  print_solver_list("default:", 0, N_DEFAULT_SOLVERS);
  print_solver_list("also:", N_DEFAULT_SOLVERS, n_solvers);
  fputs(bench_help_tail, stdout);
}

typedef struct bench_args {
  const char *output, *suite, *solvers, *problems, *manifest;
  int repeats, quiet, no_plot, write_refs;
} bench_args;

/* The options that exclude each other, the lists, the suite: 0 or a usage
 * error. */
static int check_bench_options(const bench_args *a) {
  if (a->write_refs && (a->output || a->solvers || a->repeats != 1 || a->no_plot))
    return rn_cli_usage_error("bench",
                              "--write-references solves with tr-minres once and writes "
                              "the references only: %s does not apply",
                              a->output    ? "-o"
                              : a->solvers ? "--solvers"
                              : a->no_plot ? "--no-plot"
                                           : "--repeats");
  if (!a->output && !a->write_refs) return rn_cli_usage_error("bench", "missing -o DIR");
  /* an empty list (or item) would select nothing and run nothing */
  const char *lists[2] = {a->solvers, a->problems},
             *opts[2] = {"--solvers", "--problems"};
  for (int k = 0; k < 2; k++)
    if (lists[k] && (!*lists[k] || strstr(lists[k], ",,") || *lists[k] == ',' ||
                     lists[k][strlen(lists[k]) - 1] == ','))
      return rn_cli_usage_error("bench",
                                "%s '%s': an empty name; give a comma-separated "
                                "list of names",
                                opts[k], lists[k]);
  if (strcmp(a->suite, "smoke") && strcmp(a->suite, "quick") && strcmp(a->suite, "full"))
    return rn_cli_usage_error("bench", "--suite expects smoke, quick or full, got '%s'",
                              a->suite);
  return 0;
}

static int parse_bench_args(int argc, char **argv, bench_args *a) {
  bench_solvers_make();
  memset(a, 0, sizeof *a);
  a->suite = "quick";
  a->repeats = 1;
  for (int i = 1; i < argc; i++) {
    const char *s = argv[i], *v = NULL;
    int m = 0;
    if (strcmp(s, "-h") == 0 || strcmp(s, "--help") == 0) {
      print_bench_help();
      return -1;
    }
    if (strcmp(s, "-q") == 0 || strcmp(s, "--quiet") == 0)
      a->quiet = 1;
    else if (strcmp(s, "--no-plot") == 0)
      a->no_plot = 1;
    else if (strcmp(s, "--write-references") == 0)
      a->write_refs = 1;
    else if ((m = rn_cli_option_value("bench", argc, argv, &i, "--output", "-o", &v)))
      a->output = v;
    else if ((m = rn_cli_option_value("bench", argc, argv, &i, "--suite", NULL, &v)))
      a->suite = v;
    else if ((m = rn_cli_option_value("bench", argc, argv, &i, "--solvers", NULL, &v)))
      a->solvers = v;
    else if ((m = rn_cli_option_value("bench", argc, argv, &i, "--problems", NULL, &v)))
      a->problems = v;
    else if ((m = rn_cli_option_value("bench", argc, argv, &i, "--manifest", NULL, &v)))
      a->manifest = v;
    else if ((m = rn_cli_option_value("bench", argc, argv, &i, "--repeats", NULL, &v))) {
      if (m > 0 && rn_cli_parse_int("bench", "--repeats", v, 1, 1000, &a->repeats))
        return RN_EXIT_USAGE;
    } else if (s[0] == '-')
      return rn_cli_usage_error("bench", "unknown option '%s'", s);
    else
      return rn_cli_usage_error("bench", "unexpected argument '%s'", s);
    if (m < 0) return RN_EXIT_USAGE;
  }
  static const char *const valued[] = {"--output|-o", "--suite",    "--solvers",
                                       "--problems",  "--manifest", "--repeats",
                                       NULL};
  int rc = rn_cli_check_repeats("bench", argc, argv, valued);
  if (rc) return rc;
  if ((rc = check_bench_options(a))) return rc;
  if (a->solvers) {
    for (const char *p = a->solvers; *p;) {
      const char *c = strchr(p, ',');
      size_t len = c ? (size_t)(c - p) : strlen(p);
      int found = 0;
      for (int k = 0; k < n_solvers; k++)
        found |= strlen(solvers[k].name) == len && !strncmp(solvers[k].name, p, len);
      if (!found) {
        char known[1024];
        solver_names(0, n_solvers, known, sizeof known);
        return rn_cli_usage_error("bench",
                                  "unknown solver '%.*s' in --solvers (known: %s)",
                                  (int)len, p, known);
      }
      if (!c) break;
      p = c + 1;
    }
  }
  if (!a->manifest) a->manifest = getenv("RODNET_BENCH_SUITE");
  if (!a->manifest || !*a->manifest) a->manifest = RN_BENCH_SUITE;
  return 0;
}

#ifdef RN_HAVE_SOLVER

/* 1 if name is an item of the comma-separated list. */
static int in_list(const char *list, const char *name) {
  size_t n = strlen(name);
  for (const char *p = list; p && *p;) {
    const char *c = strchr(p, ',');
    size_t len = c ? (size_t)(c - p) : strlen(p);
    if (len == n && strncmp(p, name, n) == 0) return 1;
    p = c ? c + 1 : NULL;
  }
  return 0;
}

/* ---- the suite's manifest ---------------------------------------------------- */

typedef struct bench_problem {
  char *name, *cls, *scene, *reference; /* paths resolved against the manifest */
  int selected;
} bench_problem;

typedef struct bench_suite {
  bench_problem *p;
  int n;
} bench_suite;

static void suite_free(bench_suite *s) {
  for (int i = 0; i < s->n; i++) {
    free(s->p[i].name);
    free(s->p[i].cls);
    free(s->p[i].scene);
    free(s->p[i].reference);
  }
  free(s->p);
  s->p = NULL;
  s->n = 0;
}

/* dir of base (with its '/') + rel; rel itself when absolute. */
static char *join_path(const char *base, const char *rel) {
  const char *slash = strrchr(base, '/');
  size_t dlen = rel[0] == '/' || !slash ? 0 : (size_t)(slash - base) + 1;
  char *out = malloc(dlen + strlen(rel) + 1);
  if (!out) return NULL;
  memcpy(out, base, dlen);
  strcpy(out + dlen, rel);
  return out;
}

/* A string member of obj (NULL if absent); an error message when the wrong type. */
static const char *member_string(const cJSON *obj, const char *key, int *bad) {
  const cJSON *v = cJSON_GetObjectItemCaseSensitive(obj, key);
  if (!v) return NULL;
  if (!cJSON_IsString(v) || !v->valuestring[0]) {
    *bad = 1;
    return NULL;
  }
  return v->valuestring;
}

/* Read the manifest; select the problems of suite (and of the --problems list).
 * 0 or an exit status (message printed). */
/* The manifest's JSON into *root, its array "problems" into *list; 0 or an
 * exit status (message printed). */
static int read_manifest(const char *manifest, cJSON **root, const cJSON **list) {
  rn_context *ctx = NULL;
  char *text = NULL;
  size_t len = 0;
  *root = NULL;
  if (rn_context_create(&ctx) != RN_OK) return RN_EXIT_INTERNAL;
  if (rn_text_file_read(ctx, manifest, (size_t)1 << 24, &text, &len) != RN_OK) {
    fprintf(stderr, "rodnet bench: %s\n", rn_context_last_error(ctx));
    rn_context_destroy(&ctx);
    return RN_EXIT_INPUT;
  }
  rn_context_destroy(&ctx);
  *root = cJSON_ParseWithLength(text, len);
  free(text);
  *list = *root ? cJSON_GetObjectItemCaseSensitive(*root, "problems") : NULL;
  if (!cJSON_IsArray(*list)) {
    fprintf(stderr, "rodnet bench: %s: %s\n", manifest,
            *root ? "no array \"problems\"" : "not valid JSON");
    cJSON_Delete(*root);
    *root = NULL;
    return RN_EXIT_INPUT;
  }
  return 0;
}

/* Every name of the --problems list is a problem of the manifest: 0, else a
 * usage error (message printed). */
static int check_problem_names(const bench_args *a, const bench_suite *s) {
  for (const char *q = a->problems; *q;) {
    const char *c = strchr(q, ',');
    size_t l = c ? (size_t)(c - q) : strlen(q);
    int found = 0;
    for (int i = 0; i < s->n; i++)
      found |= strlen(s->p[i].name) == l && !strncmp(s->p[i].name, q, l);
    if (!found) {
      fprintf(stderr, "rodnet bench: %s has no problem '%.*s'\n", a->manifest, (int)l, q);
      return RN_EXIT_USAGE;
    }
    q = c ? c + 1 : q + l;
  }
  return 0;
}

static int suite_load(const bench_args *a, bench_suite *s) {
  cJSON *root = NULL;
  const cJSON *list = NULL;
  memset(s, 0, sizeof *s);
  int rc = read_manifest(a->manifest, &root, &list);
  if (rc) return rc;
  int n = cJSON_GetArraySize(list), idx = 0;
  s->p = calloc((size_t)n + 1, sizeof *s->p);
  if (!s->p) rc = RN_EXIT_INTERNAL;
  for (const cJSON *e = list->child; e && !rc; e = e->next, idx++) {
    int bad = !cJSON_IsObject(e);
    const char *name = bad ? NULL : member_string(e, "name", &bad);
    const char *cls = bad ? NULL : member_string(e, "class", &bad);
    const char *scene = bad ? NULL : member_string(e, "scene", &bad);
    const char *ref = bad ? NULL : member_string(e, "reference", &bad);
    const cJSON *suites = bad ? NULL : cJSON_GetObjectItemCaseSensitive(e, "suites");
    if (bad || !name || !scene || !cJSON_IsArray(suites)) {
      fprintf(stderr,
              "rodnet bench: %s: problems[%d]: needs \"name\", \"scene\" (strings) and "
              "\"suites\" (an array); \"class\" and \"reference\" are optional "
              "strings\n",
              a->manifest, idx);
      rc = RN_EXIT_INPUT;
      break;
    }
    bench_problem *p = &s->p[s->n++];
    p->name = strdup(name);
    p->cls = strdup(cls ? cls : "");
    p->scene = join_path(a->manifest, scene);
    p->reference = ref ? join_path(a->manifest, ref) : NULL;
    if (!p->name || !p->cls || !p->scene || (ref && !p->reference)) rc = RN_EXIT_INTERNAL;
    for (const cJSON *t = suites->child; t; t = t->next)
      if (cJSON_IsString(t) && strcmp(t->valuestring, a->suite) == 0) p->selected = 1;
    if (a->problems) p->selected = in_list(a->problems, name);
  }
  cJSON_Delete(root);
  if (rc == RN_EXIT_INTERNAL) fprintf(stderr, "rodnet bench: out of memory\n");
  if (!rc && a->problems) rc = check_problem_names(a, s); /* every name must exist */
  if (rc) suite_free(s);
  return rc;
}

/* ---- one run ---------------------------------------------------------------- */

/* All vertex positions of the network, rod after rod: a malloc'd array of
 * 3 * (*nv) doubles, NULL when out of memory. */
static double *all_vertices(const rn_network *net, long *nv) {
  long total = 0;
  int nr = rn_network_num_rods(net);
  for (int r = 0; r < nr; r++) total += rn_network_rod_num_vertices(net, r);
  double *x = malloc(sizeof(double) * 3 * (size_t)(total > 0 ? total : 1));
  long off = 0;
  for (int r = 0; x && r < nr; r++) {
    rn_network_rod_vertices(net, r, x + 3 * off);
    off += rn_network_rod_num_vertices(net, r);
  }
  *nv = total;
  return x;
}

/* Whether the state is a verified local minimum (rn_network_stability: the
 * lowest eigenvalue of the reduced Hessian outside the zero modes above 1e-12
 * ||H||_inf, no zero modes): 1 verified, 0 not, -1 could not tell; *lowest its
 * lowest eigenvalue (NAN if not computed). */
static int verified_minimum(rn_network *net, double *lowest) {
  rn_stability sb;
  *lowest = NAN;
  if (rn_network_stability(net, &sb) != RN_OK || !sb.checked) return -1;
  *lowest = sb.lowest_eigenvalue;
  return sb.verified_minimum != 0;
}

typedef struct bench_run {
  rn_solve_report rep;
  double time_median, time_min, error, lowest;
  int verified, repeats, status_ok;
  size_t dofs;
  long vertices;
  char message[256];
} bench_run;

/* A reference answer: the vertex positions. */
typedef struct bench_ref {
  double *x;
  long nv;
} bench_ref;

/* Read a reference answer ({"vertices": [[x, y, z], ...]}); x NULL if the file
 * is missing; an exit status if it is malformed. */
static int ref_load(const char *path, bench_ref *ref) {
  memset(ref, 0, sizeof *ref);
  struct stat st;
  if (!path || stat(path, &st) != 0) return 0;
  rn_context *ctx = NULL;
  char *text = NULL;
  size_t len = 0;
  if (rn_context_create(&ctx) != RN_OK) return RN_EXIT_INTERNAL;
  rn_status s = rn_text_file_read(ctx, path, (size_t)1 << 28, &text, &len);
  if (s) fprintf(stderr, "rodnet bench: %s\n", rn_context_last_error(ctx));
  rn_context_destroy(&ctx);
  if (s) return RN_EXIT_INPUT;
  cJSON *root = cJSON_ParseWithLength(text, len);
  free(text);
  const cJSON *v = root ? cJSON_GetObjectItemCaseSensitive(root, "vertices") : NULL;
  int n = cJSON_IsArray(v) ? cJSON_GetArraySize(v) : -1, i = 0, ok = n > 0;
  ref->x = ok ? malloc(sizeof(double) * 3 * (size_t)n) : NULL;
  for (const cJSON *e = ok ? v->child : NULL; e && ok; e = e->next, i++) {
    ok = cJSON_IsArray(e) && cJSON_GetArraySize(e) == 3 && ref->x;
    for (int k = 0; ok && k < 3; k++) {
      const cJSON *c = cJSON_GetArrayItem(e, k);
      ok = cJSON_IsNumber(c);
      if (ok) ref->x[3 * i + k] = c->valuedouble;
    }
  }
  cJSON_Delete(root);
  if (!ok) {
    fprintf(stderr,
            "rodnet bench: %s: not a reference answer (needs \"vertices\": "
            "[[x, y, z], ...]; rodnet bench --write-references writes them)\n",
            path);
    free(ref->x);
    ref->x = NULL;
    return RN_EXIT_INPUT;
  }
  ref->nv = n;
  return 0;
}

/* Largest vertex distance from the reference over the largest displacement of
 * the reference from the start (the size of the answer); NAN if the counts
 * differ. */
static double answer_error(const double *x, long nv, const double *x0,
                           const bench_ref *ref) {
  if (!ref->x || ref->nv != nv) return NAN;
  double err = 0.0, disp = 0.0;
  for (long i = 0; i < nv; i++) {
    double d2 = 0.0, u2 = 0.0;
    for (int k = 0; k < 3; k++) {
      double d = x[3 * i + k] - ref->x[3 * i + k], u = ref->x[3 * i + k] - x0[3 * i + k];
      d2 += d * d;
      u2 += u * u;
    }
    err = fmax(err, sqrt(d2));
    disp = fmax(disp, sqrt(u2));
  }
  return disp > 0.0 ? err / disp : err;
}

static int cmp_double(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

/* Solve the scene with solver s once; returns the solve's time.  first: the
 * first run, whose counters, answer check and stability fill it (else NULL). */
static double solve_scene(rn_context *ctx, rn_scene *scene, const bench_solver *s,
                          const bench_ref *ref, bench_run *first) {
  rn_network *net = rn_scene_network(scene);
  rn_solve_options opt;
  rn_solve_report rep;
  rn_solve_options_default(&opt);
  rn_scene_apply_solver(scene, &opt);
  opt.solver = s->kind;
  opt.preconditioner = s->precond;
  if (s->max_iterations > 0) opt.max_iterations = s->max_iterations;
  if (s->max_load_cuts >= 0) opt.max_load_cuts = s->max_load_cuts;
  opt.stability = 0; /* checked below, outside the solve's time */
  long nv = 0;
  double *x0 = first ? all_vertices(net, &nv) : NULL;
  memset(&rep, 0, sizeof rep);
  rn_status st = rn_solve(net, &opt, &rep);
  if (first) {
    bench_run *r = first;
    r->rep = rep;
    r->status_ok = st == RN_OK;
    r->dofs = rn_network_num_dofs(net);
    r->vertices = nv;
    if (st) snprintf(r->message, sizeof r->message, "%s", rn_context_last_error(ctx));
    if (!st && rep.converged) r->verified = verified_minimum(net, &r->lowest);
    double *x = all_vertices(net, &nv);
    if (x && x0 && !st) r->error = answer_error(x, nv, x0, ref);
    free(x);
  }
  free(x0);
  return rep.time_s;
}

/* Solve problem p with solver s (repeats times, the first run's counters);
 * fills r.  0, or an exit status for a scene that cannot be read. */
static int run_one(const bench_args *a, const bench_problem *p, const bench_solver *s,
                   const bench_ref *ref, bench_run *r) {
  memset(r, 0, sizeof *r);
  r->error = r->lowest = NAN;
  r->verified = -1;
  double *times = calloc((size_t)a->repeats, sizeof(double));
  if (!times) return RN_EXIT_INTERNAL;
  int rc = 0;
  for (int k = 0; k < a->repeats && !rc; k++) {
    rn_context *ctx = NULL;
    rn_scene *scene = NULL;
    if (rn_context_create(&ctx) != RN_OK) {
      rc = RN_EXIT_INTERNAL;
      break;
    }
    rn_status st = rn_scene_load(ctx, p->scene, &scene);
    if (st) {
      fprintf(stderr, "rodnet bench: problem %s: %s\n", p->name,
              rn_context_last_error(ctx));
      rc = rn_cli_load_exit_code(st);
    } else
      times[k] = solve_scene(ctx, scene, s, ref, k == 0 ? r : NULL);
    rn_scene_destroy(&scene);
    rn_context_destroy(&ctx);
  }
  if (!rc) {
    qsort(times, (size_t)a->repeats, sizeof(double), cmp_double);
    r->time_min = times[0];
    r->time_median = a->repeats % 2
                         ? times[a->repeats / 2]
                         : 0.5 * (times[a->repeats / 2 - 1] + times[a->repeats / 2]);
    r->repeats = a->repeats;
  }
  free(times);
  return rc;
}

/* ---- the machine ---------------------------------------------------------------- */

typedef struct machine_info {
  char cpu[128], blas[256], host[64], date[32];
  long cores;
} machine_info;

static int find_blas(struct dl_phdr_info *info, size_t size, void *user) {
  (void)size;
  machine_info *m = user;
  const char *name = info->dlpi_name;
  if (name && strstr(name, "blas") && !m->blas[0]) {
    char *real = realpath(name, NULL);
    snprintf(m->blas, sizeof m->blas, "%s", real ? real : name);
    free(real);
  }
  return 0;
}

static void machine_probe(machine_info *m) {
  memset(m, 0, sizeof *m);
  FILE *f = fopen("/proc/cpuinfo", "r");
  char line[512];
  while (f && fgets(line, sizeof line, f))
    if (strncmp(line, "model name", 10) == 0) {
      const char *c = strchr(line, ':');
      if (c) snprintf(m->cpu, sizeof m->cpu, "%s", c + 2);
      m->cpu[strcspn(m->cpu, "\n")] = '\0';
      break;
    }
  if (f) fclose(f);
  if (!m->cpu[0]) snprintf(m->cpu, sizeof m->cpu, "unknown");
  m->cores = sysconf(_SC_NPROCESSORS_ONLN);
  dl_iterate_phdr(find_blas, m);
  if (!m->blas[0]) snprintf(m->blas, sizeof m->blas, "unknown");
  if (gethostname(m->host, sizeof m->host - 1) != 0) snprintf(m->host, 8, "unknown");
  time_t now = time(NULL);
  struct tm tm;
  gmtime_r(&now, &tm);
  strftime(m->date, sizeof m->date, "%Y-%m-%dT%H:%M:%SZ", &tm);
}

/* ---- output ---------------------------------------------------------------------- */

typedef struct bench_table {
  const bench_args *a;
  const bench_suite *suite;
  const machine_info *m;
  bench_run *runs; /* [problem * NSOLVERS + solver] */
  const int *ran;  /* the same index: 1 if run */
} bench_table;

/* A CSV field: quoted, inner quotes doubled. */
static void csv_text(FILE *f, const char *s) {
  fputc('"', f);
  for (; *s; s++) {
    if (*s == '"') fputc('"', f);
    fputc(*s, f);
  }
  fputc('"', f);
}

/* A number, or an empty field for one not available: a run that failed or a
 * quantity not computed (NaN) or a solver that diverged (infinite); documented
 * in docs/benchmarking.md ("empty"). */
static void csv_number(FILE *f, double v) {
  if (isfinite(v)) fprintf(f, "%.6e", v);
}

static rn_status write_csv(FILE *f, void *user, rn_context *ctx) {
  (void)ctx;
  const bench_table *t = user;
  fprintf(f, "problem,class,solver,converged,verified_minimum,iterations,gradients,hvps,"
             "krylov_iterations,gradient_norm,error,time_s,time_min_s,repeats,stop,"
             "energy,lowest_eigenvalue,energy_evals,factorizations,load_steps,dofs,"
             "suite,commit,compiler,flags,cpu,cores,blas,host,date\n");
  for (int i = 0; i < t->suite->n; i++)
    for (int k = 0; k < n_solvers; k++) {
      if (!t->ran[i * NSOLVERS + k]) continue;
      const bench_run *r = &t->runs[i * NSOLVERS + k];
      const bench_problem *p = &t->suite->p[i];
      fprintf(f, "%s,%s,%s,%d,", p->name, p->cls, solvers[k].name, r->rep.converged);
      if (r->verified >= 0) fprintf(f, "%d", r->verified);
      fprintf(f, ",%d,%ld,%ld,%ld,", r->rep.iterations, r->rep.gradient_evals,
              r->rep.hvp_evals, r->rep.krylov_iterations);
      csv_number(f, r->status_ok ? r->rep.gradient_norm : NAN);
      fputc(',', f);
      csv_number(f, r->error);
      fprintf(f, ",%.6e,%.6e,%d,%s,", r->time_median, r->time_min, r->repeats,
              r->status_ok ? rn_solve_stop_name(r->rep.stop) : "error");
      csv_number(f, r->status_ok ? r->rep.energy : NAN);
      fputc(',', f);
      csv_number(f, r->lowest);
      fprintf(f, ",%ld,%ld,%d,%zu,%s,", r->rep.energy_evals, r->rep.factorizations,
              r->rep.load_steps, r->dofs, t->a->suite);
      csv_text(f, RN_BUILD_COMMIT);
      fputc(',', f);
      csv_text(f, RN_BUILD_COMPILER);
      fputc(',', f);
      csv_text(f, RN_BUILD_FLAGS);
      fputc(',', f);
      csv_text(f, t->m->cpu);
      fprintf(f, ",%ld,", t->m->cores);
      csv_text(f, t->m->blas);
      fputc(',', f);
      csv_text(f, t->m->host);
      fprintf(f, ",%s\n", t->m->date);
    }
  return ferror(f) ? RN_ERR_IO : RN_OK;
}

/* The reference answer of one solved network. */
typedef struct ref_writer {
  const char *problem, *path;
  const double *x;
  long nv;
  double gtol;
} ref_writer;

static rn_status write_ref(FILE *f, void *user, rn_context *ctx) {
  const ref_writer *w = user;
  rn_num_check chk = {0, 0.0, ""};
  for (long i = 0; i < 3 * w->nv && !chk.bad; i++) {
    char field[64];
    snprintf(field, sizeof field, "vertices[%ld]", i / 3);
    rn_num_checked(&chk, field, w->x[i]);
  }
  if (chk.bad) { /* a reference is never "nan" (issue 22) */
    char msg[512];
    return rn_context_set_error(ctx, RN_ERR_NOT_FINITE, "%s",
                                rn_num_check_message(&chk, w->path, msg, sizeof msg));
  }
  fprintf(f,
          "{\n  \"problem\": \"%s\",\n  \"solver\": \"tr-minres\",\n  \"gtol\": %g,\n"
          "  \"commit\": \"%s\",\n  \"vertices\": [\n",
          w->problem, w->gtol, RN_BUILD_COMMIT);
  for (long i = 0; i < w->nv; i++)
    fprintf(f, "    [%.17g, %.17g, %.17g]%s\n", w->x[3 * i], w->x[3 * i + 1],
            w->x[3 * i + 2], i + 1 < w->nv ? "," : "");
  fprintf(f, "  ]\n}\n");
  return ferror(f) ? RN_ERR_IO : RN_OK;
}

/* --write-references: tr-minres to gtol 1e-11 on every selected problem. */
static int write_references(const bench_args *a, const bench_suite *s) {
  int rc = 0;
  for (int i = 0; i < s->n && !rc; i++) {
    const bench_problem *p = &s->p[i];
    if (!p->selected || !p->reference) continue;
    rn_context *ctx = NULL;
    rn_scene *scene = NULL;
    if (rn_context_create(&ctx) != RN_OK) return RN_EXIT_INTERNAL;
    rn_status st = rn_scene_load(ctx, p->scene, &scene);
    rn_solve_report rep;
    memset(&rep, 0, sizeof rep);
    if (!st) {
      rn_solve_options opt;
      rn_solve_options_default(&opt);
      rn_scene_apply_solver(scene, &opt);
      opt.solver = RN_SOLVER_TR_MINRES;
      opt.gtol_rel = 1e-11;
      st = rn_solve(rn_scene_network(scene), &opt, &rep);
    }
    if (st || !rep.converged) {
      fprintf(stderr, "rodnet bench: %s: no reference: %s\n", p->name,
              st ? rn_context_last_error(ctx) : rn_solve_stop_name(rep.stop));
      rc = st ? rn_cli_load_exit_code(st) : RN_EXIT_INTERNAL;
    } else {
      ref_writer w = {p->name, p->reference, NULL, 0, 1e-11};
      double *x = all_vertices(rn_scene_network(scene), &w.nv);
      w.x = x;
      st = x ? rn_file_write_atomic(ctx, p->reference, write_ref, &w) : RN_ERR_ALLOC;
      if (st) {
        fprintf(stderr, "rodnet bench: %s\n", rn_context_last_error(ctx));
        rc = RN_EXIT_INPUT;
      } else if (!a->quiet)
        fprintf(stderr, "rodnet bench: wrote %s (%d iterations)\n", p->reference,
                rep.iterations);
      free(x);
    }
    rn_scene_destroy(&scene);
    rn_context_destroy(&ctx);
  }
  return rc;
}

/* python3 SCRIPT DIR/runs.csv -o DIR; 0 on success. */
static int run_plot(const char *csv, const char *dir) {
  const char *const args[] = {csv, "-o", dir, NULL};
  /* the script's temporary files (benchmarks/bench_profiles.py), removed if a
   * signal ends the command while it runs (cli_signals.c) */
  static const char *const temps[] = {
      "/profile_time.png.tmp.png", "/profile_hvp.png.tmp.png",
      "/data_profile.png.tmp.png", "/profile_summary.csv.tmp"};
  enum { NTEMPS = (int)(sizeof temps / sizeof temps[0]) };
  char *names[NTEMPS];
  for (int k = 0; k < NTEMPS; k++)
    if ((names[k] = malloc(strlen(dir) + strlen(temps[k]) + 1))) {
      sprintf(names[k], "%s%s", dir, temps[k]);
      rn_cli_temp_file(names[k], 1);
    }
  int rc = rn_cli_run_script("RODNET_PLOT_BENCH", RN_PLOT_BENCH_SCRIPT, args);
  for (int k = 0; k < NTEMPS; k++) {
    if (names[k]) rn_cli_temp_file(names[k], 0);
    free(names[k]);
  }
  return rc;
}

static int make_dir(const char *dir) {
  struct stat st;
  if (stat(dir, &st) == 0) {
    if (S_ISDIR(st.st_mode)) return 0;
    fprintf(stderr, "rodnet bench: %s exists and is not a directory\n", dir);
    return RN_EXIT_INPUT;
  }
  if (mkdir(dir, 0777) != 0) {
    fprintf(stderr, "rodnet bench: cannot create %s: %s\n", dir, strerror(errno));
    return RN_EXIT_INPUT;
  }
  return 0;
}

/* The progress table's row of one run (stderr). */
static void print_run(const bench_problem *p, const bench_solver *solver,
                      const bench_run *r) {
  fprintf(stderr, "%-22s %-17s %4d %3s %6d %7ld %8ld %9.2e %9.2e %9.4f%s%s\n", p->name,
          solver->name, r->rep.converged,
          r->verified < 0 ? "-"
          : r->verified   ? "yes"
                          : "no",
          r->rep.iterations, r->rep.gradient_evals, r->rep.hvp_evals,
          r->rep.gradient_norm, r->error, r->time_median,
          r->status_ok ? "" : "  error: ", r->message);
}

static int run_suite(const bench_args *a, const bench_suite *s) {
  machine_info m;
  machine_probe(&m);
  bench_run *runs = calloc((size_t)s->n * NSOLVERS + 1, sizeof *runs);
  int *ran = calloc((size_t)s->n * NSOLVERS + 1, sizeof *ran);
  size_t dlen = strlen(a->output);
  char *csv = malloc(dlen + 16);
  int rc = runs && ran && csv ? make_dir(a->output) : RN_EXIT_INTERNAL;
  if (csv) sprintf(csv, "%s/runs.csv", a->output);
  rn_context *ctx = NULL;
  if (!rc && rn_context_create(&ctx) != RN_OK) rc = RN_EXIT_INTERNAL;
  if (!rc && rn_file_probe_writable(ctx, csv) != RN_OK) {
    fprintf(stderr, "rodnet bench: %s\n", rn_context_last_error(ctx));
    rc = RN_EXIT_INPUT;
  }
  if (!rc && !a->quiet)
    fprintf(stderr, "%-22s %-17s %4s %3s %6s %7s %8s %9s %9s %9s\n", "problem", "solver",
            "conv", "min", "iter", "grads", "hvps", "|g|", "error", "time[s]");
  for (int i = 0; i < s->n && !rc; i++) {
    const bench_problem *p = &s->p[i];
    if (!p->selected) continue;
    bench_ref ref;
    if ((rc = ref_load(p->reference, &ref))) break;
    for (int k = 0; k < n_solvers && !rc; k++) {
      if (a->solvers ? !in_list(a->solvers, solvers[k].name) : k >= N_DEFAULT_SOLVERS)
        continue;
      bench_run *r = &runs[i * NSOLVERS + k];
      if ((rc = run_one(a, p, &solvers[k], &ref, r))) break;
      ran[i * NSOLVERS + k] = 1;
      if (!a->quiet) print_run(p, &solvers[k], r);
    }
    free(ref.x);
  }
  if (!rc) {
    bench_table t = {a, s, &m, runs, ran};
    if (rn_file_write_atomic(ctx, csv, write_csv, &t) != RN_OK) {
      fprintf(stderr, "rodnet bench: %s\n", rn_context_last_error(ctx));
      rc = RN_EXIT_INTERNAL;
    } else
      printf("rodnet bench: wrote %s (%s, %s)\n", csv, RN_BUILD_COMMIT, m.cpu);
  }
  if (!rc && !a->no_plot && run_plot(csv, a->output) != 0) {
    fprintf(stderr,
            "rodnet bench: the profiles could not be drawn (python3 with matplotlib "
            "running %s; RODNET_PYTHON, RODNET_PLOT_BENCH override them); %s is "
            "written\n",
            getenv("RODNET_PLOT_BENCH") ? getenv("RODNET_PLOT_BENCH")
                                        : RN_PLOT_BENCH_SCRIPT,
            csv);
    rc = RN_EXIT_INTERNAL;
  }
  rn_context_destroy(&ctx);
  free(csv);
  free(runs);
  free(ran);
  return rc;
}

#endif /* RN_HAVE_SOLVER */

#ifdef RN_HAVE_SOLVER
/* The files read and written (cli.h): the manifest and the selected problems'
 * scenes; their references, read, or written by --write-references; the
 * folder's CSV files and profiles.  Before anything is solved: no output is
 * an input or another output, every output is writable.  0 or an exit status. */
static int check_bench_files(const bench_args *a, const bench_suite *s) {
  static const char *const outs[] = {"/runs.csv", "/profile_time.png", "/profile_hvp.png",
                                     "/data_profile.png", "/profile_summary.csv"};
  enum { NOUTS = (int)(sizeof outs / sizeof outs[0]) };
  rn_cli_file *f = calloc(2 * (size_t)s->n + NOUTS + 2, sizeof *f);
  int n = 0, rc;
  if (!f) return RN_EXIT_INTERNAL;
  f[n++] = (rn_cli_file){"the manifest", a->manifest, NULL, RN_CLI_IN};
  for (int i = 0; i < s->n; i++) {
    if (!s->p[i].selected) continue;
    f[n++] = (rn_cli_file){"a problem's scene", s->p[i].scene, NULL, RN_CLI_IN};
    if (s->p[i].reference)
      f[n++] =
          (rn_cli_file){a->write_refs ? "a problem's reference" : "a reference",
                        s->p[i].reference, NULL, a->write_refs ? RN_CLI_OUT : RN_CLI_IN};
  }
  if (!a->write_refs) {
    f[n++] = (rn_cli_file){"-o", a->output, NULL, RN_CLI_OUT_DIR};
    for (int k = 0; k < NOUTS; k++)
      f[n++] = (rn_cli_file){"-o", a->output, outs[k], RN_CLI_OUT};
  }
  rc = rn_cli_check_files("bench", f, n);
  if (!rc) rc = rn_cli_probe_outputs("bench", f, n);
  free(f);
  return rc;
}
#endif

int rn_cli_bench(int argc, char **argv) {
  bench_args a;
  int rc = parse_bench_args(argc, argv, &a);
  if (rc) return rc < 0 ? RN_EXIT_OK : rc;
#ifdef RN_HAVE_SOLVER
  bench_suite s;
  if ((rc = suite_load(&a, &s))) return rc;
  if ((rc = check_bench_files(&a, &s))) {
    suite_free(&s);
    return rc;
  }
  if (rn_runtime_initialize(NULL, NULL) != RN_OK) {
    fprintf(stderr, "rodnet bench: cannot start the solver runtime\n");
    rc = RN_EXIT_INTERNAL;
  } else if (a.write_refs)
    rc = write_references(&a, &s);
  else
    rc = run_suite(&a, &s);
  suite_free(&s);
  rn_runtime_finalize();
  return rc;
#else
  return rn_cli_no_solver("bench");
#endif
}
