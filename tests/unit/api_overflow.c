/* api_overflow.c - finite inputs whose products overflow must not come back
 * as NaN or inf with RN_OK: evaluations return the recoverable
 * RN_OVERFLOW with a message (a solver then rejects the trial point). */
#include <math.h>
#include <string.h>

#include "rodnet.h"
#include "testutil.h"

int main(void) {
  rn_context *ctx;
  rn_network *net;
  CHECK_STATUS(rn_context_create(&ctx), RN_OK);
  CHECK_STATUS(rn_network_create(ctx, &net), RN_OK);
  double xyz[9] = {0, 0, 0, 1, 0, 0, 2, 0.5, 0}, d1[3] = {0, 0, 1};
  int rod;
  CHECK_STATUS(rn_network_add_rod(net, "r", 3, xyz, d1, &rod), RN_OK);
  rn_material m = {.E = 1e300, .G = 1e300, .density = 0};
  rn_section s;
  CHECK_STATUS(rn_section_circle(0.1, &s), RN_OK);
  CHECK_STATUS(rn_network_set_material(net, rod, -1, &m), RN_OK);
  CHECK_STATUS(rn_network_set_section(net, rod, -1, &s), RN_OK);
  CHECK_STATUS(rn_network_finalize(net), RN_OK);
  size_t n = rn_network_num_dofs(net);
  double x[11], g[11], v[11], Hv[11], E;
  CHECK(n == 11);
  CHECK_STATUS(rn_network_get_dofs(net, x), RN_OK);
  for (size_t i = 0; i < n; ++i) x[i] *= 1e10, v[i] = 1.0; /* stretch enormously */
  CHECK_STATUS(rn_network_energy(net, x, &E), RN_OVERFLOW);
  CHECK(strstr(rn_context_last_error(ctx), "not finite") != NULL);
  CHECK_STATUS(rn_network_gradient(net, x, &E, g), RN_OVERFLOW);
  /* the Hessian there is ~E A / lbar, finite: the HVP must then be finite */
  rn_status hs = rn_network_hvp(net, x, v, Hv);
  CHECK(hs == RN_OVERFLOW || (hs == RN_OK && isfinite(Hv[0])));
  /* at the input state everything is finite (zero energy) */
  CHECK_STATUS(rn_network_get_dofs(net, x), RN_OK);
  CHECK_STATUS(rn_network_energy(net, x, &E), RN_OK);
  CHECK(E == 0.0);
  rn_network_destroy(&net);
  rn_context_destroy(&ctx);
  return rn_test_finish("api_overflow");
}
