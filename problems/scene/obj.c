/* obj.c - OBJ line-graph reader (obj.h). */
#include "scene/obj.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/text_file.h"
#include "scene/vec3.h"

/* Largest number of vertices or segments accepted (keeps allocations sane). */
#define RN_OBJ_MAX_ITEMS 50000000

typedef struct obj_vertex {
  double x[3];
  long line; /* of its v record */
  int valence;
} obj_vertex;

typedef struct obj_segment {
  long v[2]; /* raw indices while reading, then 0-based vertices */
  long line; /* of its l record */
} obj_segment;

struct rn_obj_graph {
  int nv, capv, ns, caps;
  obj_vertex *vert;
  obj_segment *seg;
};

typedef struct obj_reader {
  rn_context *ctx;
  const char *label;
  long line;
  rn_obj_graph *g;
} obj_reader;

/* A token of the current line: [s, s + n). */
typedef struct token {
  const char *s;
  size_t n;
} token;

#if defined(__GNUC__)
__attribute__((format(printf, 3, 4)))
#endif
static rn_status
fail_at(const obj_reader *r, long line, const char *fmt, ...) {
  char reason[512];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(reason, sizeof reason, fmt, ap);
  va_end(ap);
  if (line > 0)
    return rn_context_set_error(r->ctx, RN_ERR_PARSE, "%s:%ld: %s", r->label, line,
                                reason);
  return rn_context_set_error(r->ctx, RN_ERR_PARSE, "%s: %s", r->label, reason);
}

/* The token as printable text for messages (at most 32 characters). */
static const char *shown(token t, char *buf, size_t cap) {
  size_t j = 0;
  for (size_t i = 0; i < t.n && j + 4 < cap && i < 32; i++)
    buf[j++] =
        ((unsigned char)t.s[i] < 0x20 || (unsigned char)t.s[i] >= 0x7f || t.s[i] == '\'')
            ? '?'
            : t.s[i];
  if (t.n > 32 && j + 4 < cap) {
    memcpy(buf + j, "...", 3);
    j += 3;
  }
  buf[j] = '\0';
  return buf;
}

static int is_space(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

/* Next token of [*p, end), or n == 0 at the end of the line. */
static token next_token(const char **p, const char *end) {
  const char *s = *p;
  while (s < end && is_space(*s)) s++;
  const char *e = s;
  while (e < end && !is_space(*e)) e++;
  *p = e;
  token t = {s, (size_t)(e - s)};
  return t;
}

static int token_is(token t, const char *word) {
  return t.n == strlen(word) && memcmp(t.s, word, t.n) == 0;
}

/* ---- growing arrays ------------------------------------------------------- */

/* Room for need elements in *p (capacity *cap); 0 if out of memory. */
static int grow(void **p, int *cap, int need, size_t elem) {
  if (need <= *cap) return 1;
  int c = *cap ? *cap : 64;
  while (c < need) c = c > RN_OBJ_MAX_ITEMS / 2 ? RN_OBJ_MAX_ITEMS : 2 * c;
  void *np = realloc(*p, (size_t)c * elem);
  if (!np) return 0;
  *p = np;
  *cap = c;
  return 1;
}

static rn_status out_of_memory(const obj_reader *r) {
  return rn_context_set_error(r->ctx, RN_ERR_ALLOC, "%s:%ld: out of memory", r->label,
                              r->line);
}

static rn_status push_vertex(obj_reader *r, const double x[3]) {
  rn_obj_graph *g = r->g;
  if (g->nv >= RN_OBJ_MAX_ITEMS)
    return fail_at(r, r->line, "too many vertices (at most %d)", RN_OBJ_MAX_ITEMS);
  void *p = g->vert;
  if (!grow(&p, &g->capv, g->nv + 1, sizeof *g->vert)) return out_of_memory(r);
  g->vert = p;
  obj_vertex *v = &g->vert[g->nv++];
  memcpy(v->x, x, sizeof v->x);
  v->line = r->line;
  v->valence = 0;
  return RN_OK;
}

static rn_status push_segment(obj_reader *r, long a, long b) {
  rn_obj_graph *g = r->g;
  if (g->ns >= RN_OBJ_MAX_ITEMS)
    return fail_at(r, r->line, "too many segments (at most %d)", RN_OBJ_MAX_ITEMS);
  void *p = g->seg;
  if (!grow(&p, &g->caps, g->ns + 1, sizeof *g->seg)) return out_of_memory(r);
  g->seg = p;
  obj_segment *s = &g->seg[g->ns++];
  s->v[0] = a;
  s->v[1] = b;
  s->line = r->line;
  return RN_OK;
}

/* ---- records ---------------------------------------------------------------- */

static rn_status parse_coordinate(const obj_reader *r, token t, int k, double *out) {
  char buf[64], show[48];
  if (t.n >= sizeof buf)
    return fail_at(r, r->line, "coordinate %c: bad number '%s'", "xyz"[k],
                   shown(t, show, sizeof show));
  memcpy(buf, t.s, t.n);
  buf[t.n] = '\0';
  char *end = NULL;
  errno = 0;
  double x = strtod(buf, &end);
  if (end != buf + t.n || t.n == 0)
    return fail_at(r, r->line, "coordinate %c: bad number '%s'", "xyz"[k],
                   shown(t, show, sizeof show));
  if (!isfinite(x))
    return fail_at(r, r->line, "coordinate %c: '%s' is not a finite number", "xyz"[k],
                   shown(t, show, sizeof show));
  *out = x;
  return RN_OK;
}

static rn_status read_v(obj_reader *r, const char *p, const char *end) {
  double x[3];
  for (int k = 0; k < 3; k++) {
    token t = next_token(&p, end);
    if (t.n == 0)
      return fail_at(r, r->line, "a v record needs 3 coordinates (x y z), got %d", k);
    rn_status st = parse_coordinate(r, t, k, &x[k]);
    if (st) return st;
  }
  if (next_token(&p, end).n)
    return fail_at(r, r->line,
                   "a v record takes exactly 3 coordinates (x y z); "
                   "weights and vertex colours are not supported");
  return push_vertex(r, x);
}

/* An index token "i", "i/t" or "i//n": the raw vertex index (> 0), or a
 * negative one resolved against the vertices defined so far. */
static rn_status parse_index(const obj_reader *r, token t, long *out) {
  char buf[32], show[48];
  size_t n = 0;
  while (n < t.n && t.s[n] != '/') n++;
  if (n == 0 || n >= sizeof buf)
    return fail_at(r, r->line, "bad vertex index '%s'", shown(t, show, sizeof show));
  memcpy(buf, t.s, n);
  buf[n] = '\0';
  char *end = NULL;
  errno = 0;
  long i = strtol(buf, &end, 10);
  if (end != buf + n || errno)
    return fail_at(r, r->line, "bad vertex index '%s'", shown(t, show, sizeof show));
  if (i == 0)
    return fail_at(r, r->line, "vertex index 0 is invalid (OBJ indices start at 1)");
  if (i < 0) {
    long nv = r->g->nv;
    if (-i > nv)
      return fail_at(r, r->line,
                     "relative vertex index %ld is out of range (%ld vertices "
                     "defined before this line)",
                     i, nv);
    i += nv + 1;
  } else if (i > RN_OBJ_MAX_ITEMS)
    return fail_at(r, r->line, "vertex index %ld is out of range", i);
  *out = i;
  return RN_OK;
}

static rn_status read_l(obj_reader *r, const char *p, const char *end) {
  long prev = 0;
  int count = 0;
  rn_status st = RN_OK;
  for (token t = next_token(&p, end); t.n && !st; t = next_token(&p, end), count++) {
    long i = 0;
    st = parse_index(r, t, &i);
    if (!st && count > 0) st = push_segment(r, prev, i);
    prev = i;
  }
  if (!st && count < 2)
    st =
        fail_at(r, r->line, "an l record needs at least 2 vertex indices, got %d", count);
  return st;
}

static int ignored_record(token t) {
  static const char *const names[] = {"vn", "vt", "vp",     "o",
                                      "g",  "s",  "mtllib", "usemtl"};
  for (size_t i = 0; i < sizeof names / sizeof names[0]; i++)
    if (token_is(t, names[i])) return 1;
  return 0;
}

static rn_status read_line(obj_reader *r, const char *p, const char *end) {
  const char *hash = memchr(p, '#', (size_t)(end - p));
  if (hash) end = hash;
  token kw = next_token(&p, end);
  char show[48];
  if (kw.n == 0 || ignored_record(kw)) return RN_OK;
  if (token_is(kw, "v")) return read_v(r, p, end);
  if (token_is(kw, "l")) return read_l(r, p, end);
  if (token_is(kw, "f"))
    return fail_at(r, r->line,
                   "faces (f records) are not supported: rodnet reads line "
                   "graphs (v and l records)");
  return fail_at(r, r->line,
                 "unknown record '%s' (rodnet reads v and l records and ignores vn, "
                 "vt, vp, o, g, s, mtllib, usemtl)",
                 shown(kw, show, sizeof show));
}

/* ---- checks of the whole graph -------------------------------------------------- */

static rn_status resolve_indices(obj_reader *r) {
  rn_obj_graph *g = r->g;
  for (int s = 0; s < g->ns; s++) {
    obj_segment *sg = &g->seg[s];
    for (int k = 0; k < 2; k++) {
      if (sg->v[k] > g->nv)
        return fail_at(r, sg->line,
                       "vertex index %ld is out of range (the file defines %d "
                       "vertices)",
                       sg->v[k], g->nv);
      sg->v[k] -= 1;
    }
    if (sg->v[0] == sg->v[1])
      return fail_at(r, sg->line, "segment from vertex %ld to itself", sg->v[0] + 1);
    g->vert[sg->v[0]].valence++;
    g->vert[sg->v[1]].valence++;
  }
  return RN_OK;
}

/* Sort keys (qsort has no user pointer: the keys are copied). */
typedef struct seg_key {
  long lo, hi;
  int s;
} seg_key;

typedef struct pos_key {
  double x[3];
  int v;
} pos_key;

static int cmp_seg_keys(const void *pa, const void *pb) {
  const seg_key *a = pa, *b = pb;
  if (a->lo != b->lo) return a->lo < b->lo ? -1 : 1;
  if (a->hi != b->hi) return a->hi < b->hi ? -1 : 1;
  return (a->s > b->s) - (a->s < b->s);
}

static int cmp_pos_keys(const void *pa, const void *pb) {
  const pos_key *a = pa, *b = pb;
  for (int k = 0; k < 3; k++)
    if (a->x[k] != b->x[k]) return a->x[k] < b->x[k] ? -1 : 1;
  return (a->v > b->v) - (a->v < b->v);
}

/* The same unordered pair twice: reported at the later record. */
static rn_status check_duplicates(obj_reader *r) {
  rn_obj_graph *g = r->g;
  seg_key *key = malloc((size_t)(g->ns > 0 ? g->ns : 1) * sizeof *key);
  if (!key) return out_of_memory(r);
  for (int s = 0; s < g->ns; s++) {
    long a = g->seg[s].v[0], b = g->seg[s].v[1];
    key[s].lo = a < b ? a : b;
    key[s].hi = a < b ? b : a;
    key[s].s = s;
  }
  qsort(key, (size_t)g->ns, sizeof *key, cmp_seg_keys);
  rn_status st = RN_OK;
  for (int k = 1; k < g->ns && !st; k++)
    if (key[k].lo == key[k - 1].lo && key[k].hi == key[k - 1].hi) {
      const obj_segment *later = &g->seg[key[k].s], *first = &g->seg[key[k - 1].s];
      st = fail_at(r, later->line, "segment %ld-%ld is given twice (first on line %ld)",
                   later->v[0] + 1, later->v[1] + 1, first->line);
    }
  free(key);
  return st;
}

static double seg_length(const rn_obj_graph *g, int s) {
  return rn_dist3(g->vert[g->seg[s].v[0]].x, g->vert[g->seg[s].v[1]].x);
}

static rn_status check_lengths(obj_reader *r) {
  rn_obj_graph *g = r->g;
  double lmax = 0;
  for (int s = 0; s < g->ns; s++) {
    double l = seg_length(g, s);
    if (!isfinite(l))
      return fail_at(r, g->seg[s].line, "segment %ld-%ld is too long (overflow)",
                     g->seg[s].v[0] + 1, g->seg[s].v[1] + 1);
    if (l > lmax) lmax = l;
  }
  for (int s = 0; s < g->ns; s++)
    if (!(seg_length(g, s) > 1e-12 * lmax))
      return fail_at(r, g->seg[s].line,
                     "segment %ld-%ld has zero length (its vertices are at the same "
                     "position)",
                     g->seg[s].v[0] + 1, g->seg[s].v[1] + 1);
  return RN_OK;
}

/* Two used vertices at exactly the same position: reported at the later. */
static rn_status check_coincident(obj_reader *r) {
  rn_obj_graph *g = r->g;
  pos_key *key = malloc((size_t)(g->nv > 0 ? g->nv : 1) * sizeof *key);
  if (!key) return out_of_memory(r);
  int n = 0;
  for (int v = 0; v < g->nv; v++)
    if (g->vert[v].valence > 0) {
      memcpy(key[n].x, g->vert[v].x, sizeof key[n].x);
      key[n++].v = v;
    }
  qsort(key, (size_t)n, sizeof *key, cmp_pos_keys);
  rn_status st = RN_OK;
  for (int k = 1; k < n && !st; k++) {
    const pos_key *a = &key[k - 1], *b = &key[k];
    if (a->x[0] == b->x[0] && a->x[1] == b->x[1] && a->x[2] == b->x[2])
      st = fail_at(r, g->vert[b->v].line,
                   "vertex %d is at the same position as vertex %d (line %ld): merge "
                   "them (rods meeting there would not be joined)",
                   b->v + 1, a->v + 1, g->vert[a->v].line);
  }
  free(key);
  return st;
}

static rn_status check_graph(obj_reader *r) {
  if (r->g->ns == 0)
    return fail_at(r, 0, "no line segments (l records): the graph has no rods");
  rn_status st = resolve_indices(r);
  if (!st) st = check_duplicates(r);
  if (!st) st = check_lengths(r);
  if (!st) st = check_coincident(r);
  return st;
}

/* ---- entry points ----------------------------------------------------------------- */

static rn_status read_text(obj_reader *r, const char *text, size_t len) {
  const char *nul = memchr(text, '\0', len);
  const char *p = text, *end = text + len;
  rn_status st = RN_OK;
  for (r->line = 1; p < end && !st; r->line++) {
    const char *eol = memchr(p, '\n', (size_t)(end - p));
    if (!eol) eol = end;
    if (nul && nul >= p && nul < eol) return fail_at(r, r->line, "NUL byte in the file");
    st = read_line(r, p, eol);
    p = eol + 1;
  }
  return st ? st : check_graph(r);
}

rn_status rn_obj_graph_parse(rn_context *ctx, const char *label, const char *text,
                             size_t len, rn_obj_graph **out) {
  if (!out) return RN_ERR_ARG;
  *out = NULL;
  if (!ctx || (!text && len)) return RN_ERR_ARG;
  obj_reader r = {ctx, label ? label : "<obj>", 0, calloc(1, sizeof(rn_obj_graph))};
  if (!r.g) return rn_context_set_error(ctx, RN_ERR_ALLOC, "%s: out of memory", r.label);
  rn_status st = read_text(&r, text ? text : "", len);
  if (st) {
    rn_obj_graph_destroy(&r.g);
    return st;
  }
  *out = r.g;
  return RN_OK;
}

rn_status rn_obj_graph_load(rn_context *ctx, const char *path, rn_obj_graph **out) {
  if (!out) return RN_ERR_ARG;
  *out = NULL;
  if (!ctx || !path) return RN_ERR_ARG;
  char *text = NULL;
  size_t len = 0;
  rn_status st = rn_text_file_read(ctx, path, RN_OBJ_MAX_BYTES, &text, &len);
  if (st) return st;
  st = rn_obj_graph_parse(ctx, path, text, len, out);
  free(text);
  return st;
}

void rn_obj_graph_destroy(rn_obj_graph **gp) {
  if (!gp || !*gp) return;
  free((*gp)->vert);
  free((*gp)->seg);
  free(*gp);
  *gp = NULL;
}

/* ---- accessors ------------------------------------------------------------------- */

int rn_obj_graph_num_vertices(const rn_obj_graph *g) { return g ? g->nv : 0; }

rn_status rn_obj_graph_vertex(const rn_obj_graph *g, int v, double xyz[3]) {
  if (!g || !xyz) return RN_ERR_ARG;
  if (v < 0 || v >= g->nv) return RN_ERR_RANGE;
  memcpy(xyz, g->vert[v].x, 3 * sizeof(double));
  return RN_OK;
}

int rn_obj_graph_valence(const rn_obj_graph *g, int v) {
  return (g && v >= 0 && v < g->nv) ? g->vert[v].valence : -1;
}

int rn_obj_graph_vertex_line(const rn_obj_graph *g, int v) {
  return (g && v >= 0 && v < g->nv) ? (int)g->vert[v].line : -1;
}

int rn_obj_graph_num_segments(const rn_obj_graph *g) { return g ? g->ns : 0; }

rn_status rn_obj_graph_segment(const rn_obj_graph *g, int s, int ends[2]) {
  if (!g || !ends) return RN_ERR_ARG;
  if (s < 0 || s >= g->ns) return RN_ERR_RANGE;
  ends[0] = (int)g->seg[s].v[0];
  ends[1] = (int)g->seg[s].v[1];
  return RN_OK;
}

int rn_obj_graph_segment_line(const rn_obj_graph *g, int s) {
  return (g && s >= 0 && s < g->ns) ? (int)g->seg[s].line : -1;
}
