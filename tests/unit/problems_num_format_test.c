/* problems_num_format_test.c - rn_format_g17 writes the same characters as
 * snprintf("%.17g") (and so round-trips through strtod) and rn_format_long the
 * same as "%ld": random bit patterns over every exponent (subnormals included),
 * log-uniform values, short decimals, exact ties of the 17th digit (ties to even),
 * the fixed/exponential switches at 1e-5 and 1e17, powers of 2 and 10 and their
 * neighbours, and the extremes. */
#include <float.h>
#include <limits.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/num_format.h"
#include "testutil.h"

static long mismatches = 0, compared = 0;

static void check_one(double x) {
  char ours[RN_NUM_BUF], ref[64];
  size_t n = rn_format_g17(x, ours);
  int m = snprintf(ref, sizeof ref, "%.17g", x);
  compared++;
  if (n != (size_t)m || strcmp(ours, ref) != 0) {
    if (mismatches++ < 20)
      rn_test_fail(__FILE__, __LINE__,
                   "x = %a: rn_format_g17 \"%s\" (%zu), printf \"%s\"", x, ours, n, ref);
    return;
  }
  if (isfinite(x) && strtod(ours, NULL) != x && mismatches++ < 20)
    rn_test_fail(__FILE__, __LINE__, "x = %a: \"%s\" does not round-trip", x, ours);
}

/* x and its 4 nearest neighbours on each side. */
static void check_around(double x) {
  double y = x;
  check_one(x);
  for (int i = 0; i < 4; i++) check_one(y = nextafter(y, INFINITY));
  y = x;
  for (int i = 0; i < 4; i++) check_one(y = nextafter(y, -INFINITY));
}

static uint64_t next_random(uint64_t *s) {
  *s ^= *s << 13;
  *s ^= *s >> 7;
  *s ^= *s << 17;
  return *s;
}

int main(void) {
  uint64_t s = 0x9e3779b97f4a7c15ull;
  /* random bit patterns: every exponent equally likely */
  for (int i = 0; i < 1000000; i++) {
    uint64_t b = next_random(&s);
    double x;
    memcpy(&x, &b, sizeof x);
    if (isfinite(x)) check_one(x);
  }
  /* log-uniform in [1e-30, 1e30], both signs */
  for (int i = 0; i < 1000000; i++) {
    double u = (double)(next_random(&s) >> 11) / 9007199254740992.0;
    double x = pow(10.0, 60.0 * u - 30.0);
    check_one(i % 2 ? -x : x);
  }
  /* short decimals and integers */
  for (int i = -20000; i <= 20000; i++) {
    check_one(i / 1000.0);
    check_one(i * 0.1);
    check_one((double)i * 1e15);
    check_one((double)i);
  }
  /* exact ties at the 17th digit: j / 2^17 has 17 decimals after the point, so
   * in [1, 10) it has 18 significant digits ending in 5 */
  for (int64_t j = 131072; j < 131072 + 200000; j++) check_one((double)j / 131072.0);
  for (int64_t j = 1; j < 100000; j += 7) check_one((double)j / 1125899906842624.0);
  /* switches between fixed and exponential notation, powers of 10 and 2 */
  for (int k = -330; k <= 310; k++) check_around(pow(10.0, k));
  for (int k = -1074; k <= 1023; k++) check_around(ldexp(1.0, k));
  check_around(1e-5 - 5e-22);
  check_around(9.9999999999999995e16);
  check_around(9.99999999999999994e-5);
  check_around(1.7014118346046923e38); /* 2^127 */
  /* extremes and specials */
  check_around(DBL_MAX);
  check_around(DBL_MIN);
  check_around(4.9406564584124654e-324);
  check_one(0.0);
  check_one(-0.0);
  check_one(INFINITY);
  check_one(-INFINITY);
  check_one(NAN);
  printf("%ld values compared, %ld mismatches\n", compared, mismatches);
  CHECK(mismatches == 0);

  /* rn_format_long */
  const long ints[] = {0, 1, -1, 9, 10, -10, 123456789, LONG_MAX, LONG_MIN, LONG_MIN + 1};
  for (size_t i = 0; i < sizeof ints / sizeof ints[0]; i++) {
    char ours[RN_NUM_BUF], ref[64];
    size_t n = rn_format_long(ints[i], ours);
    snprintf(ref, sizeof ref, "%ld", ints[i]);
    CHECK(n == strlen(ref) && strcmp(ours, ref) == 0);
  }
  for (int i = 0; i < 100000; i++) {
    long v = (long)next_random(&s) >> (i % 60);
    char ours[RN_NUM_BUF], ref[64];
    rn_format_long(v, ours);
    snprintf(ref, sizeof ref, "%ld", v);
    if (strcmp(ours, ref) != 0) {
      CHECK(strcmp(ours, ref) == 0);
      break;
    }
  }
  return rn_test_finish("problems_num_format");
}
