/* scene_internal.h - state shared by the scene reader's files (scene.c:
 * file, top level, materials, sections, solver; scene_rods.c: rods;
 * scene_joints.c: joints; scene_graph.c: OBJ line graphs; scene_bcs.c:
 * constraints and loads).  Internal to problems/. */
#ifndef RN_SCENE_INTERNAL_H
#define RN_SCENE_INTERNAL_H

#include "scene/name_index.h"
#include "scene/scene.h"
#include "scene/scene_json.h"

/* What the scene remembers about a rod (the network has the rest). */
typedef struct rn_scene_rod {
  char *name;
  int nv;
  int clamped[2];        /* RN_START, RN_END */
  int joint[2];          /* joint at RN_START / RN_END, -1: none */
  double end_xyz[2][3];  /* initial end vertices */
  double end_len[2];     /* lengths of the terminal edges */
  long obj_line;         /* line of its OBJ segment, 0 if not from a graph */
  int json_index;        /* index in the "rods" array, -1 if from a graph */
  unsigned char *pinned; /* nv pinned components (RN_FIX_* bitmasks) */
  double max_density;    /* over its edges (gravity check) */
} rn_scene_rod;

/* What the scene remembers about a joint. */
typedef struct rn_scene_joint {
  char *name;
  int model; /* rn_joint_model */
  int clamped;
  int pinned;     /* pinned components (RN_FIX_* bitmask) */
  double x0[3];   /* initial position (its first rod end) */
  long obj_line;  /* line of its OBJ vertex, 0 if not from a graph */
  int json_index; /* index in the "joints" array, -1 if from a graph */
} rn_scene_joint;

struct rn_scene {
  char *label;
  char *description;
  rn_network *net;
  int nrods, cap_rods;
  rn_scene_rod *rods;
  int njoints, cap_joints;
  rn_scene_joint *joints;
  char *obj_path; /* the OBJ file of the "graph" (resolved), NULL if none */
  rn_name_index rod_names, joint_names; /* name -> index */
  int periodic_dim;    /* 0, or the number of lattice vectors ("periodic") */
  double lattice[9];   /* lattice vectors (rows) */
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
  const char *where; /* if set, library errors read "PATH: where: message" */
  /* the scene's "constraints" if one of them has an "at" key (NULL otherwise):
   * a rod given by "line" whose end has a clamp with "at": "midpoint" is laid
   * out for it (scene_rods.c) */
  const cJSON *constraints;
  /* rest strains of a closed rod's vertex 0 being read (scene_rods.c) */
  int closed_rest; /* 1: curvature, 2: twist given */
  double closed_kbar[2], closed_taubar;
} rn_scene_parser;

/* Wrap the library's last error (status st) at the walker's path, prefixed
 * with p->where if set; returns st. */
rn_status rn_scene_lib_error(rn_scene_parser *p, rn_status st);
/* Wrap an error of rn_network_finalize: at the JSON path (or OBJ line) of
 * the first joint or rod its message names ("joint 3 ('v4')", "rod 0
 * ('a')"), else at the walker's path; returns st. */
rn_status rn_scene_finalize_error(rn_scene_parser *p, rn_status st);

/* Index of a named material / section, -1 if none. */
int rn_scene_parser_material(const rn_scene_parser *p, const char *name);
int rn_scene_parser_section(const rn_scene_parser *p, const char *name);

/* Read a "rods" array / "joints" array / "graph" object / "constraints" array
 * / "loads" array (the value at the walker's current path). */
rn_status rn_scene_read_rods(rn_scene_parser *p, const cJSON *rods);
rn_status rn_scene_read_joints(rn_scene_parser *p, const cJSON *joints);
rn_status rn_scene_read_graph(rn_scene_parser *p, const cJSON *graph);
rn_status rn_scene_read_constraints(rn_scene_parser *p, const cJSON *list);
rn_status rn_scene_read_loads(rn_scene_parser *p, const cJSON *list);
/* After finalize: the initial state evaluates to finite numbers
 * (scene_finite.c); RN_ERR_NOT_FINITE otherwise. */
rn_status rn_scene_check_finite(rn_scene_parser *p);

/* obj["rod"] names a rod of the scene: its index in *rod. */
rn_status rn_scene_rod_ref(rn_scene_parser *p, const cJSON *obj, int *rod);
/* obj["joint"] names a joint of the scene: its index in *joint. */
rn_status rn_scene_joint_ref(rn_scene_parser *p, const cJSON *obj, int *joint);
/* obj["end"] is "start" or "end": RN_START / RN_END in *end. */
rn_status rn_scene_end_ref(rn_jwalk *w, const cJSON *obj, int *end);
/* obj["material"] / obj["section"] names a material / section: its index. */
rn_status rn_scene_material_ref(rn_scene_parser *p, const cJSON *obj, int *m);
rn_status rn_scene_section_ref(rn_scene_parser *p, const cJSON *obj, int *s);
/* obj[key] (optional) is a joint model name; *model is left unchanged if
 * the key is absent. */
rn_status rn_scene_joint_model_ref(rn_jwalk *w, const cJSON *obj, const char *key,
                                   int *model);

/* Add a rod to the network and the scene (copies name): nv vertices xyz,
 * material axis d1 (NULL: derived), material m and section sec for all
 * edges.  Library errors are reported at the walker's path.  *rod receives
 * its index. */
rn_status rn_scene_add_rod(rn_scene_parser *p, const char *name, int nv,
                           const double *xyz, const double *d1, int m, int sec, int *rod);
/* Add a joint of the rod ends (rods[k], ends[k]) to the network and the
 * scene (copies name).  The ends must be free of other joints (checked by
 * the caller); library errors are reported at the walker's path. */
rn_status rn_scene_add_joint(rn_scene_parser *p, const char *name, int model, int n,
                             const int *rods, const int *ends, const int *images,
                             int *joint);
/* The top-level "periodic" object (scene_periodic.c); read before the rods. */
rn_status rn_scene_read_periodic(rn_scene_parser *p, const cJSON *per);
/* end["image"] (optional) into image[3] (zeros if absent); errors for a scene
 * without a cell and for a wrong count.  The shift sum image_m a_m. */
rn_status rn_scene_read_image(rn_scene_parser *p, const cJSON *end, int *image);
void rn_scene_image_shift(const rn_scene *s, const int *image, double shift[3]);
/* "periodic": {"repeat": [m, n(, k)]}: *out is a new tree of the supercell (rods
 * and joints copied per cell, the copy of cell (0, 0) keeps the names, the others
 * are "name@i,j"; images rewired; the vectors multiplied), NULL without repeat. */
rn_status rn_scene_expand_repeat(rn_scene_parser *p, const cJSON *root, cJSON **out);
/* v (at the walker's path) / obj[key] is a vertex (edge when edges != 0) index of rod,
 * negative counting from the end; the resolved index in *out. */
rn_status rn_scene_index_value(rn_scene_parser *p, const cJSON *v, int rod, int edges,
                               int *out);
rn_status rn_scene_index_ref(rn_scene_parser *p, const cJSON *obj, const char *key,
                             int rod, int edges, int *out);

#endif
