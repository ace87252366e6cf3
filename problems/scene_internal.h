/* scene_internal.h - state shared by the scene reader's files (scene.c:
 * file, top level, materials, sections, solver; scene_rods.c: rods;
 * scene_bcs.c: constraints and loads).  Internal to problems/. */
#ifndef RN_SCENE_INTERNAL_H
#define RN_SCENE_INTERNAL_H

#include "scene.h"
#include "scene_json.h"

/* What the scene remembers about a rod (the network has the rest). */
typedef struct rn_scene_rod {
  char *name;
  int nv;
  int clamped[2];        /* RN_START, RN_END */
  unsigned char *pinned; /* nv flags */
  double max_density;    /* over its edges (gravity check) */
} rn_scene_rod;

struct rn_scene {
  char *label;
  char *description;
  rn_network *net;
  int nrods;
  rn_scene_rod *rods;
  unsigned solver_set; /* bits: which fields of solver_opt the scene sets */
  rn_solve_options solver_opt;
};

/* Named materials and sections of the file being read (names borrowed from
 * the cJSON tree). */
typedef struct rn_scene_parser {
  rn_jwalk w;
  rn_scene *scene;
  int nmat, nsec;
  const char **mat_names;
  rn_material *mats;
  const char **sec_names;
  rn_section *secs;
} rn_scene_parser;

/* Index of a named material / section, -1 if none. */
int rn_scene_parser_material(const rn_scene_parser *p, const char *name);
int rn_scene_parser_section(const rn_scene_parser *p, const char *name);

/* Read a "rods" array / "constraints" array / "loads" array (the value at the
 * walker's current path). */
rn_status rn_scene_read_rods(rn_scene_parser *p, const cJSON *rods);
rn_status rn_scene_read_constraints(rn_scene_parser *p, const cJSON *list);
rn_status rn_scene_read_loads(rn_scene_parser *p, const cJSON *list);

/* obj["rod"] names a rod of the scene: its index in *rod. */
rn_status rn_scene_rod_ref(rn_scene_parser *p, const cJSON *obj, int *rod);
/* v (at the walker's path) / obj[key] is a vertex (edge when edges != 0) index of rod,
 * negative counting from the end; the resolved index in *out. */
rn_status rn_scene_index_value(rn_scene_parser *p, const cJSON *v, int rod, int edges,
                               int *out);
rn_status rn_scene_index_ref(rn_scene_parser *p, const cJSON *obj, const char *key,
                             int rod, int edges, int *out);

#endif
