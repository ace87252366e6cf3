/* lattice.c - finite rod lattices (lattice.h; geometry in docs/lattices.md). */
#include "generate/lattice.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* ---- int64 -> int hash map (open addressing, keys >= 0) ---------------------- */

typedef struct id_map {
  int64_t *key; /* -1: empty */
  int *val;
  size_t cap, n; /* cap a power of two */
  int bits;      /* log2 cap */
} id_map;

/* Fibonacci hashing: the top bits of the product.  (Bits 17 and up of it, as
 * before, ignore the high half of a bar key (a << 32 | b) while cap < 2^15 and
 * mix poorly above: the probe sequences grew with the lattice, 6.6 times the
 * node look-up work for 4 times the nodes; issue 22 item 4.) */
static size_t map_slot(const id_map *m, int64_t k) {
  uint64_t h = (uint64_t)k * 0x9E3779B97F4A7C15ull;
  return (size_t)(h >> (64 - m->bits));
}

static int map_init(id_map *m, size_t cap) {
  m->cap = cap;
  m->n = 0;
  m->bits = 0;
  while (((size_t)1 << m->bits) < cap) m->bits++;
  m->key = malloc(cap * sizeof *m->key);
  m->val = malloc(cap * sizeof *m->val);
  if (!m->key || !m->val) return 0;
  for (size_t i = 0; i < cap; i++) m->key[i] = -1;
  return 1;
}

static void map_free(id_map *m) {
  free(m->key);
  free(m->val);
  m->key = NULL;
  m->val = NULL;
}

/* Value of k, or -1. */
static int map_get(const id_map *m, int64_t k) {
  for (size_t i = map_slot(m, k);; i = (i + 1) & (m->cap - 1)) {
    if (m->key[i] == k) return m->val[i];
    if (m->key[i] < 0) return -1;
  }
}

static int map_put(id_map *m, int64_t k, int v);

static int map_grow(id_map *m) {
  id_map bigger;
  if (!map_init(&bigger, 2 * m->cap)) {
    map_free(&bigger);
    return 0;
  }
  for (size_t i = 0; i < m->cap; i++)
    if (m->key[i] >= 0) map_put(&bigger, m->key[i], m->val[i]);
  map_free(m);
  *m = bigger;
  return 1;
}

/* Insert k -> v (k not present); 0 if out of memory. */
static int map_put(id_map *m, int64_t k, int v) {
  if (2 * (m->n + 1) > m->cap && !map_grow(m)) return 0;
  size_t i = map_slot(m, k);
  while (m->key[i] >= 0) i = (i + 1) & (m->cap - 1);
  m->key[i] = k;
  m->val[i] = v;
  m->n++;
  return 1;
}

/* ---- the lattice ------------------------------------------------------------ */

/* Integer grid coordinates are offset by this before packing into a key. */
#define GRID_OFFSET (1 << 20)

struct rn_lattice {
  rn_lattice_kind kind;
  double scale[3]; /* length of one grid unit per axis */
  int nn, capn, nb, capb;
  int *grid; /* [3 nn] integer coordinates */
  int *bar;  /* [2 nb] */
  int *valence;
  int lo[3], hi[3]; /* grid bounding box */
  id_map nodes, bars;
  int oom;
};

static const char *const kind_names[RN_LATTICE_KIND_COUNT] = {
    "square", "triangular", "honeycomb", "kagome", "cubic", "bcc", "octet"};

const char *rn_lattice_kind_name(rn_lattice_kind kind) {
  return (kind >= 0 && kind < RN_LATTICE_KIND_COUNT) ? kind_names[kind] : "?";
}

int rn_lattice_kind_from_name(const char *name, rn_lattice_kind *kind) {
  for (int k = 0; name && k < RN_LATTICE_KIND_COUNT; k++)
    if (strcmp(name, kind_names[k]) == 0) {
      *kind = (rn_lattice_kind)k;
      return 0;
    }
  return -1;
}

int rn_lattice_kind_dimension(rn_lattice_kind kind) {
  return kind <= RN_LATTICE_KAGOME ? 2 : 3;
}

static int64_t node_key(const int *g) {
  return ((int64_t)(g[0] + GRID_OFFSET) << 42) | ((int64_t)(g[1] + GRID_OFFSET) << 21) |
         (int64_t)(g[2] + GRID_OFFSET);
}

static int grow_array(int **p, int *cap, int need, int width) {
  if (need <= *cap) return 1;
  int c = *cap ? 2 * *cap : 1024;
  while (c < need) c *= 2;
  int *np = realloc(*p, (size_t)c * (size_t)width * sizeof *np);
  if (!np) return 0;
  *p = np;
  *cap = c;
  return 1;
}

/* Index of the node at grid point g, added if new; -1 if out of memory. */
static int node_at(rn_lattice *L, int x, int y, int z) {
  int g[3] = {x, y, z};
  int64_t k = node_key(g);
  int n = map_get(&L->nodes, k);
  if (n >= 0) return n;
  if (!grow_array(&L->grid, &L->capn, L->nn + 1, 3) || !map_put(&L->nodes, k, L->nn)) {
    L->oom = 1;
    return -1;
  }
  memcpy(&L->grid[3 * L->nn], g, sizeof g);
  return L->nn++;
}

/* The bar between grid points p and q, added (running p -> q) if new. */
static void add_bar(rn_lattice *L, const int *p, const int *q) {
  int a = node_at(L, p[0], p[1], p[2]), b = node_at(L, q[0], q[1], q[2]);
  if (a < 0 || b < 0) return;
  int64_t k = ((int64_t)(a < b ? a : b) << 32) | (int64_t)(a < b ? b : a);
  if (map_get(&L->bars, k) >= 0) return;
  if (!grow_array(&L->bar, &L->capb, L->nb + 1, 2) || !map_put(&L->bars, k, L->nb)) {
    L->oom = 1;
    return;
  }
  L->bar[2 * L->nb] = a;
  L->bar[2 * L->nb + 1] = b;
  L->nb++;
}

/* Closed polygon of n corners (cx + dx[k], cy + dy[k]) in the plane z = 0. */
static void add_polygon(rn_lattice *L, int cx, int cy, int n, const int *dx,
                        const int *dy) {
  for (int k = 0; k < n; k++) {
    int k1 = (k + 1) % n;
    int p[3] = {cx + dx[k], cy + dy[k], 0}, q[3] = {cx + dx[k1], cy + dy[k1], 0};
    add_bar(L, p, q);
  }
}

/* ---- the kinds (grid units and cell contents: docs/lattices.md) ----------------- */

static void build_square(rn_lattice *L, const int *c) {
  static const int dx[4] = {0, 1, 1, 0}, dy[4] = {0, 0, 1, 1};
  for (int j = 0; j < c[1]; j++)
    for (int i = 0; i < c[0]; i++) add_polygon(L, i, j, 4, dx, dy);
}

/* Node (i, j) of the row scheme (row j shifted by half a period when odd). */
static void tri_corner(int i, int j, int *x, int *y) {
  *x = 2 * i + (j & 1);
  *y = j;
}

static void build_triangular(rn_lattice *L, const int *c) {
  for (int j = 0; j < c[1]; j++)
    for (int i = 0; i < c[0]; i++) {
      /* two triangles per cell: for an even band (i,j) (i+1,j) (i,j+1) and
       * (i,j+1) (i+1,j+1) (i+1,j); for an odd band (i,j) (i+1,j) (i+1,j+1) and
       * (i,j+1) (i+1,j+1) (i,j) */
      int odd = j & 1, ci[6], cj[6];
      int ti[6] = {i, i + 1, odd ? i + 1 : i, i, i + 1, odd ? i : i + 1};
      int tj[6] = {j, j, j + 1, j + 1, j + 1, j};
      for (int k = 0; k < 6; k++) tri_corner(ti[k], tj[k], &ci[k], &cj[k]);
      for (int t = 0; t < 2; t++) {
        int dx[3], dy[3];
        for (int k = 0; k < 3; k++) {
          dx[k] = ci[3 * t + k];
          dy[k] = cj[3 * t + k];
        }
        add_polygon(L, 0, 0, 3, dx, dy);
      }
    }
}

static void build_honeycomb(rn_lattice *L, const int *c) {
  /* pointy-top hexagons, counter-clockwise from the bottom corner */
  static const int dx[6] = {0, 1, 1, 0, -1, -1}, dy[6] = {-2, -1, 1, 2, 1, -1};
  for (int j = 0; j < c[1]; j++)
    for (int i = 0; i < c[0]; i++) add_polygon(L, 2 * i + (j & 1), 3 * j, 6, dx, dy);
}

static void build_kagome(rn_lattice *L, const int *c) {
  /* flat-top hexagons touching at corners, counter-clockwise from +x */
  static const int dx[6] = {2, 1, -1, -2, -1, 1}, dy[6] = {0, 1, 1, 0, -1, -1};
  for (int j = 0; j < c[1]; j++)
    for (int i = 0; i < c[0]; i++) add_polygon(L, 4 * i + 2 * (j & 1), 2 * j, 6, dx, dy);
}

static void build_cubic(rn_lattice *L, const int *c) {
  for (int k = 0; k < c[2]; k++)
    for (int j = 0; j < c[1]; j++)
      for (int i = 0; i < c[0]; i++)
        for (int axis = 0; axis < 3; axis++)
          for (int s = 0; s < 4; s++) { /* the 4 cube edges along axis */
            int p[3] = {i, j, k};
            p[(axis + 1) % 3] += s & 1;
            p[(axis + 2) % 3] += s >> 1;
            int q[3] = {p[0], p[1], p[2]};
            q[axis] += 1;
            add_bar(L, p, q);
          }
}

static void build_bcc(rn_lattice *L, const int *c) {
  for (int k = 0; k < c[2]; k++)
    for (int j = 0; j < c[1]; j++)
      for (int i = 0; i < c[0]; i++)
        for (int s = 0; s < 8; s++) { /* centre to the 8 corners */
          int ctr[3] = {2 * i + 1, 2 * j + 1, 2 * k + 1};
          int q[3] = {2 * i + 2 * (s & 1), 2 * j + (s & 2), 2 * k + ((s & 4) >> 1)};
          add_bar(L, ctr, q);
        }
}

/* Centre of face (axis, side 0|1) of the cube with corner o (grid a/2). */
static void face_centre(const int *o, int axis, int side, int *f) {
  for (int d = 0; d < 3; d++) f[d] = o[d] + 1;
  f[axis] = o[axis] + 2 * side;
}

static void octet_cell(rn_lattice *L, const int *o) {
  for (int axis = 0; axis < 3; axis++)
    for (int side = 0; side < 2; side++) {
      int f[3];
      face_centre(o, axis, side, f);
      for (int s = 0; s < 4; s++) { /* face centre to its 4 corners */
        int q[3] = {o[0], o[1], o[2]};
        q[axis] += 2 * side;
        q[(axis + 1) % 3] += 2 * (s & 1);
        q[(axis + 2) % 3] += s & 2;
        add_bar(L, f, q);
      }
    }
  for (int a1 = 0; a1 < 3; a1++) /* centres of adjacent faces */
    for (int a2 = a1 + 1; a2 < 3; a2++)
      for (int s = 0; s < 4; s++) {
        int f1[3], f2[3];
        face_centre(o, a1, s & 1, f1);
        face_centre(o, a2, s >> 1, f2);
        add_bar(L, f1, f2);
      }
}

static void build_octet(rn_lattice *L, const int *c) {
  for (int k = 0; k < c[2]; k++)
    for (int j = 0; j < c[1]; j++)
      for (int i = 0; i < c[0]; i++) {
        int o[3] = {2 * i, 2 * j, 2 * k};
        octet_cell(L, o);
      }
}

/* Grid unit per axis for period a, and the bars the kind will have (upper
 * bound, for the size check). */
static void kind_scale(rn_lattice_kind kind, double a, double *s) {
  s[0] = s[1] = s[2] = a;
  switch (kind) {
  case RN_LATTICE_TRIANGULAR:
    s[0] = a / 2;
    s[1] = a * sqrt(3.0) / 2;
    break;
  case RN_LATTICE_HONEYCOMB:
    s[0] = a / 2;
    s[1] = a / (2 * sqrt(3.0));
    break;
  case RN_LATTICE_KAGOME:
    s[0] = a / 4;
    s[1] = a * sqrt(3.0) / 4;
    break;
  case RN_LATTICE_BCC:
  case RN_LATTICE_OCTET:
    s[0] = s[1] = s[2] = a / 2;
    break;
  default:
    break;
  }
}

static double bars_per_cell(rn_lattice_kind kind) {
  static const double n[RN_LATTICE_KIND_COUNT] = {4, 6, 6, 6, 12, 8, 36};
  return n[kind];
}

static void finish(rn_lattice *L) {
  for (int d = 0; d < 3; d++) {
    L->lo[d] = L->nn ? L->grid[d] : 0;
    L->hi[d] = L->lo[d];
  }
  for (int n = 0; n < L->nn; n++)
    for (int d = 0; d < 3; d++) {
      if (L->grid[3 * n + d] < L->lo[d]) L->lo[d] = L->grid[3 * n + d];
      if (L->grid[3 * n + d] > L->hi[d]) L->hi[d] = L->grid[3 * n + d];
    }
  for (int b = 0; b < 2 * L->nb; b++) L->valence[L->bar[b]]++;
}

static rn_status check_args(rn_context *ctx, rn_lattice_kind kind, const int *cells,
                            double a) {
  if (kind < 0 || kind >= RN_LATTICE_KIND_COUNT)
    return rn_context_set_error(ctx, RN_ERR_ARG, "lattice: unknown kind %d", (int)kind);
  int dim = rn_lattice_kind_dimension(kind);
  double total = 1;
  for (int d = 0; d < dim; d++) {
    if (cells[d] < 1 || cells[d] > RN_LATTICE_MAX_CELLS)
      return rn_context_set_error(ctx, RN_ERR_ARG,
                                  "lattice: cell count %d outside [1, %d]", cells[d],
                                  RN_LATTICE_MAX_CELLS);
    total *= cells[d];
  }
  if (!(a > 0) || !isfinite(a))
    return rn_context_set_error(ctx, RN_ERR_ARG, "lattice: cell size %g is not > 0", a);
  if (total * bars_per_cell(kind) > RN_LATTICE_MAX_BARS)
    return rn_context_set_error(ctx, RN_ERR_RANGE,
                                "lattice: %.0f cells of a %s lattice are too many (at "
                                "most %d bars)",
                                total, kind_names[kind], RN_LATTICE_MAX_BARS);
  return RN_OK;
}

rn_status rn_lattice_build(rn_context *ctx, rn_lattice_kind kind, const int cells[3],
                           double a, rn_lattice **out) {
  static void (*const builders[RN_LATTICE_KIND_COUNT])(rn_lattice *, const int *) = {
      build_square, build_triangular, build_honeycomb, build_kagome,
      build_cubic,  build_bcc,        build_octet};
  if (!out) return RN_ERR_ARG;
  *out = NULL;
  rn_status st = check_args(ctx, kind, cells, a);
  if (st) return st;
  int c[3] = {cells[0], cells[1], rn_lattice_kind_dimension(kind) == 3 ? cells[2] : 1};
  rn_lattice *L = calloc(1, sizeof *L);
  if (!L || !map_init(&L->nodes, 1024) || !map_init(&L->bars, 1024)) {
    rn_lattice_destroy(&L);
    return rn_context_set_error(ctx, RN_ERR_ALLOC, "lattice: out of memory");
  }
  L->kind = kind;
  kind_scale(kind, a, L->scale);
  builders[kind](L, c);
  if (!L->oom) L->valence = calloc((size_t)(L->nn ? L->nn : 1), sizeof *L->valence);
  if (L->oom || !L->valence) {
    rn_lattice_destroy(&L);
    return rn_context_set_error(ctx, RN_ERR_ALLOC, "lattice: out of memory");
  }
  finish(L);
  map_free(&L->nodes);
  map_free(&L->bars);
  *out = L;
  return RN_OK;
}

void rn_lattice_destroy(rn_lattice **lp) {
  if (!lp || !*lp) return;
  rn_lattice *L = *lp;
  map_free(&L->nodes);
  map_free(&L->bars);
  free(L->grid);
  free(L->bar);
  free(L->valence);
  free(L);
  *lp = NULL;
}

rn_lattice_kind rn_lattice_get_kind(const rn_lattice *L) { return L->kind; }
int rn_lattice_num_nodes(const rn_lattice *L) { return L ? L->nn : 0; }
int rn_lattice_num_bars(const rn_lattice *L) { return L ? L->nb : 0; }

void rn_lattice_node(const rn_lattice *L, int n, double xyz[3]) {
  for (int d = 0; d < 3; d++)
    xyz[d] = (double)(L->grid[3 * n + d] - L->lo[d]) * L->scale[d];
}

void rn_lattice_bar(const rn_lattice *L, int b, int nodes[2]) {
  nodes[0] = L->bar[2 * b];
  nodes[1] = L->bar[2 * b + 1];
}

int rn_lattice_valence(const rn_lattice *L, int n) { return L->valence[n]; }

int rn_lattice_face(const rn_lattice *L, int n, int axis) {
  int g = L->grid[3 * n + axis];
  if (L->lo[axis] == L->hi[axis]) return 0; /* flat along axis: no faces */
  return g == L->lo[axis] ? -1 : g == L->hi[axis] ? 1 : 0;
}

double rn_lattice_extent(const rn_lattice *L, int axis) {
  return (double)(L->hi[axis] - L->lo[axis]) * L->scale[axis];
}
