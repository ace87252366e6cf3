/* scene_periodic.c - the top-level "periodic" object of a scene: lattice
 * vectors, strain and stress control (docs/scene-format.md, "Periodic cells";
 * docs/homogenization.md), and the "image" of a joint end. */
#include <stdlib.h>
#include <string.h>

#include "scene_internal.h"

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
  static const char *const keys[] = {"vectors", "strain", "stress", NULL};
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
