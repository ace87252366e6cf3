/* scene_graph.c - the "graph" object of a scene: rods and joints from an OBJ
 * line graph (obj.h; docs/scene-format.md, "OBJ line graphs").  Segment s
 * (file order, from 1) becomes rod "e<s>" from its first to its second
 * vertex; OBJ vertex i of valence >= 2 becomes joint "v<i>". */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene/obj.h"
#include "scene/scene_internal.h"

/* Largest edges_per_rod accepted. */
#define RN_GRAPH_MAX_EDGES_PER_ROD 1000000

typedef struct graph_spec {
  int edges_per_rod, material, section, model, has_d1;
  double d1[3];
  const char *obj; /* as written in the scene */
} graph_spec;

/* path relative to the folder of the scene file label (absolute paths and
 * labels without a folder are used as they are).  Caller frees. */
static char *resolve_path(const char *label, const char *path) {
  const char *slash = strrchr(label, '/');
  size_t dir = (path[0] == '/' || !slash) ? 0 : (size_t)(slash - label) + 1;
  size_t n = strlen(path);
  char *out = malloc(dir + n + 1);
  if (!out) return NULL;
  memcpy(out, label, dir);
  memcpy(out + dir, path, n + 1);
  return out;
}

static rn_status read_spec(rn_scene_parser *p, const cJSON *v, graph_spec *g) {
  static const char *const keys[] = {
      "obj", "edges_per_rod", "material", "section", "joint_model", "d1", NULL};
  rn_jwalk *w = &p->w;
  rn_status st = rn_json_check_keys(w, v, keys);
  if (!st) st = rn_jm_string(w, v, "obj", 1, &g->obj);
  if (!st && !*g->obj) {
    size_t mark = rn_jwalk_key(w, "obj");
    st = rn_jwalk_error(w, "expected a non-empty file name");
    rn_jwalk_pop(w, mark);
  }
  if (!st)
    st = rn_jm_int(w, v, "edges_per_rod", 1, 1, RN_GRAPH_MAX_EDGES_PER_ROD,
                   &g->edges_per_rod, NULL);
  if (!st) st = rn_scene_material_ref(p, v, &g->material);
  if (!st) st = rn_scene_section_ref(p, v, &g->section);
  g->model = RN_JOINT_ELASTIC;
  if (!st) st = rn_scene_joint_model_ref(w, v, "joint_model", &g->model);
  if (!st) st = rn_jm_vec(w, v, "d1", 0, 3, RN_J_ANY, g->d1, &g->has_d1);
  if (!st && g->has_d1 && !(g->d1[0] != 0 || g->d1[1] != 0 || g->d1[2] != 0)) {
    size_t mark = rn_jwalk_key(w, "d1");
    st = rn_jwalk_error(w, "the material axis must not be the zero vector");
    rn_jwalk_pop(w, mark);
  }
  return st;
}

/* "FILE:LINE: segment e<s>: " prefix for errors about segment s. */
static rn_status segment_error(rn_scene_parser *p, const char *file,
                               const rn_obj_graph *g, int s, const char *what) {
  return rn_jwalk_error(&p->w, "%s:%d: segment e%d: %s", file,
                        rn_obj_graph_segment_line(g, s), s + 1, what);
}

/* d1 must not be parallel to the segment from a to b. */
static int d1_fits(const double *d1, const double *a, const double *b) {
  double t[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  double tt = t[0] * t[0] + t[1] * t[1] + t[2] * t[2];
  double dd = d1[0] * d1[0] + d1[1] * d1[1] + d1[2] * d1[2];
  double dt = d1[0] * t[0] + d1[1] * t[1] + d1[2] * t[2];
  return dd - dt * dt / tt > 1e-16 * dd;
}

static rn_status add_segment_rod(rn_scene_parser *p, const char *file,
                                 const rn_obj_graph *g, const graph_spec *spec, int s,
                                 double *xyz) {
  int ends[2], nv = spec->edges_per_rod + 1, rod = -1;
  double a[3], b[3];
  rn_obj_graph_segment(g, s, ends);
  rn_obj_graph_vertex(g, ends[0], a);
  rn_obj_graph_vertex(g, ends[1], b);
  if (spec->has_d1 && !d1_fits(spec->d1, a, b)) {
    size_t mark = rn_jwalk_key(&p->w, "d1");
    rn_status st = segment_error(p, file, g, s,
                                 "the material axis d1 is parallel to this segment "
                                 "(leave \"d1\" out to derive one per rod)");
    rn_jwalk_pop(&p->w, mark);
    return st;
  }
  for (int i = 0; i < nv; i++) {
    double t = (double)i / (double)(nv - 1);
    for (int k = 0; k < 3; k++) xyz[3 * i + k] = (1 - t) * a[k] + t * b[k];
  }
  char name[32], where[1200];
  snprintf(name, sizeof name, "e%d", s + 1);
  if (rn_scene_find_rod(p->scene, name) >= 0)
    return segment_error(p, file, g, s, "a rod of this name exists already");
  snprintf(where, sizeof where, "%s:%d: segment %s", file,
           rn_obj_graph_segment_line(g, s), name);
  p->where = where;
  rn_status st = rn_scene_add_rod(p, name, nv, xyz, spec->has_d1 ? spec->d1 : NULL,
                                  spec->material, spec->section, &rod);
  p->where = NULL;
  if (!st) p->scene->rods[rod].obj_line = rn_obj_graph_segment_line(g, s);
  return st;
}

/* Joints "v<i>" at the vertices of valence >= 2; first_rod is the index of
 * the rod of segment 0. */
static rn_status add_vertex_joints(rn_scene_parser *p, const char *file,
                                   const rn_obj_graph *g, const graph_spec *spec,
                                   int first_rod) {
  int nv = rn_obj_graph_num_vertices(g), ns = rn_obj_graph_num_segments(g);
  int *start = calloc((size_t)nv + 1, sizeof *start);
  int *rods = malloc(2 * (size_t)ns * sizeof *rods),
      *ends = malloc(2 * (size_t)ns * sizeof *ends);
  rn_status st = (start && rods && ends)
                     ? RN_OK
                     : rn_jwalk_fail(&p->w, RN_ERR_ALLOC, "out of memory");
  /* incident rod ends grouped by vertex (counting sort) */
  for (int v = 0; v < nv && !st; v++)
    start[v + 1] = start[v] + rn_obj_graph_valence(g, v);
  for (int s = 0; s < ns && !st; s++) {
    int e[2];
    rn_obj_graph_segment(g, s, e);
    for (int k = 0; k < 2; k++) {
      int slot = start[e[k]]++;
      rods[slot] = first_rod + s;
      ends[slot] = k == 0 ? RN_START : RN_END;
    }
  }
  for (int v = nv - 1; v > 0 && !st; v--) start[v] = start[v - 1];
  if (!st) start[0] = 0;
  for (int v = 0; v < nv && !st; v++) {
    int n = rn_obj_graph_valence(g, v), joint = -1;
    if (n < 2) continue;
    char name[32];
    snprintf(name, sizeof name, "v%d", v + 1);
    if (rn_scene_find_joint(p->scene, name) >= 0)
      st = rn_jwalk_error(&p->w, "%s:%d: vertex %d: a joint named \"%s\" exists already",
                          file, rn_obj_graph_vertex_line(g, v), v + 1, name);
    else {
      char where[1200];
      snprintf(where, sizeof where, "%s:%d: joint %s", file,
               rn_obj_graph_vertex_line(g, v), name);
      p->where = where;
      st = rn_scene_add_joint(p, name, spec->model, n, rods + start[v], ends + start[v],
                              NULL, &joint);
      p->where = NULL;
    }
    if (!st) p->scene->joints[joint].obj_line = rn_obj_graph_vertex_line(g, v);
  }
  free(start);
  free(rods);
  free(ends);
  return st;
}

static rn_status build_graph(rn_scene_parser *p, const char *file, const rn_obj_graph *g,
                             const graph_spec *spec) {
  double *xyz = malloc(3 * ((size_t)spec->edges_per_rod + 1) * sizeof *xyz);
  if (!xyz) return rn_jwalk_fail(&p->w, RN_ERR_ALLOC, "out of memory");
  int first_rod = p->scene->nrods, ns = rn_obj_graph_num_segments(g);
  rn_status st = RN_OK;
  for (int s = 0; s < ns && !st; s++) st = add_segment_rod(p, file, g, spec, s, xyz);
  free(xyz);
  return st ? st : add_vertex_joints(p, file, g, spec, first_rod);
}

rn_status rn_scene_read_graph(rn_scene_parser *p, const cJSON *v) {
  graph_spec spec;
  memset(&spec, 0, sizeof spec);
  rn_status st = read_spec(p, v, &spec);
  if (st) return st;
  char *path = resolve_path(p->scene->label, spec.obj);
  if (!path) return rn_jwalk_fail(&p->w, RN_ERR_ALLOC, "out of memory");
  rn_obj_graph *g = NULL;
  size_t mark = rn_jwalk_key(&p->w, "obj");
  st = rn_obj_graph_load(p->w.ctx, path, &g);
  if (st) st = rn_jwalk_lib_error(&p->w, st);
  rn_jwalk_pop(&p->w, mark);
  if (!st) st = build_graph(p, path, g, &spec);
  rn_obj_graph_destroy(&g);
  p->scene->obj_path = path;
  return st;
}
