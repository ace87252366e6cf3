/* kernel_counts.h - floating-point operations of the rod kernels, counted by
 * a counting build of kernels/rod.c (kernel_counts.cpp). */
#ifndef RN_KERNEL_COUNTS_H
#define RN_KERNEL_COUNTS_H

#ifdef __cplusplus
extern "C" {
#endif

enum { RN_COUNT_ENERGY = 0, RN_COUNT_GRAD = 1, RN_COUNT_HVP = 2, RN_COUNT_HESS = 3 };

/* Additions + multiplications and divisions + square roots per vertex of one
 * whole-rod evaluation (rnk_rod_energy, _grad, _hvp, _hess) of a helix with
 * nv >= 3 vertices.  Returns 0, or non-zero if the kernel reported a
 * degenerate stencil. */
int rn_bench_kernel_counts(int op, int nv, double *addmul, double *divsqrt);

#ifdef __cplusplus
}
#endif
#endif
