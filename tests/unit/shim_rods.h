/* shim_rods.h - small rods built through rodnet.h for the solver (shim) tests. */
#ifndef RN_SHIM_RODS_H
#define RN_SHIM_RODS_H

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "rodnet.h"
#include "rodnet_solve.h"
#include "testutil.h"

#define SHIM_PI 3.14159265358979323846

/* Straight rod of length L from the origin along axis (0: x, 2: z), nv vertices,
 * material E (nu = 0.3), section s, clamped at the start, tip force f[3] at the
 * last vertex.  NULL on failure (a CHECK fails). */
static inline rn_network *shim_clamped_rod(rn_context *ctx, int nv, double L, int axis,
                                           const rn_section *s, double E,
                                           const double f[3]) {
  rn_network *net = NULL;
  rn_material m;
  int rod = -1;
  double *xyz = calloc((size_t)(3 * nv), sizeof(double));
  const double d1[3] = {0.0, 1.0, 0.0};
  for (int i = 0; i < nv; ++i) xyz[3 * i + axis] = L * (double)i / (double)(nv - 1);
  CHECK_STATUS(rn_network_create(ctx, &net), RN_OK);
  CHECK_STATUS(rn_material_from_E_nu(E, 0.3, 0.0, &m), RN_OK);
  CHECK_STATUS(rn_network_add_rod(net, "rod", nv, xyz, axis == 1 ? NULL : d1, &rod),
               RN_OK);
  CHECK_STATUS(rn_network_set_material(net, rod, -1, &m), RN_OK);
  CHECK_STATUS(rn_network_set_section(net, rod, -1, s), RN_OK);
  CHECK_STATUS(rn_network_clamp(net, rod, RN_START), RN_OK);
  CHECK_STATUS(rn_network_add_force(net, rod, -1, f), RN_OK);
  CHECK_STATUS(rn_network_finalize(net), RN_OK);
  free(xyz);
  return net;
}

/* The 21-vertex cantilever of the tests: L = 1 along x, circle r = 0.01,
 * E = 1e7, tip load -P along z. */
static inline rn_network *shim_cantilever(rn_context *ctx, double P) {
  rn_section s;
  const double f[3] = {0.0, 0.0, -P};
  CHECK_STATUS(rn_section_circle(0.01, &s), RN_OK);
  return shim_clamped_rod(ctx, 21, 1.0, 0, &s, 1e7, f);
}

/* Bending stiffness E I of the cantilever's section. */
static inline double shim_cantilever_EI(void) { return 1e7 * SHIM_PI * 1e-8 / 4.0; }

/* ||a - b|| / ||b - c|| (relative difference of two solutions, measured against
 * the displacement b - c from the starting state c). */
static inline double shim_rel_diff(size_t n, const double *a, const double *b,
                                   const double *c) {
  double num = 0.0, den = 0.0;
  for (size_t i = 0; i < n; ++i) {
    num += (a[i] - b[i]) * (a[i] - b[i]);
    den += (b[i] - c[i]) * (b[i] - c[i]);
  }
  return sqrt(num / den);
}

/* LAPACK (Fortran, with gfortran's hidden character lengths). */
void dposv_(const char *uplo, const int *n, const int *nrhs, double *a, const int *lda,
            double *b, const int *ldb, int *info, size_t uplo_len);
void dsyev_(const char *jobz, const char *uplo, const int *n, double *a, const int *lda,
            double *w, double *work, const int *lwork, int *info, size_t jobz_len,
            size_t uplo_len);

/* Dense copy (n x n, column-major) of the CSR Hessian at x; caller frees. */
static inline double *shim_dense_hessian(const rn_network *net, const double *x) {
  size_t n = rn_network_num_dofs(net), nnz = 0;
  const int64_t *rowptr = NULL;
  const int32_t *col = NULL;
  double *vals, *H = calloc(n * n, sizeof(double));
  CHECK_STATUS(rn_network_hessian_pattern(net, &nnz, &rowptr, &col), RN_OK);
  vals = calloc(nnz, sizeof(double));
  CHECK_STATUS(rn_network_hessian_values(net, x, vals), RN_OK);
  for (size_t i = 0; i < n; ++i)
    for (int64_t k = rowptr[i]; k < rowptr[i + 1]; ++k)
      H[i + n * (size_t)col[k]] = vals[k];
  free(vals);
  return H;
}

/* Lowest eigenvalue of a dense symmetric matrix (destroyed) by LAPACK dsyev. */
static inline double shim_dense_min_eigenvalue(int n, double *A) {
  int info = 0, lwork = 8 * n;
  double *w = calloc((size_t)n, sizeof(double)),
         *work = calloc((size_t)lwork, sizeof(double));
  double lmin;
  dsyev_("N", "L", &n, A, &n, w, work, &lwork, &info, 1, 1);
  CHECK(info == 0);
  lmin = w[0];
  free(w);
  free(work);
  return lmin;
}

#endif
