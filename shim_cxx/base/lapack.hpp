// lapack.hpp - the LAPACK and BLAS routines (Fortran) that more than one file of the
// shim calls, with the hidden character-length arguments of gfortran.
#ifndef RODNET_SHIM_LAPACK_HPP
#define RODNET_SHIM_LAPACK_HPP

#include <cstddef>

extern "C" {
// Banded Cholesky (lower or upper band storage) and its solve.
void dpbtrf_(const char *uplo, const int *n, const int *kd, double *ab, const int *ldab,
             int *info, size_t uplo_len);
void dpbtrs_(const char *uplo, const int *n, const int *kd, const int *nrhs,
             const double *ab, const int *ldab, double *b, const int *ldb, int *info,
             size_t uplo_len);
// Dense Cholesky and its solve.
void dpotrf_(const char *uplo, const int *n, double *a, const int *lda, int *info,
             size_t uplo_len);
void dpotrs_(const char *uplo, const int *n, const int *nrhs, const double *a,
             const int *lda, double *b, const int *ldb, int *info, size_t uplo_len);
// General dense solve A X = B by LU with partial pivoting.
void dgesv_(const int *n, const int *nrhs, double *a, const int *lda, int *ipiv,
            double *b, const int *ldb, int *info);
// C = alpha A' A + beta C (or A A'), one triangle of C.
void dsyrk_(const char *uplo, const char *trans, const int *n, const int *k,
            const double *alpha, const double *a, const int *lda, const double *beta,
            double *c, const int *ldc, size_t uplo_len, size_t trans_len);
// Eigenvalues (and vectors) of a symmetric tridiagonal matrix.
void dstev_(const char *jobz, const int *n, double *d, double *e, double *z,
            const int *ldz, double *work, int *info, size_t jobz_len);
// Eigenvalues (and vectors) of a dense symmetric matrix.
void dsyev_(const char *jobz, const char *uplo, const int *n, double *a, const int *lda,
            double *w, double *work, const int *lwork, int *info, size_t jobz_len,
            size_t uplo_len);
}

#endif
