/* api_couple_fixed.c - a couple fixed in space through the C API
 * (rodnet_couple.h): the network's gradient (the residual) and Hessian (its
 * Jacobian) at a bent and twisted 3D state: HVP and the CSR values against
 * central differences of the gradient (h-sweep, order 2), the CSR matrix
 * nonsymmetric; the energy holds no term of the couple; the conservative and
 * the fixed couple give the same gradient at the start (f normal to M) and
 * different ones once the end has turned out of the plane; the derivative
 * self-test refuses it; bad models are refused.  The same on a joint
 * (rn_network_add_joint_moment_model): the Jacobian check on a rigid and an
 * elastic joint of valence 2 at the end of the rod, the count and the name
 * of the first fixed couple, the refusal on a smooth joint. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rodnet.h"
#include "rodnet_couple.h"
#include "rodnet_solve.h"
#include "testutil.h"

/* The clamped rod "r" with the couple on its last vertex (joint < 0) or on a
 * joint of model `joint` ("J") joining its end to the start of a second rod
 * "r2" that leaves it at an angle. */
static rn_network *make_net(rn_context *ctx, const double M[3], rn_couple_model model,
                            int joint) {
  enum { NV = 6 };
  double xyz[3 * NV], d1[3] = {0, 1, 0};
  for (int i = 0; i < NV; ++i) {
    xyz[3 * i] = 0.2 * i;
    xyz[3 * i + 1] = 0.0;
    xyz[3 * i + 2] = 0.0;
  }
  rn_network *net = NULL;
  int rod = -1;
  rn_material m;
  rn_section s;
  CHECK_STATUS(rn_network_create(ctx, &net), RN_OK);
  CHECK_STATUS(rn_network_add_rod(net, "r", NV, xyz, d1, &rod), RN_OK);
  CHECK_STATUS(rn_material_from_E_nu(1e3, 0.3, 0.0, &m), RN_OK);
  CHECK_STATUS(rn_section_circle(0.05, &s), RN_OK);
  CHECK_STATUS(rn_network_set_material(net, rod, -1, &m), RN_OK);
  CHECK_STATUS(rn_network_set_section(net, rod, -1, &s), RN_OK);
  CHECK_STATUS(rn_network_clamp(net, rod, RN_START), RN_OK);
  if (joint < 0) {
    CHECK_STATUS(rn_network_add_moment_model(net, rod, -1, M, model), RN_OK);
  } else {
    double xyz2[12];
    int rod2 = -1, rods[2], ends[2] = {RN_END, RN_START}, j = -1;
    for (int i = 0; i < 4; ++i) {
      xyz2[3 * i] = 1.0;
      xyz2[3 * i + 1] = 0.15 * i;
      xyz2[3 * i + 2] = 0.1 * i;
    }
    CHECK_STATUS(rn_network_add_rod(net, "r2", 4, xyz2, (double[3]){1, 0, 0}, &rod2),
                 RN_OK);
    CHECK_STATUS(rn_network_set_material(net, rod2, -1, &m), RN_OK);
    CHECK_STATUS(rn_network_set_section(net, rod2, -1, &s), RN_OK);
    rods[0] = rod;
    rods[1] = rod2;
    CHECK_STATUS(rn_network_add_joint(net, "J", (rn_joint_model)joint, 2, rods, ends, &j),
                 RN_OK);
    CHECK_STATUS(rn_network_add_joint_moment_model(net, j, M, model), RN_OK);
  }
  CHECK_STATUS(rn_network_finalize(net), RN_OK);
  return net;
}

static rn_network *make_rod(rn_context *ctx, const double M[3], rn_couple_model model) {
  return make_net(ctx, M, model, -1);
}

/* a bent, twisted state away from the start */
static void perturbed(const rn_network *net, double *x, uint64_t *seed) {
  size_t n = rn_network_num_dofs(net);
  CHECK_STATUS(rn_network_get_dofs(net, x), RN_OK);
  for (size_t i = 0; i < n; ++i) x[i] += 0.05 * rn_test_rand(seed);
}

static void test_jacobian(rn_context *ctx, int joint) {
  const double M[3] = {0.3, -0.5, 0.8};
  rn_network *net = make_net(ctx, M, RN_COUPLE_FIXED, joint);
  size_t n = rn_network_num_dofs(net), nnz = 0;
  const int64_t *rowptr;
  const int32_t *col;
  CHECK_STATUS(rn_network_hessian_pattern(net, &nnz, &rowptr, &col), RN_OK);
  double *x = malloc(n * sizeof(double)), *v = malloc(n * sizeof(double)),
         *Hv = malloc(n * sizeof(double)), *Cv = malloc(n * sizeof(double)),
         *gp = malloc(n * sizeof(double)), *gm = malloc(n * sizeof(double)),
         *xp = malloc(n * sizeof(double)), *xm = malloc(n * sizeof(double)),
         *vals = malloc(nnz * sizeof(double));
  uint64_t seed = 7;
  perturbed(net, x, &seed);
  for (size_t i = 0; i < n; ++i) v[i] = rn_test_rand(&seed);
  CHECK_STATUS(rn_network_hvp(net, x, v, Hv), RN_OK);
  CHECK_STATUS(rn_network_hessian_values(net, x, vals), RN_OK);
  double hvmax = 0.0, asym = 0.0, vmax = 0.0;
  for (size_t i = 0; i < n; ++i) {
    Cv[i] = 0.0;
    for (int64_t k = rowptr[i]; k < rowptr[i + 1]; ++k) Cv[i] += vals[k] * v[col[k]];
    hvmax = fmax(hvmax, fabs(Hv[i]));
  }
  for (size_t i = 0; i < n; ++i) CHECK_NEAR(Cv[i], Hv[i], 1e-12 * hvmax);
  /* CSR asymmetry: entry (i, j) against (j, i) */
  for (size_t i = 0; i < n; ++i)
    for (int64_t k = rowptr[i]; k < rowptr[i + 1]; ++k) {
      size_t j = (size_t)col[k];
      vmax = fmax(vmax, fabs(vals[k]));
      for (int64_t l = rowptr[j]; l < rowptr[j + 1]; ++l)
        if ((size_t)col[l] == i) asym = fmax(asym, fabs(vals[k] - vals[l]));
    }
  CHECK(asym > 1e-6 * vmax);
  double hs[4] = {1e-3, 5e-4, 2.5e-4, 1.25e-4}, err[4];
  for (int ih = 0; ih < 4; ++ih) {
    for (size_t i = 0; i < n; ++i) {
      xp[i] = x[i] + hs[ih] * v[i];
      xm[i] = x[i] - hs[ih] * v[i];
    }
    CHECK_STATUS(rn_network_gradient(net, xp, NULL, gp), RN_OK);
    CHECK_STATUS(rn_network_gradient(net, xm, NULL, gm), RN_OK);
    err[ih] = 0.0;
    for (size_t i = 0; i < n; ++i)
      err[ih] = fmax(err[ih], fabs((gp[i] - gm[i]) / (2.0 * hs[ih]) - Hv[i]));
  }
  double slope = rn_test_loglog_slope(4, hs, err);
  CHECK(slope > 1.8 && slope < 2.2);
  CHECK(err[3] < 1e-5 * hvmax);
  /* the energy has no term of the fixed couple: the same as without it */
  double E1 = 0.0, E0 = 0.0;
  CHECK_STATUS(rn_network_energy(net, x, &E1), RN_OK);
  double Mzero[3] = {0, 0, 0};
  rn_network *n0 = make_net(ctx, Mzero, RN_COUPLE_FIXED, joint);
  CHECK_STATUS(rn_network_energy(n0, x, &E0), RN_OK);
  CHECK(E1 == E0);
  rn_network_destroy(&n0);
  /* the derivative self-test does not apply */
  rn_check_report rep;
  CHECK_STATUS(rn_network_check_derivatives(net, NULL, 1, 0.01, 1, &rep), RN_ERR_ARG);
  CHECK(strstr(rn_context_last_error(ctx), "fixed in space") != NULL);
  CHECK(rn_network_fixed_couples(net, NULL, NULL) == 1);
  printf("fixed couple on %s: HVP against central differences of the gradient, "
         "order %.2f, error %.1e of max |Hv|; CSR asymmetry %.2e of max |H|\n",
         joint < 0                 ? "the rod's last edge"
         : joint == RN_JOINT_RIGID ? "a rigid joint"
                                   : "an elastic joint",
         slope, err[3] / hvmax, asym / vmax);
  free(x), free(v), free(Hv), free(Cv), free(gp), free(gm), free(xp), free(xm),
      free(vals);
  rn_network_destroy(&net);
}

static void test_models_at_start_and_off_plane(rn_context *ctx) {
  const double M[3] = {0.3, -0.5, 0.8};
  rn_network *nf = make_rod(ctx, M, RN_COUPLE_FIXED);
  rn_network *nc = make_rod(ctx, M, RN_COUPLE_CONSERVATIVE);
  CHECK(rn_network_fixed_couples(nc, NULL, NULL) == 0);
  size_t n = rn_network_num_dofs(nf);
  double *x = malloc(n * sizeof(double)), *gf = malloc(n * sizeof(double)),
         *gc = malloc(n * sizeof(double));
  CHECK_STATUS(rn_network_get_dofs(nf, x), RN_OK);
  CHECK_STATUS(rn_network_gradient(nf, x, NULL, gf), RN_OK);
  CHECK_STATUS(rn_network_gradient(nc, x, NULL, gc), RN_OK);
  for (size_t i = 0; i < n; ++i) CHECK_NEAR(gf[i], gc[i], 1e-13);
  uint64_t seed = 11;
  perturbed(nf, x, &seed);
  CHECK_STATUS(rn_network_gradient(nf, x, NULL, gf), RN_OK);
  CHECK_STATUS(rn_network_gradient(nc, x, NULL, gc), RN_OK);
  double d = 0.0;
  for (size_t i = 0; i < n; ++i) d = fmax(d, fabs(gf[i] - gc[i]));
  CHECK(d > 1e-3);
  free(x), free(gf), free(gc);
  rn_network_destroy(&nf);
  rn_network_destroy(&nc);
}

static void test_bad_model(rn_context *ctx) {
  rn_network *net = NULL;
  double xyz[9] = {0, 0, 0, 1, 0, 0, 2, 0, 0}, d1[3] = {0, 1, 0}, M[3] = {0, 0, 1};
  int rod;
  CHECK_STATUS(rn_network_create(ctx, &net), RN_OK);
  CHECK_STATUS(rn_network_add_rod(net, "r", 3, xyz, d1, &rod), RN_OK);
  CHECK_STATUS(rn_network_add_moment_model(net, rod, -1, M, (rn_couple_model)7),
               RN_ERR_ARG);
  CHECK(rn_network_fixed_couples(net, NULL, NULL) == 0);
  int r = -5, v = -5;
  CHECK_STATUS(rn_network_add_moment_model(net, rod, -1, M, RN_COUPLE_FIXED), RN_OK);
  CHECK(rn_network_fixed_couples(net, &r, &v) == 1);
  CHECK(r == rod && v == 2);
  rn_network_destroy(&net);
}

/* The count, the joint and the name of the first fixed couple; the derivative
 * self-test refuses it naming the joint; a smooth joint refuses any couple. */
static void test_joint_bookkeeping(rn_context *ctx) {
  const double M[3] = {0.0, 0.0, 1.0};
  char buf[64];
  int r = -5, v = -5, jt = -5;
  rn_network *net = make_net(ctx, M, RN_COUPLE_FIXED, RN_JOINT_RIGID);
  CHECK(rn_network_fixed_couples(net, &r, &v) == 1);
  CHECK(r == -1 && v == -1);
  CHECK(rn_network_fixed_couple_joint(net, &jt) == 1);
  CHECK(jt == 0);
  CHECK(strcmp(rn_network_fixed_couple_where(net, buf, sizeof buf), "joint 'J'") == 0);
  rn_check_report rep;
  CHECK_STATUS(rn_network_check_derivatives(net, NULL, 1, 0.01, 1, &rep), RN_ERR_ARG);
  CHECK(strstr(rn_context_last_error(ctx), "joint 'J' is a couple fixed in space") !=
        NULL);
  rn_network_destroy(&net);
  /* a rod couple: the joint query says -1, the name says the rod */
  net = make_rod(ctx, M, RN_COUPLE_FIXED);
  CHECK(rn_network_fixed_couple_joint(net, &jt) == 1 && jt == -1);
  CHECK(strcmp(rn_network_fixed_couple_where(net, buf, sizeof buf), "rod 'r' vertex 5") ==
        0);
  rn_network_destroy(&net);
  net = make_net(ctx, M, RN_COUPLE_CONSERVATIVE, RN_JOINT_ELASTIC);
  CHECK(rn_network_fixed_couple_joint(net, &jt) == 0);
  CHECK(strcmp(rn_network_fixed_couple_where(net, buf, sizeof buf), "") == 0);
  rn_network_destroy(&net);
  /* bad model; a smooth joint has no rotation to load */
  double xyz[9] = {0, 0, 0, 1, 0, 0, 2, 0, 0}, xyz2[9] = {2, 0, 0, 3, 0, 0, 4, 0, 0},
         d1[3] = {0, 1, 0};
  int rods[2], ends[2] = {RN_END, RN_START}, j = -1;
  CHECK_STATUS(rn_network_create(ctx, &net), RN_OK);
  CHECK_STATUS(rn_network_add_rod(net, "a", 3, xyz, d1, &rods[0]), RN_OK);
  CHECK_STATUS(rn_network_add_rod(net, "b", 3, xyz2, d1, &rods[1]), RN_OK);
  CHECK_STATUS(rn_network_add_joint(net, "S", RN_JOINT_SMOOTH, 2, rods, ends, &j), RN_OK);
  CHECK_STATUS(rn_network_add_joint_moment_model(net, j, M, (rn_couple_model)7),
               RN_ERR_ARG);
  CHECK(rn_network_fixed_couples(net, NULL, NULL) == 0);
  CHECK_STATUS(rn_network_add_joint_moment_model(net, j, M, RN_COUPLE_FIXED), RN_OK);
  CHECK_STATUS(rn_network_finalize(net), RN_ERR_BC);
  CHECK(strstr(rn_context_last_error(ctx), "loaded by a couple") != NULL);
  rn_network_destroy(&net);
}

/* The entry points that need an energy refuse a couple fixed in space, naming
 * it (as rn_solve's minimisers, rn_network_stability and rn_path_follow do):
 * rn_hessian_min_eigenvalue on the rod, rn_homogenize, rn_cell_relax,
 * rn_cell_minimize, rn_cell_bloch and rn_cell_bloch_eigen on a square cell
 * (two bars through one rigid joint and its images) with the couple on a bar;
 * with the conservative couple they run.  (They are the solver's: built with it
 * only, RN_TEST_SOLVER.) */
#ifdef RN_TEST_SOLVER
static void test_refusals(rn_context *ctx) {
  const double M[3] = {0.0, 0.0, 0.2};
  double lmin = 0.0;
  rn_network *net = make_rod(ctx, M, RN_COUPLE_FIXED);
  CHECK_STATUS(rn_hessian_min_eigenvalue(net, &lmin), RN_ERR_ARG);
  CHECK(strstr(rn_context_last_error(ctx),
               "rn_hessian_min_eigenvalue: the moment on rod "
               "'r' vertex 5 is a couple fixed in space") != NULL);
  rn_network_destroy(&net);
  for (int model = 0; model < 2; ++model) {
    const double vec[6] = {1, 0, 0, 0, 1, 0};
    double bx[9] = {0, 0, 0, 0.5, 0, 0, 1, 0, 0}, by[9] = {0, 0, 0, 0, 0.5, 0, 0, 1, 0};
    int rx = -1, ry = -1, j = -1, rods[4], ends[4] = {RN_START, RN_END, RN_START, RN_END};
    int images[12] = {0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 1, 0};
    rn_material m;
    rn_section sec;
    CHECK_STATUS(rn_network_create(ctx, &net), RN_OK);
    CHECK_STATUS(rn_network_set_periodic(net, 2, vec), RN_OK);
    CHECK_STATUS(rn_network_add_rod(net, "x", 3, bx, (double[3]){0, 0, 1}, &rx), RN_OK);
    CHECK_STATUS(rn_network_add_rod(net, "y", 3, by, (double[3]){0, 0, 1}, &ry), RN_OK);
    CHECK_STATUS(rn_material_from_E_nu(1e3, 0.3, 0.0, &m), RN_OK);
    CHECK_STATUS(rn_section_circle(0.05, &sec), RN_OK);
    for (int r = 0; r < 2; ++r) {
      CHECK_STATUS(rn_network_set_material(net, r, -1, &m), RN_OK);
      CHECK_STATUS(rn_network_set_section(net, r, -1, &sec), RN_OK);
    }
    rods[0] = rods[1] = rx;
    rods[2] = rods[3] = ry;
    CHECK_STATUS(
        rn_network_add_joint_images(net, "J", RN_JOINT_RIGID, 4, rods, ends, images, &j),
        RN_OK);
    CHECK_STATUS(rn_network_add_moment_model(net, rx, 1, M, (rn_couple_model)model),
                 RN_OK);
    CHECK_STATUS(rn_network_finalize(net), RN_OK);
    const double strain[3] = {0.0, 0.0, 0.0}, xi[3] = {0.1, 0.0, 0.0};
    double eig[2];
    rn_homogenization h;
    rn_cell_relax_report rep;
    rn_bloch_result res;
    rn_bloch_options opt;
    rn_bloch_options_default(&opt);
    opt.grid = 2;
    const rn_status want = model == RN_COUPLE_FIXED ? RN_ERR_ARG : RN_OK;
    const char *msg = "the moment on rod 'x' vertex 1 is a couple fixed in space";
    CHECK_STATUS(rn_homogenize(net, &h), want);
    CHECK(!want || strstr(rn_context_last_error(ctx), "rn_homogenize: ") != NULL);
    CHECK(!want || strstr(rn_context_last_error(ctx), msg) != NULL);
    CHECK_STATUS(rn_cell_relax(net, strain, &rep), want);
    CHECK(!want || strstr(rn_context_last_error(ctx), msg) != NULL);
    CHECK_STATUS(rn_cell_minimize(net, strain, &rep), want);
    CHECK(!want || strstr(rn_context_last_error(ctx), msg) != NULL);
    CHECK_STATUS(rn_cell_bloch(net, &opt, &res), want);
    CHECK(!want || strstr(rn_context_last_error(ctx), msg) != NULL);
    CHECK_STATUS(rn_cell_bloch_eigen(net, xi, RN_BLOCH_ALL, 2, eig, NULL), want);
    CHECK(!want || strstr(rn_context_last_error(ctx), msg) != NULL);
    CHECK_STATUS(rn_hessian_min_eigenvalue(net, &lmin), want);
    rn_network_destroy(&net);
  }
}
#endif

int main(void) {
  rn_context *ctx;
  CHECK_STATUS(rn_context_create(&ctx), RN_OK);
  test_jacobian(ctx, -1);
  test_jacobian(ctx, RN_JOINT_RIGID);
  test_jacobian(ctx, RN_JOINT_ELASTIC);
  test_joint_bookkeeping(ctx);
  test_models_at_start_and_off_plane(ctx);
  test_bad_model(ctx);
#ifdef RN_TEST_SOLVER
  test_refusals(ctx);
#endif
  rn_context_destroy(&ctx);
  return rn_test_finish("api_couple_fixed");
}
