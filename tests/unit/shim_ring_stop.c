/* shim_ring_stop.c - an unloaded, self-stressed ring converges by default (issue 22,
 * "Convergence and stopping"): Michell's twisted ring (VALIDATION.md; the
 * closed rod of api_rings.c's Michell test), 32 vertices on the unit circle,
 * naturally straight, circle section r = 0.01, E = 1e7, nu = 0.3, one stored turn
 * of twist (link 1), started at the planar circle with uniform twist (theta_j =
 * 2 pi j / N), held by the pins of tests/data/rings/twisted_ring.json (its closing
 * vertex, x and z of vertex 8, z of vertex 16) and the angle of edge 0 (the spin).
 * No loads and no reactions: before the stopping test measured the internal moment
 * of the state its scales were round-off (1e-15) and so was its tolerance.
 * Checked: rn_solve with default options converges by the gradient test; the
 * moment scale is the ring's internal moment (between the twisting moment C tau
 * and the sum of it and the bending moment B / R) and the force scale that over
 * the ring's size; and the answer is Michell's: C/B = 1/(1 + nu) = 0.77 is below
 * sqrt(3) (Phi_c = 2 pi sqrt(3) B/C for one turn), so the planar circle with
 * uniform twist is a stable equilibrium: it stays planar (|z| <= 1e-9), a verified
 * minimum, with the energy of the continuum ring pi (B + C) / R to the
 * discretisation error (2e-3 at 32 vertices). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "shim_rods.h"

enum { N = 32 };

int main(int argc, char **argv) {
  rn_context *ctx = NULL;
  rn_network *net = NULL;
  rn_material m;
  rn_section s;
  rn_solve_options opt;
  rn_solve_report rep;
  int rod = -1, joint = -1;
  double xyz[3 * N], zero[2 * N];
  const double d1[3] = {0, 0, 1};
  CHECK_STATUS(rn_runtime_initialize(&argc, &argv), RN_OK);
  CHECK_STATUS(rn_context_create(&ctx), RN_OK);
  for (int i = 0; i < N; ++i) {
    xyz[3 * i] = cos(2.0 * SHIM_PI * i / N);
    xyz[3 * i + 1] = sin(2.0 * SHIM_PI * i / N);
    xyz[3 * i + 2] = 0.0;
    zero[2 * i] = zero[2 * i + 1] = 0.0;
  }
  CHECK_STATUS(rn_network_create(ctx, &net), RN_OK);
  CHECK_STATUS(rn_network_add_closed_rod(net, "ring", N, xyz, d1, &rod, &joint), RN_OK);
  CHECK_STATUS(rn_material_from_E_nu(1e7, 0.3, 0.0, &m), RN_OK);
  CHECK_STATUS(rn_section_circle(0.01, &s), RN_OK);
  CHECK_STATUS(rn_network_set_material(net, rod, -1, &m), RN_OK);
  CHECK_STATUS(rn_network_set_section(net, rod, -1, &s), RN_OK);
  CHECK_STATUS(rn_network_set_joint_link(net, joint, 1), RN_OK);
  CHECK_STATUS(rn_network_set_rest_curvature(net, rod, zero), RN_OK);
  CHECK_STATUS(rn_network_set_joint_rest_straight(net, joint), RN_OK);
  CHECK_STATUS(rn_network_pin_joint(net, joint), RN_OK);
  CHECK_STATUS(rn_network_pin_components(net, rod, 8, RN_FIX_X | RN_FIX_Z), RN_OK);
  CHECK_STATUS(rn_network_pin_components(net, rod, 16, RN_FIX_Z), RN_OK);
  CHECK_STATUS(rn_network_fix_theta(net, rod, 0), RN_OK);
  CHECK_STATUS(rn_network_finalize(net), RN_OK);
  { /* the uniform twist of Michell's circle */
    const size_t n = rn_network_num_dofs(net);
    double *x = malloc(n * sizeof *x);
    rn_dof_info *info = malloc(n * sizeof *info);
    CHECK_STATUS(rn_network_get_dofs(net, x), RN_OK);
    CHECK_STATUS(rn_network_dof_info(net, info), RN_OK);
    for (size_t i = 0; i < n; ++i)
      if (info[i].kind == RN_DOF_THETA) x[i] = 2.0 * SHIM_PI * info[i].index / N;
    CHECK_STATUS(rn_network_set_dofs(net, x), RN_OK);
    free(x);
    free(info);
  }
  rn_solve_options_default(&opt);
  CHECK_STATUS(rn_solve(net, &opt, &rep), RN_OK);
  /* the continuum ring of radius R = 1: E = pi (B + C) / R (bending B / (2 R^2) and
   * twisting C (2 pi / L)^2 / 2 over L = 2 pi R) */
  const double B = m.E * s.I11, C = m.G * s.J, tau = 1.0, Eref = SHIM_PI * (B + C);
  printf("Michell ring: converged %d (stop %s), %d iterations; force residual %.3e "
         "(scale %.3e, tolerance %.3e), moment residual %.3e (scale %.3e, tolerance "
         "%.3e); C tau %.4e, B/R %.4e; energy %.15e (closed form %.15e); lowest "
         "eigenvalue %.3e (scale %.3e)\n",
         rep.converged, rn_solve_stop_name(rep.stop), rep.iterations, rep.force_residual,
         rep.force_scale, rep.force_tolerance, rep.moment_residual, rep.moment_scale,
         rep.moment_tolerance, C * tau, B, rep.energy, Eref,
         rep.stability.lowest_eigenvalue, rep.stability.scale);
  CHECK(rep.converged == 1 && rep.stop == RN_STOP_GRADIENT);
  CHECK(rep.moment_scale >= C * tau && rep.moment_scale <= C * tau + B);
  CHECK(rep.force_scale >= 0.1 * rep.moment_scale && rep.force_scale <= rep.moment_scale);
  CHECK(rep.moment_tolerance >= 1e-10 * C * tau);
  CHECK_REL(rep.energy, Eref, 2e-3); /* discretisation: O((pi / N)^2) */
  CHECK(rep.stability.verified_minimum == 1);
  {
    double v[3 * (N + 1)], zmax = 0.0;
    CHECK_STATUS(rn_network_rod_vertices(net, rod, v), RN_OK);
    for (int i = 0; i <= N; ++i) zmax = fmax(zmax, fabs(v[3 * i + 2]));
    CHECK(zmax <= 1e-9);
  }
  rn_network_destroy(&net);
  rn_context_destroy(&ctx);
  rn_runtime_finalize();
  return rn_test_finish("shim_ring_stop");
}
