/* vtk.h - VTK XML unstructured grid (.vtu) of a scene's current state, for
 * ParaView.  Points are all rod vertices (rod after rod); cells are the
 * edges (VTK_LINE segments), so per-edge quantities are cell data.
 *   point data: displacement (from the initial shape, vector),
 *               curvature (material curvature kappa1, kappa2 per unit
 *               length: integrated curvature / current Voronoi length; 0 at
 *               rod ends), twist_rate (likewise);
 *   cell data:  rod (index), edge (index in its rod), theta (material angle),
 *               stretch (strain l / l_rest - 1), d1 and d2 (material
 *               directors).
 * ASCII, %.17g numbers, written atomically; RN_ERR_NOT_FINITE and no file
 * if any value is NaN or infinite. */
#ifndef RN_VTK_H
#define RN_VTK_H

#include "rodnet.h"
#include "scene.h"

rn_status rn_vtk_write(rn_context *ctx, const char *path, const rn_scene *scene);

#endif
