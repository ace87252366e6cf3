/* fixed.c - fixed position components of rod vertices and joints (the pins
 * and clamps as RN_FIX_* bitmasks) and their names in messages. */
#include "core/network_internal.h"

int rn_rod_in_clamp(const rn_rod *r, int v) {
  return (r->clamped[RN_START] && v <= 1) || (r->clamped[RN_END] && v >= r->nv - 2);
}

int rn_rod_fixed_components(const rn_rod *r, int v) {
  return rn_rod_in_clamp(r, v) ? RN_FIX_XYZ : r->pinned[v];
}

int rn_free_displaced_component(int mask, const double disp[3]) {
  for (int k = 0; k < 3; ++k)
    if (disp[k] != 0.0 && !rn_component_fixed(mask, k)) return k;
  return -1;
}

const char *rn_components_name(int mask, char buf[4]) {
  int n = 0;
  for (int k = 0; k < 3; ++k)
    if (rn_component_fixed(mask, k)) buf[n++] = "xyz"[k];
  buf[n] = '\0';
  return buf;
}
