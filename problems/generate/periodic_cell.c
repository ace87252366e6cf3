/* periodic_cell.c - periodic cells of rod lattices (periodic_cell.h). */
#include "generate/periodic_cell.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/atomic_file.h"
#include "generate/lattice_check.h"
#include "io/num_format.h"

void rn_pcell_free(rn_pcell *c) {
  if (!c) return;
  free(c->xyz);
  free(c->bar);
  free(c->section_scale);
  memset(c, 0, sizeof(*c));
}

/* Fractional coordinates f of p in the lattice vectors (dim x dim solve; 2D
 * cells lie in the xy plane). */
static void fractional(const rn_pcell *c, const double p[3], double f[3]) {
  const double *A = c->vec;
  if (c->dim == 2) {
    double det = A[0] * A[4] - A[1] * A[3];
    f[0] = (p[0] * A[4] - p[1] * A[3]) / det;
    f[1] = (A[0] * p[1] - A[1] * p[0]) / det;
    f[2] = 0.0;
    return;
  }
  double m[9] = {A[0], A[3], A[6], A[1], A[4], A[7], A[2], A[5], A[8]}; /* columns */
  double det = m[0] * (m[4] * m[8] - m[5] * m[7]) - m[1] * (m[3] * m[8] - m[5] * m[6]) +
               m[2] * (m[3] * m[7] - m[4] * m[6]);
  for (int k = 0; k < 3; k++) { /* Cramer */
    double t[9];
    memcpy(t, m, sizeof t);
    for (int r = 0; r < 3; r++) t[3 * r + k] = p[r];
    f[k] = (t[0] * (t[4] * t[8] - t[5] * t[7]) - t[1] * (t[3] * t[8] - t[5] * t[6]) +
            t[2] * (t[3] * t[7] - t[4] * t[6])) /
           det;
  }
}

/* Sort keys of the bars: their canonical (u, v, image). */
typedef struct bar_key {
  int k[5];
  int e;
} bar_key;

static int bar_cmp(const void *a, const void *b) {
  const bar_key *p = a, *q = b;
  for (int i = 0; i < 5; i++)
    if (p->k[i] != q->k[i]) return (p->k[i] > q->k[i]) - (p->k[i] < q->k[i]);
  return (p->e > q->e) - (p->e < q->e);
}

/* A hash grid of boxes of side h: node n in box floor(q / h) (per axis), the
 * boxes' nodes chained through next[]; open addressing on the packed box
 * index, Fibonacci hashing (the top bits). */
typedef struct box_grid {
  int64_t *key; /* packed box index, INT64_MIN: empty */
  int *head;    /* first node of the box; next[n] the following one, -1 ends */
  size_t mask;
  int bits;
} box_grid;

static int64_t box_key(const long long g[3]) {
  /* 21 bits per axis, offset: boxes within +-2^20 of the origin (the caller's
   * h keeps the cell within +-1e5 boxes) */
  return ((int64_t)(g[0] + (1 << 20)) << 42) | ((int64_t)(g[1] + (1 << 20)) << 21) |
         (int64_t)(g[2] + (1 << 20));
}

static size_t box_slot(const box_grid *g, int64_t k) {
  return (size_t)(((uint64_t)k * 0x9E3779B97F4A7C15ull) >> (64 - g->bits));
}

/* The first node of box k, -1 if none. */
static int box_find(const box_grid *g, int64_t k) {
  for (size_t i = box_slot(g, k);; i = (i + 1) & g->mask) {
    if (g->key[i] == k) return g->head[i];
    if (g->key[i] == INT64_MIN) return -1;
  }
}

/* The head slot of box k, created (empty) if new. */
static int *box_insert(box_grid *g, int64_t k) {
  size_t i = box_slot(g, k);
  while (g->key[i] != k && g->key[i] != INT64_MIN) i = (i + 1) & g->mask;
  if (g->key[i] == INT64_MIN) {
    g->key[i] = k;
    g->head[i] = -1;
  }
  return &g->head[i];
}

/* Canonical copy of every node in the cell: rep[n] = the node's cluster (the
 * first node, in index order, within 1e-9 of the cell size after the shift),
 * q[3 n] its position in the cell, img[3 n] its lattice shift.  A hash grid of
 * boxes of 1e-5 of the cell size finds the neighbours in the 27 boxes around a
 * node: O(nn).  (A sweep over x with a 1e-9 window, as before, compared every
 * node with the whole column of nodes sharing its x: O(nn sqrt(nn)) in 2D;
 * issue 22 item 4.) */
static rn_status canonical_nodes(const rn_pcell *c, int nn, const double *p, double *q,
                                 int *img, int *rep) {
  double scale = 0.0;
  for (int k = 0; k < 9; k++) scale = fmax(scale, fabs(c->vec[k]));
  const double tol = 1e-9 * scale, h = 1e-5 * scale;
  box_grid g;
  g.bits = 4;
  while (((size_t)1 << g.bits) < 2 * (size_t)(nn ? nn : 1)) g.bits++;
  g.mask = ((size_t)1 << g.bits) - 1;
  g.key = malloc((g.mask + 1) * sizeof(*g.key));
  g.head = malloc((g.mask + 1) * sizeof(*g.head));
  int *next = malloc((size_t)(nn ? nn : 1) * sizeof(int));
  if (!g.key || !g.head || !next) {
    free(g.key);
    free(g.head);
    free(next);
    return RN_ERR_ALLOC;
  }
  for (size_t i = 0; i <= g.mask; i++) g.key[i] = INT64_MIN;
  for (int n = 0; n < nn; n++) {
    double f[3];
    long long box[3];
    fractional(c, p + 3 * n, f);
    for (int m = 0; m < 3; m++) img[3 * n + m] = m < c->dim ? (int)floor(f[m] + 1e-9) : 0;
    for (int k = 0; k < 3; k++) {
      q[3 * n + k] = p[3 * n + k];
      for (int m = 0; m < c->dim; m++) q[3 * n + k] -= img[3 * n + m] * c->vec[3 * m + k];
      box[k] = h > 0.0 ? (long long)floor(q[3 * n + k] / h) : 0;
    }
    rep[n] = n;
    for (int s = 0; s < 27 && rep[n] == n; s++) { /* the boxes around: earlier nodes */
      long long nb[3] = {box[0] + s % 3 - 1, box[1] + (s / 3) % 3 - 1,
                         box[2] + s / 9 - 1};
      for (int b = box_find(&g, box_key(nb)); b >= 0; b = next[b]) {
        double d = fabs(q[3 * n] - q[3 * b]) + fabs(q[3 * n + 1] - q[3 * b + 1]) +
                   fabs(q[3 * n + 2] - q[3 * b + 2]);
        if (d <= tol) {
          rep[n] = rep[b];
          break;
        }
      }
    }
    int *head = box_insert(&g, box_key(box));
    next[n] = *head;
    *head = n;
  }
  free(g.key);
  free(g.head);
  free(next);
  return RN_OK;
}

/* Wraps the graph (nn nodes p, nb bars b[2 nb]) onto the cell c (vec, dim set):
 * nodes numbered in order of first appearance, bars that are periodic copies of
 * an earlier one dropped (O((nn + nb) log)). */
static rn_status wrap(rn_context *ctx, rn_pcell *c, int nn, const double *p, int nb,
                      const int *b) {
  size_t n1 = (size_t)(nn ? nn : 1), b1 = (size_t)(nb ? nb : 1);
  int *canon = malloc(n1 * sizeof(int)), *rep = malloc(n1 * sizeof(int));
  int *img = malloc(3 * n1 * sizeof(int)), *keep = malloc(b1 * sizeof(int));
  double *q = malloc(3 * n1 * sizeof(double));
  bar_key *bk = malloc(b1 * sizeof(*bk));
  rn_status st = RN_ERR_ALLOC;
  c->xyz = malloc(3 * n1 * sizeof(double));
  c->bar = malloc(5 * b1 * sizeof(int));
  if (!canon || !rep || !img || !keep || !q || !bk || !c->xyz || !c->bar) goto done;
  if (canonical_nodes(c, nn, p, q, img, rep)) goto done;
  c->nnodes = c->nbars = 0;
  for (int n = 0; n < nn; n++) canon[n] = -1;
  for (int n = 0; n < nn; n++) /* numbers in order of first appearance */
    if (canon[rep[n]] < 0) {
      memcpy(c->xyz + 3 * c->nnodes, q + 3 * rep[n], 3 * sizeof(double));
      canon[rep[n]] = c->nnodes++;
    }
  for (int e = 0; e < nb; e++) {
    int u = canon[rep[b[2 * e]]], v = canon[rep[b[2 * e + 1]]], r[3], flip = 0;
    for (int m = 0; m < 3; m++) r[m] = img[3 * b[2 * e + 1] + m] - img[3 * b[2 * e] + m];
    if (u > v ||
        (u == v && (r[0] < 0 || (r[0] == 0 && (r[1] < 0 || (r[1] == 0 && r[2] < 0))))))
      flip = 1;
    bk[e].k[0] = flip ? v : u;
    bk[e].k[1] = flip ? u : v;
    for (int m = 0; m < 3; m++) bk[e].k[2 + m] = flip ? -r[m] : r[m];
    bk[e].e = e;
    keep[e] = 1;
  }
  qsort(bk, (size_t)nb, sizeof(*bk), bar_cmp);
  for (int i = 1; i < nb; i++) /* the first of equal keys (lowest e) stays */
    if (memcmp(bk[i].k, bk[i - 1].k, sizeof(bk[i].k)) == 0) keep[bk[i].e] = 0;
  for (int e = 0; e < nb; e++) {
    if (!keep[e]) continue;
    int *o = c->bar + 5 * c->nbars++;
    o[0] = canon[rep[b[2 * e]]];
    o[1] = canon[rep[b[2 * e + 1]]];
    for (int m = 0; m < 3; m++)
      o[2 + m] = img[3 * b[2 * e + 1] + m] - img[3 * b[2 * e] + m];
  }
  st = RN_OK;
done:
  free(canon);
  free(rep);
  free(img);
  free(keep);
  free(q);
  free(bk);
  return st ? rn_context_set_error(ctx, st, "generate: out of memory") : RN_OK;
}

rn_status rn_pcell_from_lattice(rn_context *ctx, rn_lattice_kind kind, const int cells[3],
                                double a, rn_pcell *out) {
  rn_lattice *lat = NULL;
  memset(out, 0, sizeof(*out));
  rn_status st = rn_lattice_build(ctx, kind, cells, a, &lat);
  if (st) return st;
  int nn = rn_lattice_num_nodes(lat), nb = rn_lattice_num_bars(lat);
  double *p = malloc(3 * (size_t)nn * sizeof(double));
  int *b = malloc(2 * (size_t)nb * sizeof(int));
  if (!p || !b) st = rn_context_set_error(ctx, RN_ERR_ALLOC, "generate: out of memory");
  for (int n = 0; !st && n < nn; n++) rn_lattice_node(lat, n, p + 3 * n);
  for (int e = 0; !st && e < nb; e++) rn_lattice_bar(lat, e, b + 2 * e);
  out->dim = rn_lattice_kind_dimension(kind);
  if (out->dim == 3) {
    for (int k = 0; k < 3; k++) out->vec[4 * k] = cells[k] * a;
  } else {
    double h = kind == RN_LATTICE_SQUARE ? a : 0.5 * sqrt(3.0) * a; /* row spacing */
    out->vec[0] = cells[0] * a;
    out->vec[3] = kind == RN_LATTICE_SQUARE ? 0.0 : (cells[1] % 2) * 0.5 * a;
    out->vec[4] = cells[1] * h;
  }
  if (!st) st = wrap(ctx, out, nn, p, nb, b);
  free(p);
  free(b);
  rn_lattice_destroy(&lat);
  if (st) rn_pcell_free(out);
  return st;
}

/* floor division */
static int fdiv(int a, int b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }

rn_status rn_pcell_tile(rn_context *ctx, const rn_pcell *prim, const int rep[3],
                        rn_pcell *out) {
  int m[3] = {rep[0], rep[1], prim->dim == 3 ? rep[2] : 1}, nc = m[0] * m[1] * m[2];
  memset(out, 0, sizeof(*out));
  out->dim = prim->dim;
  out->nnodes = prim->nnodes * nc;
  out->nbars = prim->nbars * nc;
  out->xyz = malloc(3 * (size_t)out->nnodes * sizeof(double));
  out->bar = malloc(5 * (size_t)out->nbars * sizeof(int));
  if (!out->xyz || !out->bar) {
    rn_pcell_free(out);
    return rn_context_set_error(ctx, RN_ERR_ALLOC, "generate: out of memory");
  }
  for (int d = 0; d < 3; d++)
    for (int k = 0; k < 3; k++) out->vec[3 * d + k] = m[d] * prim->vec[3 * d + k];
  for (int c = 0; c < nc; c++) {
    int ci[3] = {c % m[0], (c / m[0]) % m[1], c / (m[0] * m[1])};
    for (int n = 0; n < prim->nnodes; n++)
      for (int k = 0; k < 3; k++) {
        double x = prim->xyz[3 * n + k];
        for (int d = 0; d < 3; d++) x += ci[d] * prim->vec[3 * d + k];
        out->xyz[3 * (c * prim->nnodes + n) + k] = x;
      }
    for (int e = 0; e < prim->nbars; e++) {
      const int *b = prim->bar + 5 * e;
      int *o = out->bar + 5 * (c * prim->nbars + e), t[3];
      for (int d = 0; d < 3; d++) {
        int q = ci[d] + b[2 + d];
        o[2 + d] = fdiv(q, m[d]);
        t[d] = q - o[2 + d] * m[d];
      }
      o[0] = c * prim->nnodes + b[0];
      o[1] = (t[0] + m[0] * (t[1] + m[1] * t[2])) * prim->nnodes + b[1];
    }
  }
  return RN_OK;
}

rn_status rn_pcell_reentrant(rn_context *ctx, const int cells[2], double a,
                             rn_pcell *out) {
  /* primitive cell: A = (0, 0), B = (0, h); bars A-B, B-(A + a2), B-(A + a2 - a1),
   * a1 = (2 l cos t, 0), a2 = (l cos t, h + l sin t), t = -30 degrees, h = 2 l */
  const double l = a / sqrt(3.0), h = 2.0 * l, th = -3.14159265358979323846 / 6.0;
  double xyz[6] = {0.0, 0.0, 0.0, 0.0, h, 0.0};
  int bar[15] = {0, 1, 0, 0, 0, 1, 0, 0, 1, 0, 1, 0, -1, 1, 0};
  rn_pcell prim = {
      2,    {2.0 * l * cos(th), 0, 0, l * cos(th), h + l * sin(th), 0, 0, 0, 0},
      2,    3,
      xyz,  bar,
      NULL, NULL};
  int rep[3] = {cells[0], cells[1], 1};
  return rn_pcell_tile(ctx, &prim, rep, out);
}

static double uniform(unsigned long long *state) { /* splitmix64 -> [-1, 1) */
  unsigned long long z = (*state += 0x9e3779b97f4a7c15ULL);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  z ^= z >> 31;
  return (double)(z >> 11) / 4503599627370496.0 - 1.0;
}

void rn_pcell_perturb(rn_pcell *c, double amp, unsigned long seed) {
  double L, V;
  unsigned long long state = seed;
  rn_pcell_measures(c, &L, &V);
  const double d = amp * L / (c->nbars ? c->nbars : 1);
  for (int n = 0; n < c->nnodes; n++)
    for (int k = 0; k < c->dim; k++) c->xyz[3 * n + k] += d * uniform(&state);
}

int rn_pcell_section_scatter(rn_pcell *c, double rel, unsigned long seed) {
  unsigned long long state = (unsigned long long)seed ^ 0x5ec7105ca77e2ULL;
  free(c->section_scale);
  c->section_scale = malloc((size_t)(c->nbars ? c->nbars : 1) * sizeof(double));
  if (!c->section_scale) return -1;
  for (int e = 0; e < c->nbars; e++) {
    double u1 = 0.5 * (uniform(&state) + 1.0), u2 = 0.5 * (uniform(&state) + 1.0);
    double g = sqrt(-2.0 * log(1.0 - u1)) * cos(6.283185307179586 * u2);
    c->section_scale[e] = fmax(0.05, 1.0 + rel * g);
  }
  return 0;
}

void rn_pcell_measures(const rn_pcell *c, double *length, double *measure) {
  const double *A = c->vec;
  double L = 0.0;
  for (int e = 0; e < c->nbars; e++) {
    const int *o = c->bar + 5 * e;
    double d2 = 0.0;
    for (int k = 0; k < 3; k++) {
      double d = c->xyz[3 * o[1] + k] - c->xyz[3 * o[0] + k];
      for (int m = 0; m < c->dim; m++) d += o[2 + m] * A[3 * m + k];
      d2 += d * d;
    }
    L += sqrt(d2);
  }
  *length = L;
  if (c->dim == 2)
    *measure = fabs(A[0] * A[4] - A[1] * A[3]);
  else
    *measure =
        fabs(A[0] * (A[4] * A[8] - A[5] * A[7]) - A[1] * (A[3] * A[8] - A[5] * A[6]) +
             A[2] * (A[3] * A[7] - A[4] * A[6]));
}

typedef struct pcell_out {
  const rn_pcell *c;
  const rn_lattice_scene *opt;
  const int *repeat;
  /* the rod ends at each node, 2 e + end in order of e then end: node n's are
   * end_list[end_start[n] .. end_start[n + 1]) (one pass over the bars, so the
   * joints are written in O(nodes + bars), not O(nodes x bars)) */
  int *end_start, *end_list;
} pcell_out;

/* Fills o->end_start and o->end_list (counting sort of the bar ends by node);
 * -1 if out of memory. */
static int index_ends(pcell_out *o) {
  const rn_pcell *c = o->c;
  o->end_start = calloc((size_t)c->nnodes + 1, sizeof(int));
  o->end_list = malloc(2 * (size_t)(c->nbars ? c->nbars : 1) * sizeof(int));
  int *fill = malloc(((size_t)c->nnodes + 1) * sizeof(int));
  if (!o->end_start || !o->end_list || !fill) {
    free(fill);
    return -1;
  }
  for (int e = 0; e < c->nbars; e++)
    for (int end = 0; end < 2; end++) o->end_start[c->bar[5 * e + end] + 1]++;
  for (int n = 0; n < c->nnodes; n++) o->end_start[n + 1] += o->end_start[n];
  memcpy(fill, o->end_start, ((size_t)c->nnodes + 1) * sizeof(int));
  for (int e = 0; e < c->nbars; e++) /* ascending e, then end: the written order */
    for (int end = 0; end < 2; end++)
      o->end_list[fill[c->bar[5 * e + end]]++] = 2 * e + end;
  free(fill);
  return 0;
}

static void put_vec3(FILE *f, const double *v) {
  fprintf(f, "[%.17g, %.17g, %.17g]", v[0], v[1], v[2]);
}

/* ---- write_pcell's parts: the scene's objects, in the order written ---- */

/* "periodic": the vectors, the repeat counts, the prescribed strain. */
static void put_periodic(FILE *f, const pcell_out *o) {
  const rn_pcell *c = o->c;
  const rn_lattice_scene *opt = o->opt;
  fputs("  \"periodic\": {\"vectors\": [", f);
  for (int m = 0; m < c->dim; m++) {
    if (m) fputs(", ", f);
    put_vec3(f, c->vec + 3 * m);
  }
  fputc(']', f);
  if (o->repeat) {
    fprintf(f, ", \"repeat\": [%d, %d", o->repeat[0], o->repeat[1]);
    if (c->dim == 3) fprintf(f, ", %d", o->repeat[2]);
    fputc(']', f);
  }
  if (opt->load == RN_LLOAD_BIAXIAL || opt->load == RN_LLOAD_SHEAR) {
    /* prescribed strain components (Voigt, engineering shear), the others free */
    int n = c->dim == 2 ? 3 : 6;
    fputs(", \"strain\": [", f);
    for (int v = 0; v < n; v++) {
      if (v) fputs(", ", f);
      if (opt->load == RN_LLOAD_BIAXIAL && v < 2)
        fprintf(f, "%.17g", v == 0 ? opt->load_value : opt->load_value2);
      else if (opt->load == RN_LLOAD_SHEAR && v == n - 1)
        fprintf(f, "%.17g", opt->load_value);
      else
        fputs("null", f);
    }
    fputc(']', f);
  }
  fputs("},\n", f);
}

/* "sections": one, or one per bar ("s1", ...) scaled by section_scale. */
static void put_sections(FILE *f, const rn_pcell *c, const rn_lattice_scene *opt) {
  fputs("  \"sections\": {", f);
  for (int e = 0; e < (c->section_scale ? c->nbars : 1); e++) {
    const double k = c->section_scale ? c->section_scale[e] : 1.0;
    if (c->section_scale)
      fprintf(f, "%s\n    \"s%d\": ", e ? "," : "", e + 1);
    else
      fputs("\"section\": ", f);
    if (opt->shape == RN_LSEC_CIRCLE)
      fprintf(f, "{\"shape\": \"circle\", \"radius\": %.17g}", k * opt->section[0]);
    else if (opt->shape == RN_LSEC_RECTANGLE)
      fprintf(f, "{\"shape\": \"rectangle\", \"width\": %.17g, \"height\": %.17g}",
              k * opt->section[0], k * opt->section[1]);
    else
      fprintf(f, "{\"shape\": \"ellipse\", \"a\": %.17g, \"b\": %.17g}",
              k * opt->section[0], k * opt->section[1]);
  }
  fputs("},\n", f);
}

/* "rods": bar e from node x to the image's x + s. */
static void put_rods(FILE *f, const rn_pcell *c, const rn_lattice_scene *opt) {
  fputs("  \"rods\": [\n", f);
  for (int e = 0; e < c->nbars; e++) {
    const int *b = c->bar + 5 * e;
    double q[3];
    for (int k = 0; k < 3; k++) { /* x + s, s summed as the library does */
      double s = 0.0;
      for (int m = 0; m < c->dim; m++) s += b[2 + m] * c->vec[3 * m + k];
      q[k] = c->xyz[3 * b[1] + k] + s;
    }
    char sec[32] = "section";
    if (c->section_scale) snprintf(sec, sizeof sec, "s%d", e + 1);
    fprintf(f,
            "    {\"name\": \"e%d\", \"material\": \"material\", \"section\": "
            "\"%s\",\n     \"line\": {\"from\": ",
            e + 1, sec);
    put_vec3(f, c->xyz + 3 * b[0]);
    fputs(", \"to\": ", f);
    put_vec3(f, q);
    fprintf(f, ", \"vertices\": %d}%s}%s\n", opt->edges_per_rod + 1,
            c->dim == 2 ? ", \"d1\": [0, 0, 1]" : "", e + 1 < c->nbars ? "," : "");
  }
  fputs("  ],\n", f);
}

/* "joints": node n joins the rod ends at it, those without an image first. */
static void put_joints(FILE *f, const pcell_out *o) {
  const rn_pcell *c = o->c;
  fputs("  \"joints\": [\n", f);
  for (int n = 0; n < c->nnodes; n++) {
    int first = 1;
    fprintf(f, "    {\"name\": \"v%d\", \"model\": \"%s\", \"ends\": [", n + 1,
            o->opt->joint_model == RN_JOINT_RIGID ? "rigid" : "elastic");
    for (int pass = 0; pass < 2; pass++) /* ends without an image first */
      for (int i = o->end_start[n]; i < o->end_start[n + 1]; i++) {
        const int e = o->end_list[i] >> 1, end = o->end_list[i] & 1;
        if (c->work) ++*c->work;
        const int *b = c->bar + 5 * e;
        int shifted = end && (b[2] || b[3] || b[4]);
        if (shifted != pass) continue;
        fprintf(f, "%s\n      {\"rod\": \"e%d\", \"end\": \"%s\"", first ? "" : ",",
                e + 1, end ? "end" : "start");
        if (shifted) {
          fprintf(f, ", \"image\": [%d, %d", b[2], b[3]);
          if (c->dim == 3) fprintf(f, ", %d", b[4]);
          fputc(']', f);
        }
        fputc('}', f);
        first = 0;
      }
    fprintf(f, "]}%s\n", n + 1 < c->nnodes ? "," : "");
  }
  fputs("  ]\n", f);
}

static rn_status write_pcell(FILE *f, void *user, rn_context *ctx) {
  const pcell_out *o = user;
  const rn_lattice_scene *opt = o->opt;
  (void)ctx;
  fputs("{\n  \"description\": ", f);
  rn_put_json_string(f, opt->description ? opt->description : "rodnet periodic cell");
  fputs(",\n", f);
  put_periodic(f, o);
  if (opt->model) fprintf(f, "  \"model\": \"%s\",\n", opt->model);
  fprintf(f, "  \"materials\": {\"material\": {\"E\": %.17g, \"nu\": %.17g}},\n", opt->E,
          opt->nu);
  put_sections(f, o->c, opt);
  put_rods(f, o->c, opt);
  put_joints(f, o);
  fputs("}\n", f);
  return RN_OK;
}

rn_status rn_pcell_write_scene(rn_context *ctx, const char *path, const rn_pcell *c,
                               const rn_lattice_scene *opt, const int *repeat) {
  /* a scene with "nan" or "inf" is not JSON (issue 22): refuse it */
  rn_num_check chk = {0, 0.0, ""};
  rn_lattice_scene_finite(opt, &chk);
  for (int k = 0; k < 9; k++) rn_num_checked(&chk, "periodic.vectors", c->vec[k]);
  for (int k = 0; k < 3 * c->nnodes && !chk.bad; k++) {
    char field[64];
    snprintf(field, sizeof field, "the position of joint v%d", k / 3 + 1);
    rn_num_checked(&chk, field, c->xyz[k]);
  }
  for (int e = 0; c->section_scale && e < c->nbars; e++)
    rn_num_checked(&chk, "a section scale", c->section_scale[e]);
  if (chk.bad) {
    char msg[512];
    return rn_context_set_error(ctx, RN_ERR_NOT_FINITE, "generate: %s",
                                rn_num_check_message(&chk, path, msg, sizeof msg));
  }
  pcell_out o = {c, opt, repeat, NULL, NULL};
  rn_status st = index_ends(&o)
                     ? rn_context_set_error(ctx, RN_ERR_ALLOC, "generate: out of memory")
                     : rn_file_write_atomic(ctx, path, write_pcell, &o);
  free(o.end_start);
  free(o.end_list);
  return st;
}

void rn_pcell_section_for_density(const rn_pcell *c, double rho, rn_lattice_scene *opt) {
  double L, V, t;
  rn_pcell_measures(c, &L, &V);
  t = c->dim == 2 ? rho * V / L : sqrt(4.0 * rho * V / (3.14159265358979323846 * L));
  opt->shape = c->dim == 2 ? RN_LSEC_RECTANGLE : RN_LSEC_CIRCLE;
  opt->section[0] = c->dim == 2 ? t : 0.5 * t;
  opt->section[1] = t;
}
