/* scene_rods.c - the "rods" array of a scene: geometry, material axis,
 * properties (per rod and per edge range) and rest shape. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rodnet_ring.h"
#include "scene/scene_internal.h"
#include "scene/vec3.h"

/* Largest vertex count accepted for one rod (keeps allocations sane). */
#define RN_SCENE_MAX_VERTICES 100000000L

static char *dup_string(const char *s) {
  size_t n = strlen(s) + 1;
  char *d = malloc(n);
  if (d) memcpy(d, s, n);
  return d;
}

/* "a, b, c" of the names, truncated to fit. */
static void name_list(const char *const *names, int n, char *buf, size_t cap) {
  size_t len = 0;
  buf[0] = '\0';
  for (int i = 0; i < n && len + 1 < cap; i++) {
    int k = snprintf(buf + len, cap - len, "%s\"%s\"", i ? ", " : "", names[i]);
    if (k < 0) break;
    len += (size_t)k;
  }
}

/* ---- references from constraints and loads --------------------------------- */

rn_status rn_scene_rod_ref(rn_scene_parser *p, const cJSON *obj, int *rod) {
  const char *name = NULL;
  rn_status st = rn_jm_string(&p->w, obj, "rod", 1, &name);
  if (st) return st;
  *rod = rn_scene_find_rod(p->scene, name);
  if (*rod >= 0) return RN_OK;
  const rn_scene *s = p->scene;
  char list[512];
  size_t len = 0;
  list[0] = '\0';
  for (int i = 0; i < s->nrods && len + 1 < sizeof list; i++) {
    int k = snprintf(list + len, sizeof list - len, "%s\"%s\"", i ? ", " : "",
                     s->rods[i].name);
    if (k < 0) break;
    len += (size_t)k;
  }
  size_t mark = rn_jwalk_key(&p->w, "rod");
  st = rn_jwalk_error(&p->w, "no rod named \"%s\" (rods: %s)", name, list);
  rn_jwalk_pop(&p->w, mark);
  return st;
}

rn_status rn_scene_index_value(rn_scene_parser *p, const cJSON *v, int rod, int edges,
                               int *out) {
  const rn_scene_rod *r = &p->scene->rods[rod];
  int n = edges ? r->nv - 1 : r->nv, idx = 0;
  rn_status st = rn_jv_int(&p->w, v, -2147483647L, 2147483646L, &idx);
  if (st) return st;
  if (idx >= n || idx < -n)
    return rn_jwalk_error(&p->w,
                          "%s index %d is out of range for rod \"%s\" with %d "
                          "%s (valid: 0 .. %d, or -%d .. -1 from the end)",
                          edges ? "edge" : "vertex", idx, r->name, n,
                          edges ? "edges" : "vertices", n - 1, n);
  *out = idx < 0 ? idx + n : idx;
  return RN_OK;
}

rn_status rn_scene_index_ref(rn_scene_parser *p, const cJSON *obj, const char *key,
                             int rod, int edges, int *out) {
  const cJSON *v;
  rn_status st = rn_jm_require(&p->w, obj, key, &v);
  if (st) return st;
  size_t mark = rn_jwalk_key(&p->w, key);
  st = rn_scene_index_value(p, v, rod, edges, out);
  rn_jwalk_pop(&p->w, mark);
  return st;
}

/* ---- geometry ---------------------------------------------------------------- */

/* Which ends of the rod called name have a clamp with "at": "midpoint" in the
 * scene's constraints (bit RN_START / RN_END set in the result).  Loose: the
 * constraints are checked strictly when they are read (scene_bcs.c). */
static int midpoint_clamps(const cJSON *constraints, const char *name) {
  int ends = 0;
  for (const cJSON *c = constraints ? constraints->child : NULL; c; c = c->next) {
    const cJSON *type = rn_jm_get(c, "type"), *rod = rn_jm_get(c, "rod");
    const cJSON *end = rn_jm_get(c, "end"), *at = rn_jm_get(c, "at");
    if (!cJSON_IsString(type) || strcmp(type->valuestring, "clamp") ||
        !cJSON_IsString(rod) || strcmp(rod->valuestring, name) || !cJSON_IsString(end) ||
        !cJSON_IsString(at) || strcmp(at->valuestring, "midpoint"))
      continue;
    if (!strcmp(end->valuestring, "start")) ends |= 1 << RN_START;
    if (!strcmp(end->valuestring, "end")) ends |= 1 << RN_END;
  }
  return ends;
}

/* A straight rod from a to b: n vertices equally spaced, the end vertex at a
 * (b) or, if midpoint has bit RN_START (RN_END) set, the midpoint of the end
 * edge at a (b): the rod then reaches half an edge beyond. */
static rn_status read_line(rn_jwalk *w, const cJSON *v, double **xyz, int *nv,
                           int midpoint) {
  static const char *const keys[] = {"from", "to", "vertices", NULL};
  double a[3], b[3];
  int n = 0;
  rn_status st = rn_json_check_keys(w, v, keys);
  if (!st) st = rn_jm_vec(w, v, "from", 1, 3, RN_J_ANY, a, NULL);
  if (!st) st = rn_jm_vec(w, v, "to", 1, 3, RN_J_ANY, b, NULL);
  if (!st) st = rn_jm_int(w, v, "vertices", 1, 2, 2147483647L, &n, NULL);
  if (st) return st;
  if (n > RN_SCENE_MAX_VERTICES) {
    size_t mark = rn_jwalk_key(w, "vertices");
    st = rn_jwalk_error(w, "too many vertices: %d (at most %ld per rod)", n,
                        RN_SCENE_MAX_VERTICES);
    rn_jwalk_pop(w, mark);
    return st;
  }
  if (a[0] == b[0] && a[1] == b[1] && a[2] == b[2])
    return rn_jwalk_error(w, "\"from\" and \"to\" coincide: the edges would have "
                             "zero length");
  /* the parameter s of vertex i runs from s0 to 1 - s1 in equal steps, with
   * s0 = s1 = 0 for vertex ends and -h/2 for midpoint ends (h the step in s) */
  const int mid0 = (midpoint >> RN_START) & 1, mid1 = (midpoint >> RN_END) & 1;
  const double half0 = mid0 ? 0.5 : 0.0, half1 = mid1 ? 0.5 : 0.0;
  const double steps = (double)(n - 1) - half0 - half1;
  if (!(steps > 0.0))
    return rn_jwalk_error(w, "a clamp \"at\": \"midpoint\" at both ends needs at "
                             "least 3 vertices");
  const double h = 1.0 / steps;
  double *x = malloc(3 * (size_t)n * sizeof *x);
  if (!x) return rn_jwalk_fail(w, RN_ERR_ALLOC, "out of memory for %d vertices", n);
  for (int i = 0; i < n; i++) {
    double s = !midpoint             ? (double)i / (double)(n - 1)
               : i == n - 1 && !mid1 ? 1.0
                                     : ((double)i - half0) * h;
    for (int k = 0; k < 3; k++) x[3 * i + k] = (1 - s) * a[k] + s * b[k];
  }
  *xyz = x;
  *nv = n;
  return RN_OK;
}

static rn_status read_vertex_list(rn_jwalk *w, const cJSON *v, double **xyz, int *nv) {
  int n = 0;
  rn_status st = rn_jv_array(w, v, &n);
  if (st) return st;
  if (n < 2) return rn_jwalk_error(w, "expected at least 2 vertices, got %d", n);
  if (n > RN_SCENE_MAX_VERTICES)
    return rn_jwalk_error(w, "too many vertices: %d (at most %ld per rod)", n,
                          RN_SCENE_MAX_VERTICES);
  double *x = malloc(3 * (size_t)n * sizeof *x);
  if (!x) return rn_jwalk_fail(w, RN_ERR_ALLOC, "out of memory for %d vertices", n);
  int i = 0;
  for (const cJSON *c = v->child; c && !st; c = c->next, i++) {
    size_t mark = rn_jwalk_index(w, i);
    st = rn_jv_vec(w, c, 3, RN_J_ANY, &x[3 * i]);
    rn_jwalk_pop(w, mark);
  }
  if (st) {
    free(x);
    return st;
  }
  *xyz = x;
  *nv = n;
  return RN_OK;
}

/* Zero-length edges and fold-backs.  explicit_list: the walker is at the
 * "vertices" list, so errors name the offending vertex. */
static rn_status check_polyline(rn_jwalk *w, const double *x, int nv, int explicit_list) {
  double lmax = 0;
  for (int i = 0; i + 1 < nv; i++) {
    double e[3] = {x[3 * i + 3] - x[3 * i], x[3 * i + 4] - x[3 * i + 1],
                   x[3 * i + 5] - x[3 * i + 2]};
    double l = sqrt(rn_dot3(e, e));
    if (!isfinite(l)) return rn_jwalk_error(w, "edge %d is too long (overflow)", i);
    if (l > lmax) lmax = l;
  }
  for (int i = 0; i + 1 < nv; i++) {
    const double *a = &x[3 * i], *b = &x[3 * i + 3];
    double e[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    double l = sqrt(rn_dot3(e, e));
    rn_status st = RN_OK;
    size_t mark = explicit_list ? rn_jwalk_index(w, i + 1) : w->len;
    if (!(l > 1e-12 * lmax))
      st = rn_jwalk_error(w, "edge %d has zero length (vertices %d and %d coincide)", i,
                          i, i + 1);
    else if (i > 0) {
      const double *z = &x[3 * i - 3];
      double f[3] = {a[0] - z[0], a[1] - z[1], a[2] - z[2]};
      double c = rn_dot3(e, f) / (l * sqrt(rn_dot3(f, f)));
      if (c <= -1 + 1e-12)
        st = rn_jwalk_error(w,
                            "edges %d and %d point in opposite directions (the "
                            "polyline folds back on itself at vertex %d)",
                            i - 1, i, i);
    }
    rn_jwalk_pop(w, mark);
    if (st) return st;
  }
  return RN_OK;
}

static rn_status read_geometry(rn_jwalk *w, const cJSON *rod, int midpoint, double **xyz,
                               int *nv) {
  const cJSON *line = rn_jm_get(rod, "line"), *verts = rn_jm_get(rod, "vertices");
  if ((line != NULL) == (verts != NULL))
    return rn_jwalk_error(w, "give exactly one of \"line\" ({from, to, vertices}) "
                             "and \"vertices\" ([[x, y, z], ...])");
  if (verts && midpoint)
    return rn_jwalk_error(w, "a clamp \"at\": \"midpoint\" lays out a rod given by "
                             "\"line\"; for \"vertices\" place the clamped edge "
                             "yourself and drop \"at\"");
  size_t mark = rn_jwalk_key(w, line ? "line" : "vertices");
  rn_status st =
      line ? read_line(w, line, xyz, nv, midpoint) : read_vertex_list(w, verts, xyz, nv);
  if (!st) {
    st = check_polyline(w, *xyz, *nv, verts != NULL);
    if (st) {
      free(*xyz);
      *xyz = NULL;
    }
  }
  rn_jwalk_pop(w, mark);
  return st;
}

static rn_status read_d1(rn_jwalk *w, const cJSON *rod, const double *xyz, double d1[3],
                         int *present) {
  rn_status st = rn_jm_vec(w, rod, "d1", 0, 3, RN_J_ANY, d1, present);
  if (st || !*present) return st;
  double t[3] = {xyz[3] - xyz[0], xyz[4] - xyz[1], xyz[5] - xyz[2]};
  double tt = rn_dot3(t, t), dd = rn_dot3(d1, d1), dt = rn_dot3(d1, t);
  size_t mark = rn_jwalk_key(w, "d1");
  if (!(dd > 0))
    st = rn_jwalk_error(w, "the material axis must not be the zero vector");
  else if (!(dd - dt * dt / tt > 1e-16 * dd))
    st = rn_jwalk_error(w, "the material axis is parallel to the rod's first edge; "
                           "it needs a component perpendicular to it");
  rn_jwalk_pop(w, mark);
  return st;
}

/* ---- properties ---------------------------------------------------------------- */

/* The material or section (what) that obj's key names: its index into *out,
 * else an error listing the names defined. */
static rn_status property_ref(rn_scene_parser *p, const cJSON *obj, const char *key,
                              int (*find)(const rn_scene_parser *, const char *),
                              const char *const *names, int n, int *out) {
  const char *name = NULL;
  rn_status st = rn_jm_string(&p->w, obj, key, 1, &name);
  if (st) return st;
  *out = find(p, name);
  if (*out >= 0) return RN_OK;
  char list[512];
  name_list(names, n, list, sizeof list);
  size_t mark = rn_jwalk_key(&p->w, key);
  st = rn_jwalk_error(&p->w, "unknown %s \"%s\" (defined: %s)", key, name, list);
  rn_jwalk_pop(&p->w, mark);
  return st;
}

rn_status rn_scene_material_ref(rn_scene_parser *p, const cJSON *obj, int *m) {
  return property_ref(p, obj, "material", rn_scene_parser_material, p->mat_names, p->nmat,
                      m);
}

rn_status rn_scene_section_ref(rn_scene_parser *p, const cJSON *obj, int *s) {
  return property_ref(p, obj, "section", rn_scene_parser_section, p->sec_names, p->nsec,
                      s);
}

/* Set material m / section s (either may be -1) on edges [first, last]. */
static rn_status set_properties(rn_scene_parser *p, int rod, int first, int last, int m,
                                int s) {
  rn_network *net = p->scene->net;
  int all = first == 0 && last == p->scene->rods[rod].nv - 2;
  rn_status st = RN_OK;
  for (int e = all ? -1 : first; e <= (all ? -1 : last) && !st; e++) {
    if (m >= 0) st = rn_network_set_material(net, rod, e, &p->mats[m]);
    if (!st && s >= 0) st = rn_network_set_section(net, rod, e, &p->secs[s]);
  }
  if (st) return rn_jwalk_lib_error(&p->w, st);
  if (m >= 0 && p->mats[m].density > p->scene->rods[rod].max_density)
    p->scene->rods[rod].max_density = p->mats[m].density;
  return RN_OK;
}

/* "edges": [first, last] or "edge": k of an edge_properties entry. */
static rn_status edge_range(rn_scene_parser *p, const cJSON *v, int rod, int *first,
                            int *last) {
  const cJSON *one = rn_jm_get(v, "edge"), *range = rn_jm_get(v, "edges");
  if ((one != NULL) == (range != NULL))
    return rn_jwalk_error(&p->w, "give exactly one of \"edge\" (an index) and "
                                 "\"edges\" ([first, last], inclusive)");
  if (one) {
    rn_status st = rn_scene_index_ref(p, v, "edge", rod, 1, first);
    *last = *first;
    return st;
  }
  size_t mark = rn_jwalk_key(&p->w, "edges");
  int n = 0;
  rn_status st = rn_jv_array(&p->w, range, &n);
  if (!st && n != 2)
    st = rn_jwalk_error(&p->w,
                        "expected [first, last] (2 edge indices), got an "
                        "array of %d",
                        n);
  int *ends[2] = {first, last};
  int k = 0;
  for (const cJSON *c = range->child; c && !st; c = c->next, k++) {
    size_t m2 = rn_jwalk_index(&p->w, k);
    st = rn_scene_index_value(p, c, rod, 1, ends[k]);
    rn_jwalk_pop(&p->w, m2);
  }
  if (!st && *first > *last)
    st = rn_jwalk_error(&p->w, "first edge %d comes after last edge %d", *first, *last);
  rn_jwalk_pop(&p->w, mark);
  return st;
}

static rn_status read_edge_properties(rn_scene_parser *p, const cJSON *list, int rod) {
  static const char *const keys[] = {"edge", "edges", "material", "section", NULL};
  int n = 0;
  rn_status st = rn_jv_array(&p->w, list, &n);
  int i = 0;
  for (const cJSON *v = list ? list->child : NULL; v && !st; v = v->next, i++) {
    size_t mark = rn_jwalk_index(&p->w, i);
    int first = 0, last = 0, m = -1, s = -1;
    st = rn_json_check_keys(&p->w, v, keys);
    if (!st) st = edge_range(p, v, rod, &first, &last);
    if (!st && !rn_jm_get(v, "material") && !rn_jm_get(v, "section"))
      st = rn_jwalk_error(&p->w, "give \"material\" and/or \"section\"");
    if (!st && rn_jm_get(v, "material")) st = rn_scene_material_ref(p, v, &m);
    if (!st && rn_jm_get(v, "section")) st = rn_scene_section_ref(p, v, &s);
    if (!st) st = set_properties(p, rod, first, last, m, s);
    rn_jwalk_pop(&p->w, mark);
  }
  return st;
}

/* ---- rest shape ------------------------------------------------------------------ */

/* value at the walker's path: an array of rows entries, each a number
 * (cols == 0) or an array of cols numbers. */
static rn_status read_table(rn_jwalk *w, const cJSON *v, int rows, int cols, rn_jrange r,
                            const char *per, double *out) {
  int n = 0;
  rn_status st = rn_jv_array(w, v, &n);
  if (st) return st;
  if (n != rows)
    return rn_jwalk_error(w, "expected %d entries (one per %s), got %d", rows, per, n);
  int i = 0;
  for (const cJSON *c = v->child; c && !st; c = c->next, i++) {
    size_t mark = rn_jwalk_index(w, i);
    if (cols == 0)
      st = rn_jv_number(w, c, r, &out[i]);
    else
      st = rn_jv_vec(w, c, cols, r, &out[cols * i]);
    rn_jwalk_pop(w, mark);
  }
  return st;
}

/* A closed rod's closing joint (-1 if the rod is open). */
static int closing_joint(const rn_scene *s, int rod) {
  const rn_scene_rod *r = &s->rods[rod];
  return (r->joint[RN_START] >= 0 && r->joint[RN_START] == r->joint[RN_END] &&
          rn_network_rod_is_closed(s->net, rod))
             ? r->joint[RN_START]
             : -1;
}

/* Per-vertex rest values of a closed rod: entry 0 belongs to the closing
 * joint (rest curvature and twist are set together: the one not given is
 * the input shape's, read back as 0 curvature / 0 twist only if given). */
static rn_status closed_rest(rn_scene_parser *p, int rod, int which, const double *buf) {
  rn_network *net = p->scene->net;
  if (which == 0) {
    rn_status st = rn_network_set_rest_curvature(net, rod, buf + 2);
    if (!st) memcpy(p->closed_kbar, buf, 2 * sizeof(double));
    p->closed_rest |= 1;
    return st;
  }
  rn_status st = rn_network_set_rest_twist(net, rod, buf + 1);
  if (!st) p->closed_taubar = buf[0];
  p->closed_rest |= 2;
  return st;
}

static rn_status read_rest_item(rn_scene_parser *p, const cJSON *rest, int rod,
                                int which) {
  static const char *const key[] = {"curvature", "twist", "lengths"};
  const cJSON *v = rn_jm_get(rest, key[which]);
  if (!v) return RN_OK;
  int nv = p->scene->rods[rod].nv, closed = closing_joint(p->scene, rod) >= 0;
  int rows = which == 2 ? nv - 1 : (closed ? nv - 1 : nv - 2), cols = which == 0 ? 2 : 0;
  double *buf = malloc(((size_t)rows * 2 + 1) * sizeof *buf);
  if (!buf) return rn_jwalk_fail(&p->w, RN_ERR_ALLOC, "out of memory");
  size_t mark = rn_jwalk_key(&p->w, key[which]);
  rn_status st =
      read_table(&p->w, v, rows, cols, which == 2 ? RN_J_POSITIVE : RN_J_ANY,
                 which == 2 ? "edge" : (closed ? "vertex" : "interior vertex"), buf);
  if (!st && closed && which < 2) {
    if ((st = closed_rest(p, rod, which, buf))) st = rn_jwalk_lib_error(&p->w, st);
  } else if (!st) {
    rn_network *net = p->scene->net;
    if (which == 0)
      st = rn_network_set_rest_curvature(net, rod, buf);
    else if (which == 1)
      st = rn_network_set_rest_twist(net, rod, buf);
    else
      st = rn_network_set_rest_lengths(net, rod, buf);
    if (st) st = rn_jwalk_lib_error(&p->w, st);
  }
  rn_jwalk_pop(&p->w, mark);
  free(buf);
  return st;
}

static rn_status read_rest(rn_scene_parser *p, const cJSON *rest, int rod) {
  static const char *const keys[] = {"curvature", "twist", "lengths", NULL};
  rn_status st = rn_json_check_keys(&p->w, rest, keys);
  p->closed_rest = 0;
  p->closed_kbar[0] = p->closed_kbar[1] = p->closed_taubar = 0.0;
  for (int which = 0; which < 3 && !st; which++) st = read_rest_item(p, rest, rod, which);
  if (!st && p->closed_rest) { /* vertex 0 of a closed rod: its joint's rest strains */
    int J = closing_joint(p->scene, rod);
    if (p->closed_rest != 3)
      return rn_jwalk_error(&p->w, "a closed rod gives \"curvature\" and \"twist\" "
                                   "together (vertex 0 is its closing joint's)");
    st = rn_network_set_joint_rest_strains(p->scene->net, J, p->closed_kbar,
                                           p->closed_taubar);
    if (st) st = rn_jwalk_lib_error(&p->w, st);
  }
  return st;
}

/* "closed": true: the vertex list does not repeat the first vertex; the rod is
 * stored with it repeated and closed by a smooth joint named after it.
 * "twist": {"link": n}: n full turns of twist stored in the ring
 * (rn_network_set_joint_link); {"total": T}: the ring's total twist starts at T
 * radians (rn_network_set_ring_total_twist). */
static rn_status read_closed(rn_scene_parser *p, const cJSON *v, int *closed) {
  const cJSON *c = rn_jm_get(v, "closed");
  *closed = 0;
  if (!c) return RN_OK;
  size_t mark = rn_jwalk_key(&p->w, "closed");
  rn_status st = RN_OK;
  if (!cJSON_IsBool(c))
    st = rn_jwalk_error(&p->w, "expected true or false");
  else
    *closed = cJSON_IsTrue(c);
  rn_jwalk_pop(&p->w, mark);
  return st;
}

static rn_status read_ring_twist(rn_scene_parser *p, const cJSON *v, int joint) {
  static const char *const keys[] = {"link", "total", NULL};
  const cJSON *t = rn_jm_get(v, "twist");
  rn_status st;
  int link = 0, has_link = 0, has_total = 0;
  double total = 0.0;
  if (!t) return RN_OK;
  size_t mark = rn_jwalk_key(&p->w, "twist");
  st = joint < 0 ? rn_jwalk_error(&p->w, "\"twist\" applies to closed rods only")
                 : rn_jv_object(&p->w, t);
  if (!st) st = rn_json_check_keys(&p->w, t, keys);
  if (!st && rn_jm_get(t, "link") && rn_jm_get(t, "total"))
    st = rn_jwalk_error(&p->w, "give either \"link\" or \"total\", not both");
  if (!st) st = rn_jm_int(&p->w, t, "link", 0, -1000000, 1000000, &link, &has_link);
  if (!st) st = rn_jm_number(&p->w, t, "total", 0, RN_J_ANY, &total, &has_total);
  if (!st && !has_link && !has_total)
    st = rn_jwalk_error(&p->w, "expected \"link\" (full turns) or \"total\" (radians)");
  if (!st && has_link && (st = rn_network_set_joint_link(p->scene->net, joint, link)))
    st = rn_jwalk_lib_error(&p->w, st);
  if (!st && has_total &&
      (st = rn_network_set_ring_total_twist(p->scene->net, joint, total)))
    st = rn_jwalk_lib_error(&p->w, st);
  rn_jwalk_pop(&p->w, mark);
  return st;
}

/* ---- one rod ------------------------------------------------------------------ */

rn_status rn_scene_lib_error(rn_scene_parser *p, rn_status st) {
  if (!p->where) return rn_jwalk_lib_error(&p->w, st);
  char msg[1024];
  const char *last = rn_context_last_error(p->w.ctx);
  snprintf(msg, sizeof msg, "%s", (last && *last) ? last : rn_status_message(st));
  return rn_jwalk_fail(&p->w, st, "%s: %s", p->where, msg);
}

static rn_status reserve_rods(rn_scene_parser *p, int extra) {
  rn_scene *s = p->scene;
  if (s->nrods + extra <= s->cap_rods) return RN_OK;
  int cap = s->nrods + extra;
  rn_scene_rod *r = realloc(s->rods, (size_t)cap * sizeof *r);
  if (!r) return rn_jwalk_fail(&p->w, RN_ERR_ALLOC, "out of memory");
  s->rods = r;
  s->cap_rods = cap;
  return RN_OK;
}

rn_status rn_scene_add_rod(rn_scene_parser *p, const char *name, int nv,
                           const double *xyz, const double *d1, int m, int sec,
                           int *rod) {
  rn_scene *s = p->scene;
  rn_status st = reserve_rods(p, 1);
  if (st) return st;
  rn_scene_rod *r = &s->rods[s->nrods];
  memset(r, 0, sizeof *r);
  r->joint[0] = r->joint[1] = -1;
  r->json_index = -1;
  r->name = dup_string(name);
  r->pinned = calloc((size_t)nv, 1);
  int idx = -1;
  if (!r->name || !r->pinned)
    st = rn_jwalk_fail(&p->w, RN_ERR_ALLOC, "out of memory");
  else if ((st = rn_network_add_rod(s->net, name, nv, xyz, d1, &idx)))
    st = rn_scene_lib_error(p, st);
  else if (idx != s->nrods)
    st =
        rn_jwalk_fail(&p->w, RN_ERR_INTERNAL, "rod index %d, expected %d", idx, s->nrods);
  if (st) {
    free(r->name);
    free(r->pinned);
    return st;
  }
  r->nv = nv;
  memcpy(r->end_xyz[RN_START], xyz, 3 * sizeof(double));
  memcpy(r->end_xyz[RN_END], &xyz[3 * (nv - 1)], 3 * sizeof(double));
  r->end_len[RN_START] = rn_dist3(&xyz[0], &xyz[3]);
  r->end_len[RN_END] = rn_dist3(&xyz[3 * (nv - 2)], &xyz[3 * (nv - 1)]);
  s->nrods++;
  *rod = idx;
  if (rn_name_index_put(&s->rod_names, r->name, idx))
    return rn_jwalk_fail(&p->w, RN_ERR_ALLOC, "out of memory");
  return set_properties(p, idx, 0, nv - 2, m, sec);
}

static rn_status read_rod_name(rn_scene_parser *p, const cJSON *v, const char **out) {
  const char *name = NULL;
  rn_status st = rn_jm_string(&p->w, v, "name", 1, &name);
  if (st) return st;
  size_t mark = rn_jwalk_key(&p->w, "name");
  if (!*name)
    st = rn_jwalk_error(&p->w, "expected a non-empty name");
  else if (rn_scene_find_rod(p->scene, name) >= 0)
    st = rn_jwalk_error(&p->w, "duplicate rod name \"%s\"", name);
  rn_jwalk_pop(&p->w, mark);
  *out = name;
  return st;
}

static rn_status read_rod(rn_scene_parser *p, const cJSON *v, int json_index) {
  static const char *const keys[] = {
      "name", "material", "section", "line", "vertices", "d1", "edge_properties",
      "rest", "closed",   "twist",   NULL};
  const char *name = NULL;
  double *xyz = NULL, d1[3];
  int nv = 0, has_d1 = 0, m = -1, sec = -1, rod = -1, closed = 0, joint = -1;
  rn_status st = rn_json_check_keys(&p->w, v, keys);
  if (!st) st = read_rod_name(p, v, &name);
  if (!st) st = read_closed(p, v, &closed);
  if (!st) st = rn_scene_material_ref(p, v, &m);
  if (!st) st = rn_scene_section_ref(p, v, &sec);
  if (!st) st = read_geometry(&p->w, v, midpoint_clamps(p->constraints, name), &xyz, &nv);
  if (!st && closed && nv < 3)
    st = rn_jwalk_error(&p->w, "a closed rod needs at least 3 vertices, got %d", nv);
  if (!st && closed) { /* repeat the first vertex: the stored rod */
    double *xc = realloc(xyz, 3 * ((size_t)nv + 1) * sizeof(double));
    if (!xc) st = rn_jwalk_fail(&p->w, RN_ERR_ALLOC, "out of memory");
    if (!st) {
      xyz = xc;
      memcpy(xyz + 3 * (size_t)nv, xyz, 3 * sizeof(double));
      nv++;
    }
  }
  if (!st) st = read_d1(&p->w, v, xyz, d1, &has_d1);
  if (!st) st = rn_scene_add_rod(p, name, nv, xyz, has_d1 ? d1 : NULL, m, sec, &rod);
  free(xyz);
  if (!st && closed) {
    int rods[2] = {rod, rod}, ends[2] = {RN_END, RN_START};
    st = rn_scene_add_joint(p, name, RN_JOINT_SMOOTH, 2, rods, ends, NULL, &joint);
  }
  if (!st) st = read_ring_twist(p, v, joint);
  if (st) return st;
  p->scene->rods[rod].json_index = json_index;
  const cJSON *ep = rn_jm_get(v, "edge_properties"), *rest = rn_jm_get(v, "rest");
  if (ep) {
    size_t mark = rn_jwalk_key(&p->w, "edge_properties");
    st = read_edge_properties(p, ep, rod);
    rn_jwalk_pop(&p->w, mark);
  }
  if (!st && rest) {
    size_t mark = rn_jwalk_key(&p->w, "rest");
    st = read_rest(p, rest, rod);
    rn_jwalk_pop(&p->w, mark);
  }
  return st;
}

rn_status rn_scene_read_rods(rn_scene_parser *p, const cJSON *rods) {
  int n = 0;
  rn_status st = rn_jv_array(&p->w, rods, &n);
  if (st) return st;
  if (n == 0) return rn_jwalk_error(&p->w, "expected at least one rod");
  if ((st = reserve_rods(p, n))) return st;
  int i = 0;
  for (const cJSON *v = rods->child; v && !st; v = v->next, i++) {
    size_t mark = rn_jwalk_index(&p->w, i);
    st = read_rod(p, v, i);
    rn_jwalk_pop(&p->w, mark);
  }
  return st;
}
