/* scene_periodic.c - the top-level "periodic" object of a scene: lattice
 * vectors, strain and stress control (docs/scene-format.md, "Periodic cells";
 * docs/homogenization.md), and the "image" of a joint end. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene/scene_internal.h"

/* "strain": one entry per component, a number (prescribed, scaled by the load
 * factor) or null (a DOF); "stress": numbers (applied macroscopic stress). */
static rn_status read_control(rn_scene_parser *p, const cJSON *per, int ns) {
  rn_jwalk *w = &p->w;
  const cJSON *v = rn_jm_get(per, "strain");
  rn_status st = RN_OK;
  if (v) {
    int n = 0, fixed[6] = {0}, k = 0;
    double e[6] = {0};
    size_t mark = rn_jwalk_key(w, "strain");
    st = rn_jv_array(w, v, &n);
    if (!st && n != ns)
      st = rn_jwalk_error(w, "expected %d strain components (%s), got %d", ns,
                          ns == 3 ? "E11, E22, E12" : "E11, E22, E33, E23, E13, E12", n);
    for (const cJSON *c = st ? NULL : v->child; c && !st; c = c->next, k++) {
      size_t m2 = rn_jwalk_index(w, k);
      if (!cJSON_IsNull(c)) {
        fixed[k] = 1;
        st = rn_jv_number(w, c, RN_J_ANY, &e[k]);
      }
      rn_jwalk_pop(w, m2);
    }
    if (!st && (st = rn_network_set_cell_strain(p->scene->net, fixed, e)))
      st = rn_scene_lib_error(p, st);
    rn_jwalk_pop(w, mark);
  }
  if (!st && (v = rn_jm_get(per, "stress"))) {
    double s[6] = {0};
    size_t mark = rn_jwalk_key(w, "stress");
    st = rn_jv_vec(w, v, ns, RN_J_ANY, s);
    if (!st && (st = rn_network_set_cell_stress(p->scene->net, s)))
      st = rn_scene_lib_error(p, st);
    rn_jwalk_pop(w, mark);
  }
  return st;
}

rn_status rn_scene_read_periodic(rn_scene_parser *p, const cJSON *per) {
  static const char *const keys[] = {"vectors", "strain", "stress", "repeat", NULL};
  rn_jwalk *w = &p->w;
  rn_scene *s = p->scene;
  const cJSON *vec = NULL;
  int n = 0, k = 0;
  rn_status st = rn_jv_object(w, per);
  if (!st) st = rn_json_check_keys(w, per, keys);
  if (!st) st = rn_jm_require(w, per, "vectors", &vec);
  if (st) return st;
  size_t mark = rn_jwalk_key(w, "vectors");
  st = rn_jv_array(w, vec, &n);
  if (!st && n != 2 && n != 3)
    st = rn_jwalk_error(
        w, "expected 2 lattice vectors (a 2D cell) or 3 (a 3D cell), got %d", n);
  memset(s->lattice, 0, sizeof s->lattice);
  for (const cJSON *c = st ? NULL : vec->child; c && !st; c = c->next, k++) {
    size_t m2 = rn_jwalk_index(w, k);
    st = rn_jv_vec(w, c, 3, RN_J_ANY, s->lattice + 3 * k);
    rn_jwalk_pop(w, m2);
  }
  if (!st && (st = rn_network_set_periodic(s->net, n, s->lattice)))
    st = rn_scene_lib_error(p, st);
  rn_jwalk_pop(w, mark);
  if (st) return st;
  s->periodic_dim = n;
  return read_control(p, per, n == 2 ? 3 : 6);
}

rn_status rn_scene_read_image(rn_scene_parser *p, const cJSON *end, int *image) {
  rn_jwalk *w = &p->w;
  const cJSON *v = rn_jm_get(end, "image");
  int n = 0, k = 0, dim = p->scene->periodic_dim;
  rn_status st = RN_OK;
  image[0] = image[1] = image[2] = 0;
  if (!v) return RN_OK;
  size_t mark = rn_jwalk_key(w, "image");
  if (dim == 0)
    st = rn_jwalk_error(w, "an image needs a periodic cell (the top-level \"periodic\" "
                           "object with its lattice vectors)");
  if (!st) st = rn_jv_array(w, v, &n);
  if (!st && n != dim)
    st = rn_jwalk_error(w, "expected %d lattice shifts (the cell has %d vectors), got %d",
                        dim, dim, n);
  for (const cJSON *c = st ? NULL : v->child; c && !st; c = c->next, k++) {
    size_t m2 = rn_jwalk_index(w, k);
    st = rn_jv_int(w, c, -1000000, 1000000, &image[k]);
    rn_jwalk_pop(w, m2);
  }
  rn_jwalk_pop(w, mark);
  return st;
}

void rn_scene_image_shift(const rn_scene *s, const int *image, double shift[3]) {
  for (int c = 0; c < 3; c++) {
    shift[c] = 0.0;
    for (int m = 0; m < s->periodic_dim; m++)
      shift[c] += image[m] * s->lattice[3 * m + c];
  }
}

/* ---- "repeat": the supercell of a periodic scene ---------------------------- */

/* Adds d to every point of a [[x, y, z], ...] array or a {"from", "to"} line
 * (numbers that are not there are left to the reader's checks). */
static void shift_point(cJSON *pt, const double d[3]) {
  int k = 0;
  for (cJSON *c = pt ? pt->child : NULL; c && k < 3; c = c->next, k++)
    if (cJSON_IsNumber(c)) cJSON_SetNumberValue(c, c->valuedouble + d[k]);
}

static void shift_rod(cJSON *rod, const double d[3]) {
  cJSON *line = cJSON_GetObjectItemCaseSensitive(rod, "line");
  cJSON *verts = cJSON_GetObjectItemCaseSensitive(rod, "vertices");
  if (line) {
    shift_point(cJSON_GetObjectItemCaseSensitive(line, "from"), d);
    shift_point(cJSON_GetObjectItemCaseSensitive(line, "to"), d);
  } else if (cJSON_IsArray(verts))
    for (cJSON *v = verts->child; v; v = v->next) shift_point(v, d);
}

/* "name" of copy c (cell (0, 0, 0) keeps the name: constraints and loads refer
 * to it). */
static int copy_name(char *buf, size_t n, const char *name, const int *c, int dim) {
  if (c[0] == 0 && c[1] == 0 && c[2] == 0) return snprintf(buf, n, "%s", name) < (int)n;
  if (dim == 2) return snprintf(buf, n, "%s@%d,%d", name, c[0], c[1]) < (int)n;
  return snprintf(buf, n, "%s@%d,%d,%d", name, c[0], c[1], c[2]) < (int)n;
}

static int fdiv_floor(int a, int b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }

/* One copy of a joint: its ends point at the rod copies whose ends meet it. */
static int copy_joint(cJSON *j, const int *c, const int *rep, int dim) {
  cJSON *ends = cJSON_GetObjectItemCaseSensitive(j, "ends");
  char buf[512];
  cJSON *nm = cJSON_GetObjectItemCaseSensitive(j, "name");
  if (!cJSON_IsString(nm) || !copy_name(buf, sizeof buf, nm->valuestring, c, dim) ||
      !cJSON_SetValuestring(nm, buf))
    return 0;
  for (cJSON *e = ends ? ends->child : NULL; e; e = e->next) {
    cJSON *rod = cJSON_GetObjectItemCaseSensitive(e, "rod");
    cJSON *img = cJSON_GetObjectItemCaseSensitive(e, "image");
    int n[3] = {0, 0, 0}, d[3], N[3], k = 0, any = 0;
    for (cJSON *v = img ? img->child : NULL; v && k < 3; v = v->next, k++)
      n[k] = cJSON_IsNumber(v) ? v->valueint : 0;
    for (int m = 0; m < 3; m++) { /* rod copy d ends at x_J + (n + d) a = x_J + c a
                                     + N (rep a): d = (c - n) mod rep */
      int f = m < dim ? fdiv_floor(c[m] - n[m], rep[m]) : 0;
      d[m] = c[m] - n[m] - f * rep[m];
      N[m] = -f;
      any |= N[m] != 0;
    }
    if (!cJSON_IsString(rod) || !copy_name(buf, sizeof buf, rod->valuestring, d, dim) ||
        !cJSON_SetValuestring(rod, buf))
      return 0;
    if (img) cJSON_DeleteItemFromObjectCaseSensitive(e, "image");
    if (any) {
      cJSON *arr = cJSON_CreateIntArray(N, dim);
      if (!arr) return 0;
      cJSON_AddItemToObject(e, "image", arr);
    }
  }
  return 1;
}

/* The "periodic" object's "repeat" (rv) of a cell of dim vectors: the counts
 * into rep, their product into *copies; the tiled scene's size bounded. */
static rn_status read_repeat(rn_jwalk *w, const cJSON *root, const cJSON *rv, int dim,
                             int rep[3], long *copies) {
  size_t mark = rn_jwalk_key(w, "periodic");
  size_t m2 = rn_jwalk_key(w, "repeat");
  int n = 0, k = 0;
  rn_status st =
      (dim == 2 || dim == 3)
          ? rn_jv_array(w, rv, &n)
          : rn_jwalk_error(w, "\"repeat\" needs the cell's \"vectors\" (2 or 3)");
  if (!st && n != dim)
    st = rn_jwalk_error(w, "expected %d repeat counts (the cell has %d vectors), got %d",
                        dim, dim, n);
  for (const cJSON *c = st ? NULL : rv->child; c && !st; c = c->next, k++) {
    size_t m3 = rn_jwalk_index(w, k);
    st = rn_jv_int(w, c, 1, 1000, &rep[k]);
    *copies *= rep[k];
    rn_jwalk_pop(w, m3);
  }
  if (!st && *copies > 100000)
    st = rn_jwalk_error(w, "%ld copies of the cell: at most 100000", *copies);
  if (!st) { /* the tiled scene's size: at most 2e6 rods and joints */
    const cJSON *ro = rn_jm_get(root, "rods"), *jo = rn_jm_get(root, "joints");
    long items = (cJSON_IsArray(ro) ? cJSON_GetArraySize(ro) : 0) +
                 (cJSON_IsArray(jo) ? cJSON_GetArraySize(jo) : 0);
    if (items * *copies > 2000000L)
      st = rn_jwalk_error(w,
                          "%ld copies of %ld rods and joints: at most 2000000 in the "
                          "tiled scene",
                          *copies, items);
  }
  if (!st && rn_jm_get(root, "graph"))
    st = rn_jwalk_error(w, "\"repeat\" needs explicit \"rods\" and \"joints\" (not a "
                           "\"graph\")");
  rn_jwalk_pop(w, m2);
  rn_jwalk_pop(w, mark);
  return st;
}

/* The copy c of the cell's rods and joints (orods, ojoints), shifted by d,
 * appended to rods and joints; 0 out of memory. */
static int add_copy(const cJSON *orods, const cJSON *ojoints, const int c[3],
                    const int rep[3], int dim, const double d[3], cJSON *rods,
                    cJSON *joints) {
  char buf[512];
  int ok = 1;
  for (const cJSON *o = cJSON_IsArray(orods) ? orods->child : NULL; ok && o;
       o = o->next) {
    cJSON *cp = cJSON_Duplicate(o, 1), *nm;
    ok = cp != NULL;
    if (ok && cJSON_IsString(nm = cJSON_GetObjectItemCaseSensitive(cp, "name")))
      ok = copy_name(buf, sizeof buf, nm->valuestring, c, dim) &&
           cJSON_SetValuestring(nm, buf) != NULL;
    if (ok) shift_rod(cp, d);
    if (cp) cJSON_AddItemToArray(rods, cp);
  }
  for (const cJSON *o = cJSON_IsArray(ojoints) ? ojoints->child : NULL; ok && o;
       o = o->next) {
    cJSON *cp = cJSON_Duplicate(o, 1);
    ok = cp != NULL && copy_joint(cp, c, rep, dim);
    if (cp) cJSON_AddItemToArray(joints, cp);
  }
  return ok;
}

/* The supercell's vectors rep[m] a[m] (NULL out of memory). */
static cJSON *supercell_vectors(double a[3][3], const int rep[3], int dim) {
  cJSON *nv = cJSON_CreateArray();
  for (int m = 0; nv && m < dim; m++) {
    double v3[3] = {rep[m] * a[m][0], rep[m] * a[m][1], rep[m] * a[m][2]};
    cJSON *x = cJSON_CreateDoubleArray(v3, 3);
    if (!x) {
      cJSON_Delete(nv);
      return NULL;
    }
    cJSON_AddItemToArray(nv, x);
  }
  return nv;
}

rn_status rn_scene_expand_repeat(rn_scene_parser *p, const cJSON *root, cJSON **out) {
  rn_jwalk *w = &p->w;
  const cJSON *per = rn_jm_get(root, "periodic"), *rv, *vec;
  int rep[3] = {1, 1, 1}, dim = 0, k = 0;
  long copies = 1;
  *out = NULL;
  if (!cJSON_IsObject(per) || !(rv = rn_jm_get(per, "repeat"))) return RN_OK;
  vec = rn_jm_get(per, "vectors");
  dim = cJSON_IsArray(vec) ? cJSON_GetArraySize(vec) : 0;
  rn_status st = read_repeat(w, root, rv, dim, rep, &copies);
  if (st) return st;
  cJSON *r = cJSON_Duplicate(root, 1), *rods = cJSON_CreateArray(),
        *joints = cJSON_CreateArray();
  const cJSON *orods = rn_jm_get(root, "rods"), *ojoints = rn_jm_get(root, "joints");
  double a[3][3] = {{0}};
  int ok = r && rods && joints;
  for (const cJSON *v = vec->child; v && k < 3; v = v->next, k++) {
    int q = 0;
    for (const cJSON *x = v->child; x && q < 3; x = x->next, q++)
      a[k][q] = cJSON_IsNumber(x) ? x->valuedouble : 0.0;
  }
  for (long ci = 0; ok && ci < copies; ci++) {
    int c[3] = {(int)(ci % rep[0]), (int)((ci / rep[0]) % rep[1]),
                (int)(ci / ((long)rep[0] * rep[1]))};
    double d[3] = {0.0, 0.0, 0.0};
    for (int q = 0; q < 3; q++)
      for (int m = 0; m < dim; m++) d[q] += c[m] * a[m][q];
    ok = add_copy(orods, ojoints, c, rep, dim, d, rods, joints);
  }
  cJSON *nv = ok ? supercell_vectors(a, rep, dim) : NULL;
  ok = ok && nv;
  if (ok) { /* the supercell's vectors, no repeat */
    cJSON *rper = cJSON_GetObjectItemCaseSensitive(r, "periodic");
    cJSON_ReplaceItemInObjectCaseSensitive(rper, "vectors", nv);
    cJSON_DeleteItemFromObjectCaseSensitive(rper, "repeat");
    if (orods) cJSON_ReplaceItemInObjectCaseSensitive(r, "rods", rods), rods = NULL;
    if (ojoints)
      cJSON_ReplaceItemInObjectCaseSensitive(r, "joints", joints), joints = NULL;
  }
  cJSON_Delete(rods);
  cJSON_Delete(joints);
  if (!ok) {
    cJSON_Delete(r);
    return rn_jwalk_fail(w, RN_ERR_ALLOC, "out of memory");
  }
  *out = r;
  return RN_OK;
}
