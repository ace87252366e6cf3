/* scene.h - JSON scene reader (docs/scene-format.md).
 *
 * A scene builds a finalized rn_network through the public API and keeps what
 * the network does not: the file label, the rod and joint name tables and
 * the solver settings of the scene's "solver" block.  A scene may take its
 * rods and joints from an OBJ line graph (obj.h), whose path is resolved
 * against the folder of the scene's label.  Every error is recorded in the
 * context as ONE line "FILE: $.json.path: reason" (malformed JSON:
 * "FILE:LINE:COLUMN: reason"); nothing is printed.
 */
#ifndef RN_SCENE_H
#define RN_SCENE_H

#include <stddef.h>

#include "rodnet.h"
#include "rodnet_solve.h"

typedef struct rn_scene rn_scene;

/* Read and build the scene in the file at path (label in messages = path).
 * RN_ERR_IO if the file cannot be read, RN_ERR_PARSE for malformed JSON or a
 * scene that breaks the format, the library's status for anything it
 * rejects (message prefixed with the file and JSON path).  *out is NULL on
 * error. */
rn_status rn_scene_load(rn_context *ctx, const char *path, rn_scene **out);

/* Same from the len bytes at text (no NUL terminator needed; a NUL byte
 * among them is an error); label names it in messages. */
rn_status rn_scene_parse(rn_context *ctx, const char *label, const char *text, size_t len,
                         rn_scene **out);

/* What network a scene builds (distributed solves, docs/parallel.md): the
 * whole network (mode RN_SCENE_WHOLE, the default of rn_scene_load), only the
 * rod graph (RN_SCENE_GRAPH: rn_network_set_graph_only), or part `part` of
 * nparts of the partition rod_part of that graph (RN_SCENE_PART:
 * rn_network_set_part; arrays borrowed for the call).  A part is validated as
 * far as it holds the scene (docs/parallel.md). */
typedef enum rn_scene_mode {
  RN_SCENE_WHOLE = 0,
  RN_SCENE_GRAPH,
  RN_SCENE_PART
} rn_scene_mode;
typedef struct rn_scene_part {
  rn_scene_mode mode;
  int nparts, part;
  int nrods, njoints;
  const int *rod_nv, *rod_part, *joint_ptr, *joint_rods;
} rn_scene_part;
/* rn_scene_load building the network that part describes (NULL: whole). */
rn_status rn_scene_load_part(rn_context *ctx, const char *path, const rn_scene_part *part,
                             rn_scene **out);

/* Destroy the scene and its network; accepts NULL; sets *s to NULL. */
void rn_scene_destroy(rn_scene **s);

/* The scene's finalized network (owned by the scene). */
rn_network *rn_scene_network(const rn_scene *s);
/* The file label given at load; borrowed. */
const char *rn_scene_label(const rn_scene *s);
/* The scene's "description" ("" if none); borrowed. */
const char *rn_scene_description(const rn_scene *s);
/* Index of the rod called name, -1 if there is none. */
int rn_scene_find_rod(const rn_scene *s, const char *name);
/* Index of the joint called name, -1 if there is none (joint indices are
 * the network's). */
int rn_scene_find_joint(const rn_scene *s, const char *name);
/* Initial position x[3] of a joint (where its rod ends met in the input);
 * RN_ERR_RANGE for a bad index. */
rn_status rn_scene_joint_initial_position(const rn_scene *s, int joint, double x[3]);
/* Total number of vertices over all rods. */
long rn_scene_num_vertices(const rn_scene *s);

/* Override the fields of opt that the scene's "solver" block sets (call
 * rn_solve_options_default first, then this, then command-line options). */
void rn_scene_apply_solver(const rn_scene *s, rn_solve_options *opt);
/* 1 if the scene's "solver" block names the solver kind ("method"), else 0. */
int rn_scene_sets_solver_kind(const rn_scene *s);

#endif
