/* cell_stress.c - the macroscopic stress of a periodic cell at a state: the
 * strain rows of the full gradient (docs/homogenization.md). */
#include <stdlib.h>

#include "eval/eval.h"
#include "periodic/periodic.h"

rn_status rn_network_cell_stress(const rn_network *net, const double *x, double *stress) {
  static const char *where = "rn_network_cell_stress";
  rn_status st;
  double *gfull;
  rn_cell *c;
  if (!net) return RN_ERR_ARG;
  if ((st = rn_cell_check(net, where, 0))) return st;
  if (!stress || (!x && net->nred))
    return rn_fail(net->ctx, RN_ERR_ARG, where, "NULL array");
  c = net->cell;
  gfull = malloc(net->nfull * sizeof(double));
  if (!gfull) return rn_fail(net->ctx, RN_ERR_ALLOC, where, "out of memory");
  st = rn_eval_gradient_full(net, x, gfull, where);
  if (st == RN_OK)
    for (int v = 0; v < c->nstrain; ++v) /* the gradient includes -lambda V sigma */
      stress[v] = gfull[c->off + (size_t)v] / c->measure +
                  (rn_cell_owned_here(net) ? net->lambda * c->stress[v] : 0.0);
  free(gfull);
  return st;
}
