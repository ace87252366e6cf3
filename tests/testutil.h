/* testutil.h - tiny assertion helpers for rodnet's C tests.
 * A failed check prints file:line and the values, counts a failure, and the
 * test's main returns rn_test_finish() (non-zero if anything failed). */
#ifndef RN_TESTUTIL_H
#define RN_TESTUTIL_H
#include <stdint.h>

extern int rn_test_failures;
extern int rn_test_checks;

void rn_test_fail(const char *file, int line, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;
/* Prints "N passed, M failed" and returns 0 if no check failed. */
int rn_test_finish(const char *name);

#define CHECK(cond)                                                    \
  do {                                                                 \
    rn_test_checks++;                                                  \
    if (!(cond)) rn_test_fail(__FILE__, __LINE__, "CHECK(%s)", #cond); \
  } while (0)

/* |a - b| <= tol (absolute). */
#define CHECK_NEAR(a, b, tol)                                                            \
  do {                                                                                   \
    double a_ = (a), b_ = (b), t_ = (tol);                                               \
    rn_test_checks++;                                                                    \
    if (!(fabs(a_ - b_) <= t_))                                                          \
      rn_test_fail(__FILE__, __LINE__, "%s = %.17g vs %s = %.17g, |diff| = %.3g > %.3g", \
                   #a, a_, #b, b_, fabs(a_ - b_), t_);                                   \
  } while (0)

/* |a - b| <= rtol * |b| (relative to the reference b). */
#define CHECK_REL(a, b, rtol)                                                         \
  do {                                                                                \
    double a_ = (a), b_ = (b), t_ = (rtol);                                           \
    rn_test_checks++;                                                                 \
    if (!(fabs(a_ - b_) <= t_ * fabs(b_)))                                            \
      rn_test_fail(__FILE__, __LINE__, "%s = %.17g vs %s = %.17g, rel = %.3g > %.3g", \
                   #a, a_, #b, b_, fabs(a_ - b_) / fabs(b_), t_);                     \
  } while (0)

#define CHECK_STATUS(expr, expected)                                             \
  do {                                                                           \
    int s_ = (int)(expr);                                                        \
    rn_test_checks++;                                                            \
    if (s_ != (int)(expected))                                                   \
      rn_test_fail(__FILE__, __LINE__, "%s returned %d, expected %d", #expr, s_, \
                   (int)(expected));                                             \
  } while (0)

/* Deterministic uniform random numbers in [-1, 1). */
double rn_test_rand(uint64_t *state);

/* 3-vector helpers shared by the kernel tests. */
void rn_test_normalize3(double v[3]);
void rn_test_cross3(const double a[3], const double b[3], double r[3]);

/* Least-squares slope of log(err) against log(h) over n points. */
double rn_test_loglog_slope(int n, const double *h, const double *err);

#endif
