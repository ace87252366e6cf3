/* lattice.h - finite rod lattices for `rodnet generate` (docs/lattices.md).
 *
 * A lattice is a graph of nodes and bars built as the union of the cells'
 * polygons (2D) or strut sets (3D), with shared nodes and bars merged.  Node
 * positions are kept as integers on a per-lattice grid (scale per axis) so
 * that merging and face tests are exact; the bounding box starts at the
 * origin.  Nodes and bars are numbered in the order they first appear while
 * the cells are visited x fastest, then y, then z.
 */
#ifndef RN_LATTICE_H
#define RN_LATTICE_H

#include "rodnet.h"

typedef enum rn_lattice_kind {
  RN_LATTICE_SQUARE = 0,
  RN_LATTICE_TRIANGULAR,
  RN_LATTICE_HONEYCOMB,
  RN_LATTICE_KAGOME,
  RN_LATTICE_CUBIC,
  RN_LATTICE_BCC,
  RN_LATTICE_OCTET,
  RN_LATTICE_KIND_COUNT
} rn_lattice_kind;

/* Largest cell count per direction and largest number of bars. */
#define RN_LATTICE_MAX_CELLS 100000
#define RN_LATTICE_MAX_BARS 20000000

typedef struct rn_lattice rn_lattice;

/* Name of a kind ("square", "triangular", "honeycomb", "kagome", "cubic",
 * "bcc", "octet"); the kind of a name (0 and *kind set, or -1). */
const char *rn_lattice_kind_name(rn_lattice_kind kind);
int rn_lattice_kind_from_name(const char *name, rn_lattice_kind *kind);
/* 2 for the planar lattices (in the xy plane), 3 for the others. */
int rn_lattice_kind_dimension(rn_lattice_kind kind);

/* Build cells[0] x cells[1] (x cells[2] in 3D) cells of period a > 0
 * (cells[2] is ignored in 2D).  RN_ERR_ARG for counts outside [1,
 * RN_LATTICE_MAX_CELLS] or a bad a, RN_ERR_RANGE if the lattice would have
 * more than RN_LATTICE_MAX_BARS bars (messages in ctx). */
rn_status rn_lattice_build(rn_context *ctx, rn_lattice_kind kind, const int cells[3],
                           double a, rn_lattice **out);
void rn_lattice_destroy(rn_lattice **lat);

rn_lattice_kind rn_lattice_get_kind(const rn_lattice *lat);
int rn_lattice_num_nodes(const rn_lattice *lat);
int rn_lattice_num_bars(const rn_lattice *lat);
/* Position xyz[3] of node n (0-based). */
void rn_lattice_node(const rn_lattice *lat, int n, double xyz[3]);
/* Nodes of bar b in the order the bar runs (rod start, rod end). */
void rn_lattice_bar(const rn_lattice *lat, int b, int nodes[2]);
/* Number of bars at node n. */
int rn_lattice_valence(const rn_lattice *lat, int n);
/* Face membership along axis (0 x, 1 y, 2 z): -1 on the minimum face, +1 on
 * the maximum face, 0 otherwise (exact: integer grid). */
int rn_lattice_face(const rn_lattice *lat, int n, int axis);
/* Extent of the lattice along axis (max - min node coordinate). */
double rn_lattice_extent(const rn_lattice *lat, int axis);

#endif
