/* obj.h - OBJ line-graph reader (seed 001 section 1; docs/scene-format.md,
 * "OBJ line graphs").
 *
 * Reads the `v x y z` and `l i j [k ...]` records of a Wavefront OBJ file
 * into a graph: vertices (positions) and segments (every consecutive pair of
 * an `l` record, in file order).  Indices are 1-based; negative indices count
 * back from the last vertex defined so far (-1 = the previous `v`); an index
 * may carry a texture part (`3/7`), which is ignored.  `#` starts a comment.
 * The records vn, vt, vp, o, g, s, mtllib and usemtl are ignored; any other
 * record (f, p, curv, ...) is an error.
 *
 * The graph is checked: finite coordinates, indices in range, no segment
 * from a vertex to itself, no segment given twice (either direction), no
 * segment of zero length, and no two vertices used by segments at exactly
 * the same position (an unwelded mesh: rods meeting there would not be
 * joined).  Every error is recorded in the context as ONE line
 * "FILE:LINE: reason" with status RN_ERR_PARSE (RN_ERR_IO for an unreadable
 * file, "FILE: reason"); nothing is printed.
 */
#ifndef RN_OBJ_H
#define RN_OBJ_H

#include <stddef.h>

#include "rodnet.h"

typedef struct rn_obj_graph rn_obj_graph;

/* Parse the len bytes at text (no NUL terminator needed; a NUL byte among
 * them is an error); label names the file in messages.  *out is NULL on
 * error. */
rn_status rn_obj_graph_parse(rn_context *ctx, const char *label, const char *text,
                             size_t len, rn_obj_graph **out);
/* Read and parse the file at path (label = path).  Only regular files of at
 * most RN_OBJ_MAX_BYTES are read. */
#define RN_OBJ_MAX_BYTES ((size_t)1 << 30)
rn_status rn_obj_graph_load(rn_context *ctx, const char *path, rn_obj_graph **out);
/* Destroy; accepts NULL; sets *g to NULL. */
void rn_obj_graph_destroy(rn_obj_graph **g);

/* Vertices: all `v` records, index 0 = OBJ index 1. */
int rn_obj_graph_num_vertices(const rn_obj_graph *g);
/* Position xyz[3] of vertex v (0-based); RN_ERR_RANGE if out of range. */
rn_status rn_obj_graph_vertex(const rn_obj_graph *g, int v, double xyz[3]);
/* Number of segments incident to vertex v (0 if unused, -1 if invalid). */
int rn_obj_graph_valence(const rn_obj_graph *g, int v);
/* Line of the file where vertex v was defined (-1 if invalid). */
int rn_obj_graph_vertex_line(const rn_obj_graph *g, int v);

/* Segments in file order. */
int rn_obj_graph_num_segments(const rn_obj_graph *g);
/* Vertices ends[2] (0-based, first and second of the pair as written) of
 * segment s; RN_ERR_RANGE if out of range. */
rn_status rn_obj_graph_segment(const rn_obj_graph *g, int s, int ends[2]);
/* Line of the `l` record of segment s (-1 if invalid). */
int rn_obj_graph_segment_line(const rn_obj_graph *g, int s);

#endif
