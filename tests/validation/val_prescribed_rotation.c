/* val_prescribed_rotation.c - prescribed clamp rotations of any size (issue 10
 * section 2) against closed forms:
 *
 * (1) twist: a straight rod clamped at both ends (mid-edge clamps, n edges of
 *     length h, the clamped edges' midpoints L = (n-1) h apart), the end clamp
 *     turned about the rod's axis by alpha = 1.5 pi, 2 pi, 5 pi.  The material
 *     angle then grows linearly, theta_j = alpha j / (n-1), and the twist
 *     energy is exactly GJ alpha^2 / (2 L) (the discrete twist alpha/(n-1) at each
 *     of the n-1 interior vertices over its Voronoi length h).  Before the solve
 *     (the state rn_network_finalize leaves at load factor 1: the whole turn at
 *     the vertex next to the end clamp) it is GJ alpha^2 / (2 h): the winding is
 *     kept, not wrapped into (-pi, pi].  Automatic, 1 and 4 load steps give the
 *     same state.  Bending and torsion are stiffened (I x 100) so that the
 *     straight twisted rod is far from twist buckling (Greenhill).
 * (2) bending: the end clamp turned by 2 pi about z and moved back onto the
 *     start clamp: the rod closes into a regular (n-1)-gon of side h (turning
 *     angle 2 pi/(n-1) at every interior vertex), the discrete-exact ring, in
 *     one load step (split internally into turns below pi) and in 3 steps. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "testutil.h"
#include "valutil.h"

static void fail_status(const rn_network *net, rn_status st, const char *what) {
  rn_test_fail(__FILE__, __LINE__, "%s: %s: %s", what, rn_status_name(st),
               rn_context_last_error(rn_network_context(net)));
}

/* A rod clamped at both ends, the end clamp moved by disp and turned by rot. */
static rn_network *two_clamps(rn_context *ctx, int n, double L, const rn_material *m,
                              const rn_section *s, const double disp[3],
                              const double rot[3]) {
  rn_network *net = val_clamped_rod(ctx, n, L, m, s, NULL, NULL, 0);
  rn_status st;
  if ((st = rn_network_clamp(net, 0, RN_END)) ||
      (st = rn_network_displace_end(net, 0, RN_END, disp, rot)) ||
      (st = rn_network_finalize(net))) {
    fail_status(net, st, "two_clamps");
    rn_network_destroy(&net);
  }
  return net;
}

static double twist_energy(const rn_network *net) {
  size_t nd = rn_network_num_dofs(net);
  double *x = malloc((nd + 1) * sizeof(double)), E[RN_TERM_COUNT] = {0};
  rn_status st = rn_network_get_dofs(net, x);
  if (!st) st = rn_network_energy_terms(net, x, E);
  if (st) fail_status(net, st, "energy_terms");
  free(x);
  return E[RN_TERM_TWIST];
}

static rn_solve_report solve_steps(rn_network *net, int load_steps) {
  rn_solve_options opt;
  rn_solve_report rep;
  rn_solve_options_default(&opt);
  opt.load_steps = load_steps;
  rn_status st = rn_solve(net, &opt, &rep);
  if (st) fail_status(net, st, "rn_solve");
  CHECK(rep.converged);
  CHECK(rep.stability.verified_minimum);
  return rep;
}

static void twist_case(rn_context *ctx, const rn_material *m, const rn_section *s,
                       double alpha) {
  const int n = 16, steps[3] = {0, 1, 4};
  const double L = 1.0, h = L / (n - 0.5), Leff = (n - 1) * h, GJ = m->G * s->J;
  const double rot[3] = {alpha, 0, 0};
  double theta_ref[16] = {0}, x_ref[3 * 17] = {0};
  for (int c = 0; c < 3; ++c) {
    rn_network *net = two_clamps(ctx, n, L, m, s, NULL, rot);
    double theta[16], x[3 * 17];
    if (!net) return;
    if (c == 0) { /* the jumped state: the whole turn at vertex n-1 */
      double E0 = twist_energy(net);
      CHECK_REL(E0, GJ * alpha * alpha / (2.0 * h), 1e-12);
      printf(
          "alpha = %.2f pi: before the solve E_twist = %.15e (GJ alpha^2/(2h) %.15e)\n",
          alpha / M_PI, E0, GJ * alpha * alpha / (2.0 * h));
    }
    rn_solve_report rep = solve_steps(net, steps[c]);
    double E = twist_energy(net), Eref = GJ * alpha * alpha / (2.0 * Leff);
    CHECK_REL(E, Eref, 1e-9);
    CHECK_REL(rep.energy, Eref, 1e-9);
    rn_network_rod_theta(net, 0, theta);
    rn_network_rod_vertices(net, 0, x);
    for (int j = 1; j < n - 1; ++j) CHECK_NEAR(theta[j], alpha * j / (n - 1), 1e-8);
    for (int i = 0; i <= n; ++i) { /* stays straight */
      CHECK_NEAR(x[3 * i], -0.5 * h + i * h, 1e-10);
      CHECK_NEAR(x[3 * i + 1], 0.0, 1e-10);
      CHECK_NEAR(x[3 * i + 2], 0.0, 1e-10);
    }
    if (c == 0) {
      for (int j = 0; j < n; ++j) theta_ref[j] = theta[j];
      for (int i = 0; i < 3 * (n + 1); ++i) x_ref[i] = x[i];
    } else { /* the same state for any number of load steps */
      for (int j = 0; j < n; ++j) CHECK_NEAR(theta[j], theta_ref[j], 1e-8);
      for (int i = 0; i < 3 * (n + 1); ++i) CHECK_NEAR(x[i], x_ref[i], 1e-10);
    }
    printf("alpha = %.2f pi, load_steps %d: E_twist = %.15e (GJ alpha^2/(2L) %.15e), "
           "theta mid %.12f (%.12f), %d load steps, %d iterations\n",
           alpha / M_PI, steps[c], E, Eref, theta[n / 2], alpha * (n / 2) / (n - 1),
           rep.load_steps, rep.iterations);
    rn_network_destroy(&net);
  }
}

static void ring_case(rn_context *ctx, const rn_material *m, const rn_section *s) {
  const int n = 12, steps[2] = {1, 3};
  const double L = 1.0, h = L / (n - 0.5), phi = 2.0 * M_PI / (n - 1);
  const double disp[3] = {-(n - 1) * h, 0, 0}, rot[3] = {0, 0, 2.0 * M_PI};
  for (int c = 0; c < 2; ++c) {
    rn_network *net = two_clamps(ctx, n, L, m, s, disp, rot);
    double x[3 * 13], p[3] = {-0.5 * h, 0, 0}, err = 0.0;
    if (!net) return;
    rn_solve_report rep = solve_steps(net, steps[c]);
    rn_network_rod_vertices(net, 0, x);
    for (int i = 0; i <= n; ++i) { /* the regular polygon */
      for (int k = 0; k < 3; ++k) err = fmax(err, fabs(x[3 * i + k] - p[k]));
      p[0] += h * cos(i * phi);
      p[1] += h * sin(i * phi);
    }
    CHECK(err <= 1e-9 * L);
    printf("ring by a 2 pi clamp turn, load_steps %d: max |x - polygon| = %.3e "
           "(%d load steps, %d iterations)\n",
           steps[c], err, rep.load_steps, rep.iterations);
    rn_network_destroy(&net);
  }
}

int main(void) {
  rn_context *ctx;
  rn_material m;
  rn_section s, ring;
  CHECK_STATUS(rn_context_create(&ctx), RN_OK);
  CHECK_STATUS(rn_material_from_E_nu(1e7, 0.3, 0.0, &m), RN_OK);
  CHECK_STATUS(rn_section_circle(0.01, &s), RN_OK);
  ring = s;
  s.I11 *= 100.0;
  s.I22 *= 100.0;
  twist_case(ctx, &m, &s, 1.5 * M_PI);
  twist_case(ctx, &m, &s, 2.0 * M_PI);
  twist_case(ctx, &m, &s, 5.0 * M_PI);
  /* the ring stays planar: stiff out of plane and in torsion (as val_end_moment) */
  ring.I22 *= 100.0;
  ring.J *= 100.0;
  ring_case(ctx, &m, &ring);
  rn_context_destroy(&ctx);
  return rn_test_finish("val_prescribed_rotation");
}
