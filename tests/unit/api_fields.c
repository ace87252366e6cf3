/* api_fields.c - stress resultants and energies per stencil
 * (rn_network_rod_vertex_fields, rn_network_rod_edge_fields,
 * rn_network_rod_rest_lengths) against hand computations:
 *  - a circular arc held in a straight rest shape (pure bending): the moment
 *    is E I |kb| / vlen with |kb| = 2 tan(phi / 2) exactly, E I / R up to
 *    O(phi^2), along the expected material component; the bending energy is
 *    |M|^2 vlen / (2 E I);
 *  - the same arc with an anisotropic section (I12 != 0) and rest curvature:
 *    m = B (kappa - kbar) / vlen in both material frame orientations;
 *  - a uniformly twisted straight rod: G J alpha / vlen;
 *  - a uniformly stretched rod with different sections per edge: E A eps;
 *  - the sums of the per-stencil energies equal the energy split by term;
 *  - error paths. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rodnet.h"
#include "testutil.h"

enum { NV = 9, NIN = NV - 2, NE = NV - 1 };

static const double R = 2.0, PHI = 0.1; /* arc radius, turning angle per vertex */
static const double YOUNG = 3.0, SHEAR = 1.2;

/* NV vertices on a circle of radius R in the xy plane, counterclockwise from
 * (R, 0, 0): consecutive edges turn by PHI about +z. */
static void arc(double *xyz) {
  for (int i = 0; i < NV; ++i) {
    xyz[3 * i] = R * cos(PHI * i);
    xyz[3 * i + 1] = R * sin(PHI * i);
    xyz[3 * i + 2] = 0.0;
  }
}

/* A free rod through xyz with one material and section, rest curvature kbar
 * (NULL: the input shape) and finalized. */
static rn_network *rod(rn_context *ctx, int nv, const double *xyz, const double *d1,
                       const rn_section *s, const double *kbar) {
  rn_network *net = NULL;
  rn_material m = {YOUNG, SHEAR, 0.0};
  CHECK_STATUS(rn_network_create(ctx, &net), RN_OK);
  CHECK_STATUS(rn_network_add_rod(net, "r", nv, xyz, d1, NULL), RN_OK);
  CHECK_STATUS(rn_network_set_material(net, 0, -1, &m), RN_OK);
  CHECK_STATUS(rn_network_set_section(net, 0, -1, s), RN_OK);
  if (kbar) CHECK_STATUS(rn_network_set_rest_curvature(net, 0, kbar), RN_OK);
  CHECK_STATUS(rn_network_finalize(net), RN_OK);
  return net;
}

/* Sums of the per-stencil energies equal the energy split by term. */
static void check_sums(rn_network *net) {
  int nv = rn_network_rod_num_vertices(net, 0);
  size_t n = rn_network_num_dofs(net);
  double *x = malloc(n * sizeof *x), terms[RN_TERM_COUNT];
  double eb[64], et[64], es[64], sb = 0, st = 0, ss = 0;
  CHECK_STATUS(rn_network_get_dofs(net, x), RN_OK);
  CHECK_STATUS(rn_network_energy_terms(net, x, terms), RN_OK);
  CHECK_STATUS(rn_network_rod_vertex_fields(net, 0, NULL, NULL, eb, et), RN_OK);
  CHECK_STATUS(rn_network_rod_edge_fields(net, 0, NULL, es), RN_OK);
  for (int i = 0; i < nv - 2; ++i) {
    sb += eb[i];
    st += et[i];
  }
  for (int j = 0; j < nv - 1; ++j) ss += es[j];
  CHECK_NEAR(sb, terms[RN_TERM_BEND], 1e-13 * fabs(terms[RN_TERM_BEND]) + 1e-300);
  CHECK_NEAR(st, terms[RN_TERM_TWIST], 1e-13 * fabs(terms[RN_TERM_TWIST]) + 1e-300);
  CHECK_NEAR(ss, terms[RN_TERM_STRETCH], 1e-13 * fabs(terms[RN_TERM_STRETCH]) + 1e-300);
  free(x);
}

/* Pure bending of an isotropic rod: |M| = E I |kb| / vlen about the binormal,
 * which with d1 = +z (normal to the plane) is the -kappa2 component. */
static void test_arc_isotropic(rn_context *ctx) {
  double xyz[3 * NV], zero[2 * NIN] = {0}, d1[3] = {0, 0, 1};
  double m[2 * NIN], mt[NIN], eb[NIN], et[NIN], len[NE];
  rn_section s;
  CHECK_STATUS(rn_section_circle(0.05, &s), RN_OK);
  arc(xyz);
  rn_network *net = rod(ctx, NV, xyz, d1, &s, zero);
  const double EI = YOUNG * s.I11, chord = 2 * R * sin(PHI / 2), kb = 2 * tan(PHI / 2);
  const double Mexact = EI * kb / chord;
  CHECK_STATUS(rn_network_rod_rest_lengths(net, 0, len), RN_OK);
  for (int j = 0; j < NE; ++j) CHECK_REL(len[j], chord, 1e-14);
  CHECK_STATUS(rn_network_rod_vertex_fields(net, 0, m, mt, eb, et), RN_OK);
  for (int i = 0; i < NIN; ++i) {
    CHECK_NEAR(m[2 * i], 0.0, 1e-12 * Mexact);
    CHECK_REL(m[2 * i + 1], -Mexact, 1e-12);
    CHECK_REL(hypot(m[2 * i], m[2 * i + 1]), EI / R, 0.15 * PHI * PHI); /* phi^2 / 8 */
    CHECK_REL(eb[i], 0.5 * Mexact * Mexact * chord / EI, 1e-12);
    CHECK_NEAR(mt[i], 0.0, 1e-12 * Mexact);
    CHECK_NEAR(et[i], 0.0, 1e-24);
  }
  check_sums(net);
  rn_network_destroy(&net);
}

/* Anisotropic section with I12 != 0 and a rest curvature: m = B (kappa -
 * kbar) / vlen.  d1 toward the centre (in the plane): kappa = (|kb|, 0);
 * d1 = +z: kappa = (0, -|kb|). */
static void test_arc_anisotropic(rn_context *ctx) {
  const rn_section s = {1e-2, 3e-5, 1e-5, 4e-6, 2e-5};
  const double kb = 2 * tan(PHI / 2), chord = 2 * R * sin(PHI / 2);
  const double B11 = YOUNG * s.I11, B12 = YOUNG * s.I12, B22 = YOUNG * s.I22;
  const double d1s[2][3] = {{-1, 0, 0}, {0, 0, 1}};
  const double kappa[2][2] = {{kb, 0}, {0, -kb}};
  double xyz[3 * NV], kbar[2 * NIN], m[2 * NIN], eb[NIN];
  arc(xyz);
  for (int o = 0; o < 2; ++o) {
    for (int i = 0; i < NIN; ++i) {
      kbar[2 * i] = 0.3 * kb;
      kbar[2 * i + 1] = -0.2 * kb;
    }
    rn_network *net = rod(ctx, NV, xyz, d1s[o], &s, kbar);
    const double dk0 = kappa[o][0] - 0.3 * kb, dk1 = kappa[o][1] + 0.2 * kb;
    const double m0 = (B11 * dk0 + B12 * dk1) / chord,
                 m1 = (B12 * dk0 + B22 * dk1) / chord;
    const double E =
        0.5 * (dk0 * (B11 * dk0 + B12 * dk1) + dk1 * (B12 * dk0 + B22 * dk1)) / chord;
    CHECK_STATUS(rn_network_rod_vertex_fields(net, 0, m, NULL, eb, NULL), RN_OK);
    for (int i = 0; i < NIN; ++i) {
      CHECK_REL(m[2 * i], m0, 1e-12);
      CHECK_REL(m[2 * i + 1], m1, 1e-12);
      CHECK_REL(eb[i], E, 1e-12);
    }
    check_sums(net);
    rn_network_destroy(&net);
  }
}

/* A straight free rod along x with NV vertices spaced h; no BCs, so the
 * reduced DOFs are the full ones (x_0, theta^0, x_1, ...). */
static rn_network *straight(rn_context *ctx, double h, double *x) {
  double xyz[3 * NV];
  rn_section s;
  for (int i = 0; i < NV; ++i) {
    xyz[3 * i] = h * i;
    xyz[3 * i + 1] = xyz[3 * i + 2] = 0.0;
  }
  CHECK_STATUS(rn_section_circle(0.04, &s), RN_OK);
  rn_network *net = rod(ctx, NV, xyz, NULL, &s, NULL);
  CHECK(rn_network_num_dofs(net) == 4 * NV - 1);
  CHECK_STATUS(rn_network_get_dofs(net, x), RN_OK);
  return net;
}

/* theta^j = j alpha: twist alpha at every interior vertex. */
static void test_twist(rn_context *ctx) {
  const double h = 0.2, alpha = 0.05;
  double x[4 * NV], m[2 * NIN], mt[NIN], eb[NIN], et[NIN];
  rn_section s;
  CHECK_STATUS(rn_section_circle(0.04, &s), RN_OK);
  rn_network *net = straight(ctx, h, x);
  for (int j = 0; j < NE; ++j) x[4 * j + 3] = alpha * j;
  CHECK_STATUS(rn_network_set_dofs(net, x), RN_OK);
  CHECK_STATUS(rn_network_rod_vertex_fields(net, 0, m, mt, eb, et), RN_OK);
  const double GJ = SHEAR * s.J;
  for (int i = 0; i < NIN; ++i) {
    CHECK_REL(mt[i], GJ * alpha / h, 1e-12);
    CHECK_REL(et[i], 0.5 * GJ * alpha * alpha / h, 1e-12);
    CHECK_NEAR(hypot(m[2 * i], m[2 * i + 1]), 0.0, 1e-15);
    CHECK_NEAR(eb[i], 0.0, 1e-30);
  }
  check_sums(net);
  rn_network_destroy(&net);
}

/* Uniform stretch by eps, a different section on each edge. */
static void test_stretch(rn_context *ctx) {
  const double h = 0.2, eps = 0.01;
  double x[4 * NV], f[NE], es[NE], len[NE], strain[NE];
  rn_section s[NE];
  rn_network *net = NULL;
  {
    double xyz[3 * NV];
    rn_material mat = {YOUNG, SHEAR, 0.0};
    for (int i = 0; i < NV; ++i) {
      xyz[3 * i] = h * i;
      xyz[3 * i + 1] = xyz[3 * i + 2] = 0.0;
    }
    CHECK_STATUS(rn_network_create(ctx, &net), RN_OK);
    CHECK_STATUS(rn_network_add_rod(net, "s", NV, xyz, NULL, NULL), RN_OK);
    CHECK_STATUS(rn_network_set_material(net, 0, -1, &mat), RN_OK);
    for (int j = 0; j < NE; ++j) {
      CHECK_STATUS(rn_section_circle(0.01 * (1 + j), &s[j]), RN_OK);
      CHECK_STATUS(rn_network_set_section(net, 0, j, &s[j]), RN_OK);
    }
    /* rest lengths are readable before finalize */
    CHECK_STATUS(rn_network_rod_rest_lengths(net, 0, len), RN_OK);
    for (int j = 0; j < NE; ++j) CHECK_REL(len[j], h, 1e-14);
    CHECK_STATUS(rn_network_finalize(net), RN_OK);
  }
  CHECK_STATUS(rn_network_get_dofs(net, x), RN_OK);
  for (int i = 0; i < NV; ++i) x[4 * i] *= 1 + eps;
  CHECK_STATUS(rn_network_set_dofs(net, x), RN_OK);
  CHECK_STATUS(rn_network_rod_edge_fields(net, 0, f, es), RN_OK);
  CHECK_STATUS(rn_network_rod_strains(net, 0, strain, NULL, NULL), RN_OK);
  for (int j = 0; j < NE; ++j) {
    double EA = YOUNG * s[j].A;
    CHECK_REL(f[j], EA * eps, 1e-11);
    CHECK_REL(f[j], EA * strain[j], 1e-14);
    CHECK_REL(es[j], 0.5 * EA * eps * eps * h, 1e-11);
  }
  check_sums(net);
  rn_network_destroy(&net);
}

/* Everything at once on a deformed arc: bent, twisted and stretched. */
static void test_sums_deformed(rn_context *ctx) {
  const rn_section s = {1e-2, 3e-5, 1e-5, 4e-6, 2e-5};
  double xyz[3 * NV], x[4 * NV];
  uint64_t seed = 7;
  arc(xyz);
  rn_network *net = rod(ctx, NV, xyz, NULL, &s, NULL);
  CHECK_STATUS(rn_network_get_dofs(net, x), RN_OK);
  for (int k = 0; k < 4 * NV - 1; ++k) x[k] += 0.02 * rn_test_rand(&seed);
  CHECK_STATUS(rn_network_set_dofs(net, x), RN_OK);
  check_sums(net);
  rn_network_destroy(&net);
}

static void test_errors(rn_context *ctx) {
  double v[64], x[4 * NV];
  CHECK_STATUS(rn_network_rod_vertex_fields(NULL, 0, v, v, v, v), RN_ERR_ARG);
  CHECK_STATUS(rn_network_rod_edge_fields(NULL, 0, v, v), RN_ERR_ARG);
  CHECK_STATUS(rn_network_rod_rest_lengths(NULL, 0, v), RN_ERR_ARG);
  rn_network *net = NULL;
  double xyz[6] = {0, 0, 0, 1, 0, 0};
  rn_material m = {1, 1, 0};
  rn_section s;
  CHECK_STATUS(rn_section_circle(0.1, &s), RN_OK);
  CHECK_STATUS(rn_network_create(ctx, &net), RN_OK);
  CHECK_STATUS(rn_network_add_rod(net, "one_edge", 2, xyz, NULL, NULL), RN_OK);
  CHECK_STATUS(rn_network_set_material(net, 0, -1, &m), RN_OK);
  CHECK_STATUS(rn_network_set_section(net, 0, -1, &s), RN_OK);
  CHECK_STATUS(rn_network_rod_vertex_fields(net, 0, v, v, v, v), RN_ERR_STATE);
  CHECK_STATUS(rn_network_rod_edge_fields(net, 0, v, v), RN_ERR_STATE);
  CHECK(strstr(rn_context_last_error(ctx), "rn_network_rod_edge_fields") != NULL);
  CHECK_STATUS(rn_network_rod_rest_lengths(net, 0, NULL), RN_ERR_ARG);
  CHECK_STATUS(rn_network_rod_rest_lengths(net, 1, v), RN_ERR_RANGE);
  CHECK_STATUS(rn_network_finalize(net), RN_OK);
  CHECK_STATUS(rn_network_rod_vertex_fields(net, 1, v, v, v, v), RN_ERR_RANGE);
  CHECK_STATUS(rn_network_rod_edge_fields(net, -1, v, v), RN_ERR_RANGE);
  /* a rod of one edge has no interior vertex; NULL outputs are allowed */
  CHECK_STATUS(rn_network_rod_vertex_fields(net, 0, v, v, v, v), RN_OK);
  CHECK_STATUS(rn_network_rod_vertex_fields(net, 0, NULL, NULL, NULL, NULL), RN_OK);
  CHECK_STATUS(rn_network_rod_edge_fields(net, 0, NULL, NULL), RN_OK);
  rn_network_destroy(&net);
  /* a degenerate state (two coincident vertices) is recoverable, not an error */
  net = straight(ctx, 0.2, x);
  for (int k = 0; k < 3; ++k) x[4 * 3 + k] = x[4 * 2 + k];
  CHECK_STATUS(rn_network_set_dofs(net, x), RN_OK);
  CHECK_STATUS(rn_network_rod_vertex_fields(net, 0, v, v, v, v), RN_DEGENERATE);
  CHECK(strstr(rn_context_last_error(ctx), "degenerate") != NULL);
  CHECK_STATUS(rn_network_rod_edge_fields(net, 0, v, v), RN_DEGENERATE);
  rn_network_destroy(&net);
}

int main(void) {
  rn_context *ctx = NULL;
  CHECK_STATUS(rn_context_create(&ctx), RN_OK);
  test_arc_isotropic(ctx);
  test_arc_anisotropic(ctx);
  test_twist(ctx);
  test_stretch(ctx);
  test_sums_deformed(ctx);
  test_errors(ctx);
  rn_context_destroy(&ctx);
  return rn_test_finish("api_fields");
}
