/* api_pattern_linear.c - the Hessian pattern of a periodic supercell is built
 * in work linear in its size (docs/homogenization.md, "Reading large
 * supercells").  Square-lattice supercells of n x n cells (a joint per cell,
 * two rods of 3 vertices, the rods that cross the supercell's boundary at
 * joint images) for n = 8, 16, 32: the entries the pattern build's
 * candidate loops look at (net->pattern_work, counted, not timed) per stored
 * entry (nnz) are the same at every n, and grow by 4 per doubling of n like
 * the number of cells.  The version that scanned every row for each row of a
 * stencil at an image (the strain columns) looked at nred entries per such
 * row: about n^3 in all, 8 per doubling (reading the 150 x 150 honeycomb
 * supercell took 41.7 s before the fix and 21.9 s after, medians under load:
 * docs/homogenization.md). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "core/network_internal.h"
#include "rodnet.h"
#include "testutil.h"

/* The n x n supercell, rigid joints, finalized. */
static rn_network *square_supercell(rn_context *ctx, int n) {
  rn_network *net = NULL;
  rn_material m;
  rn_section s;
  double vec[6] = {n, 0, 0, 0, n, 0}, d1[3] = {0, 0, 1};
  CHECK_STATUS(rn_network_create(ctx, &net), RN_OK);
  CHECK_STATUS(rn_network_set_periodic(net, 2, vec), RN_OK);
  CHECK_STATUS(rn_material_from_E_nu(1.0, 0.3, 0.0, &m), RN_OK);
  CHECK_STATUS(rn_section_circle(0.02, &s), RN_OK);
  /* rods 2 (i + n j) (along x) and 2 (i + n j) + 1 (along y) start at node (i, j) */
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      for (int d = 0; d < 2; ++d) {
        double xyz[9];
        int rod = -1;
        for (int v = 0; v < 3; ++v) {
          xyz[3 * v] = i + (d == 0 ? 0.5 * v : 0.0);
          xyz[3 * v + 1] = j + (d == 1 ? 0.5 * v : 0.0);
          xyz[3 * v + 2] = 0.0;
        }
        CHECK_STATUS(rn_network_add_rod(net, NULL, 3, xyz, d1, &rod), RN_OK);
        CHECK_STATUS(rn_network_set_material(net, rod, -1, &m), RN_OK);
        CHECK_STATUS(rn_network_set_section(net, rod, -1, &s), RN_OK);
      }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      int im = (i + n - 1) % n, jm = (j + n - 1) % n, J = -1;
      int rods[4] = {2 * (i + n * j), 2 * (i + n * j) + 1, 2 * (im + n * j),
                     2 * (i + n * jm) + 1};
      int ends[4] = {RN_START, RN_START, RN_END, RN_END};
      int images[12] = {0};
      images[6] = i == 0; /* the x rod from the last column ends one period on */
      images[10] = j == 0;
      CHECK_STATUS(rn_network_add_joint_images(net, NULL, RN_JOINT_RIGID, 4, rods, ends,
                                               images, &J),
                   RN_OK);
    }
  CHECK_STATUS(rn_network_finalize(net), RN_OK);
  return net;
}

int main(void) {
  rn_context *ctx;
  CHECK_STATUS(rn_context_create(&ctx), RN_OK);
  double work[3], ratio[3];
  for (int k = 0; k < 3; ++k) {
    int n = 8 << k;
    rn_network *net = square_supercell(ctx, n);
    work[k] = (double)net->pattern_work;
    ratio[k] = work[k] / (double)net->nnz;
    printf("n = %2d: %6zu reduced DOFs, nnz %8zu, pattern work %9.0f (%.3f per entry)\n",
           n, net->nred, net->nnz, work[k], ratio[k]);
    rn_network_destroy(&net);
  }
  for (int k = 1; k < 3; ++k) {
    printf("n %d -> %d: work x %.3f (cells x 4)\n", 8 << (k - 1), 8 << k,
           work[k] / work[k - 1]);
    CHECK(work[k] / work[k - 1] > 3.5 && work[k] / work[k - 1] < 4.5);
    CHECK(fabs(ratio[k] / ratio[0] - 1.0) < 0.05);
  }
  rn_context_destroy(&ctx);
  return rn_test_finish("api_pattern_linear");
}
