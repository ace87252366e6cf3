/* lattice_check.h - is a generated lattice a lattice of rods?  The geometric
 * bounds of `rodnet generate` (docs/lattices.md, "Admissible sections"): the
 * relative density below 1 and struts that do not overlap at the joints, and
 * the numeric range of what the generator writes (every length and stiffness
 * readable back by the scene reader).
 *
 * A strut graph: nnodes nodes, nbars bars; bar e runs from node uv[2 e] to
 * node uv[2 e + 1] (or a periodic image of it) along the vector d[3 e].  Every
 * bar has the same section scaled by scale[e] (NULL: 1). */
#ifndef RN_LATTICE_CHECK_H
#define RN_LATTICE_CHECK_H

#include "generate/lattice_scene.h"
#include "generate/periodic_cell.h"
#include "io/num_format.h"
#include "rodnet.h"

typedef struct rn_strut_bounds {
  /* sum of the strut volumes (2D: in-plane width x length) over the measure */
  double density;
  /* the largest factor by which every section dimension can be multiplied
   * before the joint zones of the two ends of some bar meet (the struts
   * overlap along the whole bar): min over bars of L / (z_u + z_v), z the
   * joint zone of docs/lattices.md; HUGE_VAL if no bar has a joint zone */
  double joint_factor;
  int joint_bar; /* the bar that sets joint_factor (0-based), -1 if none */
  /* the largest factor allowed by both bounds: min(joint_factor,
   * density^(-1/p)), p = 1 in 2D (the in-plane width scales) and 2 in 3D */
  double factor;
  int coincident_node; /* >= 0: two bars leave this node along one direction */
  int zero_bar;        /* >= 0: a bar of zero length */
} rn_strut_bounds;

/* In-plane half width (2D: the section's extent across the bar in the plane,
 * with the first dimension along d1 = +z) or the radius of the smallest
 * circle about the centroid holding the section (3D); and the "area" of the
 * density (2D: the in-plane width, 3D: the section area). */
void rn_strut_section_size(int dim, const rn_lattice_scene *sec, double *half_width,
                           double *area);

/* The bounds of a strut graph in dim (2 or 3) dimensions whose cell (or
 * bounding box) has area or volume measure.  Returns 0, or -1 if out of
 * memory. */
int rn_strut_bounds_compute(int dim, int nnodes, int nbars, const int *uv,
                            const double *d, const double *scale,
                            const rn_lattice_scene *sec, double measure,
                            rn_strut_bounds *out);

/* The bars of a periodic cell c as a strut graph: uv[2 nbars] their end nodes,
 * d[3 nbars] their vectors to the image ends; returns the largest coordinate a
 * node or image end reaches. */
double rn_pcell_bar_vectors(const rn_pcell *c, int *uv, double *d);

/* rn_strut_bounds_compute on a periodic cell c with the section sec (the bar
 * vectors reach the image ends; the measure is the cell's); *extent (may be
 * NULL): the largest coordinate a node or image end reaches.  Returns 0, or -1
 * if out of memory.  `rodnet generate --periodic` and `rodnet sweep` both
 * check their cells with it. */
int rn_pcell_strut_bounds(const rn_pcell *c, const rn_lattice_scene *sec,
                          rn_strut_bounds *out, double *extent);

/* The numeric range of a generated scene: RN_OK, or RN_ERR_RANGE with a
 * message naming what is out of range: a length (a bar, the extent, the cell
 * size) outside [RN_GEN_MIN_LENGTH, RN_GEN_MAX_LENGTH], or a section whose
 * stiffnesses E A, E I, G J (scaled by smin and smax, the extreme per-bar
 * scales) are not finite and normal.  min_len and max_len: the shortest and
 * longest bar; extent: the largest coordinate magnitude written. */
#define RN_GEN_MIN_LENGTH 1e-30
#define RN_GEN_MAX_LENGTH 1e30
rn_status rn_generate_check_range(rn_context *ctx, const rn_lattice_scene *sec,
                                  double min_len, double max_len, double extent,
                                  double smin, double smax);

/* The numbers of opt a scene writer writes (E, nu, the section, the load
 * values) are finite: 1, or 0 with the first offender in *chk. */
int rn_lattice_scene_finite(const rn_lattice_scene *opt, rn_num_check *chk);

#endif
