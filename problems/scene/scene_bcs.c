/* scene_bcs.c - the "constraints" and "loads" arrays of a scene. */
#include <stdio.h>
#include <string.h>

#include "rodnet_couple.h"
#include "scene/scene_internal.h"

/* obj["type"] as one of names[]; its index in *which. */
static rn_status read_type(rn_jwalk *w, const cJSON *obj, const char *what,
                           const char *const *names, int n, int *which) {
  const char *type = NULL;
  rn_status st = rn_jm_string(w, obj, "type", 1, &type);
  if (st) return st;
  for (int i = 0; i < n; i++)
    if (strcmp(type, names[i]) == 0) {
      *which = i;
      return RN_OK;
    }
  char list[256];
  size_t len = 0;
  list[0] = '\0';
  for (int i = 0; i < n; i++)
    len +=
        (size_t)snprintf(list + len, sizeof list - len, "%s%s", i ? ", " : "", names[i]);
  size_t mark = rn_jwalk_key(w, "type");
  st = rn_jwalk_error(w, "unknown %s type \"%s\" (known: %s)", what, type, list);
  rn_jwalk_pop(w, mark);
  return st;
}

rn_status rn_scene_end_ref(rn_jwalk *w, const cJSON *obj, int *end) {
  const char *s = NULL;
  rn_status st = rn_jm_string(w, obj, "end", 1, &s);
  if (st) return st;
  if (strcmp(s, "start") == 0)
    *end = RN_START;
  else if (strcmp(s, "end") == 0)
    *end = RN_END;
  else {
    size_t mark = rn_jwalk_key(w, "end");
    st = rn_jwalk_error(w, "expected \"start\" or \"end\", got \"%s\"", s);
    rn_jwalk_pop(w, mark);
  }
  return st;
}

/* Error msg at obj[key]. */
static rn_status error_at_key(rn_jwalk *w, const char *key, const char *msg) {
  size_t mark = rn_jwalk_key(w, key);
  rn_status st = rn_jwalk_error(w, "%s", msg);
  rn_jwalk_pop(w, mark);
  return st;
}

static rn_status lib(rn_jwalk *w, rn_status st) {
  return st ? rn_jwalk_lib_error(w, st) : RN_OK;
}

/* Exactly one of "rod" and "joint": *is_joint says which. */
static rn_status read_target(rn_jwalk *w, const cJSON *v, int *is_joint) {
  int has_rod = rn_jm_get(v, "rod") != NULL, has_joint = rn_jm_get(v, "joint") != NULL;
  if (has_rod && has_joint)
    return rn_jwalk_error(w, "give either \"rod\" or \"joint\", not both");
  if (!has_rod && !has_joint)
    return rn_jwalk_error(w, "missing required key \"rod\" (or \"joint\")");
  *is_joint = has_joint;
  return RN_OK;
}

/* The joint at vertex (0 or the last) of a rod, -1 if none. */
static int joint_at_vertex(const rn_scene_rod *r, int vertex) {
  if (vertex == 0 && r->joint[RN_START] >= 0) return r->joint[RN_START];
  if (vertex == r->nv - 1 && r->joint[RN_END] >= 0) return r->joint[RN_END];
  return -1;
}

/* Error at obj[key]: vertex of rod r is joint j (the whole end if clamp);
 * suggests {"type": type, "joint": ...}. */
static rn_status at_joint_error(rn_scene_parser *p, const char *key,
                                const rn_scene_rod *r, int vertex, int j,
                                const char *type) {
  char what[64];
  if (strcmp(type, "clamp") == 0)
    snprintf(what, sizeof what, "the %s", vertex == 0 ? "start" : "end");
  else
    snprintf(what, sizeof what, "vertex %d", vertex);
  const char *jn = p->scene->joints[j].name;
  size_t mark = rn_jwalk_key(&p->w, key);
  rn_status st = rn_jwalk_error(&p->w,
                                "%s of rod \"%s\" belongs to joint \"%s\": constrain "
                                "the joint instead ({\"type\": \"%s\", \"joint\": "
                                "\"%s\"})",
                                what, r->name, jn, type, jn);
  rn_jwalk_pop(&p->w, mark);
  return st;
}

/* ---- constraints ---------------------------------------------------------------- */

/* obj["components"] (optional): a non-empty array of distinct "x", "y", "z";
 * *mask receives the RN_FIX_* bitmask (RN_FIX_XYZ without the key), *given
 * whether the key is there. */
static rn_status read_components(rn_jwalk *w, const cJSON *obj, int *mask, int *given) {
  const cJSON *list = rn_jm_get(obj, "components");
  char got[64];
  rn_status st = RN_OK;
  *mask = RN_FIX_XYZ;
  *given = list != NULL;
  if (!list) return RN_OK;
  size_t mark = rn_jwalk_key(w, "components");
  rn_json_describe(list, got, sizeof got);
  if (!cJSON_IsArray(list) || !list->child)
    st = rn_jwalk_error(w,
                        "expected a non-empty array of distinct components \"x\", "
                        "\"y\", \"z\", got %s",
                        got);
  *mask = 0;
  int i = 0;
  for (const cJSON *c = st ? NULL : list->child; c && !st; c = c->next, i++) {
    size_t m = rn_jwalk_index(w, i);
    const char *s = cJSON_IsString(c) ? c->valuestring : NULL;
    int k = s && s[0] >= 'x' && s[0] <= 'z' && s[1] == '\0' ? s[0] - 'x' : -1;
    rn_json_describe(c, got, sizeof got);
    if (k < 0)
      st = rn_jwalk_error(w, "expected a component \"x\", \"y\" or \"z\", got %s", got);
    else if (*mask & (1 << k))
      st = rn_jwalk_error(w, "component \"%c\" is listed twice", "xyz"[k]);
    else
      *mask |= 1 << k;
    rn_jwalk_pop(w, m);
  }
  rn_jwalk_pop(w, mark);
  return st;
}

/* "[\"x\", \"z\"]" for a bitmask into buf[16]; returns buf. */
static const char *components_json(int mask, char *buf) {
  size_t n = 0;
  buf[n++] = '[';
  for (int k = 0; k < 3; k++)
    if (mask & (1 << k)) {
      if (n > 1) buf[n++] = ',', buf[n++] = ' ';
      buf[n++] = '"', buf[n++] = "xyz"[k], buf[n++] = '"';
    }
  buf[n++] = ']';
  buf[n] = '\0';
  return buf;
}

/* A displacement d of a point whose fixed components are `fixed`: with
 * "components" (mask, given) the value is zero outside them, and every
 * component it prescribes (the listed ones, else the non-zero ones of d) is
 * fixed.  what: "joint \"v3\"" or "vertex 4 of rod \"a\""; pin: the start of
 * the pin to suggest ("{\"type\": \"pin\", \"joint\": \"v3\""). */
static rn_status check_displaced_components(rn_jwalk *w, const double d[3], int mask,
                                            int given, int fixed, const char *what,
                                            const char *pin) {
  int want = 0;
  char missing[16], pinned[16], sugg[256];
  for (int k = 0; k < 3; k++) {
    if (d[k] != 0.0 && !(mask & (1 << k))) {
      size_t m1 = rn_jwalk_key(w, "value"), m2 = rn_jwalk_index(w, k);
      rn_status st = rn_jwalk_error(w,
                                    "the displacement along %c is %g, but \"components\" "
                                    "does not list \"%c\"",
                                    "xyz"[k], d[k], "xyz"[k]);
      rn_jwalk_pop(w, m2);
      rn_jwalk_pop(w, m1);
      return st;
    }
    if (given ? (mask & (1 << k)) : d[k] != 0.0) want |= 1 << k;
  }
  if (!(want & ~fixed)) return RN_OK;
  components_json(want & ~fixed, missing);
  components_json(fixed, pinned);
  snprintf(sugg, sizeof sugg, "%s, \"components\": %s}", pin, missing);
  return rn_jwalk_error(w,
                        "%s is not pinned in %s (pinned: %s): add %s to prescribe its "
                        "displacement there",
                        what, missing, pinned, sugg);
}

enum { C_CLAMP = 0, C_PIN, C_FIX_THETA, C_DISPLACE, C_COUNT };
static const char *const constraint_names[C_COUNT] = {"clamp", "pin", "fix_theta",
                                                      "displace"};

/* {"type": "clamp", "joint": name} or {"type": "pin", "joint": name,
 * "components": [...]}. */
static rn_status read_joint_support(rn_scene_parser *p, const cJSON *v, int clamp) {
  static const char *const clamp_keys[] = {"type", "joint", NULL};
  static const char *const pin_keys[] = {"type", "joint", "components", NULL};
  int j = -1, mask = RN_FIX_XYZ, given = 0;
  rn_status st = rn_json_check_keys(&p->w, v, clamp ? clamp_keys : pin_keys);
  if (!st) st = rn_scene_joint_ref(p, v, &j);
  if (!st) st = read_components(&p->w, v, &mask, &given);
  if (st) return st;
  rn_network *net = p->scene->net;
  st = lib(&p->w, clamp ? rn_network_clamp_joint(net, j)
                        : rn_network_pin_joint_components(net, j, mask));
  if (!st && clamp) p->scene->joints[j].clamped = 1;
  if (!st && !clamp) p->scene->joints[j].pinned |= mask;
  return st;
}

static rn_status read_clamp(rn_scene_parser *p, const cJSON *v) {
  static const char *const keys[] = {"type", "rod", "end", "at", NULL};
  int rod = -1, end = 0, is_joint = 0;
  rn_status st = read_target(&p->w, v, &is_joint);
  if (st || is_joint) return st ? st : read_joint_support(p, v, 1);
  st = rn_json_check_keys(&p->w, v, keys);
  if (!st) st = rn_scene_rod_ref(p, v, &rod);
  if (!st) st = rn_scene_end_ref(&p->w, v, &end);
  if (st) return st;
  const char *at = NULL; /* the rod's layout used it (scene_rods.c) */
  if ((st = rn_jm_string(&p->w, v, "at", 0, &at))) return st;
  if (at && strcmp(at, "midpoint") && strcmp(at, "vertex")) {
    size_t mark = rn_jwalk_key(&p->w, "at");
    st = rn_jwalk_error(&p->w, "expected \"midpoint\" or \"vertex\", got \"%s\"", at);
    rn_jwalk_pop(&p->w, mark);
    return st;
  }
  const rn_scene_rod *r = &p->scene->rods[rod];
  if (r->joint[end] >= 0)
    return at_joint_error(p, "end", r, end == RN_START ? 0 : r->nv - 1, r->joint[end],
                          "clamp");
  st = lib(&p->w, rn_network_clamp(p->scene->net, rod, end));
  if (!st) p->scene->rods[rod].clamped[end] = 1;
  return st;
}

static rn_status read_pin(rn_scene_parser *p, const cJSON *v) {
  static const char *const keys[] = {"type", "rod", "vertex", "components", NULL};
  int rod = -1, vertex = 0, is_joint = 0, mask = RN_FIX_XYZ, given = 0;
  rn_status st = read_target(&p->w, v, &is_joint);
  if (st || is_joint) return st ? st : read_joint_support(p, v, 0);
  st = rn_json_check_keys(&p->w, v, keys);
  if (!st) st = rn_scene_rod_ref(p, v, &rod);
  if (!st) st = rn_scene_index_ref(p, v, "vertex", rod, 0, &vertex);
  if (!st) st = read_components(&p->w, v, &mask, &given);
  if (st) return st;
  const rn_scene_rod *r = &p->scene->rods[rod];
  int j = joint_at_vertex(r, vertex);
  if (j >= 0) return at_joint_error(p, "vertex", r, vertex, j, "pin");
  st = lib(&p->w, rn_network_pin_components(p->scene->net, rod, vertex, mask));
  if (!st) p->scene->rods[rod].pinned[vertex] |= (unsigned char)mask;
  return st;
}

static rn_status read_fix_theta(rn_scene_parser *p, const cJSON *v) {
  static const char *const keys[] = {"type", "rod", "edge", NULL};
  int rod = -1, edge = 0;
  rn_status st = rn_json_check_keys(&p->w, v, keys);
  if (!st) st = rn_scene_rod_ref(p, v, &rod);
  if (!st) st = rn_scene_index_ref(p, v, "edge", rod, 1, &edge);
  if (!st) st = lib(&p->w, rn_network_fix_theta(p->scene->net, rod, edge));
  return st;
}

/* Fixed components of a rod vertex: its pins, all if in a clamped end. */
static int vertex_fixed(const rn_scene_rod *r, int vertex) {
  int in_clamp = (r->clamped[RN_START] && vertex <= 1) ||
                 (r->clamped[RN_END] && vertex >= r->nv - 2);
  return in_clamp ? RN_FIX_XYZ : r->pinned[vertex];
}

static rn_status read_displace_end(rn_scene_parser *p, const cJSON *v, int rod) {
  const rn_scene_rod *r = &p->scene->rods[rod];
  double d[3] = {0, 0, 0}, rot[3] = {0, 0, 0};
  int end = 0, has_d = 0, has_rot = 0;
  if (rn_jm_get(v, "components"))
    return error_at_key(&p->w, "components",
                        "\"components\" applies to a pinned vertex or joint; a clamped "
                        "end moves as a whole");
  rn_status st = rn_scene_end_ref(&p->w, v, &end);
  if (!st) st = rn_jm_vec(&p->w, v, "value", 0, 3, RN_J_ANY, d, &has_d);
  if (!st) st = rn_jm_vec(&p->w, v, "rotation", 0, 3, RN_J_ANY, rot, &has_rot);
  if (st) return st;
  if (!has_d && !has_rot)
    return rn_jwalk_error(&p->w, "give \"value\" (a displacement) and/or \"rotation\" "
                                 "(a rotation vector)");
  if (!r->clamped[end])
    return rn_jwalk_error(&p->w,
                          "the %s of rod \"%s\" is not clamped: add {\"type\": "
                          "\"clamp\", \"rod\": \"%s\", \"end\": \"%s\"}",
                          end == RN_START ? "start" : "end", r->name, r->name,
                          end == RN_START ? "start" : "end");
  return lib(&p->w, rn_network_displace_end(p->scene->net, rod, end, has_d ? d : NULL,
                                            has_rot ? rot : NULL));
}

static rn_status read_displace_vertex(rn_scene_parser *p, const cJSON *v, int rod) {
  const rn_scene_rod *r = &p->scene->rods[rod];
  double d[3];
  int vertex = 0;
  if (rn_jm_get(v, "rotation"))
    return error_at_key(&p->w, "rotation",
                        "a rotation applies to a clamped end; give \"end\" instead of "
                        "\"vertex\"");
  int mask = RN_FIX_XYZ, given = 0;
  rn_status st = rn_scene_index_ref(p, v, "vertex", rod, 0, &vertex);
  if (!st) st = rn_jm_vec(&p->w, v, "value", 1, 3, RN_J_ANY, d, NULL);
  if (!st) st = read_components(&p->w, v, &mask, &given);
  if (st) return st;
  int j = joint_at_vertex(r, vertex);
  if (j >= 0) return at_joint_error(p, "vertex", r, vertex, j, "displace");
  if (!vertex_fixed(r, vertex))
    return rn_jwalk_error(&p->w,
                          "vertex %d of rod \"%s\" is free: pin it (or clamp "
                          "its end) to prescribe its displacement",
                          vertex, r->name);
  char what[160], pin[192];
  snprintf(what, sizeof what, "vertex %d of rod \"%s\"", vertex, r->name);
  snprintf(pin, sizeof pin, "{\"type\": \"pin\", \"rod\": \"%s\", \"vertex\": %d",
           r->name, vertex);
  st = check_displaced_components(&p->w, d, mask, given, vertex_fixed(r, vertex), what,
                                  pin);
  if (st) return st;
  return lib(&p->w, rn_network_displace_vertex(p->scene->net, rod, vertex, d));
}

/* {"type": "displace", "joint": name, "value": d, "rotation": r,
 * "components": [...]}. */
static rn_status read_displace_joint(rn_scene_parser *p, const cJSON *v) {
  static const char *const keys[] = {"type",     "joint",      "value",
                                     "rotation", "components", NULL};
  double d[3] = {0, 0, 0}, rot[3] = {0, 0, 0};
  int j = -1, has_d = 0, has_rot = 0, mask = RN_FIX_XYZ, given = 0;
  rn_status st = rn_json_check_keys(&p->w, v, keys);
  if (!st) st = rn_scene_joint_ref(p, v, &j);
  if (!st) st = rn_jm_vec(&p->w, v, "value", 0, 3, RN_J_ANY, d, &has_d);
  if (!st) st = rn_jm_vec(&p->w, v, "rotation", 0, 3, RN_J_ANY, rot, &has_rot);
  if (!st) st = read_components(&p->w, v, &mask, &given);
  if (st) return st;
  const rn_scene_joint *J = &p->scene->joints[j];
  if (!has_d && !has_rot)
    return rn_jwalk_error(&p->w, "give \"value\" (a displacement) and/or \"rotation\" "
                                 "(a rotation vector)");
  if (!J->clamped && (has_rot || !J->pinned))
    return rn_jwalk_error(
        &p->w,
        "joint \"%s\" is not %s: add {\"type\": \"%s\", "
        "\"joint\": \"%s\"}",
        J->name, has_rot ? "clamped (a rotation needs a clamp)" : "pinned or clamped",
        has_rot ? "clamp" : "pin", J->name);
  char what[160], pin[192];
  snprintf(what, sizeof what, "joint \"%s\"", J->name);
  snprintf(pin, sizeof pin, "{\"type\": \"pin\", \"joint\": \"%s\"", J->name);
  st = check_displaced_components(&p->w, d, mask, given && has_d,
                                  J->clamped ? RN_FIX_XYZ : J->pinned, what, pin);
  if (st) return st;
  return lib(&p->w, rn_network_displace_joint(p->scene->net, j, has_d ? d : NULL,
                                              has_rot ? rot : NULL));
}

static rn_status read_displace(rn_scene_parser *p, const cJSON *v) {
  static const char *const keys[] = {"type",  "rod",      "end",        "vertex",
                                     "value", "rotation", "components", NULL};
  int rod = -1, is_joint = 0;
  rn_status st = read_target(&p->w, v, &is_joint);
  if (st || is_joint) return st ? st : read_displace_joint(p, v);
  st = rn_json_check_keys(&p->w, v, keys);
  if (!st) st = rn_scene_rod_ref(p, v, &rod);
  if (st) return st;
  int has_end = rn_jm_get(v, "end") != NULL, has_vertex = rn_jm_get(v, "vertex") != NULL;
  if (has_end == has_vertex)
    return rn_jwalk_error(&p->w, "give exactly one of \"end\" (a clamped end) and "
                                 "\"vertex\" (a pinned vertex)");
  return has_end ? read_displace_end(p, v, rod) : read_displace_vertex(p, v, rod);
}

/* Pass 0: clamp, pin, fix_theta; pass 1: displace (which needs them). */
rn_status rn_scene_read_constraints(rn_scene_parser *p, const cJSON *list) {
  int n = 0;
  rn_status st = rn_jv_array(&p->w, list, &n);
  for (int pass = 0; pass < 2 && !st; pass++) {
    int i = 0;
    for (const cJSON *v = list->child; v && !st; v = v->next, i++) {
      size_t mark = rn_jwalk_index(&p->w, i);
      int type = 0;
      st = rn_jv_object(&p->w, v);
      if (!st) st = read_type(&p->w, v, "constraint", constraint_names, C_COUNT, &type);
      if (!st && (type == C_DISPLACE) == (pass == 1)) {
        switch (type) {
        case C_CLAMP:
          st = read_clamp(p, v);
          break;
        case C_PIN:
          st = read_pin(p, v);
          break;
        case C_FIX_THETA:
          st = read_fix_theta(p, v);
          break;
        default:
          st = read_displace(p, v);
          break;
        }
      }
      rn_jwalk_pop(&p->w, mark);
    }
  }
  return st;
}

/* ---- loads ------------------------------------------------------------------------ */

enum { L_FORCE = 0, L_MOMENT, L_LINE_LOAD, L_GRAVITY, L_COUNT };
static const char *const load_names[L_COUNT] = {"force", "moment", "line_load",
                                                "gravity"};

/* The optional "model" of a moment load on a rod vertex or a joint
 * (rodnet_couple.h): "conservative" (default) or "fixed". */
static rn_status read_couple_model(rn_jwalk *w, const cJSON *v, rn_couple_model *model) {
  const char *s = "conservative";
  rn_status st = rn_jm_string(w, v, "model", 0, &s);
  if (st) return st;
  if (strcmp(s, "conservative") == 0) {
    *model = RN_COUPLE_CONSERVATIVE;
    return RN_OK;
  }
  size_t mark = rn_jwalk_key(w, "model");
  if (strcmp(s, "fixed") == 0)
    *model = RN_COUPLE_FIXED;
  else
    st = rn_jwalk_error(w, "unknown moment model \"%s\" (known: conservative, fixed)", s);
  rn_jwalk_pop(w, mark);
  return st;
}

/* {"type": "force" | "moment", "joint": name, "value": v}. */
static rn_status read_joint_load(rn_scene_parser *p, const cJSON *v, int moment) {
  static const char *const keys[] = {"type", "joint", "value", NULL};
  static const char *const moment_keys[] = {"type", "joint", "value", "model", NULL};
  int j = -1;
  double f[3];
  rn_couple_model model = RN_COUPLE_CONSERVATIVE;
  rn_status st = rn_json_check_keys(&p->w, v, moment ? moment_keys : keys);
  if (!st && moment) st = read_couple_model(&p->w, v, &model);
  if (!st) st = rn_scene_joint_ref(p, v, &j);
  if (!st) st = rn_jm_vec(&p->w, v, "value", 1, 3, RN_J_ANY, f, NULL);
  if (st) return st;
  rn_network *net = p->scene->net;
  return lib(&p->w, moment ? rn_network_add_joint_moment_model(net, j, f, model)
                           : rn_network_add_joint_force(net, j, f));
}

static rn_status read_point_load(rn_scene_parser *p, const cJSON *v, int moment) {
  static const char *const keys[] = {"type", "rod", "vertex", "value", NULL};
  static const char *const moment_keys[] = {"type",  "rod",   "vertex",
                                            "value", "model", NULL};
  int rod = -1, vertex = 0, is_joint = 0;
  double f[3];
  rn_couple_model model = RN_COUPLE_CONSERVATIVE;
  rn_status st = read_target(&p->w, v, &is_joint);
  if (st || is_joint) return st ? st : read_joint_load(p, v, moment);
  st = rn_json_check_keys(&p->w, v, moment ? moment_keys : keys);
  if (!st && moment) st = read_couple_model(&p->w, v, &model);
  if (!st) st = rn_scene_rod_ref(p, v, &rod);
  if (!st) st = rn_scene_index_ref(p, v, "vertex", rod, 0, &vertex);
  if (!st) st = rn_jm_vec(&p->w, v, "value", 1, 3, RN_J_ANY, f, NULL);
  if (st) return st;
  rn_network *net = p->scene->net;
  return lib(&p->w, moment ? rn_network_add_moment_model(net, rod, vertex, f, model)
                           : rn_network_add_force(net, rod, vertex, f));
}

static rn_status read_line_load(rn_scene_parser *p, const cJSON *v) {
  static const char *const keys[] = {"type", "rod", "value", NULL};
  int rod = -1;
  double w[3];
  rn_status st = rn_json_check_keys(&p->w, v, keys);
  if (!st) st = rn_scene_rod_ref(p, v, &rod);
  if (!st) st = rn_jm_vec(&p->w, v, "value", 1, 3, RN_J_ANY, w, NULL);
  if (!st) st = lib(&p->w, rn_network_add_line_load(p->scene->net, rod, w));
  return st;
}

static rn_status read_gravity(rn_scene_parser *p, const cJSON *v) {
  static const char *const keys[] = {"type", "value", NULL};
  double g[3];
  rn_status st = rn_json_check_keys(&p->w, v, keys);
  if (!st) st = rn_jm_vec(&p->w, v, "value", 1, 3, RN_J_ANY, g, NULL);
  if (st) return st;
  int any = 0;
  for (int i = 0; i < p->scene->nrods; i++) any |= p->scene->rods[i].max_density > 0;
  if (!any)
    return rn_jwalk_error(&p->w, "gravity acts through the material density, but no "
                                 "rod's material has a \"density\" > 0");
  return lib(&p->w, rn_network_add_gravity(p->scene->net, g));
}

rn_status rn_scene_read_loads(rn_scene_parser *p, const cJSON *list) {
  int n = 0;
  rn_status st = rn_jv_array(&p->w, list, &n);
  int i = 0;
  for (const cJSON *v = st ? NULL : list->child; v && !st; v = v->next, i++) {
    size_t mark = rn_jwalk_index(&p->w, i);
    int type = 0;
    st = rn_jv_object(&p->w, v);
    if (!st) st = read_type(&p->w, v, "load", load_names, L_COUNT, &type);
    if (!st) {
      switch (type) {
      case L_FORCE:
        st = read_point_load(p, v, 0);
        break;
      case L_MOMENT:
        st = read_point_load(p, v, 1);
        break;
      case L_LINE_LOAD:
        st = read_line_load(p, v);
        break;
      default:
        st = read_gravity(p, v);
        break;
      }
    }
    rn_jwalk_pop(&p->w, mark);
  }
  return st;
}
