/* homog_load.c - the macroscopic loading of `rodnet homogenize --path`,
 * `--path-stress` and `--path-file`: which strain components are strain- or
 * stress-controlled, their targets, the waypoints file (homog_path.h). */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli/homog_path.h"
#include "scene/scene_json.h"
#include "io/text_file.h"

int hp_parse_targets(const char *s, int stress_default, double *target, int *stress,
                     int *count) {
  int n = 0;
  const char *p = s;
  for (;;) {
    const char *end = p + 1;
    int is_stress = stress_default;
    double v = 0.0;
    if (n == 6) return -1;
    if (p[0] == '-' && (p[1] == ',' || p[1] == '\0')) {
      is_stress = 1;
    } else {
      char *e = NULL;
      if ((p[0] == 's' || p[0] == 'e') && p[1] == ':') {
        is_stress = p[0] == 's';
        p += 2;
      }
      v = strtod(p, &e);
      if (e == p || !isfinite(v)) return -1;
      end = e;
    }
    target[n] = v;
    stress[n++] = is_stress;
    if (*end == '\0') break;
    if (*end != ',') return -1;
    p = end + 1;
  }
  *count = n;
  return 0;
}

static const char *path_kind(const rn_cell_path_segment *g, int ns) {
  int nstress = 0;
  for (int v = 0; v < ns; ++v) nstress += g->stress[v];
  return nstress == 0 ? "strain" : nstress == ns ? "stress" : "mixed";
}

rn_status hp_single_segment(rn_context *ctx, hp_path *p, const double *target,
                            const int *stress, int steps) {
  p->seg = calloc(1, sizeof(rn_cell_path_segment));
  if (!p->seg) return rn_context_set_error(ctx, RN_ERR_ALLOC, "out of memory");
  p->nseg = 1;
  p->seg->steps = steps;
  for (int v = 0; v < p->ns; ++v) {
    p->seg->target[v] = target[v];
    p->seg->stress[v] = stress[v];
  }
  p->kind = path_kind(p->seg, p->ns);
  p->steps = steps;
  memcpy(p->target, p->seg->target, sizeof(p->target));
  return RN_OK;
}

/* An optional array of ns entries, each a number or null: given[v] says which. */
static rn_status read_controls(rn_jwalk *w, const cJSON *wp, const char *key, int ns,
                               double *val, int *given) {
  const cJSON *a = rn_jm_get(wp, key);
  int n = 0;
  rn_status st;
  for (int v = 0; v < ns; ++v) given[v] = 0;
  if (!a) return RN_OK;
  size_t mark = rn_jwalk_key(w, key);
  if ((st = rn_jv_array(w, a, &n))) goto done;
  if (n != ns) {
    st = rn_jwalk_error(w,
                        "expected %d entries (one per strain component of this %s "
                        "cell), got %d",
                        ns, ns == 3 ? "2D" : "3D", n);
    goto done;
  }
  for (int v = 0; v < ns; ++v) {
    const cJSON *e = cJSON_GetArrayItem(a, v);
    if (cJSON_IsNull(e)) continue;
    size_t m2 = rn_jwalk_index(w, v);
    st = rn_jv_number(w, e, RN_J_ANY, &val[v]);
    rn_jwalk_pop(w, m2);
    if (st) goto done;
    given[v] = 1;
  }
done:
  rn_jwalk_pop(w, mark);
  return st;
}

static rn_status read_waypoint(rn_jwalk *w, const cJSON *wp, int ns, int default_steps,
                               rn_cell_path_segment *g) {
  static const char *const keys[] = {"strain", "stress", "steps", NULL};
  static const char *const names2[] = {"E11", "E22", "E12"};
  static const char *const names3[] = {"E11", "E22", "E33", "E23", "E13", "E12"};
  double strain[6] = {0}, stress[6] = {0};
  int has_e[6], has_s[6], present = 0;
  rn_status st;
  if ((st = rn_jv_object(w, wp)) || (st = rn_json_check_keys(w, wp, keys))) return st;
  g->steps = default_steps;
  if ((st = rn_jm_int(w, wp, "steps", 0, 1, 100000, &g->steps, &present))) return st;
  if ((st = read_controls(w, wp, "strain", ns, strain, has_e)) ||
      (st = read_controls(w, wp, "stress", ns, stress, has_s)))
    return st;
  for (int v = 0; v < ns; ++v) {
    const char *name = ns == 3 ? names2[v] : names3[v];
    if (has_e[v] && has_s[v])
      return rn_jwalk_error(w,
                            "component %d (%s) has both a strain and a stress (give one "
                            "of them, the other null)",
                            v + 1, name);
    if (!has_e[v] && !has_s[v])
      return rn_jwalk_error(w,
                            "component %d (%s) has neither a strain nor a stress (a "
                            "number in \"strain\" or in \"stress\")",
                            v + 1, name);
    g->stress[v] = has_s[v];
    g->target[v] = has_s[v] ? stress[v] : strain[v];
  }
  return RN_OK;
}

rn_status hp_read_path_file(rn_context *ctx, const char *file, int default_steps,
                            hp_path *p) {
  char *text = NULL;
  size_t len = 0;
  cJSON *root = NULL;
  rn_jwalk w;
  int n = 0, total = 0;
  static const char *const keys[] = {"waypoints", NULL};
  rn_status st = rn_text_file_read(ctx, file, 1 << 24, &text, &len);
  if (!st) st = rn_json_parse_text(ctx, file, text, len, &root);
  if (st) goto done;
  rn_jwalk_init(&w, ctx, file);
  const cJSON *wps = NULL;
  if ((st = rn_jv_object(&w, root)) || (st = rn_json_check_keys(&w, root, keys)) ||
      (st = rn_jm_require(&w, root, "waypoints", &wps)))
    goto done;
  size_t mark = rn_jwalk_key(&w, "waypoints");
  if ((st = rn_jv_array(&w, wps, &n))) goto done;
  if (n < 1 || n > 1000) {
    st = rn_jwalk_error(&w, "expected 1 to 1000 waypoints, got %d", n);
    goto done;
  }
  p->seg = calloc((size_t)n, sizeof(rn_cell_path_segment));
  if (!p->seg) {
    st = rn_context_set_error(ctx, RN_ERR_ALLOC, "out of memory");
    goto done;
  }
  p->nseg = n;
  for (int k = 0; k < n; ++k) {
    size_t m2 = rn_jwalk_index(&w, k);
    if ((st = read_waypoint(&w, cJSON_GetArrayItem(wps, k), p->ns, default_steps,
                            &p->seg[k])))
      goto done;
    rn_jwalk_pop(&w, m2);
    total += p->seg[k].steps;
    if (total > 100000) {
      st = rn_jwalk_error(&w, "more than 100000 steps in all");
      goto done;
    }
  }
  rn_jwalk_pop(&w, mark);
  p->steps = total;
  p->kind = "waypoints";
  memcpy(p->target, p->seg[n - 1].target, sizeof(p->target));
done:
  if (st) {
    free(p->seg);
    p->seg = NULL;
    p->nseg = 0;
  }
  cJSON_Delete(root);
  free(text);
  return st;
}
