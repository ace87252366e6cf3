/* shim_predictor.c - the load-step predictor of rn_solve (opt.predictor):
 *  - a 6 x 6 square lattice of rods between rigid joints, stretched by 1e-3
 *    between frictionless grips (faces pinned in x and z, one joint in y):
 *    predictor on and off reach the same state (to 1e-8 of the largest
 *    displacement) and energy (1e-10 relative); the prediction is accepted
 *    (predictor_steps == 1) and strictly fewer Newton iterations are needed;
 *  - the cantilever under a large tip load (0.39, far from linear) converges
 *    to the same state with the predictor on, whether or not it is accepted;
 *  - invalid predictor values are rejected. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rodnet.h"
#include "rodnet_solve.h"
#include "shim_rods.h"
#include "testutil.h"

enum { CELLS = 6, NJ = CELLS + 1, NVR = 5, MAXENDS = 4 };

typedef struct joint_ends {
  int n, rod[MAXENDS], end[MAXENDS];
} joint_ends;

static void add_lattice_rod(rn_network *net, const double a[2], const double b[2],
                            joint_ends *ja, joint_ends *jb) {
  double xyz[3 * NVR];
  rn_material m;
  rn_section s;
  int rod = -1;
  for (int i = 0; i < NVR; ++i) {
    double u = (double)i / (NVR - 1);
    xyz[3 * i] = a[0] + u * (b[0] - a[0]);
    xyz[3 * i + 1] = a[1] + u * (b[1] - a[1]);
    xyz[3 * i + 2] = 0.0;
  }
  CHECK_STATUS(rn_network_add_rod(net, NULL, NVR, xyz, NULL, &rod), RN_OK);
  CHECK_STATUS(rn_material_from_E_nu(1e7, 0.3, 0.0, &m), RN_OK);
  CHECK_STATUS(rn_section_circle(0.02, &s), RN_OK);
  CHECK_STATUS(rn_network_set_material(net, rod, -1, &m), RN_OK);
  CHECK_STATUS(rn_network_set_section(net, rod, -1, &s), RN_OK);
  ja->rod[ja->n] = rod;
  ja->end[ja->n++] = RN_START;
  jb->rod[jb->n] = rod;
  jb->end[jb->n++] = RN_END;
}

/* Square lattice of unit cells, rigid joints, stretched along x by 1e-3. */
static rn_network *lattice(rn_context *ctx) {
  rn_network *net = NULL;
  joint_ends je[NJ][NJ];
  const double disp[3] = {1e-3 * CELLS, 0.0, 0.0};
  memset(je, 0, sizeof(je));
  CHECK_STATUS(rn_network_create(ctx, &net), RN_OK);
  for (int i = 0; i < NJ; ++i)
    for (int j = 0; j < NJ; ++j) {
      const double a[2] = {i, j}, bx[2] = {i + 1, j}, by[2] = {i, j + 1};
      if (i + 1 < NJ) add_lattice_rod(net, a, bx, &je[i][j], &je[i + 1][j]);
      if (j + 1 < NJ) add_lattice_rod(net, a, by, &je[i][j], &je[i][j + 1]);
    }
  for (int i = 0; i < NJ; ++i)
    for (int j = 0; j < NJ; ++j) {
      int jt = -1;
      CHECK_STATUS(rn_network_add_joint(net, NULL, RN_JOINT_RIGID, je[i][j].n,
                                        je[i][j].rod, je[i][j].end, &jt),
                   RN_OK);
      if (i == 0 || i == CELLS)
        CHECK_STATUS(
            rn_network_pin_joint_components(
                net, jt, RN_FIX_X | RN_FIX_Z | (i == 0 && j == 0 ? RN_FIX_Y : 0)),
            RN_OK);
      if (i == CELLS) CHECK_STATUS(rn_network_displace_joint(net, jt, disp, NULL), RN_OK);
    }
  CHECK_STATUS(rn_network_finalize(net), RN_OK);
  return net;
}

typedef struct outcome {
  rn_solve_report rep;
  double *x, *x0;
  size_t n;
} outcome;

static outcome solve_with(rn_network *net, int predictor) {
  outcome o;
  rn_solve_options opt;
  rn_solve_options_default(&opt);
  CHECK(opt.predictor == 1);
  opt.predictor = predictor;
  o.n = rn_network_num_dofs(net);
  o.x = malloc(o.n * sizeof(double));
  o.x0 = malloc(o.n * sizeof(double));
  CHECK_STATUS(rn_network_get_dofs(net, o.x0), RN_OK);
  CHECK_STATUS(rn_solve(net, &opt, &o.rep), RN_OK);
  CHECK(o.rep.converged);
  CHECK_STATUS(rn_network_get_dofs(net, o.x), RN_OK);
  return o;
}

static void outcome_free(outcome *o) {
  free(o->x);
  free(o->x0);
}

static void test_lattice(rn_context *ctx) {
  rn_network *on_net = lattice(ctx), *off_net = lattice(ctx);
  outcome on = solve_with(on_net, 1), off = solve_with(off_net, 0);
  double umax = 0.0, dmax = 0.0;
  for (size_t i = 0; i < off.n; ++i) {
    umax = fmax(umax, fabs(off.x[i] - off.x0[i]));
    dmax = fmax(dmax, fabs(on.x[i] - off.x[i]));
  }
  printf("lattice %dx%d: %zu DOFs, Newton iterations %d with the predictor, %d without; "
         "factorisations %ld / %ld; |x_on - x_off| = %.3g (largest displacement %.3g)\n",
         CELLS, CELLS, on.n, on.rep.iterations, off.rep.iterations, on.rep.factorizations,
         off.rep.factorizations, dmax, umax);
  CHECK(umax > 0.0);
  CHECK(dmax <= 1e-8 * umax);
  CHECK_REL(on.rep.energy, off.rep.energy, 1e-10);
  CHECK(on.rep.predictor_steps == 1);
  CHECK(off.rep.predictor_steps == 0);
  CHECK(on.rep.iterations < off.rep.iterations);
  outcome_free(&on);
  outcome_free(&off);
  rn_network_destroy(&on_net);
  rn_network_destroy(&off_net);
}

static void test_cantilever(rn_context *ctx) {
  rn_network *on_net = shim_cantilever(ctx, 0.39), *off_net = shim_cantilever(ctx, 0.39);
  outcome on = solve_with(on_net, 1), off = solve_with(off_net, 0);
  double rel = shim_rel_diff(on.n, on.x, off.x, off.x0);
  printf("cantilever P = 0.39: iterations %d with the predictor (%d accepted), %d "
         "without; relative difference %.3g\n",
         on.rep.iterations, on.rep.predictor_steps, off.rep.iterations, rel);
  CHECK(rel <= 1e-7);
  CHECK_REL(on.rep.energy, off.rep.energy, 1e-10);
  outcome_free(&on);
  outcome_free(&off);
  rn_network_destroy(&on_net);
  rn_network_destroy(&off_net);
}

static void test_bad_option(rn_context *ctx) {
  rn_network *net = shim_cantilever(ctx, 0.01);
  rn_solve_options opt;
  rn_solve_report rep;
  rn_solve_options_default(&opt);
  opt.predictor = 2;
  CHECK_STATUS(rn_solve(net, &opt, &rep), RN_ERR_ARG);
  CHECK(strstr(rn_context_last_error(ctx), "predictor") != NULL);
  rn_network_destroy(&net);
}

int main(int argc, char **argv) {
  rn_context *ctx = NULL;
  CHECK_STATUS(rn_runtime_initialize(&argc, &argv), RN_OK);
  CHECK_STATUS(rn_context_create(&ctx), RN_OK);
  test_lattice(ctx);
  test_cantilever(ctx);
  test_bad_option(ctx);
  rn_context_destroy(&ctx);
  rn_runtime_finalize();
  return rn_test_finish("shim_predictor");
}
