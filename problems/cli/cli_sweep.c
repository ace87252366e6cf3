/* cli_sweep.c - `rodnet sweep SWEEP.json -o DIR [--plot PNG]`: homogenisation of
 * periodic cells over a grid of parameters (lattice, joint model, relative
 * density, imperfection seed) from a sweep file (docs/homogenization.md,
 * "Sweeps").  Every point is written atomically as soon as it is done
 * (DIR/point_NNNN.json) with its record (every key of the sweep file at that
 * point, the rodnet version, a hash of the cell scene); a rerun skips the points
 * whose record is unchanged, so a killed sweep loses nothing, and recomputes the
 * others; then DIR/sweep.csv (this sweep's points only) and the plot. */
#define _POSIX_C_SOURCE 200809L
#include <cjson/cJSON.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "io/atomic_file.h"
#include "cli/cli.h"
#include "io/num_format.h"
#include "cli/homog_path.h"
#include "generate/lattice_check.h"
#include "generate/periodic_cell.h"
#include "rodnet_solve.h"
#include "scene/scene.h"
#include "io/text_file.h"

#ifndef RN_PLOT_SWEEP_SCRIPT
#define RN_PLOT_SWEEP_SCRIPT "plot_sweep.py"
#endif

static const char sweep_help[] =
    "Usage: rodnet sweep SWEEP.json -o DIR [--plot PNG] [-q]\n"
    "\n"
    "Effective stiffness of periodic cells over a grid of parameters given by a\n"
    "sweep file (docs/homogenization.md, \"Sweeps\"):\n"
    "  {\"lattice\": \"honeycomb\" or [...], \"joint_model\": \"rigid\" or [...],\n"
    "   \"relative_density\": [...] or {\"from\": a, \"to\": b, \"count\": n,\n"
    "   \"scale\": \"log\" or \"linear\"}, \"seed\": [...], \"perturb\": amp,\n"
    "   \"edges_per_rod\": N, \"cells\": [m, n(, k)], \"E\": 1, \"nu\": 0.3,\n"
    "   \"path\": {\"strain\": [E11, E22, E12] or \"stress\": [...], \"steps\": 20}}\n"
    "Every point (the product of the lists) is written atomically to\n"
    "DIR/point_NNNN.json as soon as it is done, with its record (every parameter\n"
    "of the sweep file at that point, the rodnet version, a hash of its cell\n"
    "scene); a rerun skips the points whose record is unchanged and recomputes the\n"
    "others, so a killed sweep loses nothing.  Then DIR/sweep.csv (atomically) and,\n"
    "with --plot, a PNG of E1 and nu12 against relative density (the frame closed\n"
    "forms on the same axes for the rigid-jointed honeycomb).\n"
    "With \"path\", every point also follows the macroscopic path (null entries:\n"
    "the other control at zero) to its first instability, written to the point\n"
    "file and the CSV.  Under mpirun the points are spread over the ranks (each\n"
    "point on one rank; rank 0 prints the one progress bar and writes the CSV).\n"
    "\n"
    "Options:\n"
    "  -o, --output DIR    output folder (created if missing)\n"
    "      --plot PNG      the plot (python3 with matplotlib)\n"
    "  -q, --quiet         no progress bar\n"
    "  -h, --help          show this help\n"
    "\n"
    "Exit status: 0 done, 2 usage error, 3 bad sweep file or unwritable folder,\n"
    "4 a point failed (the others are written) or the plot failed.\n";

enum { MAX_LIST = 4096 };

typedef struct sweep_spec {
  int nlat, njm, nrho, nseed;
  char lat[16][32];
  int jm[2];
  double rho[MAX_LIST];
  long seed[MAX_LIST];
  double perturb, E, nu;
  int edges, cells[3];
  /* "path": a proportional macroscopic path per point, with its first
   * instability (has_path 0: none) */
  int has_path, path_ns, path_stress_given, path_steps;
  double path_target[6];
  int path_stress[6]; /* per component: 1 stress-controlled */
  rn_bloch_modes path_modes;
  int path_method; /* rn_bloch_method */
} sweep_spec;

typedef struct point {
  int index;
  const char *lattice;
  int joint_model;
  double rho;
  long seed;
} point;

static int sweep_error(const char *file, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;
static int sweep_error(const char *file, const char *fmt, ...) {
  va_list ap;
  if (rn_cli_quiet_rank()) return RN_EXIT_INPUT; /* rank 0 of the MPI job says it */
  fprintf(stderr, "rodnet sweep: %s: ", file);
  va_start(ap, fmt);
  vfprintf(stderr, fmt, ap);
  va_end(ap);
  fputc('\n', stderr);
  return RN_EXIT_INPUT;
}

/* A string or a list of strings into out (at most max). */
static int string_list(const cJSON *v, char (*out)[32], int max, int *n) {
  *n = 0;
  if (cJSON_IsString(v)) {
    snprintf(out[0], 32, "%s", v->valuestring);
    *n = 1;
    return 0;
  }
  if (!cJSON_IsArray(v)) return -1;
  const cJSON *e;
  cJSON_ArrayForEach(e, v) {
    if (!cJSON_IsString(e) || *n >= max) return -1;
    snprintf(out[(*n)++], 32, "%s", e->valuestring);
  }
  return *n > 0 ? 0 : -1;
}

static const char *joint_name(int jm) {
  return jm == RN_JOINT_RIGID ? "rigid" : "elastic";
}

/* ---- the keys of a sweep file and a point's record of them ------------------
 * One table: parse_spec accepts exactly these keys, and the record of a point
 * (its point file's "parameters", compared on a rerun) holds each of them with
 * its effective value at that point (a list key: the point's entry; a key left
 * out: its default), written by the key's own function.  A key added to the
 * sweep file format is added here, with what defines a point by it. */
typedef int (*put_key)(cJSON *rec, const char *name, const sweep_spec *s, const point *p);
static int put_lattice(cJSON *r, const char *k, const sweep_spec *s, const point *p) {
  (void)s;
  return cJSON_AddStringToObject(r, k, p->lattice) != NULL;
}
static int put_joint(cJSON *r, const char *k, const sweep_spec *s, const point *p) {
  (void)s;
  return cJSON_AddStringToObject(r, k, joint_name(p->joint_model)) != NULL;
}
static int put_rho(cJSON *r, const char *k, const sweep_spec *s, const point *p) {
  (void)s;
  return cJSON_AddNumberToObject(r, k, p->rho) != NULL;
}
static int put_seed(cJSON *r, const char *k, const sweep_spec *s, const point *p) {
  (void)s;
  return cJSON_AddNumberToObject(r, k, (double)p->seed) != NULL;
}
static int put_perturb(cJSON *r, const char *k, const sweep_spec *s, const point *p) {
  (void)p;
  return cJSON_AddNumberToObject(r, k, s->perturb) != NULL;
}
static int put_edges(cJSON *r, const char *k, const sweep_spec *s, const point *p) {
  (void)p;
  return cJSON_AddNumberToObject(r, k, s->edges) != NULL;
}
static int put_cells(cJSON *r, const char *k, const sweep_spec *s, const point *p) {
  (void)p;
  cJSON *a = cJSON_CreateIntArray(s->cells, 3);
  return a && cJSON_AddItemToObject(r, k, a);
}
static int put_E(cJSON *r, const char *k, const sweep_spec *s, const point *p) {
  (void)p;
  return cJSON_AddNumberToObject(r, k, s->E) != NULL;
}
static int put_nu(cJSON *r, const char *k, const sweep_spec *s, const point *p) {
  (void)p;
  return cJSON_AddNumberToObject(r, k, s->nu) != NULL;
}
static const char *const bloch_method_names[] = {"auto", "dense", "sparse"};
static const char *const bloch_mode_names[] = {"all", "in-plane", "out-of-plane"};
/* "path" (only when given: a sweep without one keeps the records it had) */
static int put_path(cJSON *r, const char *k, const sweep_spec *s, const point *p) {
  (void)p;
  if (!s->has_path) return 1;
  cJSON *o = cJSON_AddObjectToObject(r, k), *a;
  if (!o || !(a = cJSON_AddArrayToObject(o, s->path_stress_given ? "stress" : "strain")))
    return 0;
  for (int i = 0; i < s->path_ns; ++i) {
    /* an entry of the other control (at zero): null */
    int other = s->path_stress[i] != s->path_stress_given;
    cJSON *e = other ? cJSON_CreateNull() : cJSON_CreateNumber(s->path_target[i]);
    if (!e || !cJSON_AddItemToArray(a, e)) return 0;
  }
  return cJSON_AddNumberToObject(o, "steps", s->path_steps) &&
         cJSON_AddStringToObject(o, "modes", bloch_mode_names[s->path_modes]) &&
         cJSON_AddStringToObject(o, "bloch_method", bloch_method_names[s->path_method]);
}
static const struct {
  const char *name;
  put_key put;
} spec_keys[] = {{"lattice", put_lattice},
                 {"joint_model", put_joint},
                 {"relative_density", put_rho},
                 {"seed", put_seed},
                 {"perturb", put_perturb},
                 {"edges_per_rod", put_edges},
                 {"cells", put_cells},
                 {"E", put_E},
                 {"nu", put_nu},
                 {"path", put_path}};
enum { NKEYS = (int)(sizeof spec_keys / sizeof spec_keys[0]) };

/* The record of point p of sweep s: every key of the table (NULL out of memory). */
static cJSON *point_record(const sweep_spec *s, const point *p) {
  cJSON *rec = cJSON_CreateObject();
  for (int k = 0; rec && k < NKEYS; ++k)
    if (!spec_keys[k].put(rec, spec_keys[k].name, s, p)) {
      cJSON_Delete(rec);
      rec = NULL;
    }
  return rec;
}

/* ---- parse_spec's parts: each reads its keys of the sweep file root into s;
 * 0 or the error's exit status (message printed).  In the order of the
 * checks. */

/* Every key is one of the table's, given once. */
static int check_keys(const char *file, const cJSON *root) {
  const cJSON *e;
  cJSON_ArrayForEach(e, root) {
    int ok = 0;
    for (int k = 0; k < NKEYS; ++k) ok |= strcmp(e->string, spec_keys[k].name) == 0;
    if (!ok) return sweep_error(file, "unknown key '%s'", e->string);
    /* a repeated key: the reader would take the first and ignore the others */
    for (const cJSON *b = root->child; b != e; b = b->next)
      if (strcmp(b->string, e->string) == 0)
        return sweep_error(file, "\"%s\" given more than once: give it once", e->string);
  }
  return 0;
}

static int parse_lattices(const char *file, const cJSON *root, sweep_spec *s) {
  if (string_list(cJSON_GetObjectItemCaseSensitive(root, "lattice"), s->lat, 16,
                  &s->nlat))
    return sweep_error(file, "\"lattice\" must be a lattice name or a list of them");
  for (int k = 0; k < s->nlat; ++k) {
    rn_lattice_kind kind;
    if (strcmp(s->lat[k], "reentrant") &&
        rn_lattice_kind_from_name(s->lat[k], &kind) != 0)
      return sweep_error(file, "unknown lattice '%s'", s->lat[k]);
  }
  return 0;
}

static int parse_joint_models(const char *file, const cJSON *root, sweep_spec *s) {
  const cJSON *v = cJSON_GetObjectItemCaseSensitive(root, "joint_model");
  char jm[2][32];
  s->njm = 1;
  s->jm[0] = RN_JOINT_RIGID;
  if (!v) return 0;
  if (string_list(v, jm, 2, &s->njm))
    return sweep_error(file, "\"joint_model\" must be rigid, elastic or a list");
  for (int k = 0; k < s->njm; ++k) {
    if (strcmp(jm[k], "rigid") == 0)
      s->jm[k] = RN_JOINT_RIGID;
    else if (strcmp(jm[k], "elastic") == 0)
      s->jm[k] = RN_JOINT_ELASTIC;
    else
      return sweep_error(file, "unknown joint model '%s'", jm[k]);
  }
  return 0;
}

/* "relative_density": a list, or a range {from, to, count, scale}. */
static int parse_densities(const char *file, const cJSON *root, sweep_spec *s) {
  const cJSON *v = cJSON_GetObjectItemCaseSensitive(root, "relative_density"), *e;
  if (cJSON_IsArray(v)) {
    cJSON_ArrayForEach(e, v) {
      if (!cJSON_IsNumber(e) || s->nrho >= MAX_LIST || !(e->valuedouble > 0.0) ||
          !(e->valuedouble < 1.0))
        return sweep_error(file,
                           "\"relative_density\"[%d]: the entries must be numbers in "
                           "(0, 1), at most %d of them",
                           s->nrho, MAX_LIST);
      s->rho[s->nrho++] = e->valuedouble;
    }
    return 0;
  }
  if (!cJSON_IsObject(v))
    return sweep_error(file, "\"relative_density\" (a list or a range) is required");
  const cJSON *a = cJSON_GetObjectItemCaseSensitive(v, "from"),
              *b = cJSON_GetObjectItemCaseSensitive(v, "to"),
              *n = cJSON_GetObjectItemCaseSensitive(v, "count"),
              *sc = cJSON_GetObjectItemCaseSensitive(v, "scale");
  int logs = !sc || (cJSON_IsString(sc) && strcmp(sc->valuestring, "log") == 0);
  if (!cJSON_IsNumber(a) || !cJSON_IsNumber(b) || !cJSON_IsNumber(n) ||
      !(a->valuedouble > 0.0) || !(b->valuedouble < 1.0) ||
      !(a->valuedouble <= b->valuedouble) || n->valuedouble < 1 ||
      n->valuedouble > MAX_LIST || n->valuedouble != floor(n->valuedouble) ||
      (sc && !logs && !(cJSON_IsString(sc) && strcmp(sc->valuestring, "linear") == 0)))
    return sweep_error(file, "%s",
                       "\"relative_density\" range needs from <= to in (0, 1), count in "
                       "1 .. 4096, scale log or linear");
  s->nrho = (int)n->valuedouble;
  for (int k = 0; k < s->nrho; ++k) {
    double f = s->nrho > 1 ? (double)k / (s->nrho - 1) : 0.0;
    s->rho[k] = logs ? a->valuedouble * pow(b->valuedouble / a->valuedouble, f)
                     : a->valuedouble + f * (b->valuedouble - a->valuedouble);
  }
  return 0;
}

static int parse_seeds(const char *file, const cJSON *root, sweep_spec *s) {
  const cJSON *v = cJSON_GetObjectItemCaseSensitive(root, "seed"), *e;
  if (!v) return 0;
  s->nseed = 0;
  cJSON_ArrayForEach(e, v) {
    if (!cJSON_IsNumber(e) || s->nseed >= MAX_LIST || e->valuedouble < 0 ||
        e->valuedouble != floor(e->valuedouble))
      return sweep_error(file, "\"seed\"[%d]: the seeds must be integers >= 0", s->nseed);
    s->seed[s->nseed++] = (long)e->valuedouble;
  }
  if (!cJSON_IsArray(v) || s->nseed == 0)
    return sweep_error(file, "\"seed\" must be a list of integers >= 0");
  return 0;
}

/* "perturb" and "edges_per_rod". */
static int parse_cell_options(const char *file, const cJSON *root, sweep_spec *s) {
  const cJSON *v;
  if ((v = cJSON_GetObjectItemCaseSensitive(root, "perturb")) &&
      (!cJSON_IsNumber(v) || !(v->valuedouble >= 0.0) || !(v->valuedouble < 0.5)))
    return sweep_error(file, "\"perturb\" must be in [0, 0.5)");
  if (v) s->perturb = v->valuedouble;
  if ((v = cJSON_GetObjectItemCaseSensitive(root, "edges_per_rod")) &&
      (!cJSON_IsNumber(v) || v->valuedouble < 1 || v->valuedouble > 10000 ||
       v->valuedouble != floor(v->valuedouble)))
    return sweep_error(file, "\"edges_per_rod\" must be an integer in 1 .. 10000");
  if (v) s->edges = (int)v->valuedouble;
  return 0;
}

/* "cells": one count per lattice vector of every lattice swept. */
static int parse_cells(const char *file, const cJSON *root, sweep_spec *s) {
  const cJSON *v = cJSON_GetObjectItemCaseSensitive(root, "cells"), *e;
  int k = 0;
  if (!v) return 0;
  cJSON_ArrayForEach(e, v) {
    if (!cJSON_IsNumber(e) || k >= 3 || e->valuedouble < 1 || e->valuedouble > 1000 ||
        e->valuedouble != floor(e->valuedouble))
      return sweep_error(file, "\"cells\" must be 2 or 3 integers in 1 .. 1000");
    s->cells[k++] = (int)e->valuedouble;
  }
  if (!cJSON_IsArray(v) || k < 2)
    return sweep_error(file, "\"cells\" must be 2 or 3 integers in 1 .. 1000");
  /* one count per lattice vector: a third count of a planar lattice (or a
   * missing one of a 3D lattice) would be ignored (or taken as 1) */
  for (int j = 0; j < s->nlat; ++j) {
    rn_lattice_kind kind = RN_LATTICE_HONEYCOMB;
    if (strcmp(s->lat[j], "reentrant")) rn_lattice_kind_from_name(s->lat[j], &kind);
    int dim = rn_lattice_kind_dimension(kind);
    if (k != dim)
      return sweep_error(file,
                         "\"cells\" has %d counts but the lattice '%s' is %dD: give one "
                         "count per lattice vector (%d)%s",
                         k, s->lat[j], dim, dim,
                         s->nlat > 1 ? "; sweep planar and 3D lattices in separate "
                                       "files"
                                     : "");
  }
  return 0;
}

/* "E" and "nu". */
static int parse_material(const char *file, const cJSON *root, sweep_spec *s) {
  for (int k = 0; k < 2; ++k) {
    const char *name = k ? "nu" : "E";
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(root, name);
    if (!v) continue;
    if (!cJSON_IsNumber(v) || !isfinite(v->valuedouble) ||
        (k == 0 && !(v->valuedouble > 0.0)) ||
        (k == 1 && !(v->valuedouble > -1.0 && v->valuedouble < 0.5)))
      return sweep_error(file, "\"%s\" must be %s", name,
                         k ? "Poisson's ratio, a number in (-1, 0.5)"
                           : "Young's modulus, a finite number > 0");
    *(k ? &s->nu : &s->E) = v->valuedouble;
  }
  return 0;
}

/* The index of str among names[n]; -1 if it is not one (or NULL). */
static int name_index(const char *str, const char *const *names, int n) {
  for (int i = 0; str && i < n; ++i)
    if (strcmp(str, names[i]) == 0) return i;
  return -1;
}

/* "path": {"strain": [...] or "stress": [...], "steps", "modes", "bloch_method"};
 * one entry per strain component of every lattice swept (3 in 2D, 6 in 3D,
 * Voigt order, engineering shear), a number or null (the other control, at
 * zero: null in "strain" is a stress-free component, as '-' of homogenize
 * --path). */
static int parse_path(const char *file, const cJSON *root, sweep_spec *s) {
  const cJSON *v = cJSON_GetObjectItemCaseSensitive(root, "path"), *e;
  if (!v) return 0;
  if (!cJSON_IsObject(v))
    return sweep_error(file, "\"path\" must be an object {\"strain\": [...] or "
                             "\"stress\": [...], \"steps\": N}");
  cJSON_ArrayForEach(e, v) {
    static const char *const keys[] = {"strain", "stress", "steps", "modes",
                                       "bloch_method"};
    if (name_index(e->string, keys, 5) < 0)
      return sweep_error(file,
                         "\"path\": unknown key '%s' (strain, stress, steps, modes, "
                         "bloch_method)",
                         e->string);
  }
  const cJSON *se = cJSON_GetObjectItemCaseSensitive(v, "strain"),
              *ss = cJSON_GetObjectItemCaseSensitive(v, "stress"),
              *st = cJSON_GetObjectItemCaseSensitive(v, "steps"),
              *mo = cJSON_GetObjectItemCaseSensitive(v, "modes"),
              *me = cJSON_GetObjectItemCaseSensitive(v, "bloch_method");
  if (!se == !ss)
    return sweep_error(file, "\"path\" needs exactly one of \"strain\" and \"stress\"");
  const cJSON *t = se ? se : ss;
  const char *tname = se ? "strain" : "stress";
  s->has_path = 1;
  s->path_stress_given = ss != NULL;
  int n = 0, any = 0;
  cJSON_ArrayForEach(e, t) {
    if (n >= 6 || !(cJSON_IsNull(e) || (cJSON_IsNumber(e) && isfinite(e->valuedouble))))
      return sweep_error(file,
                         "\"path\".\"%s\"[%d]: the entries must be finite numbers or "
                         "null (the other control, at zero), at most 6",
                         tname, n);
    s->path_stress[n] = cJSON_IsNull(e) ? !s->path_stress_given : s->path_stress_given;
    s->path_target[n] = cJSON_IsNull(e) ? 0.0 : e->valuedouble;
    any |= !cJSON_IsNull(e) && e->valuedouble != 0.0;
    ++n;
  }
  if (!cJSON_IsArray(t) || !any)
    return sweep_error(file,
                       "\"path\".\"%s\" must be a list with a non-zero entry (the "
                       "path's end)",
                       tname);
  s->path_ns = n;
  for (int j = 0; j < s->nlat; ++j) {
    rn_lattice_kind kind = RN_LATTICE_HONEYCOMB;
    if (strcmp(s->lat[j], "reentrant")) rn_lattice_kind_from_name(s->lat[j], &kind);
    const int dim = rn_lattice_kind_dimension(kind), ns = dim == 2 ? 3 : 6;
    if (n != ns)
      return sweep_error(
          file,
          "\"path\".\"%s\" has %d entries but the lattice '%s' is %dD: "
          "give %d (%s)%s",
          tname, n, s->lat[j], dim, ns, ns == 3 ? "11, 22, 12" : "11, 22, 33, 23, 13, 12",
          s->nlat > 1 ? "; sweep planar and 3D lattices in separate files" : "");
    if (dim == 3 && mo && !(cJSON_IsString(mo) && strcmp(mo->valuestring, "all") == 0))
      return sweep_error(file,
                         "\"path\".\"modes\": the 3D lattice '%s' has no "
                         "in-plane / out-of-plane split of its modes (use \"all\")",
                         s->lat[j]);
  }
  s->path_steps = 20;
  if (st && (!cJSON_IsNumber(st) || st->valuedouble < 1 || st->valuedouble > 10000 ||
             st->valuedouble != floor(st->valuedouble)))
    return sweep_error(file, "\"path\".\"steps\" must be an integer in 1 .. 10000");
  if (st) s->path_steps = (int)st->valuedouble;
  int m = mo ? name_index(cJSON_GetStringValue(mo), bloch_mode_names, 3) : 0;
  if (m < 0)
    return sweep_error(file, "\"path\".\"modes\" must be all, in-plane or out-of-plane");
  s->path_modes = (rn_bloch_modes)m;
  int b = me ? name_index(cJSON_GetStringValue(me), bloch_method_names, 3) : 0;
  if (b < 0)
    return sweep_error(file, "\"path\".\"bloch_method\" must be auto, dense or sparse");
  s->path_method = b;
  return 0;
}

static int parse_spec(const char *file, const char *text, sweep_spec *s) {
  cJSON *root = cJSON_Parse(text);
  int rc = 0;
  memset(s, 0, sizeof(*s));
  s->edges = 16;
  s->cells[0] = s->cells[1] = s->cells[2] = 1;
  s->E = 1.0;
  s->nu = 0.3;
  s->nseed = 1;
  if (!cJSON_IsObject(root)) {
    cJSON_Delete(root);
    return sweep_error(file, "not a JSON object");
  }
  if ((rc = check_keys(file, root)) || (rc = parse_lattices(file, root, s)) ||
      (rc = parse_joint_models(file, root, s)) || (rc = parse_densities(file, root, s)) ||
      (rc = parse_seeds(file, root, s)) || (rc = parse_cell_options(file, root, s)) ||
      (rc = parse_cells(file, root, s)) || (rc = parse_material(file, root, s)) ||
      (rc = parse_path(file, root, s))) {
    cJSON_Delete(root);
    return rc;
  }
  /* the seeds draw the random perturbation only: without one every seed
   * would give the same cell (and the same answer) */
  if (cJSON_GetObjectItemCaseSensitive(root, "seed") && !(s->perturb > 0.0))
    rc = sweep_error(file, "\"seed\" draws the random joint perturbation only: give "
                           "\"perturb\" > 0 (with \"perturb\" 0 every seed gives the "
                           "same cell)");
  cJSON_Delete(root);
  return rc;
}

/* The point's cell and section (rn_pcell_free(c) after a success). */
static rn_status make_cell(rn_context *ctx, const sweep_spec *s, const point *p,
                           rn_pcell *c, rn_lattice_scene *sc) {
  rn_lattice_kind kind = RN_LATTICE_HONEYCOMB;
  rn_status st;
  int reentrant = strcmp(p->lattice, "reentrant") == 0;
  if (!reentrant) rn_lattice_kind_from_name(p->lattice, &kind);
  st = reentrant ? rn_pcell_reentrant(ctx, s->cells, 1.0, c)
                 : rn_pcell_from_lattice(ctx, kind, s->cells, 1.0, c);
  if (st) return st;
  if (s->perturb > 0.0) rn_pcell_perturb(c, s->perturb, (unsigned long)p->seed);
  const rn_lattice_scene sc0 = {"rodnet sweep",
                                s->edges,
                                p->joint_model,
                                s->E,
                                s->nu,
                                RN_LSEC_RECTANGLE,
                                {0.0, 0.0},
                                RN_LLOAD_NONE,
                                0,
                                0.0,
                                0.0,
                                NULL};
  *sc = sc0;
  rn_pcell_section_for_density(c, p->rho, sc);
  return RN_OK;
}

/* The point's cell as a scene file at path. */
static rn_status write_cell(rn_context *ctx, const sweep_spec *s, const point *p,
                            const char *path) {
  rn_pcell c;
  rn_lattice_scene sc;
  rn_status st = make_cell(ctx, s, p, &c, &sc);
  if (st) return st;
  st = rn_pcell_write_scene(ctx, path, &c, &sc, NULL);
  rn_pcell_free(&c);
  return st;
}

/* Every point's cell is a lattice of rods (docs/lattices.md, "Admissible
 * sections"; the bounds of `rodnet generate --periodic`): the section that
 * gives the relative density must leave every bar a free length between its
 * joint zones.  Checked before any point is computed: 0, or RN_EXIT_INPUT with
 * the point named (the density itself is below 1 by the sweep file's rules). */
static int check_cells(rn_context *ctx, const sweep_spec *s, const char *file) {
  int k = 0;
  for (int i = 0; i < s->nlat; ++i)
    for (int j = 0; j < s->njm; ++j)
      for (int c = 0; c < s->nrho; ++c)
        for (int d = 0; d < (s->perturb > 0.0 ? s->nseed : 1); ++d, ++k) {
          point p = {k, s->lat[i], s->jm[j], s->rho[c], s->seed[d]};
          rn_pcell cell;
          rn_lattice_scene sc;
          rn_strut_bounds b;
          if (make_cell(ctx, s, &p, &cell, &sc))
            return sweep_error(file, "the %s cell: %s", p.lattice,
                               rn_context_last_error(ctx));
          int rc = rn_pcell_strut_bounds(&cell, &sc, &b, NULL);
          const double pw = cell.dim == 2 ? 1.0 : 2.0; /* density ~ size^pw */
          rn_pcell_free(&cell);
          if (rc) return sweep_error(file, "out of memory");
          if (b.zero_bar >= 0 || b.coincident_node >= 0)
            return sweep_error(file,
                               "the %s cell%s has a bar of zero length or two bars "
                               "leaving a joint in one direction (\"perturb\" %g)",
                               p.lattice, s->perturb > 0.0 ? " (perturbed)" : "",
                               s->perturb);
          if (!(b.factor > 1.0))
            return sweep_error(
                file,
                "\"relative_density\" %g: the section that gives it to the %s cell%s "
                "makes its struts overlap at the joints (the joint zones cover all of "
                "bar e%d): not a lattice of rods; keep it below %.6g (docs/lattices.md)",
                p.rho, p.lattice, s->perturb > 0.0 ? " (perturbed)" : "", b.joint_bar + 1,
                p.rho * pow(b.factor, pw));
        }
  return 0;
}

typedef struct point_out {
  const point *p;
  const rn_homogenization *h;
  const double *S;
  double seconds;
  const char *path;             /* the file being written (messages) */
  const char *record;           /* point_record, unformatted JSON */
  const char *hash;             /* scene_hash of the cell scene homogenised */
  const rn_cell_path_result *r; /* the sweep's "path" (NULL: none) */
  double path_seconds;
} point_out;

/* The numbers of a point file are finite (issue 22: no "nan" in JSON): C,
 * the relative density and the engineering constants 1/S_ii, -S_ij/S_ii that
 * rn_homog_put_constants writes. */
static int point_finite(const point_out *o, rn_num_check *chk) {
  const int n = o->h->nstrain;
  char field[64];
  rn_num_checked(chk, "relative_density", o->h->relative_density);
  for (int i = 0; i < n * n; ++i) {
    snprintf(field, sizeof field, "C[%d]", i);
    rn_num_checked(chk, field, o->h->C[i]);
  }
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      snprintf(field, sizeof field, "constants (compliance S[%d][%d])", i, j);
      rn_num_checked(chk, field,
                     i == j ? 1.0 / o->S[i * n + i] : -o->S[i * n + j] / o->S[i * n + i]);
    }
  rn_num_checked(chk, "time_s", o->seconds);
  if (o->r && o->r->inst.found) {
    const rn_cell_path_instability *in = &o->r->inst;
    rn_num_checked(chk, "instability.load_factor", in->t);
    for (int i = 0; i < o->r->ns; ++i) {
      rn_num_checked(chk, "instability.strain", in->strain[i]);
      rn_num_checked(chk, "instability.stress", in->stress[i]);
    }
    for (int i = 0; i < 3; ++i) rn_num_checked(chk, "instability.wave_vector", in->xi[i]);
  }
  return !chk->bad;
}

/* FNV-1a (64 bit) of the file at path as "fnv1a64:HEX" in out[32]; 0 on success. */
static int scene_hash(rn_context *ctx, const char *path, char out[32]) {
  char *text = NULL;
  size_t len = 0;
  uint64_t h = 14695981039346656037ULL;
  if (rn_text_file_read(ctx, path, 1 << 30, &text, &len)) return -1;
  for (size_t i = 0; i < len; ++i) {
    h ^= (unsigned char)text[i];
    h *= 1099511628211ULL;
  }
  free(text);
  snprintf(out, 32, "fnv1a64:%016llx", (unsigned long long)h);
  return 0;
}

/* The point file's "path" and "instability" members (each ends ",\n"). */
static void put_path_result(FILE *f, const point_out *o) {
  const rn_cell_path_result *r = o->r;
  const rn_cell_path_instability *in = &r->inst;
  fprintf(f, "  \"path\": {\"steps\": %d, \"steps_done\": %d, \"stopped\": ", r->steps,
          r->done);
  if (r->stopped)
    fprintf(f, "\"%s\"", r->stopped);
  else
    fputs("null", f);
  fprintf(f, ", \"limit_end\": %d, \"time_s\": %.6g},\n", r->limit_end, o->path_seconds);
  fputs("  \"instability\": ", f);
  if (!in->found) {
    fputs("null,\n", f);
    return;
  }
  fprintf(f, "{\"kind\": \"%s\", \"criterion\": \"%s\", \"load_factor\": %.17g, ",
          hp_instability_kind(in), hp_instability_criterion(in), in->t);
  fputs("\"strain\": ", f);
  hp_put_vec(f, r->ns, in->strain);
  fputs(", \"stress\": ", f);
  hp_put_vec(f, r->ns, in->stress);
  fputs(", \"wave_vector\": ", f);
  hp_put_vec(f, o->h->dim, in->xi);
  fprintf(f, ", \"multiplicity\": %d},\n", in->multiplicity);
}

static rn_status write_point(FILE *f, void *user, rn_context *ctx) {
  const point_out *o = user;
  int n = o->h->nstrain;
  rn_num_check chk = {0, 0.0, ""};
  if (!point_finite(o, &chk)) {
    char msg[512];
    return rn_context_set_error(ctx, RN_ERR_NOT_FINITE, "%s",
                                rn_num_check_message(&chk, o->path, msg, sizeof msg));
  }
  fprintf(f,
          "{\n  \"index\": %d,\n  \"lattice\": \"%s\",\n  \"joint_model\": \"%s\",\n"
          "  \"relative_density_target\": %.17g,\n  \"seed\": %ld,\n",
          o->p->index, o->p->lattice, joint_name(o->p->joint_model), o->p->rho,
          o->p->seed);
  fprintf(f, "  \"rodnet_version\": \"%s\",\n  \"scene_hash\": \"%s\",\n",
          rn_version_string(), o->hash);
  fprintf(f, "  \"parameters\": %s,\n", o->record);
  fprintf(f, "  \"dimension\": %d,\n  \"relative_density\": %.17g,\n  \"C\": [",
          o->h->dim, o->h->relative_density);
  for (int i = 0; i < n * n; ++i) fprintf(f, "%s%.17g", i ? ", " : "", o->h->C[i]);
  fputs("],\n", f);
  rn_homog_put_constants(f, o->h, o->S);
  if (o->r) put_path_result(f, o);
  fprintf(f, "  \"time_s\": %.6g\n}\n", o->seconds);
  return RN_OK;
}

static double now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* 1 if path holds a finished point of index p->index with the record rec (every
 * parameter that defines it), this rodnet version and the cell scene of hash. */
static int point_done(rn_context *ctx, const char *path, const point *p, const cJSON *rec,
                      const char *hash) {
  char *text = NULL;
  size_t len = 0;
  int ok = 0;
  if (access(path, R_OK) != 0 || rn_text_file_read(ctx, path, 1 << 20, &text, &len))
    return 0;
  cJSON *root = cJSON_Parse(text);
  const cJSON *i = cJSON_GetObjectItemCaseSensitive(root, "index"),
              *l = cJSON_GetObjectItemCaseSensitive(root, "lattice"),
              *j = cJSON_GetObjectItemCaseSensitive(root, "joint_model"),
              *r = cJSON_GetObjectItemCaseSensitive(root, "relative_density_target"),
              *s = cJSON_GetObjectItemCaseSensitive(root, "seed"),
              *c = cJSON_GetObjectItemCaseSensitive(root, "constants"),
              *v = cJSON_GetObjectItemCaseSensitive(root, "rodnet_version"),
              *h = cJSON_GetObjectItemCaseSensitive(root, "scene_hash"),
              *pr = cJSON_GetObjectItemCaseSensitive(root, "parameters");
  ok = cJSON_IsNumber(i) && i->valuedouble == p->index && cJSON_IsString(l) &&
       strcmp(l->valuestring, p->lattice) == 0 && cJSON_IsString(j) &&
       strcmp(j->valuestring, joint_name(p->joint_model)) == 0 && cJSON_IsNumber(r) &&
       r->valuedouble == p->rho && cJSON_IsNumber(s) &&
       s->valuedouble == (double)p->seed && cJSON_IsObject(c) && cJSON_IsString(v) &&
       strcmp(v->valuestring, rn_version_string()) == 0 && cJSON_IsString(h) &&
       strcmp(h->valuestring, hash) == 0 && cJSON_IsObject(pr) &&
       cJSON_Compare(pr, rec, 1);
  cJSON_Delete(root);
  free(text);
  return ok;
}

/* The ranks of the sweep (docs/parallel.md, "Sweeps"): every point on one
 * rank; rank 0 prints the progress bar and the failures of every rank (sent as
 * notices) and writes the CSV and the plot. */
typedef struct sweep_run {
  int rank, size, quiet, total;
  int shown;    /* points shown on the progress bar */
  int finished; /* rank 0: ranks that said they are done */
  const sweep_spec *s;
} sweep_run;

/* Notice ints: point index (-1: the rank is done), status, skipped. */
enum { NOTE_INDEX, NOTE_STATUS, NOTE_SKIP, NOTE_N };

/* The MPI helpers of the solver's shim (rodnet_solve.h); without the solver
 * (no MPI, and sweep refuses before any point) one rank and nothing to send. */
#ifdef RN_HAVE_SOLVER
#define SW_MPI(call) call
#else
#define SW_MPI(call) RN_OK
#endif
static rn_status sw_allreduce(int *v, int n, int op) {
  (void)v, (void)n, (void)op;
  return SW_MPI(rn_dist_allreduce_int(v, n, op));
}
static rn_status sw_send(const int *v, int n, const char *text) {
  (void)v, (void)n, (void)text;
  return SW_MPI(rn_dist_notice_send(v, n, text));
}
static int sw_poll(int *v, int n, char *text, size_t size) {
  int from = 0;
  (void)v, (void)n, (void)text, (void)size, (void)from;
  return SW_MPI(rn_dist_notice_poll(v, n, text, size, &from));
}
static rn_status sw_flush(void) { return SW_MPI(rn_dist_notice_flush()); }
/* Under mpirun: MPI started, this rank and the number of ranks (RN_OK). */
static rn_status sw_start(int *rank, int *size) {
  (void)rank, (void)size;
  rn_status st = SW_MPI(rn_runtime_initialize(NULL, NULL));
#ifdef RN_HAVE_SOLVER
  if (!st) rn_runtime_ranks(rank, size);
#endif
  return st;
}
static void sw_stop(void) {
#ifdef RN_HAVE_SOLVER
  rn_runtime_finalize();
#endif
}

static void progress(const sweep_run *w, const point *p, int skipped);

/* The point of index k (the grid's order: lattice, joint model, density, seed). */
static point point_at(const sweep_spec *s, int k) {
  const int d = k % s->nseed, c = (k / s->nseed) % s->nrho,
            j = (k / (s->nseed * s->nrho)) % s->njm,
            i = k / (s->nseed * s->nrho * s->njm);
  point p = {k, s->lat[i], s->jm[j], s->rho[c], s->seed[d]};
  return p;
}

/* A point's failure on the console (rank 0). */
static void print_failure(const sweep_run *w, int k, const char *msg) {
  point p = point_at(w->s, k);
  fprintf(stderr, "%srodnet sweep: point %d (%s %s rho %g seed %ld): %s\n",
          w->quiet ? "" : "\n", k, p.lattice, joint_name(p.joint_model), p.rho, p.seed,
          msg);
}

/* Rank 0: the notices that have arrived (progress and failures of the other
 * ranks' points); *failed counts the failures. */
static void take_notices(sweep_run *w, int *failed) {
  int v[NOTE_N];
  char text[RN_DIST_NOTICE_TEXT];
  while (w->size > 1 && sw_poll(v, NOTE_N, text, sizeof text)) {
    if (v[NOTE_INDEX] < 0) {
      ++w->finished;
      continue;
    }
    if (v[NOTE_SKIP] < 0) { /* a failure already counted (the first round) */
      print_failure(w, v[NOTE_INDEX], text);
      continue;
    }
    if (v[NOTE_STATUS]) {
      print_failure(w, v[NOTE_INDEX], text);
      if (failed) ++*failed;
    }
    ++w->shown;
    point p = point_at(w->s, v[NOTE_INDEX]);
    if (!w->quiet) progress(w, &p, v[NOTE_SKIP]);
  }
}

#ifdef RN_HAVE_SOLVER
/* rn_cell_path_run's progress: rank 0 keeps the bar going during its own
 * long points. */
static void path_tick(void *user, const rn_cell_path_result *res) {
  (void)res;
  sweep_run *w = user;
  if (w->rank == 0) take_notices(w, NULL);
}
#endif

/* Homogenise one point (its cell already written to scene, of hash; rec its
 * record), then follow the sweep's path if it has one, into
 * DIR/point_NNNN.json; RN_OK or the failure. */
static rn_status run_point(rn_context *ctx, sweep_run *w, const point *p, const char *dir,
                           const char *scene, const char *rec, const char *hash) {
  char out[4096];
  rn_scene *sc = NULL;
  rn_homogenization h;
  rn_cell_path_result r;
  double S[36], path_seconds = 0.0;
  rn_status st;
  const sweep_spec *s = w->s;
  memset(&r, 0, sizeof r);
  snprintf(out, sizeof out, "%s/point_%04d.json", dir, p->index);
  if ((st = rn_scene_load(ctx, scene, &sc))) return st;
  double t0 = now();
#ifdef RN_HAVE_SOLVER
  st = rn_homogenize(rn_scene_network(sc), &h);
#else
  st = rn_context_set_error(ctx, RN_ERR_STATE,
                            "rodnet was built without the solver (RN_WITH_TRILINOS=OFF)");
#endif
  double seconds = now() - t0;
  if (!st && !rn_homog_invert(h.nstrain, h.C, S))
    st = rn_context_set_error(ctx, RN_ERR_SOLVER, "the effective stiffness is singular");
#ifdef RN_HAVE_SOLVER
  if (!st && s->has_path) {
    rn_cell_path_segment seg;
    rn_cell_path_options o;
    memset(&seg, 0, sizeof seg);
    seg.steps = s->path_steps;
    for (int v = 0; v < s->path_ns; ++v) {
      seg.stress[v] = s->path_stress[v];
      seg.target[v] = s->path_target[v];
    }
    rn_cell_path_options_default(&o);
    o.modes = s->path_modes;
    o.bloch_method = s->path_method;
    o.progress = path_tick;
    o.user = w;
    t0 = now();
    st = rn_cell_path_run(rn_scene_network(sc), 1, &seg, &o, &r);
    path_seconds = now() - t0;
    if (!st && r.ns != s->path_ns)
      st = rn_context_set_error(ctx, RN_ERR_ARG, "the cell has %d strain components",
                                r.ns);
  }
#endif
  if (!st) {
    point_out o = {p,           &h, S, seconds, out, rec, hash, s->has_path ? &r : NULL,
                   path_seconds};
    st = rn_file_write_atomic(ctx, out, write_point, &o);
  }
#ifdef RN_HAVE_SOLVER
  rn_cell_path_result_free(&r);
#endif
  rn_scene_destroy(&sc);
  return st;
}

typedef struct csv_in {
  const char *dir;
  int npoints;
  const int *valid; /* [npoints]: the point file is this sweep's */
  int path;         /* the sweep has a "path": its columns */
} csv_in;

/* A JSON list of numbers as one CSV field, space-separated ("" if not a list);
 * 0 if an entry is not a finite number. */
static int csv_vec(FILE *f, const cJSON *a) {
  const cJSON *e;
  int first = 1;
  cJSON_ArrayForEach(e, a) {
    if (!cJSON_IsNumber(e) || !isfinite(e->valuedouble)) return 0;
    fprintf(f, "%s%.17g", first ? "" : " ", e->valuedouble);
    first = 0;
  }
  return 1;
}

/* The path columns of a point (after its other columns): instability kind and
 * criterion, its load factor, strain, stress and wave vector, the steps done
 * and why the path stopped ("" if it did not).  0 if the point file lacks
 * them. */
static int csv_path(FILE *f, const cJSON *r) {
  const cJSON *pa = cJSON_GetObjectItemCaseSensitive(r, "path"),
              *in = cJSON_GetObjectItemCaseSensitive(r, "instability");
  const cJSON *done = cJSON_GetObjectItemCaseSensitive(pa, "steps_done"),
              *why = cJSON_GetObjectItemCaseSensitive(pa, "stopped");
  if (!cJSON_IsObject(pa) || !cJSON_IsNumber(done) ||
      !(cJSON_IsNull(in) || cJSON_IsObject(in)))
    return 0;
  if (cJSON_IsObject(in)) {
    const cJSON *lf = cJSON_GetObjectItemCaseSensitive(in, "load_factor");
    const char *kind = cJSON_GetStringValue(cJSON_GetObjectItemCaseSensitive(in, "kind")),
               *crit = cJSON_GetStringValue(
                   cJSON_GetObjectItemCaseSensitive(in, "criterion"));
    if (!kind || !crit || !cJSON_IsNumber(lf) || !isfinite(lf->valuedouble)) return 0;
    fprintf(f, ",%s,%s,%.17g,", kind, crit, lf->valuedouble);
    if (!csv_vec(f, cJSON_GetObjectItemCaseSensitive(in, "strain"))) return 0;
    fputc(',', f);
    if (!csv_vec(f, cJSON_GetObjectItemCaseSensitive(in, "stress"))) return 0;
    fputc(',', f);
    if (!csv_vec(f, cJSON_GetObjectItemCaseSensitive(in, "wave_vector"))) return 0;
  } else
    fputs(",none,,,,,", f);
  fprintf(f, ",%.0f,", done->valuedouble);
  if (cJSON_IsString(why)) fprintf(f, "\"%s\"", why->valuestring); /* static texts */
  return 1;
}

/* DIR/sweep.csv from the point files. */
static rn_status write_csv(FILE *f, void *user, rn_context *ctx) {
  const csv_in *in = user;
  fprintf(f,
          "index,lattice,joint_model,relative_density_target,seed,relative_density,"
          "dimension,E1,E2,nu12,G12,time_s%s\n",
          in->path ? ",instability,criterion,critical_load_factor,critical_strain,"
                     "critical_stress,wave_vector,path_steps_done,path_stopped"
                   : "");
  for (int k = 0; k < in->npoints; ++k) {
    char path[4096], *text = NULL;
    size_t len = 0;
    snprintf(path, sizeof path, "%s/point_%04d.json", in->dir, k);
    if (!in->valid[k]) continue; /* failed: an older file there is another point's */
    if (rn_text_file_read(ctx, path, 1 << 20, &text, &len)) continue; /* failed point */
    cJSON *r = cJSON_Parse(text);
    const cJSON *c = cJSON_GetObjectItemCaseSensitive(r, "constants");
#define NUM(o, k) cJSON_GetNumberValue(cJSON_GetObjectItemCaseSensitive(o, k))
#define STR(o, k) cJSON_GetStringValue(cJSON_GetObjectItemCaseSensitive(o, k))
    /* a number missing from the point file reads as NaN: refused, not "nan" */
    static const char *const col[] = {"relative_density_target",
                                      "seed",
                                      "relative_density",
                                      "dimension",
                                      "constants.E1",
                                      "constants.E2",
                                      "constants.nu12",
                                      "constants.G12",
                                      "time_s"};
    const double v[] = {NUM(r, "relative_density_target"),
                        NUM(r, "seed"),
                        NUM(r, "relative_density"),
                        NUM(r, "dimension"),
                        NUM(c, "E1"),
                        NUM(c, "E2"),
                        NUM(c, "nu12"),
                        NUM(c, "G12"),
                        NUM(r, "time_s")};
    const char *lattice = STR(r, "lattice"), *joint = STR(r, "joint_model");
    rn_num_check chk = {0, 0.0, ""};
    for (int i = 0; i < 9; ++i) rn_num_checked(&chk, col[i], v[i]);
    if (!lattice || !joint)
      rn_num_checked(&chk, lattice ? "joint_model" : "lattice", NAN);
    if (!chk.bad) {
      fprintf(f, "%d,%s,%s,%.17g,%.0f,%.17g,%.0f,%.17g,%.17g,%.17g,%.17g,%.6g", k,
              lattice, joint, v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7], v[8]);
      if (in->path && !csv_path(f, r)) rn_num_checked(&chk, "path or instability", NAN);
      fputc('\n', f);
    }
#undef NUM
#undef STR
    cJSON_Delete(r);
    free(text);
    if (chk.bad) {
      char msg[512], what[4200];
      snprintf(what, sizeof what, "%s/sweep.csv (from %s)", in->dir, path);
      return rn_context_set_error(ctx, RN_ERR_NOT_FINITE, "%s",
                                  rn_num_check_message(&chk, what, msg, sizeof msg));
    }
  }
  return RN_OK;
}

static void progress(const sweep_run *w, const point *p, int skipped) {
  char bar[31];
  const int done = w->shown, total = w->total;
  int fill = total ? 30 * done / total : 30;
  for (int i = 0; i < 30; ++i) bar[i] = i < fill ? '#' : '.';
  bar[30] = '\0';
  fprintf(stderr, "\rrodnet sweep: [%s] %d/%d  %s %s rho %.4g seed %ld%s   ", bar, done,
          total, p->lattice, joint_name(p->joint_model), p->rho, p->seed,
          skipped ? " (done before)" : "");
  if (done == total) fputc('\n', stderr);
  fflush(stderr);
}

typedef struct sweep_args {
  const char *file, *dir, *plot;
  int quiet;
} sweep_args;

/* The command line into a; 0, -1 after the help, else the usage error's
 * status (message printed). */
static int parse_sweep_args(int argc, char **argv, sweep_args *a) {
  memset(a, 0, sizeof(*a));
  for (int i = 1; i < argc; i++) {
    const char *s = argv[i], *v = NULL;
    int m;
    if (strcmp(s, "-h") == 0 || strcmp(s, "--help") == 0) {
      fputs(sweep_help, stdout);
      return -1;
    }
    if (strcmp(s, "-q") == 0 || strcmp(s, "--quiet") == 0) {
      a->quiet = 1;
      continue;
    }
    if ((m = rn_cli_option_value("sweep", argc, argv, &i, "--output", "-o", &v))) {
      if (m < 0) return RN_EXIT_USAGE;
      a->dir = v;
      continue;
    }
    if ((m = rn_cli_option_value("sweep", argc, argv, &i, "--plot", NULL, &v))) {
      if (m < 0) return RN_EXIT_USAGE;
      a->plot = v;
      continue;
    }
    if (s[0] == '-' && s[1] != '\0')
      return rn_cli_usage_error("sweep", "unknown option '%s'", s);
    if (a->file) return rn_cli_usage_error("sweep", "more than one sweep file given");
    a->file = s;
  }
  static const char *const valued[] = {"--output|-o", "--plot", NULL};
  int rc = rn_cli_check_repeats("sweep", argc, argv, valued);
  if (rc) return rc;
  if (!a->file) return rn_cli_usage_error("sweep", "missing the sweep file");
  if (!a->dir) return rn_cli_usage_error("sweep", "missing -o DIR");
  return 0;
}

/* Point p of the sweep: its cell scene written and hashed, and its record;
 * *skip: DIR/point_NNNN.json is done before (same record, version, scene);
 * else, if run, the point computed into it.  RN_OK or the failure (message in
 * ctx). */
static rn_status sweep_point(rn_context *ctx, sweep_run *w, const point *p,
                             const char *dir, int run, int *skip) {
  char out[4096], scene[4096], hash[32];
  snprintf(out, sizeof out, "%s/point_%04d.json", dir, p->index);
  snprintf(scene, sizeof scene, "%s/point_%04d.scene.json", dir, p->index);
  /* the point's record: its parameters, the version, its cell scene */
  cJSON *rec = point_record(w->s, p);
  char *rec_text = rec ? cJSON_PrintUnformatted(rec) : NULL;
  rn_status st =
      rec_text ? RN_OK : rn_context_set_error(ctx, RN_ERR_ALLOC, "out of memory");
  if (!st) st = write_cell(ctx, w->s, p, scene);
  if (!st && scene_hash(ctx, scene, hash)) st = RN_ERR_IO;
  *skip = !st && point_done(ctx, out, p, rec, hash);
  if (!st && !*skip && run) st = run_point(ctx, w, p, dir, scene, rec_text, hash);
  cJSON_Delete(rec);
  cJSON_free(rec_text);
  return st;
}

/* Every point of the grid (docs/parallel.md, "Sweeps"), in two rounds over
 * the ranks: first each rank writes the cell scenes of every size-th point and
 * finds which are done before; then the points to compute are dealt out in
 * turn (the j-th to rank j mod size), so that a resumed sweep is shared as
 * evenly as a fresh one.  valid[k] (every rank): point k succeeded.  0, else
 * RN_EXIT_INPUT (the folder failed on some rank: no point in going on);
 * *failed counts the failed points. */
static int sweep_points(rn_context *ctx, sweep_run *w, const sweep_args *a, int *valid,
                        int *failed) {
  const int total = w->total;
  int *todo = calloc((size_t)total + 1, sizeof(int)), io = 0, ntodo = 0;
  if (!todo) return RN_EXIT_INTERNAL;
  *failed = 0;
  /* round 1: the done-before points */
  for (int k = w->rank; k < total && !io; k += w->size) {
    point p = point_at(w->s, k);
    int skip = 0;
    rn_status st = sweep_point(ctx, w, &p, a->dir, 0, &skip);
    if (st == RN_ERR_IO) {
      if (w->rank == 0) fprintf(stderr, "rodnet sweep: %s\n", rn_context_last_error(ctx));
      io = 1;
    } else if (st) { /* out of memory, a generator failure: the point fails */
      int v[NOTE_N] = {k, (int)st, -1};
      todo[k] = 2;
      if (w->rank == 0)
        print_failure(w, k, rn_context_last_error(ctx));
      else
        sw_send(v, NOTE_N, rn_context_last_error(ctx));
    } else {
      todo[k] = skip ? 0 : 1;
      valid[k] = skip;
    }
  }
  todo[total] = io;
  sw_allreduce(todo, total + 1, RN_DIST_MAX);
  sw_allreduce(valid, total, RN_DIST_MAX);
  if (todo[total]) {
    free(todo);
    return RN_EXIT_INPUT;
  }
  for (int k = 0; k < total; ++k) {
    if (todo[k] == 1) continue;
    *failed += todo[k] == 2;
    ++w->shown;
    point p = point_at(w->s, k);
    if (todo[k] == 0 && w->rank == 0 && !a->quiet) progress(w, &p, 1);
  }
  /* round 2: the points to compute, dealt out in turn */
  for (int k = 0; k < total && !io; ++k) {
    if (todo[k] != 1) continue;
    if (ntodo++ % w->size != w->rank) continue;
    point p = point_at(w->s, k);
    int skip = 0, v[NOTE_N];
    rn_status st = sweep_point(ctx, w, &p, a->dir, 1, &skip);
    valid[k] = !st;
    io = st == RN_ERR_IO;
    v[NOTE_INDEX] = k;
    v[NOTE_STATUS] = (int)st;
    v[NOTE_SKIP] = skip;
    if (w->rank == 0) {
      if (st) {
        print_failure(w, k, rn_context_last_error(ctx));
        ++*failed;
      }
      ++w->shown;
      if (!a->quiet) progress(w, &p, skip);
      take_notices(w, failed);
    } else
      sw_send(v, NOTE_N, st ? rn_context_last_error(ctx) : NULL);
  }
  /* the end of the independent work: rank 0 takes every rank's last notices */
  if (w->rank == 0) {
    while (w->finished < w->size - 1) {
      const int before = w->finished, shown = w->shown;
      take_notices(w, failed);
      if (w->finished == before && w->shown == shown) {
        struct timespec ts = {0, 2000000L}; /* nothing arrived: 2 ms */
        nanosleep(&ts, NULL);
      }
    }
  } else {
    int v[NOTE_N] = {-1, 0, 0};
    sw_send(v, NOTE_N, NULL);
    sw_flush();
  }
  int agreed[2] = {io, w->rank == 0 ? *failed : 0};
  sw_allreduce(agreed, 1, RN_DIST_MAX);
  sw_allreduce(agreed + 1, 1, RN_DIST_SUM);
  sw_allreduce(valid, total, RN_DIST_MAX);
  *failed = agreed[1];
  free(todo);
  if (agreed[0] && w->rank == 0 && !io)
    fprintf(stderr, "rodnet sweep: %s: a rank could not write the folder\n", a->dir);
  return agreed[0] ? RN_EXIT_INPUT : 0;
}

/* The sweep file's points into the folder, then (rank 0) its CSV and the
 * plot; the exit status, the same on every rank. */
static int run_sweep(rn_context *ctx, sweep_run *w, const sweep_args *a) {
  int total = w->total, failed = 0, rc;
  int *valid = calloc((size_t)total, sizeof(int));
  if (!valid) return RN_EXIT_INTERNAL;
  if ((rc = check_cells(ctx, w->s, a->file)) ||
      (rc = sweep_points(ctx, w, a, valid, &failed))) {
    free(valid);
    return rc;
  }
  if (w->rank == 0) {
    char csv[4096];
    snprintf(csv, sizeof csv, "%s/sweep.csv", a->dir);
    csv_in in = {a->dir, total, valid, w->s->has_path};
    if (rn_file_write_atomic(ctx, csv, write_csv, &in)) {
      fprintf(stderr, "rodnet sweep: %s\n", rn_context_last_error(ctx));
      rc = RN_EXIT_INPUT;
    } else {
      if (!a->quiet) {
        printf("rodnet sweep: %d points (%d failed); wrote %s", total, failed, csv);
        if (w->size > 1) printf(" (%d ranks)", w->size);
        putchar('\n');
      }
      if (failed) rc = RN_EXIT_INTERNAL;
      if (a->plot &&
          rn_cli_plot("RODNET_PLOT_SWEEP", RN_PLOT_SWEEP_SCRIPT, csv, a->plot) != 0) {
        fprintf(stderr, "rodnet sweep: the plot %s failed (python3 with matplotlib)\n",
                a->plot);
        rc = RN_EXIT_INTERNAL;
      }
    }
  }
  free(valid);
  sw_allreduce(&rc, 1, RN_DIST_MAX); /* rank 0's */
  return rc;
}

/* The same exit status on every rank: the largest (checks that every rank ran
 * on the same input agree; one that differs would otherwise leave a rank
 * waiting in a collective). */
static int agree_exit(int rc) {
  sw_allreduce(&rc, 1, RN_DIST_MAX);
  return rc;
}

static int sweep_main(const sweep_args *ap, const rn_cli_file *files, sweep_run *w) {
  const sweep_args a = *ap;
  int rc = 0;
  rn_context *ctx = NULL;
  if (rn_context_create(&ctx) != RN_OK) return agree_exit(RN_EXIT_INTERNAL);
  char *text = NULL;
  size_t len = 0;
  sweep_spec *s = calloc(1, sizeof(*s));
  if (!s) {
    rn_context_destroy(&ctx);
    return agree_exit(RN_EXIT_INTERNAL);
  }
  if (rn_text_file_read(ctx, a.file, 1 << 20, &text, &len)) {
    if (w->rank == 0) fprintf(stderr, "rodnet sweep: %s\n", rn_context_last_error(ctx));
    rc = RN_EXIT_INPUT;
  } else if (!(rc = parse_spec(a.file, text, s)) &&
             !(rc = rn_cli_probe_outputs("sweep", files, 5))) {
    if (mkdir(a.dir, 0777) != 0 && errno != EEXIST) {
      if (w->rank == 0)
        fprintf(stderr, "rodnet sweep: %s: cannot create the folder: %s\n", a.dir,
                strerror(errno));
      rc = RN_EXIT_INPUT;
    }
  }
  if (!(rc = agree_exit(rc))) {
    w->s = s;
    w->total = s->nlat * s->njm * s->nrho * s->nseed;
    rc = run_sweep(ctx, w, &a);
  }
  free(text);
  free(s);
  rn_context_destroy(&ctx);
  return rc;
}

int rn_cli_sweep(int argc, char **argv) {
  sweep_args a;
  int rc = parse_sweep_args(argc, argv, &a);
  if (rc) return rc < 0 ? RN_EXIT_OK : rc;
  /* the files read and written: the folder's point files and CSV, the plot */
  const rn_cli_file files[] = {{"the sweep file", a.file, NULL, RN_CLI_IN},
                               {"-o", a.dir, NULL, RN_CLI_OUT_DIR},
                               {"-o", a.dir, "/point_*.json", RN_CLI_OUT},
                               {"-o", a.dir, "/sweep.csv", RN_CLI_OUT},
                               {"--plot", a.plot, NULL, RN_CLI_OUT}};
#ifndef RN_HAVE_SOLVER
  if ((rc = rn_cli_check_files("sweep", files, 5))) return rc;
  return rn_cli_no_solver("sweep"); /* rn_homogenize is the solver's */
#endif
  sweep_run w = {0, 1, a.quiet, 0, 0, 0, NULL};
  const int mpi = rn_cli_env_ranks() != 1;
  if (mpi) { /* under mpirun: the runtime first, to know the ranks */
    if (sw_start(&w.rank, &w.size) != RN_OK) {
      fprintf(stderr, "rodnet sweep: cannot start the MPI runtime\n");
      return RN_EXIT_INTERNAL;
    }
  }
  rc = rn_cli_check_files("sweep", files, 5);
  rc = agree_exit(rc);
  if (!rc) rc = sweep_main(&a, files, &w);
  if (mpi) sw_stop();
  return rc;
}
