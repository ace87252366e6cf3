/* api_dofs_load_factor.c - rn_network_dofs_load_factor (rodnet_ramp.h): the load
 * factor the free DOFs belong to.  A clamped rod whose end is displaced: NaN before
 * finalize and for NULL; 0 after finalize even when finalize moved the prescribed
 * motion to load factor 0.8 (the initial geometry is load factor 0's); the load
 * factor of rn_network_set_dofs and of rn_network_update_reference; unchanged by
 * rn_network_set_load_factor, rn_network_load_step_size and a failed
 * rn_network_update_reference (non-finite x); restored by rn_network_state_restore. */
#include <math.h>
#include <stdlib.h>

#include "rodnet.h"
#include "rodnet_ramp.h"
#include "testutil.h"

enum { NV = 5 };

int main(void) {
  rn_context *ctx = NULL;
  rn_network *net = NULL;
  rn_material m;
  rn_section s;
  rn_state *saved = NULL;
  double xyz[3 * NV], d[3] = {-0.3, 0.1, 0.0}, rot[3] = {0.0, 0.0, 0.0}, stretch = 0.0,
                      angle = 0.0;
  int rod = -1;
  for (int i = 0; i < NV; ++i) {
    xyz[3 * i] = 0.25 * i;
    xyz[3 * i + 1] = xyz[3 * i + 2] = 0.0;
  }
  CHECK(isnan(rn_network_dofs_load_factor(NULL)));
  CHECK_STATUS(rn_context_create(&ctx), RN_OK);
  CHECK_STATUS(rn_network_create(ctx, &net), RN_OK);
  CHECK_STATUS(rn_network_add_rod(net, NULL, NV, xyz, NULL, &rod), RN_OK);
  CHECK_STATUS(rn_material_from_E_nu(1e4, 0.3, 0.0, &m), RN_OK);
  CHECK_STATUS(rn_section_circle(0.02, &s), RN_OK);
  CHECK_STATUS(rn_network_set_material(net, rod, -1, &m), RN_OK);
  CHECK_STATUS(rn_network_set_section(net, rod, -1, &s), RN_OK);
  CHECK_STATUS(rn_network_clamp(net, rod, RN_START), RN_OK);
  CHECK_STATUS(rn_network_clamp(net, rod, RN_END), RN_OK);
  CHECK_STATUS(rn_network_displace_end(net, rod, RN_END, d, rot), RN_OK);
  CHECK_STATUS(rn_network_set_load_factor(net, 0.8), RN_OK);
  CHECK(isnan(rn_network_dofs_load_factor(net))); /* not finalized */
  CHECK_STATUS(rn_network_finalize(net), RN_OK);
  CHECK(rn_network_load_factor(net) == 0.8);
  CHECK(rn_network_dofs_load_factor(net) == 0.0);

  const size_t n = rn_network_num_dofs(net);
  double *x = malloc(n * sizeof(double));
  CHECK(x != NULL);
  if (!x) return rn_test_finish("api_dofs_load_factor");
  CHECK_STATUS(rn_network_get_dofs(net, x), RN_OK);
  CHECK_STATUS(rn_network_set_load_factor(net, 0.5), RN_OK);
  CHECK(rn_network_dofs_load_factor(net) == 0.0); /* the DOFs did not move */
  CHECK_STATUS(rn_network_set_dofs(net, x), RN_OK);
  CHECK(rn_network_dofs_load_factor(net) == 0.5);
  CHECK_STATUS(rn_network_load_step_size(net, 0.0, 1.0, &stretch, &angle), RN_OK);
  CHECK(stretch > 0.0);
  CHECK(rn_network_dofs_load_factor(net) == 0.5);
  CHECK_STATUS(rn_network_state_save(net, &saved), RN_OK);
  CHECK_STATUS(rn_network_set_load_factor(net, 0.7), RN_OK);
  x[0] += 1e-3;
  CHECK_STATUS(rn_network_update_reference(net, x), RN_OK);
  CHECK(rn_network_dofs_load_factor(net) == 0.7);
  CHECK_STATUS(rn_network_set_load_factor(net, 0.9), RN_OK);
  x[0] = NAN;
  CHECK(rn_network_update_reference(net, x) != RN_OK);
  CHECK(rn_network_dofs_load_factor(net) == 0.7);
  CHECK_STATUS(rn_network_state_restore(net, saved), RN_OK);
  CHECK(rn_network_dofs_load_factor(net) == 0.5);
  CHECK(rn_network_load_factor(net) == 0.5);
  rn_state_destroy(&saved);
  free(x);
  rn_network_destroy(&net);
  rn_context_destroy(&ctx);
  return rn_test_finish("api_dofs_load_factor");
}
