/* scene.h - JSON scene reader (docs/scene-format.md): the public part is
 * rodnet_scene.h (librodnet_scene); this header adds what only the rodnet command
 * uses, the loading of one part of a scene's network for distributed solves.
 */
#ifndef RN_SCENE_H
#define RN_SCENE_H

#include <stddef.h>

#include "rodnet.h"
#include "rodnet_scene.h"
#include "rodnet_solve.h"

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

#endif
