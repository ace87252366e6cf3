/* material.c - rn_material from (E, nu). */
#include <math.h>

#include "rodnet.h"

rn_status rn_material_from_E_nu(double E, double nu, double density, rn_material *m) {
  if (!m) return RN_ERR_ARG;
  if (!isfinite(E) || !isfinite(nu) || !isfinite(density)) return RN_ERR_NOT_FINITE;
  if (!(E > 0.0) || !(nu > -1.0) || !(nu <= 0.5) || !(density >= 0.0)) return RN_ERR_ARG;
  m->E = E;
  m->G = E / (2.0 * (1.0 + nu));
  m->density = density;
  return RN_OK;
}
