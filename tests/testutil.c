#include "testutil.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>

int rn_test_failures = 0;
int rn_test_checks = 0;

void rn_test_fail(const char *file, int line, const char *fmt, ...) {
  va_list ap;
  rn_test_failures++;
  fprintf(stderr, "%s:%d: FAILED: ", file, line);
  va_start(ap, fmt);
  vfprintf(stderr, fmt, ap);
  va_end(ap);
  fputc('\n', stderr);
}

int rn_test_finish(const char *name) {
  printf("%s: %d passed, %d failed\n", name, rn_test_checks - rn_test_failures,
         rn_test_failures);
  return rn_test_failures == 0 ? 0 : 1;
}

double rn_test_rand(uint64_t *state) {
  /* splitmix64 */
  uint64_t z = (*state += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  z ^= z >> 31;
  return (double)(z >> 11) * (2.0 / 9007199254740992.0) - 1.0;
}

double rn_test_loglog_slope(int n, const double *h, const double *err) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (int i = 0; i < n; ++i) {
    double x = log(h[i]), y = log(err[i] > 0 ? err[i] : 1e-300);
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

void rn_test_normalize3(double v[3]) {
  double n = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  for (int k = 0; k < 3; ++k) v[k] /= n;
}

void rn_test_cross3(const double a[3], const double b[3], double r[3]) {
  double t[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                 a[0] * b[1] - a[1] * b[0]};
  r[0] = t[0], r[1] = t[1], r[2] = t[2];
}
