/* api_dof_blocks.c - rn_network_dof_blocks, the rod / interface classification
 * of the reduced DOFs for rod-level domain decomposition:
 *  - no nonzero Hessian entry (at a random deformed state) couples the
 *    interiors of two different rods, on free networks of rigid, elastic and
 *    mixed joints (rods of one, two and many edges, several rods between the
 *    same joints, a free rod end) and on the shim tests' portal frames and grid
 *    (clamped, pinned, loaded joints);
 *  - the interface is exactly the joint DOFs plus, for elastic joints, the
 *    free DOFs of the vertex next to the joint and of the terminal angle of every
 *    end (counts by hand), and every such end DOF does couple with another rod;
 *  - the rigid-body modes built from the kinds (rn_network_dof_info), point and
 *    axis are in the null space
 *    of the Hessian of a free network at rest (translations at any state);
 *  - kinds and points of joint and rod DOFs; error paths. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "shim_networks.h"
#include "rodnet.h"
#include "testutil.h"

static uint64_t rng = 77;

/* Free network: triangle A B C of rods with ne edges, a second rod of one edge
 * between B and C, a rod of two edges from C to A, and a rod from A to a free end
 * D.  Joint models: A, B, C as given (model_c for C). */
static rn_network *triangle(rn_context *ctx, int ne, int model_ab, int model_c) {
  rn_network *net = NULL;
  const double A[3] = {0, 0, 0}, B[3] = {1, 0, 0}, C[3] = {0.5, 0.8, 0.3},
               D[3] = {-0.2, 0.1, 1.0};
  int r[6], ja, jb, jc;
  CHECK_STATUS(rn_network_create(ctx, &net), RN_OK);
  r[0] = shimnet_line(net, "AB", A, B, ne, NULL);
  r[1] = shimnet_line(net, "BC", B, C, ne, NULL);
  r[2] = shimnet_line(net, "CA", C, A, ne, NULL);
  r[3] = shimnet_line(net, "BC1", B, C, 1, NULL);
  {
    /* CA2 bends out of the triangle's plane: no point shared with CA */
    const double x[9] = {C[0], C[1], C[2], 0.25, 0.4, 0.45, A[0], A[1], A[2]};
    rn_material m;
    rn_section s;
    shimnet_props(&m, &s);
    CHECK_STATUS(rn_network_add_rod(net, "CA2", 3, x, NULL, &r[4]), RN_OK);
    CHECK_STATUS(rn_network_set_material(net, r[4], -1, &m), RN_OK);
    CHECK_STATUS(rn_network_set_section(net, r[4], -1, &s), RN_OK);
  }
  r[5] = shimnet_line(net, "AD", A, D, ne, NULL);
  {
    int ra[4] = {r[0], r[2], r[4], r[5]}, ea[4] = {RN_START, RN_END, RN_END, RN_START};
    int rb[3] = {r[0], r[1], r[3]}, eb[3] = {RN_END, RN_START, RN_START};
    int rc[4] = {r[1], r[2], r[3], r[4]}, ec[4] = {RN_END, RN_START, RN_END, RN_START};
    CHECK_STATUS(rn_network_add_joint(net, "A", model_ab, 4, ra, ea, &ja), RN_OK);
    CHECK_STATUS(rn_network_add_joint(net, "B", model_ab, 3, rb, eb, &jb), RN_OK);
    CHECK_STATUS(rn_network_add_joint(net, "C", model_c, 4, rc, ec, &jc), RN_OK);
  }
  CHECK_STATUS(rn_network_finalize(net), RN_OK);
  return net;
}

/* DOF kinds of these tests: 0, 1, 2 position components, 3, 4, 5 rotation
 * components, 6 a material angle (from rn_network_dof_info). */
enum { K_ROT = 3, K_THETA = 6 };

typedef struct blocks {
  size_t n;
  int32_t *block;
  int *kind, *rod; /* rod: rn_dof_info.rod (-1 for joint DOFs) */
  double *point, *axis;
} blocks;

static blocks get_blocks(const rn_network *net) {
  blocks b;
  b.n = rn_network_num_dofs(net);
  b.block = malloc(b.n * sizeof(int32_t) + 1);
  b.kind = malloc(b.n * sizeof(int) + 1);
  b.rod = malloc(b.n * sizeof(int) + 1);
  b.point = malloc(3 * b.n * sizeof(double) + 1);
  b.axis = malloc(3 * b.n * sizeof(double) + 1);
  rn_dof_info *info = malloc(b.n * sizeof(rn_dof_info) + 1);
  for (size_t i = 0; i < b.n; ++i) b.block[i] = -7;
  CHECK_STATUS(rn_network_dof_blocks(net, b.block, b.point, b.axis), RN_OK);
  CHECK_STATUS(rn_network_dof_info(net, info), RN_OK);
  for (size_t i = 0; i < b.n; ++i) {
    b.kind[i] = info[i].kind == RN_DOF_POSITION   ? info[i].component
                : info[i].kind == RN_DOF_ROTATION ? K_ROT + info[i].component
                                                  : K_THETA;
    b.rod[i] = info[i].rod;
  }
  free(info);
  return b;
}

static void free_blocks(blocks *b) {
  free(b->block);
  free(b->kind);
  free(b->rod);
  free(b->point);
  free(b->axis);
}

static size_t count_interface(const blocks *b) {
  size_t c = 0;
  for (size_t i = 0; i < b->n; ++i) c += b->block[i] == RN_DOF_INTERFACE;
  return c;
}

/* Hessian values at a random deformed state (every free DOF moved by up to amp). */
static double *deformed_hessian(const rn_network *net, double amp, size_t *nnz,
                                const int64_t **rowptr, const int32_t **col) {
  size_t n = rn_network_num_dofs(net);
  double *x = malloc(n * sizeof(double));
  double *vals;
  CHECK_STATUS(rn_network_hessian_pattern(net, nnz, rowptr, col), RN_OK);
  vals = malloc(*nnz * sizeof(double));
  CHECK_STATUS(rn_network_get_dofs(net, x), RN_OK);
  for (size_t i = 0; i < n; ++i) x[i] += amp * rn_test_rand(&rng);
  CHECK_STATUS(rn_network_hessian_values(net, x, vals), RN_OK);
  free(x);
  return vals;
}

/* No nonzero entry between the interiors of two rods; every DOF classified. */
static void check_no_coupling(const rn_network *net, const char *name) {
  size_t nnz = 0, bad = 0, n = rn_network_num_dofs(net);
  const int64_t *rowptr;
  const int32_t *col;
  double *vals = deformed_hessian(net, 1e-2, &nnz, &rowptr, &col);
  blocks b = get_blocks(net);
  for (size_t i = 0; i < n; ++i) {
    CHECK(b.block[i] >= RN_DOF_INTERFACE && b.block[i] < rn_network_num_rods(net));
    CHECK(b.kind[i] >= 0 && b.kind[i] <= K_THETA);
    CHECK(b.block[i] == RN_DOF_INTERFACE || b.block[i] == b.rod[i]); /* its own rod */
    for (int64_t p = rowptr[i]; p < rowptr[i + 1]; ++p) {
      int32_t j = col[p];
      if (vals[p] != 0.0 && b.block[i] >= 0 && b.block[j] >= 0 &&
          b.block[i] != b.block[j])
        bad++;
    }
  }
  if (bad) printf("%s: %zu entries couple two rod interiors\n", name, bad);
  CHECK(bad == 0);
  free(vals);
  free_blocks(&b);
}

/* Interface count by hand.  Triangle: joints A, B (model_ab) and C (model_c), all
 * free: 3 position DOFs each, +3 rotation if rigid; an elastic joint adds per end
 * the 3 DOFs of the vertex next to it and the terminal angle, except where that
 * vertex is itself a joint (the one-edge rod BC1) and where two ends share one
 * (the terminal angle of BC1 counted once, the middle vertex of CA2 once). */
static size_t triangle_interface(int model_ab, int model_c) {
  const int elastic_ab = model_ab == RN_JOINT_ELASTIC,
            elastic_c = model_c == RN_JOINT_ELASTIC;
  size_t n = (size_t)(elastic_ab ? 3 : 6) * 2 + (size_t)(elastic_c ? 3 : 6);
  if (elastic_ab) {
    n += 4 * 4;     /* A: ends of AB, CA, CA2 (its middle vertex) and AD */
    n += 4 + 4 + 1; /* B: AB, BC; BC1 only its angle (its other vertex is C) */
  }
  if (elastic_c) {
    n += 4 + 4;              /* C: BC, CA */
    n += elastic_ab ? 0 : 1; /* BC1's angle, if B did not count it */
    n += elastic_ab ? 1 : 4; /* CA2: first angle; its middle vertex if A did not */
  }
  return n;
}

static void test_triangle(int model_ab, int model_c, const char *name) {
  rn_context *ctx = NULL;
  rn_network *net;
  blocks b;
  CHECK_STATUS(rn_context_create(&ctx), RN_OK);
  net = triangle(ctx, 5, model_ab, model_c);
  check_no_coupling(net, name);
  b = get_blocks(net);
  printf("%s: %zu DOFs, %zu interface (expected %zu)\n", name, b.n, count_interface(&b),
         triangle_interface(model_ab, model_c));
  CHECK(count_interface(&b) == triangle_interface(model_ab, model_c));
  free_blocks(&b);
  rn_network_destroy(&net);
  rn_context_destroy(&ctx);
}

/* Every interface DOF that is not a joint DOF couples (nonzero entry) with a DOF
 * of another rod: the interface is no larger than the stencils make it. */
static void check_interface_needed(const rn_network *net, const char *name) {
  size_t nnz = 0, n = rn_network_num_dofs(net), unneeded = 0;
  const int64_t *rowptr;
  const int32_t *col;
  double *vals = deformed_hessian(net, 1e-2, &nnz, &rowptr, &col);
  blocks b = get_blocks(net);
  const int *owner = b.rod; /* owning rod regardless of the interface, -1: joint */
  for (size_t i = 0; i < n; ++i) {
    int coupled = 0;
    if (b.block[i] != RN_DOF_INTERFACE || owner[i] < 0) continue;
    for (int64_t p = rowptr[i]; p < rowptr[i + 1]; ++p)
      if (vals[p] != 0.0 && owner[col[p]] >= 0 && owner[col[p]] != owner[i]) coupled = 1;
    if (!coupled) unneeded++;
  }
  if (unneeded)
    printf("%s: %zu interface rod DOFs couple with no other rod\n", name, unneeded);
  CHECK(unneeded == 0);
  free(vals);
  free_blocks(&b);
}

/* Rigid-body modes from kind, point, axis: H t = 0 at any state for translations
 * t; H m = 0 at rest for rotations (the gradient vanishes there). */
static void check_rigid_modes(const rn_network *net, const char *name) {
  size_t n = rn_network_num_dofs(net), nnz;
  const int64_t *rowptr;
  const int32_t *col;
  double *x = malloc(n * sizeof(double)), *m = malloc(n * sizeof(double)),
         *Hm = malloc(n * sizeof(double));
  blocks b = get_blocks(net);
  double *vals, hmax = 0.0;
  CHECK_STATUS(rn_network_hessian_pattern(net, &nnz, &rowptr, &col), RN_OK);
  vals = malloc(nnz * sizeof(double));
  CHECK_STATUS(rn_network_get_dofs(net, x), RN_OK);
  CHECK_STATUS(rn_network_hessian_values(net, x, vals), RN_OK);
  for (size_t p = 0; p < nnz; ++p) hmax = fmax(hmax, fabs(vals[p]));
  for (int mode = 0; mode < 6; ++mode) {
    double w[3] = {0, 0, 0}, t[3] = {0, 0, 0}, mmax = 0.0, res = 0.0;
    if (mode < 3)
      t[mode] = 1.0;
    else
      w[mode - 3] = 1.0;
    for (size_t i = 0; i < n; ++i) {
      const double *p = b.point + 3 * i, *a = b.axis + 3 * i;
      const double wxp[3] = {w[1] * p[2] - w[2] * p[1], w[2] * p[0] - w[0] * p[2],
                             w[0] * p[1] - w[1] * p[0]};
      if (b.kind[i] < K_ROT)
        m[i] = t[b.kind[i]] + wxp[b.kind[i]];
      else if (b.kind[i] < K_THETA)
        m[i] = w[b.kind[i] - K_ROT];
      else
        m[i] = w[0] * a[0] + w[1] * a[1] + w[2] * a[2];
      mmax = fmax(mmax, fabs(m[i]));
    }
    for (size_t i = 0; i < n; ++i) {
      double s = 0.0;
      for (int64_t p = rowptr[i]; p < rowptr[i + 1]; ++p) s += vals[p] * m[col[p]];
      res = fmax(res, fabs(s));
    }
    printf("%s: rigid mode %d: max |H m| / (max |H| max |m|) = %.2e\n", name, mode,
           res / (hmax * mmax));
    CHECK(res <= 1e-11 * hmax * mmax);
  }
  free(vals);
  free(x);
  free(m);
  free(Hm);
  free_blocks(&b);
}

/* Kinds and points of a small network: joint positions and rotations, material
 * angles with unit tangents. */
static void check_kinds(void) {
  rn_context *ctx = NULL;
  rn_network *net;
  blocks b;
  size_t npos = 0, nrot = 0, nth = 0;
  CHECK_STATUS(rn_context_create(&ctx), RN_OK);
  net = triangle(ctx, 3, RN_JOINT_RIGID, RN_JOINT_ELASTIC);
  b = get_blocks(net);
  for (size_t i = 0; i < b.n; ++i) {
    double an =
        sqrt(b.axis[3 * i] * b.axis[3 * i] + b.axis[3 * i + 1] * b.axis[3 * i + 1] +
             b.axis[3 * i + 2] * b.axis[3 * i + 2]);
    if (b.kind[i] == K_THETA) {
      nth++;
      CHECK_NEAR(an, 1.0, 1e-14);
    } else {
      CHECK(an == 0.0);
      if (b.kind[i] < K_ROT)
        npos++;
      else
        nrot++;
    }
    if (b.kind[i] >= K_ROT && b.kind[i] < K_THETA) CHECK(b.block[i] == RN_DOF_INTERFACE);
  }
  /* rods AB, BC, CA, AD of 3 edges, BC1 of 1, CA2 of 2: 15 edges; vertices: 3
   * joints + 2 * 3 + 0 + 1 + 3 (AD: 2 interior and the free end); rotations of
   * the rigid joints A and B */
  CHECK(nth == 15);
  CHECK(npos == 3 * (3 + 6 + 1 + 3));
  CHECK(nrot == 6);
  free_blocks(&b);
  /* errors */
  CHECK_STATUS(rn_network_dof_blocks(net, NULL, NULL, NULL), RN_ERR_ARG);
  CHECK_STATUS(rn_network_dof_blocks(NULL, NULL, NULL, NULL), RN_ERR_ARG);
  rn_network_destroy(&net);
  {
    rn_network *open = NULL;
    int32_t blk[4];
    const double a[3] = {0, 0, 0}, c[3] = {1, 0, 0};
    CHECK_STATUS(rn_network_create(ctx, &open), RN_OK);
    shimnet_line(open, "r", a, c, 2, NULL);
    CHECK_STATUS(rn_network_dof_blocks(open, blk, NULL, NULL), RN_ERR_STATE);
    rn_network_destroy(&open);
  }
  rn_context_destroy(&ctx);
}

/* A single rod: every DOF interior to rod 0. */
static void check_single_rod(void) {
  rn_context *ctx = NULL;
  rn_network *net = NULL;
  blocks b;
  const double a[3] = {0, 0, 0}, c[3] = {0, 0, 2};
  CHECK_STATUS(rn_context_create(&ctx), RN_OK);
  CHECK_STATUS(rn_network_create(ctx, &net), RN_OK);
  shimnet_line(net, "r", a, c, 10, NULL);
  CHECK_STATUS(rn_network_clamp(net, 0, RN_START), RN_OK);
  CHECK_STATUS(rn_network_finalize(net), RN_OK);
  b = get_blocks(net);
  CHECK(b.n == 4 * 11 - 1 - 7);
  for (size_t i = 0; i < b.n; ++i) CHECK(b.block[i] == 0);
  free_blocks(&b);
  rn_network_destroy(&net);
  rn_context_destroy(&ctx);
}

int main(void) {
  rn_context *ctx = NULL;
  const int models[2] = {RN_JOINT_RIGID, RN_JOINT_ELASTIC};
  const char *names[2] = {"rigid", "elastic"};
  for (int a = 0; a < 2; ++a)
    for (int c = 0; c < 2; ++c) {
      char name[64];
      rn_network *net;
      snprintf(name, sizeof name, "triangle %s/%s", names[a], names[c]);
      test_triangle(models[a], models[c], name);
      CHECK_STATUS(rn_context_create(&ctx), RN_OK);
      net = triangle(ctx, 4, models[a], models[c]);
      check_rigid_modes(net, name);
      check_interface_needed(net, name);
      rn_network_destroy(&net);
      rn_context_destroy(&ctx);
    }
  CHECK_STATUS(rn_context_create(&ctx), RN_OK);
  for (int a = 0; a < 2; ++a)
    for (int c = 0; c < 2; ++c) {
      rn_network *net = shimnet_portal(ctx, models[a], models[c], 4, 0.1, 1);
      check_no_coupling(net, "portal");
      check_interface_needed(net, "portal");
      rn_network_destroy(&net);
    }
  {
    rn_network *net = shimnet_grid(ctx, 3, 0.1);
    check_no_coupling(net, "grid");
    check_interface_needed(net, "grid");
    rn_network_destroy(&net);
  }
  rn_context_destroy(&ctx);
  check_kinds();
  check_single_rod();
  return rn_test_finish("api_dof_blocks");
}
