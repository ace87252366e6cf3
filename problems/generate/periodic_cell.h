/* periodic_cell.h - periodic cells of rod lattices for `rodnet generate --periodic`
 * (docs/homogenization.md): the nodes of one period of a lattice and its bars,
 * each bar running from a node to a periodic image of a node. */
#ifndef RN_PERIODIC_CELL_H
#define RN_PERIODIC_CELL_H

#include "generate/lattice.h"
#include "generate/lattice_scene.h"
#include "rodnet.h"

typedef struct rn_pcell {
  int dim;       /* 2 (xy plane) or 3 */
  double vec[9]; /* lattice vectors (rows) */
  int nnodes, nbars;
  double *xyz;           /* node positions [3 nnodes], inside the cell */
  int *bar;              /* [5 nbars]: from node, to node, image of the "to" node (3) */
  double *section_scale; /* NULL, or [nbars]: each bar's section dimensions scaled */
  /* NULL, or a counter that rn_pcell_write_scene increases by the rod ends it
   * visits while listing the joints' ends (4 per bar: a test of its linear
   * cost, tests/unit/problems_generate_test.c) */
  long *work;
} rn_pcell;

/* The periodic cell of cells[0] x cells[1] (x cells[2]) cells of a lattice kind
 * (lattice.h), period a: the finite block of rn_lattice_build wrapped onto the
 * torus of its lattice vectors (2D: (NX a, 0), ((NY mod 2) a/2, NY h) with h the
 * row spacing; square and 3D: the box).  RN_ERR_ARG / RN_ERR_RANGE as
 * rn_lattice_build. */
rn_status rn_pcell_from_lattice(rn_context *ctx, rn_lattice_kind kind, const int cells[3],
                                double a, rn_pcell *out);
/* Re-entrant (auxetic) honeycomb: vertical walls of length h = 2 l, inclined
 * walls of length l at -30 degrees (l = a / sqrt(3)), tiled cells[0] x
 * cells[1] times. */
rn_status rn_pcell_reentrant(rn_context *ctx, const int cells[2], double a,
                             rn_pcell *out);
/* The supercell of rep[0] x rep[1] (x rep[2]) copies of a cell. */
rn_status rn_pcell_tile(rn_context *ctx, const rn_pcell *prim, const int rep[3],
                        rn_pcell *out);
void rn_pcell_free(rn_pcell *c);
/* Imperfections: every node moved by a uniform random vector with components in
 * [-amp, amp] times the mean bar length (2D cells: in plane only), from a
 * deterministic generator seeded by seed. */
void rn_pcell_perturb(rn_pcell *c, double amp, unsigned long seed);
/* Per-rod section scatter: each bar's section dimensions (radius; width and
 * height) scaled by max(0.05, 1 + rel g), g a standard normal deviate (Box-Muller
 * on the generator of rn_pcell_perturb, seeded by seed and a stream of its own).
 * Returns 0, -1 out of memory. */
int rn_pcell_section_scatter(rn_pcell *c, double rel, unsigned long seed);
/* Sections of relative density rho (docs/homogenization.md): square t x t struts
 * in 2D (t = rho V / L), circles of diameter t in 3D (t = sqrt(4 rho V / (pi L))),
 * V the cell measure and L the total bar length; into opt->shape, section. */
void rn_pcell_section_for_density(const rn_pcell *c, double rho, rn_lattice_scene *opt);
/* Sum of the bar lengths and the cell area (2D) or volume (3D). */
void rn_pcell_measures(const rn_pcell *c, double *length, double *measure);
/* Write the cell as a JSON scene (top-level "periodic", rods "e<k>", joints
 * "v<k>" with "image" on the ends at images), atomically; opt->load ignored;
 * repeat (NULL: none) is written as "periodic": {"repeat": [...]}. */
rn_status rn_pcell_write_scene(rn_context *ctx, const char *path, const rn_pcell *c,
                               const rn_lattice_scene *opt, const int *repeat);

#endif
