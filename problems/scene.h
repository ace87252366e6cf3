/* scene.h - JSON scene reader (docs/scene-format.md).
 *
 * A scene builds a finalized rn_network through the public API and keeps what
 * the network does not: the file label, the rod name table and the solver
 * settings of the scene's "solver" block.  Every error is recorded in the
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

/* Same from text[len] in memory; label names it in messages. */
rn_status rn_scene_parse(rn_context *ctx, const char *label, const char *text, size_t len,
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
/* Total number of vertices over all rods. */
long rn_scene_num_vertices(const rn_scene *s);

/* Override the fields of opt that the scene's "solver" block sets (call
 * rn_solve_options_default first, then this, then command-line options). */
void rn_scene_apply_solver(const rn_scene *s, rn_solve_options *opt);

#endif
