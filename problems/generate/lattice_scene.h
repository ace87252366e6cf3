/* lattice_scene.h - write a lattice (lattice.h) as a JSON scene with explicit
 * rods and joints (docs/lattices.md, docs/scene-format.md). */
#ifndef RN_LATTICE_SCENE_H
#define RN_LATTICE_SCENE_H

#include "generate/lattice.h"
#include "rodnet.h"

typedef enum rn_lattice_section_shape {
  RN_LSEC_CIRCLE = 0, /* p[0] = radius */
  RN_LSEC_RECTANGLE,  /* p[0] = width (along d1), p[1] = height */
  RN_LSEC_ELLIPSE     /* p[0] = a (along d1), p[1] = b */
} rn_lattice_section_shape;

typedef enum rn_lattice_load_kind {
  RN_LLOAD_NONE = 0,
  /* Uniaxial displacement control, frictionless grips: the joints of the two
   * faces normal to axis are pinned along axis only, those of the maximum
   * face displaced by value * extent along axis (value < 0 compresses); a
   * few more component pins remove the other rigid motions (and, for planar
   * lattices, the out-of-plane ones) without loading the lattice
   * (docs/lattices.md). */
  RN_LLOAD_STRETCH,
  /* Displacement control, gripped faces: as RN_LLOAD_STRETCH but the face
   * joints are pinned in all three components (no lateral motion). */
  RN_LLOAD_GRIP,
  /* Force control: total force value along axis spread equally over the
   * joints of the maximum face, and -value over those of the minimum face,
   * one of which (the one nearest the face's centre) is clamped instead of
   * loaded. */
  RN_LLOAD_PULL,
  /* Biaxial displacement control (planar lattices), frictionless grips on all
   * four faces: the x faces pinned along x, the y faces along y, the maximum
   * faces displaced by value * extent along x and value2 * extent along y;
   * z pinned at three nodes (the out-of-plane rigid motions).  Periodic
   * cells: the strain (E11, E22) = (value, value2), the others free. */
  RN_LLOAD_BIAXIAL,
  /* Simple shear (planar lattices): the joints of the minimum y face pinned in
   * x and y, those of the maximum y face pinned in x and y and displaced by
   * value * extent_y along x; z pinned at three nodes.  Periodic cells: the
   * engineering shear strain G12 = value, the others free. */
  RN_LLOAD_SHEAR
} rn_lattice_load_kind;

typedef struct rn_lattice_scene {
  const char *description; /* may be NULL */
  int edges_per_rod;       /* >= 1 */
  int joint_model;         /* rn_joint_model */
  double E, nu;
  rn_lattice_section_shape shape;
  double section[2];
  rn_lattice_load_kind load;
  int load_axis; /* 0 x, 1 y, 2 z */
  double load_value;
  double load_value2; /* RN_LLOAD_BIAXIAL: the strain along y */
  const char *model;  /* top-level "model" ("planar", "3d"), NULL: none */
} rn_lattice_scene;

/* Write the scene atomically to path: material "material", section
 * "section", rod "e<k>" for bar k-1 (from its first to its second node,
 * edges_per_rod edges, d1 = +z for planar lattices, derived otherwise),
 * joint "v<k>" for node k-1 (every node, any valence), and the constraints
 * and loads of opt->load.  RN_ERR_ARG if the load names an axis along which
 * the lattice is flat; RN_ERR_IO if the file cannot be written. */
rn_status rn_lattice_write_scene(rn_context *ctx, const char *path, const rn_lattice *lat,
                                 const rn_lattice_scene *opt);

#endif
