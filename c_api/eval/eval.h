/* eval.h - evaluation of the energy terms (assembly.c, hessian.c,
 * load_increment.c, check.c, stretch_correction.c): the Hessian pattern and
 * its CSR assembly, and the full-layout gradients and Bloch blocks that
 * reactions and homogenisation read. */
#ifndef RN_EVAL_MODULE_H
#define RN_EVAL_MODULE_H

#include "core/network_internal.h"
#include "periodic/periodic.h"

/* ---- load increment (assembly.c) -------------------------------------------- */
/* Hv[nred] = H_{free,fixed}(x) vfull: every stencil's Hessian block applied to
 * the fixed entries of the full-layout direction vfull[nfull], free rows only.
 * No argument checks (where names the caller in messages). */
rn_status rn_eval_fixed_hvp(const rn_network *net, const double *x, const double *vfull,
                            double *Hv, const char *where);
/* g[nred] = gradient of the load terms (forces, couples) at load factor 1: their
 * derivative with respect to the load factor (loads are linear in it). */
rn_status rn_eval_load_rate(const rn_network *net, const double *x, double *g,
                            const char *where);

/* gfull[nfull] = gradient of the energy with respect to every full DOF (free and
 * fixed; an aliased rod end slot gets its rod's stencils, the joint's slot the
 * joint stencil and the joint force) at the reduced state x (reactions.c). */
rn_status rn_eval_gradient_full(const rn_network *net, const double *x, double *gfull,
                                const char *where);

/* gfull[nfull] += gradient of rod ir's own stretching, bending and twisting
 * energy (no loads, no joints) at the reduced state x, on its full-layout slots
 * (reactions.c: internal forces). */
rn_status rn_eval_rod_gradient_full(const rn_network *net, int ir, const double *x,
                                    double *gfull, const char *where);

/* gabs[nred] = sum over the stencils (and loads) of |their gradient| at each reduced
 * DOF: the magnitude of the forces that balance there (reactions.c). */
rn_status rn_eval_gradient_magnitude(const rn_network *net, const double *x, double *gabs,
                                     const char *where);

/* Every stencil's Hessian block at x into b (assembly.c). */
rn_status rn_eval_bloch(const rn_network *net, const double *x, rn_bloch_acc *b,
                        const char *where);

/* Builds the Hessian pattern (hessian.c). */
rn_status rn_build_hessian_pattern(rn_network *net);
/* Builds the pattern again (contact pairs changed); keeps the old one and
 * returns RN_ERR_ALLOC on failure. */
rn_status rn_rebuild_hessian_pattern(rn_network *net);
/* Adds the free-free entries of a dense n x n stencil block at full index s
 * into CSR values (hessian.c). */
void rn_csr_add_block(const rn_network *net, size_t s, int n, const double *H,
                      double *vals);
/* Adds rows s .. s + n - 1 of the full layout given in rnk.h band storage
 * (band[i * RNK_BAND + c - (s + i) + RNK_BAND_HALF] = entry (s + i, c); rod
 * stencils only) into CSR values.  Returns 1 if every value it added was at
 * most RN_HESS_BOUND in magnitude (rn_all_bounded). */
int rn_csr_add_band(const rn_network *net, size_t s, int n, const double *band,
                    double *vals);
/* Zeroes the CSR values that the rod bands do not store (net->hzero). */
void rn_hessian_zero(const rn_network *net, double *vals);
/* Frees the Hessian pattern (rowptr, col, band, rod_direct, hzero) and sets
 * the pointers NULL. */
void rn_hessian_pattern_free(rn_network *net);
/* The same for a stencil gathered by the full index list idx[n]. */
void rn_csr_add_block_idx(const rn_network *net, const size_t *idx, int n,
                          const double *H, double *vals);

#endif
