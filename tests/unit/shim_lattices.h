/* shim_lattices.h - lattices of `rodnet generate` (problems/generate/lattice.h) as loaded
 * scenes for the solver tests: period 1, E = 1, nu = 0.3, circle r = 1/50, uniaxial
 * stretch 1e-3 along x.  C and C++. */
#ifndef RN_SHIM_LATTICES_H
#define RN_SHIM_LATTICES_H

#include <stdio.h>
#include <string.h>

#include "generate/lattice.h"
#include "generate/lattice_scene.h"
#include "scene/scene.h"
#include "testutil.h"

/* The scene of a lattice of cells^d cells, edges per rod, joint model (written to
 * path and removed again); NULL after a failed check. */
static inline rn_scene *shim_lattice(rn_context *ctx, rn_lattice_kind kind, int cells,
                                     int model, int edges, const char *path) {
  const int c[3] = {cells, cells, cells};
  rn_lattice *lat = NULL;
  rn_lattice_scene sc;
  rn_scene *scene = NULL;
  memset(&sc, 0, sizeof sc);
  sc.edges_per_rod = edges;
  sc.joint_model = model;
  sc.E = 1.0;
  sc.nu = 0.3;
  sc.shape = RN_LSEC_CIRCLE;
  sc.section[0] = 1.0 / 50.0;
  sc.load = RN_LLOAD_STRETCH;
  sc.load_axis = 0;
  sc.load_value = 1e-3;
  CHECK_STATUS(rn_lattice_build(ctx, kind, c, 1.0, &lat), RN_OK);
  CHECK_STATUS(rn_lattice_write_scene(ctx, path, lat, &sc), RN_OK);
  rn_lattice_destroy(&lat);
  CHECK_STATUS(rn_scene_load(ctx, path, &scene), RN_OK);
  remove(path);
  return scene;
}

#endif
