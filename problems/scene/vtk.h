/* vtk.h - VTK XML unstructured grid (.vtu) of a scene's current state, for
 * ParaView.  Points are all rod vertices (rod after rod), then one point per
 * joint (at its current position); cells are the edges (VTK_LINE segments),
 * so per-edge quantities are cell data, then one VTK_VERTEX cell per joint.  "Interior"
 * vertices are 1 .. nv-2 of a rod; point fields of stencils are 0 at rod ends.
 *   point data: displacement (from the initial shape, vector);
 *               curvature (material curvature kappa1, kappa2 per unit length:
 *               integrated curvature / current Voronoi length);
 *               twist_rate (integrated twist / current Voronoi length);
 *               bending_moment (|M|, M = B (kappa - kbar) / Voronoi rest
 *               length, see rn_network_rod_vertex_fields);
 *               bending_moment_vector (the same as a global vector m1 e2 -
 *               m2 e1, (e1, e2) the orthonormalised mean directors of the
 *               vertex's two edges; along the curvature binormal);
 *               twisting_moment (G J (tau - taubar) / Voronoi rest length);
 *   cell data:  rod (index), edge (index in its rod), theta (material angle),
 *               stretch (strain l / l_rest - 1), d1 and d2 (material
 *               directors), twist (mean twist_rate of the edge's interior end
 *               vertices, 0 for a rod of one edge), axial_force (E A
 *               stretch), internal_force and internal_moment (3 components:
 *               the force and the moment about the edge midpoint that the
 *               part of the rod after the midpoint exerts on the part
 *               before it, rn_network_rod_internal_forces; tension:
 *               internal_force . tangent > 0), rest_length, energy_density
 *               (elastic energy per unit
 *               rest length: the edge's stretching energy / rest length plus,
 *               for each interior end vertex, half of that vertex's bending +
 *               twisting energy / Voronoi rest length; summed times
 *               rest_length over the edges it gives the elastic energy of
 *               the rods; the energy of joints, at their connection edges,
 *               is not in it).
 * Joints: point data joint_rotation (9 components, the rotation matrix
 * row-major; zeros at rod vertices) and displacement (current minus initial
 * position); cell data joint (joint index, -1 on rod edges), rod and edge
 * -1; every other field is 0 on the joints' points and cells.
 * ASCII, %.17g numbers, written atomically; RN_ERR_NOT_FINITE and no file
 * if any value is NaN or infinite. */
#ifndef RN_VTK_H
#define RN_VTK_H

#include "rodnet.h"
#include "scene/scene.h"

rn_status rn_vtk_write(rn_context *ctx, const char *path, const rn_scene *scene);

#endif
