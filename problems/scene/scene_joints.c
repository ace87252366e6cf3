/* scene_joints.c - the "joints" array of a scene: rod ends joined at a point,
 * elastic or rigid (docs/scene-format.md, "Joints"). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene/scene_internal.h"

static const char *const model_names[] = {"elastic", "rigid",
                                          "smooth"}; /* rn_joint_model */
static const char *const end_names[] = {"start", "end"};

static char *dup_string(const char *s) {
  size_t n = strlen(s) + 1;
  char *d = malloc(n);
  if (d) memcpy(d, s, n);
  return d;
}

int rn_scene_find_joint(const rn_scene *s, const char *name) {
  return s ? rn_name_index_get(&s->joint_names, name) : -1;
}

rn_status rn_scene_joint_initial_position(const rn_scene *s, int joint, double x[3]) {
  if (!s || !x) return RN_ERR_ARG;
  if (joint < 0 || joint >= s->njoints) return RN_ERR_RANGE;
  memcpy(x, s->joints[joint].x0, 3 * sizeof(double));
  return RN_OK;
}

rn_status rn_scene_joint_model_ref(rn_jwalk *w, const cJSON *obj, const char *key,
                                   int *model) {
  const char *name = NULL;
  rn_status st = rn_jm_string(w, obj, key, 0, &name);
  if (st || !name) return st;
  if (strcmp(name, model_names[RN_JOINT_ELASTIC]) == 0)
    *model = RN_JOINT_ELASTIC;
  else if (strcmp(name, model_names[RN_JOINT_RIGID]) == 0)
    *model = RN_JOINT_RIGID;
  else if (strcmp(name, model_names[RN_JOINT_SMOOTH]) == 0)
    *model = RN_JOINT_SMOOTH;
  else {
    size_t mark = rn_jwalk_key(w, key);
    st = rn_jwalk_error(w, "unknown joint model \"%s\" (known: elastic, rigid, smooth)",
                        name);
    rn_jwalk_pop(w, mark);
  }
  return st;
}

rn_status rn_scene_joint_ref(rn_scene_parser *p, const cJSON *obj, int *joint) {
  const char *name = NULL;
  rn_status st = rn_jm_string(&p->w, obj, "joint", 1, &name);
  if (st) return st;
  *joint = rn_scene_find_joint(p->scene, name);
  if (*joint >= 0) return RN_OK;
  const rn_scene *s = p->scene;
  char list[512];
  size_t len = 0;
  list[0] = '\0';
  for (int i = 0; i < s->njoints && len + 1 < sizeof list; i++) {
    int k = snprintf(list + len, sizeof list - len, "%s\"%s\"", i ? ", " : "",
                     s->joints[i].name);
    if (k < 0) break;
    len += (size_t)k;
  }
  size_t mark = rn_jwalk_key(&p->w, "joint");
  if (s->njoints == 0)
    st = rn_jwalk_error(&p->w, "no joint named \"%s\" (the scene has no joints)", name);
  else
    st = rn_jwalk_error(&p->w, "no joint named \"%s\" (joints: %s)", name, list);
  rn_jwalk_pop(&p->w, mark);
  return st;
}

static rn_status reserve_joints(rn_scene_parser *p, int extra) {
  rn_scene *s = p->scene;
  if (s->njoints + extra <= s->cap_joints) return RN_OK;
  int cap = s->njoints + extra;
  rn_scene_joint *j = realloc(s->joints, (size_t)cap * sizeof *j);
  if (!j) return rn_jwalk_fail(&p->w, RN_ERR_ALLOC, "out of memory");
  s->joints = j;
  s->cap_joints = cap;
  return RN_OK;
}

rn_status rn_scene_add_joint(rn_scene_parser *p, const char *name, int model, int n,
                             const int *rods, const int *ends, const int *images,
                             int *joint) {
  rn_scene *s = p->scene;
  rn_status st = reserve_joints(p, 1);
  if (st) return st;
  rn_scene_joint *J = &s->joints[s->njoints];
  memset(J, 0, sizeof *J);
  J->model = model;
  J->json_index = -1;
  int idx = -1;
  if (!(J->name = dup_string(name)))
    st = rn_jwalk_fail(&p->w, RN_ERR_ALLOC, "out of memory");
  else if ((st = rn_network_add_joint_images(s->net, name, (rn_joint_model)model, n, rods,
                                             ends, images, &idx)))
    st = rn_scene_lib_error(p, st);
  else if (idx != s->njoints)
    st = rn_jwalk_fail(&p->w, RN_ERR_INTERNAL, "joint index %d, expected %d", idx,
                       s->njoints);
  if (st) {
    free(J->name);
    return st;
  }
  for (int k = 0; k < n; k++) s->rods[rods[k]].joint[ends[k]] = idx;
  memcpy(J->x0, s->rods[rods[0]].end_xyz[ends[0]], sizeof J->x0);
  if (images) { /* the first end's vertex minus its lattice shift */
    double sh[3];
    rn_scene_image_shift(s, images, sh);
    for (int c = 0; c < 3; c++) J->x0[c] -= sh[c];
  }
  s->njoints++;
  *joint = idx;
  if (rn_name_index_put(&s->joint_names, J->name, idx))
    return rn_jwalk_fail(&p->w, RN_ERR_ALLOC, "out of memory");
  return RN_OK;
}

/* ---- one joint ------------------------------------------------------------------- */

static rn_status read_joint_name(rn_scene_parser *p, const cJSON *v, const char **out) {
  rn_status st = rn_jm_string(&p->w, v, "name", 1, out);
  if (st) return st;
  size_t mark = rn_jwalk_key(&p->w, "name");
  if (!**out)
    st = rn_jwalk_error(&p->w, "expected a non-empty name");
  else if (rn_scene_find_joint(p->scene, *out) >= 0)
    st = rn_jwalk_error(&p->w, "duplicate joint name \"%s\"", *out);
  rn_jwalk_pop(&p->w, mark);
  return st;
}

/* End k of the list: {"rod": name, "end": "start" | "end"}, not joined
 * elsewhere and not listed twice (ends[0 .. k-1] of this joint). */
static rn_status read_joint_end(rn_scene_parser *p, const cJSON *v, int k, int *rods,
                                int *ends, int *images) {
  static const char *const keys[] = {"rod", "end", "image", NULL};
  const rn_scene *s = p->scene;
  rn_status st = rn_json_check_keys(&p->w, v, keys);
  if (!st) st = rn_scene_rod_ref(p, v, &rods[k]);
  if (!st) st = rn_scene_end_ref(&p->w, v, &ends[k]);
  if (!st) st = rn_scene_read_image(p, v, images + 3 * k);
  if (st) return st;
  const rn_scene_rod *r = &s->rods[rods[k]];
  int other = r->joint[ends[k]];
  if (other >= 0)
    return rn_jwalk_error(&p->w, "the %s of rod \"%s\" is already joined at joint \"%s\"",
                          end_names[ends[k]], r->name, s->joints[other].name);
  for (int i = 0; i < k; i++)
    if (rods[i] == rods[k] && ends[i] == ends[k])
      return rn_jwalk_error(&p->w, "the %s of rod \"%s\" is listed twice (ends[%d])",
                            end_names[ends[k]], r->name, i);
  return RN_OK;
}

/* The end vertices must coincide to 1e-9 of the shortest terminal edge (the
 * library's tolerance, rodnet.h); the walker is at "ends". */
static rn_status check_ends_meet(rn_scene_parser *p, int n, const int *rods,
                                 const int *ends, const int *images) {
  const rn_scene *s = p->scene;
  double lmin = INFINITY, x0[3], x[3], sh[3];
  for (int k = 0; k < n; k++)
    if (s->rods[rods[k]].end_len[ends[k]] < lmin)
      lmin = s->rods[rods[k]].end_len[ends[k]];
  rn_scene_image_shift(s, images, sh); /* ends at images: shifted back */
  for (int c = 0; c < 3; c++) x0[c] = s->rods[rods[0]].end_xyz[ends[0]][c] - sh[c];
  for (int k = 1; k < n; k++) {
    rn_scene_image_shift(s, images + 3 * k, sh);
    for (int c = 0; c < 3; c++) x[c] = s->rods[rods[k]].end_xyz[ends[k]][c] - sh[c];
    double d = sqrt((x[0] - x0[0]) * (x[0] - x0[0]) + (x[1] - x0[1]) * (x[1] - x0[1]) +
                    (x[2] - x0[2]) * (x[2] - x0[2]));
    if (d > 1e-9 * lmin) {
      size_t mark = rn_jwalk_index(&p->w, k);
      rn_status st = rn_jwalk_error(
          &p->w,
          "the rod ends do not meet: the %s of rod \"%s\" at [%.17g, %.17g, %.17g] is "
          "%.3g away from the %s of rod \"%s\" at [%.17g, %.17g, %.17g] (positions "
          "shifted back by their \"image\" lattice shifts)",
          end_names[ends[k]], s->rods[rods[k]].name, x[0], x[1], x[2], d,
          end_names[ends[0]], s->rods[rods[0]].name, x0[0], x0[1], x0[2]);
      rn_jwalk_pop(&p->w, mark);
      return st;
    }
  }
  return RN_OK;
}

static rn_status read_joint_ends(rn_scene_parser *p, const cJSON *list, int **rods,
                                 int **ends, int **images, int *n) {
  rn_status st = rn_jv_array(&p->w, list, n);
  if (st) return st;
  if (*n == 0) return rn_jwalk_error(&p->w, "expected at least one rod end");
  *rods = malloc((size_t)*n * sizeof **rods);
  *ends = malloc((size_t)*n * sizeof **ends);
  *images = malloc(3 * (size_t)*n * sizeof **images);
  if (!*rods || !*ends || !*images)
    return rn_jwalk_fail(&p->w, RN_ERR_ALLOC, "out of memory");
  int k = 0;
  for (const cJSON *v = list->child; v && !st; v = v->next, k++) {
    size_t mark = rn_jwalk_index(&p->w, k);
    st = read_joint_end(p, v, k, *rods, *ends, *images);
    rn_jwalk_pop(&p->w, mark);
  }
  return st ? st : check_ends_meet(p, *n, *rods, *ends, *images);
}

/* 1 if the rows of F (row-major) are orthonormal and right-handed to tol. */
static int rest_frame_ok(const double F[9], double tol) {
  for (int a = 0; a < 3; a++)
    for (int b = 0; b < 3; b++) {
      double d = F[3 * a] * F[3 * b] + F[3 * a + 1] * F[3 * b + 1] +
                 F[3 * a + 2] * F[3 * b + 2] - (a == b ? 1.0 : 0.0);
      if (!(fabs(d) <= tol)) return 0;
    }
  double det = F[0] * (F[4] * F[8] - F[5] * F[7]) - F[1] * (F[3] * F[8] - F[5] * F[6]) +
               F[2] * (F[3] * F[7] - F[4] * F[6]);
  return det > 0.0;
}

/* "frames": one rest frame [t, d1, d2] (3 rows of 3 numbers) per end of the
 * joint, in the order of "ends" (rn_network_set_joint_rest_frames). */
static rn_status read_rest_frames(rn_scene_parser *p, const cJSON *r, int joint) {
  rn_network *net = p->scene->net;
  int n = 0, valence = rn_network_joint_valence(net, joint);
  const cJSON *list = rn_jm_get(r, "frames");
  size_t mark = rn_jwalk_key(&p->w, "frames");
  rn_status st = rn_jv_array(&p->w, list, &n);
  if (!st && n != valence)
    st = rn_jwalk_error(&p->w,
                        "expected %d frames (one per end, in the order of \"ends\"), "
                        "got %d",
                        valence, n);
  double *F = st ? NULL : malloc(9 * (size_t)(n > 0 ? n : 1) * sizeof(double));
  if (!st && !F) st = rn_jwalk_fail(&p->w, RN_ERR_ALLOC, "out of memory");
  int k = 0;
  for (const cJSON *f = list ? list->child : NULL; f && !st; f = f->next, k++) {
    size_t mk = rn_jwalk_index(&p->w, k);
    int rows = 0;
    st = rn_jv_array(&p->w, f, &rows);
    if (!st && rows != 3)
      st = rn_jwalk_error(&p->w, "expected 3 rows [t, d1, d2], got %d", rows);
    int i = 0;
    for (const cJSON *row = f->child; row && !st; row = row->next, i++) {
      size_t mr = rn_jwalk_index(&p->w, i);
      st = rn_jv_vec(&p->w, row, 3, RN_J_ANY, F + 9 * k + 3 * i);
      rn_jwalk_pop(&p->w, mr);
    }
    if (!st && !rest_frame_ok(F + 9 * k, 1e-9))
      st = rn_jwalk_error(&p->w, "the rest frame (rows t, d1, d2) is not orthonormal and "
                                 "right-handed to 1e-9");
    rn_jwalk_pop(&p->w, mk);
  }
  rn_jwalk_pop(&p->w, mark);
  if (!st && (st = rn_network_set_joint_rest_frames(net, joint, F)))
    st = rn_jwalk_lib_error(&p->w, st);
  free(F);
  return st;
}

/* "rest": "straight", {"curvature": [k1, k2], "twist": t} (smooth joints) or
 * {"frames": [...]} (rigid and elastic joints). */
static rn_status read_joint_rest(rn_scene_parser *p, const cJSON *v, int joint) {
  static const char *const keys[] = {"curvature", "twist", "frames", NULL};
  const cJSON *r = rn_jm_get(v, "rest");
  rn_network *net = p->scene->net;
  rn_status st = RN_OK;
  if (!r) return RN_OK;
  size_t mark = rn_jwalk_key(&p->w, "rest");
  if (cJSON_IsString(r)) {
    if (strcmp(r->valuestring, "straight") != 0)
      st = rn_jwalk_error(&p->w,
                          "unknown rest shape \"%s\" (known: \"straight\", or "
                          "an object {\"curvature\", \"twist\"} or {\"frames\"})",
                          r->valuestring);
    else if ((st = rn_network_set_joint_rest_straight(net, joint)))
      st = rn_jwalk_lib_error(&p->w, st);
  } else {
    double k[2] = {0.0, 0.0}, t = 0.0;
    st = rn_jv_object(&p->w, r);
    if (!st) st = rn_json_check_keys(&p->w, r, keys);
    if (!st && rn_jm_get(r, "frames")) {
      if (rn_jm_get(r, "curvature") || rn_jm_get(r, "twist"))
        st = rn_jwalk_error(&p->w,
                            "give either \"frames\" (rigid and elastic joints) or "
                            "\"curvature\" and \"twist\" (smooth joints), not both");
      if (!st) st = read_rest_frames(p, r, joint);
    } else {
      if (!st) st = rn_jm_vec(&p->w, r, "curvature", 1, 2, RN_J_ANY, k, NULL);
      if (!st) st = rn_jm_number(&p->w, r, "twist", 1, RN_J_ANY, &t, NULL);
      if (!st && (st = rn_network_set_joint_rest_strains(net, joint, k, t)))
        st = rn_jwalk_lib_error(&p->w, st);
    }
  }
  rn_jwalk_pop(&p->w, mark);
  return st;
}

static rn_status read_joint(rn_scene_parser *p, const cJSON *v, int json_index) {
  static const char *const keys[] = {"name", "model", "ends", "rest", NULL};
  const char *name = NULL;
  const cJSON *list = NULL;
  int model = RN_JOINT_ELASTIC, n = 0, *rods = NULL, *ends = NULL, *images = NULL;
  int joint = -1;
  rn_status st = rn_json_check_keys(&p->w, v, keys);
  if (!st) st = read_joint_name(p, v, &name);
  if (!st) st = rn_scene_joint_model_ref(&p->w, v, "model", &model);
  if (!st) st = rn_jm_require(&p->w, v, "ends", &list);
  if (!st) {
    size_t mark = rn_jwalk_key(&p->w, "ends");
    st = read_joint_ends(p, list, &rods, &ends, &images, &n);
    rn_jwalk_pop(&p->w, mark);
  }
  if (!st) st = rn_scene_add_joint(p, name, model, n, rods, ends, images, &joint);
  if (!st) p->scene->joints[joint].json_index = json_index;
  if (!st) st = read_joint_rest(p, v, joint);
  free(rods);
  free(ends);
  free(images);
  return st;
}

rn_status rn_scene_read_joints(rn_scene_parser *p, const cJSON *joints) {
  int n = 0;
  rn_status st = rn_jv_array(&p->w, joints, &n);
  if (!st) st = reserve_joints(p, n);
  int i = 0;
  for (const cJSON *v = st ? NULL : joints->child; v && !st; v = v->next, i++) {
    size_t mark = rn_jwalk_index(&p->w, i);
    st = read_joint(p, v, i);
    rn_jwalk_pop(&p->w, mark);
  }
  return st;
}

/* ---- errors of finalize ---------------------------------------------------------- */

/* First "joint N ('", "joints N ('" or "rod N ('" in msg: *is_joint,
 * *index; 0 if none. */
static int named_item(const char *msg, int *is_joint, int *index) {
  for (const char *p = msg; *p; p++) {
    int joints = strncmp(p, "joints ", 7) == 0;
    int joint = joints || strncmp(p, "joint ", 6) == 0, rod = strncmp(p, "rod ", 4) == 0;
    if (!joint && !rod) continue;
    const char *q = p + (joints ? 7 : joint ? 6 : 4);
    char *end = NULL;
    long i = strtol(q, &end, 10);
    if (end != q && *q >= '0' && *q <= '9' && strncmp(end, " ('", 3) == 0 &&
        i < 2147483647L) {
      *is_joint = joint;
      *index = (int)i;
      return 1;
    }
  }
  return 0;
}

rn_status rn_scene_finalize_error(rn_scene_parser *p, rn_status st) {
  const rn_scene *s = p->scene;
  char msg[1024];
  const char *last = rn_context_last_error(p->w.ctx);
  snprintf(msg, sizeof msg, "%s", (last && *last) ? last : rn_status_message(st));
  int is_joint = 0, i = -1;
  if (!named_item(msg, &is_joint, &i) || i >= (is_joint ? s->njoints : s->nrods))
    return rn_jwalk_fail(&p->w, st, "%s", msg);
  long line = is_joint ? s->joints[i].obj_line : s->rods[i].obj_line;
  int json = is_joint ? s->joints[i].json_index : s->rods[i].json_index;
  const char *name = is_joint ? s->joints[i].name : s->rods[i].name;
  size_t mark = rn_jwalk_key(&p->w, line > 0 ? "graph" : is_joint ? "joints" : "rods");
  if (line > 0)
    st = rn_jwalk_fail(&p->w, st, "%s:%ld: %s %s: %s", s->obj_path ? s->obj_path : "?",
                       line, is_joint ? "joint" : "segment", name, msg);
  else {
    if (json >= 0) rn_jwalk_index(&p->w, json);
    st = rn_jwalk_fail(&p->w, st, "%s", msg);
  }
  rn_jwalk_pop(&p->w, mark);
  return st;
}
