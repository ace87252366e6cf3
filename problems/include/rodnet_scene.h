/* rodnet_scene.h - the JSON scenes of the rodnet command for C programs: read a
 * scene (docs/scene-format.md) into a finalized rn_network, solve it with
 * rn_solve (rodnet_solve.h), write RESULT.json and the .vtu the command writes.
 * Library librodnet_scene (link rodnet::rodnet_scene, or pkg-config rodnet-scene);
 * it uses librodnet and cJSON.  Serial: nothing here is collective over MPI.
 *
 * A scene builds a finalized rn_network through the public API and keeps what
 * the network does not: the file label, the rod and joint name tables and
 * the solver settings of the scene's "solver" block.  A scene may take its
 * rods and joints from an OBJ line graph, whose path is resolved
 * against the folder of the scene's label.  Every error is recorded in the
 * context as ONE line "FILE: $.json.path: reason" (malformed JSON:
 * "FILE:LINE:COLUMN: reason"); nothing is printed.
 */
#ifndef RODNET_SCENE_H
#define RODNET_SCENE_H

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

/* The supercell of the periodic cell scene in the file at path: rep[0 .. dim - 1]
 * copies of the cell per direction ("periodic": {"repeat"}, docs/homogenization.md,
 * "Supercells"; dim the cell's dimension, 2 or 3), at rest, the cell's "strain" and
 * "stress" control dropped (every strain component a DOF), and with
 * pin_out_of_plane (2D only) z of every joint and interior vertex and every
 * material angle pinned, the first joint fully (an in-plane study, as
 * `rodnet homogenize --post-buckling` with --modes in-plane).  RN_ERR_ARG for a
 * scene that is not periodic or already has "repeat", the reader's status for a
 * file it refuses; *out is NULL on error. */
rn_status rn_scene_load_supercell(rn_context *ctx, const char *path, int dim,
                                  const int rep[3], int pin_out_of_plane, rn_scene **out);
/* For each rod r of a supercell scene (rn_scene_load_supercell): rod_base[r] the
 * rod of copy (0, 0(, 0)) it copies (r itself there), rod_cell[3 r .. 3 r + 2] the
 * copy's cell coordinates (from the copies' names NAME@i,j(,k)); arrays of
 * rn_network_num_rods and 3 times that.  The rod_base and rod_cell of
 * rn_cell_post_options.  RN_ERR_ARG for a NULL argument. */
rn_status rn_scene_supercell_copies(const rn_scene *s, int *rod_base, int *rod_cell);

/* Override the fields of opt that the scene's "solver" block sets (call
 * rn_solve_options_default first, then this, then command-line options). */
void rn_scene_apply_solver(const rn_scene *s, rn_solve_options *opt);
/* 1 if the scene's "solver" block names the solver kind ("method"), else 0. */
int rn_scene_sets_solver_kind(const rn_scene *s);

/* Write the result file of `rodnet solve` (docs/cli.md "RESULT.json") for the
 * scene's current state, as the command does after rn_solve: the solve summary
 * of rep and opt (the report and the options of the rn_solve call that brought
 * the scene's network to this state), the energy by term, every rod's vertices
 * and material angles, every joint's position and rotation, the reactions.
 * Written completely or not at all (a temporary file renamed); RN_ERR_ARG if an
 * argument is NULL, RN_ERR_NOT_FINITE and no file if a value is NaN or
 * infinite, RN_ERR_IO if it cannot be written. */
rn_status rn_scene_write_json(rn_context *ctx, const rn_scene *s,
                              const rn_solve_options *opt, const rn_solve_report *rep,
                              const char *path);
/* Write the VTK XML unstructured grid (.vtu) of the scene's current state, as
 * `rodnet solve --vtk` does (docs/cli.md lists the fields); written completely
 * or not at all. */
rn_status rn_scene_write_vtu(rn_context *ctx, const rn_scene *s, const char *path);

#endif
