/* shim_translation.c - translating a whole scene leaves the energies, the gradient
 * and the solve unchanged: the load potentials are measured from the initial state
 * (-f . (x - x0), docs/model.md "Loads").
 *
 * A frame of three rods in the xz plane joined at a rigid and an elastic joint,
 * with every kind of load (forces on rod vertices and on a joint, a line load,
 * gravity, couples on a rod edge and on a joint) and every kind of prescribed
 * motion (clamp with prescribed translation and rotation, a pinned vertex with a
 * prescribed displacement), is built at the origin and translated by T = (0, 0, 3)
 * (a frame 3 units above the origin) and T = (40, -25, 3).  Checked:
 *  - at the initial state (at load factor 1: the prescribed motions applied)
 *    every energy term and the gradient are those of the untranslated frame
 *    (round-off of the translated coordinates only), and at load factor 0 the
 *    load energy is exactly 0;
 *  - after rn_solve the displacements x - x0, the energy terms and the number of
 *    Newton iterations agree with the untranslated solve. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rodnet.h"
#include "rodnet_solve.h"
#include "testutil.h"

enum { NE = 8 };

static int add_line(rn_network *net, const char *name, const double a[3],
                    const double b[3], const double T[3]) {
  rn_material m;
  rn_section s;
  int rod = -1;
  double x[3 * (2 * NE + 1)];
  const double d1[3] = {0, 1, 0};
  const int ne = strcmp(name, "beam") == 0 ? 2 * NE : NE;
  CHECK_STATUS(rn_material_from_E_nu(1e7, 0.3, 1.0, &m), RN_OK);
  CHECK_STATUS(rn_section_circle(0.01, &s), RN_OK);
  for (int i = 0; i <= ne; ++i)
    for (int k = 0; k < 3; ++k) x[3 * i + k] = T[k] + a[k] + (b[k] - a[k]) * i / ne;
  CHECK_STATUS(rn_network_add_rod(net, name, ne + 1, x, d1, &rod), RN_OK);
  CHECK_STATUS(rn_network_set_material(net, rod, -1, &m), RN_OK);
  CHECK_STATUS(rn_network_set_section(net, rod, -1, &s), RN_OK);
  return rod;
}

/* The loaded frame translated by T (finalized). */
static rn_network *frame(rn_context *ctx, const double T[3]) {
  rn_network *net = NULL;
  const double a0[3] = {0, 0, 0}, a1[3] = {0, 0, 1}, b0[3] = {1, 0, 0}, b1[3] = {1, 0, 1};
  const double fa[3] = {0.02, 0.01, 0}, fb[3] = {0, 0, -0.08}, w[3] = {0, 0, -0.02};
  const double g[3] = {0, 0, -9.81}, mb[3] = {0, 0.01, 0}, mr[3] = {0.005, 0, 0.002};
  const double dclamp[3] = {0.01, 0, 0}, rclamp[3] = {0, 0.03, 0},
               dpin[3] = {0, 0, -0.005};
  CHECK_STATUS(rn_network_create(ctx, &net), RN_OK);
  int c0 = add_line(net, "col0", a0, a1, T), c1 = add_line(net, "col1", b0, b1, T);
  int bm = add_line(net, "beam", a1, b1, T), ja = -1, jb = -1;
  int ra[2] = {c0, bm}, ea[2] = {RN_END, RN_START};
  int rb[2] = {c1, bm}, eb[2] = {RN_END, RN_END};
  CHECK_STATUS(rn_network_add_joint(net, "A", RN_JOINT_RIGID, 2, ra, ea, &ja), RN_OK);
  CHECK_STATUS(rn_network_add_joint(net, "B", RN_JOINT_ELASTIC, 2, rb, eb, &jb), RN_OK);
  CHECK_STATUS(rn_network_clamp(net, c0, RN_START), RN_OK);
  CHECK_STATUS(rn_network_displace_end(net, c0, RN_START, dclamp, rclamp), RN_OK);
  CHECK_STATUS(rn_network_pin(net, c1, 0), RN_OK);
  CHECK_STATUS(rn_network_displace_vertex(net, c1, 0, dpin), RN_OK);
  CHECK_STATUS(rn_network_add_joint_force(net, ja, fa), RN_OK);
  CHECK_STATUS(rn_network_add_force(net, bm, NE, fb), RN_OK);
  CHECK_STATUS(rn_network_add_line_load(net, c1, w), RN_OK);
  CHECK_STATUS(rn_network_add_gravity(net, g), RN_OK);
  CHECK_STATUS(rn_network_add_joint_moment(net, jb, mb), RN_OK);
  CHECK_STATUS(rn_network_add_moment(net, bm, 2, mr), RN_OK);
  CHECK_STATUS(rn_network_finalize(net), RN_OK);
  return net;
}

typedef struct state {
  double E[RN_TERM_COUNT], E0[RN_TERM_COUNT], Ezero[RN_TERM_COUNT], u[3 * (4 * NE + 3)];
  double *g0;
  int iterations;
} state;

/* Energy terms and gradient at the initial state, then the solve: terms and the
 * displacements of every vertex from its input position. */
static void run(rn_context *ctx, const double T[3], state *st) {
  rn_network *net = frame(ctx, T);
  const size_t n = rn_network_num_dofs(net);
  double *x = malloc(n * sizeof *x);
  st->g0 = malloc(n * sizeof *st->g0);
  CHECK_STATUS(rn_network_set_load_factor(net, 0.0), RN_OK);
  CHECK_STATUS(rn_network_get_dofs(net, x), RN_OK);
  CHECK_STATUS(rn_network_energy_terms(net, x, st->Ezero), RN_OK);
  CHECK_STATUS(rn_network_set_load_factor(net, 1.0), RN_OK);
  CHECK_STATUS(rn_network_get_dofs(net, x), RN_OK);
  CHECK_STATUS(rn_network_energy_terms(net, x, st->E0), RN_OK);
  CHECK_STATUS(rn_network_gradient(net, x, NULL, st->g0), RN_OK);
  rn_solve_report rep;
  CHECK_STATUS(rn_solve(net, NULL, &rep), RN_OK);
  CHECK(rep.converged == 1);
  st->iterations = rep.iterations;
  CHECK_STATUS(rn_network_get_dofs(net, x), RN_OK);
  CHECK_STATUS(rn_network_energy_terms(net, x, st->E), RN_OK);
  size_t k = 0;
  for (int r = 0; r < rn_network_num_rods(net); ++r) {
    const int nv = rn_network_rod_num_vertices(net, r);
    double xv[3 * (2 * NE + 1)], x0[3 * (2 * NE + 1)];
    CHECK_STATUS(rn_network_rod_vertices(net, r, xv), RN_OK);
    CHECK_STATUS(rn_network_rod_initial_vertices(net, r, x0), RN_OK);
    for (int i = 0; i < 3 * nv; ++i) st->u[k++] = xv[i] - x0[i];
  }
  free(x);
  rn_network_destroy(&net);
}

static double max_abs(const double *v, size_t n) {
  double m = 0.0;
  for (size_t i = 0; i < n; ++i) m = fmax(m, fabs(v[i]));
  return m;
}

int main(int argc, char **argv) {
  rn_context *ctx = NULL;
  const double T0[3] = {0, 0, 0}, T[2][3] = {{0, 0, 3}, {40, -25, 3}};
  CHECK_STATUS(rn_runtime_initialize(&argc, &argv), RN_OK);
  CHECK_STATUS(rn_context_create(&ctx), RN_OK);
  state ref, tr;
  run(ctx, T0, &ref);
  const size_t nu = 3 * (4 * NE + 3);
  rn_network *probe = frame(ctx, T0);
  const size_t n = rn_network_num_dofs(probe);
  rn_network_destroy(&probe);
  const double gscale = max_abs(ref.g0, n), uscale = max_abs(ref.u, nu);
  printf("untranslated: load energy at the start %.3e, after the solve %.17g (%d "
         "iterations), max |u| %.4f\n",
         ref.E0[RN_TERM_LOAD], ref.E[RN_TERM_LOAD], ref.iterations, uscale);
  CHECK(uscale > 1e-3);             /* the frame moves */
  CHECK(ref.E[RN_TERM_LOAD] < 0.0); /* the loads did positive work */
  for (int t = 0; t < 2; ++t) {
    run(ctx, T[t], &tr);
    double du = 0.0, dg = 0.0;
    for (size_t i = 0; i < nu; ++i) du = fmax(du, fabs(tr.u[i] - ref.u[i]));
    for (size_t i = 0; i < n; ++i) dg = fmax(dg, fabs(tr.g0[i] - ref.g0[i]));
    printf("T = (%g, %g, %g): load energy at the start %.3e; |dg0| %.2e; after the "
           "solve: |du| / |u| %.2e, energies:",
           T[t][0], T[t][1], T[t][2], tr.E0[RN_TERM_LOAD], dg, du / uscale);
    for (int k = 0; k < RN_TERM_COUNT; ++k) printf(" %.17g", tr.E[k]);
    printf(" (%d iterations)\n", tr.iterations);
    /* load energy measured from the initial state: zero there whatever T */
    CHECK(tr.Ezero[RN_TERM_LOAD] == 0.0 && ref.Ezero[RN_TERM_LOAD] == 0.0);
    double E0ref = 0.0;
    for (int k = 0; k < RN_TERM_COUNT; ++k) E0ref += fabs(ref.E0[k]);
    for (int k = 0; k < RN_TERM_COUNT; ++k) CHECK_NEAR(tr.E0[k], ref.E0[k], 1e-9 * E0ref);
    CHECK(dg <= 1e-9 * gscale);
    /* the solve: same displacements, energies and iterations */
    CHECK(du <= 1e-8 * uscale);
    double Eref = 0.0;
    for (int k = 0; k < RN_TERM_COUNT; ++k) Eref += fabs(ref.E[k]);
    for (int k = 0; k < RN_TERM_COUNT; ++k) CHECK_NEAR(tr.E[k], ref.E[k], 1e-9 * Eref);
    CHECK(tr.iterations == ref.iterations);
    free(tr.g0);
  }
  free(ref.g0);
  rn_context_destroy(&ctx);
  rn_runtime_finalize();
  return rn_test_finish("shim_translation");
}
