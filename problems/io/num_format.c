/* num_format.c - "%.17g" without printf (see num_format.h).
 *
 * A finite x != 0 below 2^127 is |x| = m 2^e (m < 2^53 an integer).  With k the
 * decimal exponent of |x| (10^k <= |x| < 10^(k+1)) and p = 16 - k, the 17
 * significant digits of "%.17g" are those of N = round(|x| 10^p), rounded to
 * nearest with ties to even (glibc's printf in the default rounding mode), which
 * here is computed exactly: m 10^p 2^e as a multi-word integer when p >= 0, and
 * m 2^e / 10^-p with a 128-bit remainder when p < 0.  k is first estimated from
 * the binary exponent (exact or one too small) and corrected when N has 18
 * digits.  The digits are then laid out as the C standard says for %g with
 * precision 17: fixed notation when -4 <= k < 17, exponential otherwise, trailing
 * zeros and a trailing point removed, an exponent of at least two digits. */
#include "io/num_format.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

__extension__ typedef unsigned __int128 rn_u128;

/* m 10^p for p <= 340 (the smallest subnormal has k = -324) needs < 1190 bits. */
enum { BIG_WORDS = 20 };

typedef struct big {
  uint64_t w[BIG_WORDS]; /* little-endian 64-bit words */
  int n;                 /* words in use */
} big;

static void big_mul(big *b, uint64_t f) {
  uint64_t carry = 0;
  for (int i = 0; i < b->n; i++) {
    rn_u128 t = (rn_u128)b->w[i] * f + carry;
    b->w[i] = (uint64_t)t;
    carry = (uint64_t)(t >> 64);
  }
  if (carry) b->w[b->n++] = carry;
}

static uint64_t big_word(const big *b, int i) { return i < b->n ? b->w[i] : 0; }

static int bit_length(uint64_t v) { return v ? 64 - __builtin_clzll(v) : 0; }

/* floor(b / 2^q) (64 bits: the caller's N) and how the remainder compares with
 * half of 2^q: 0 below, 1 equal, 2 above.  q >= 1. */
static uint64_t big_shift_round(const big *b, int q, int *cmp) {
  const int wi = q / 64, bi = q % 64;
  uint64_t lo = big_word(b, wi), hi = big_word(b, wi + 1);
  uint64_t quot = bi ? (lo >> bi) | (hi << (64 - bi)) : lo;
  const int hw = (q - 1) / 64, hb = (q - 1) % 64;
  const uint64_t half = (big_word(b, hw) >> hb) & 1u;
  int below = (big_word(b, hw) & ((UINT64_C(1) << hb) - 1u)) != 0;
  for (int i = 0; i < hw && !below; i++) below = b->w[i] != 0;
  *cmp = half ? (below ? 2 : 1) : 0;
  return quot;
}

static const uint64_t pow10_u64[20] = {1u,
                                       10u,
                                       100u,
                                       1000u,
                                       10000u,
                                       100000u,
                                       1000000u,
                                       10000000u,
                                       100000000u,
                                       1000000000u,
                                       10000000000u,
                                       100000000000u,
                                       1000000000000u,
                                       10000000000000u,
                                       100000000000000u,
                                       1000000000000000u,
                                       10000000000000000u,
                                       100000000000000000u,
                                       1000000000000000000u,
                                       10000000000000000000u};

/* round(m 2^e 10^p), ties to even; 0 if the value needs more than 64 bits or the
 * case is not handled (the caller falls back to snprintf). */
static uint64_t scaled(uint64_t m, int e, int p) {
  int cmp = 0;
  uint64_t N;
  if (p >= 0 && e >= 0) { /* |x| < 10^17: m 2^e 10^p is an integer below 2^64 */
    rn_u128 v = ((rn_u128)m << e) * pow10_u64[p];
    return (v >> 64) ? 0 : (uint64_t)v;
  }
  if (p >= 0) { /* m 10^p / 2^q, q = -e */
    const int q = -e;
    if (p <= 19 && q < 128) { /* fits 117 bits */
      rn_u128 v = (rn_u128)m * pow10_u64[p];
      rn_u128 quot = v >> q, rem = v - (quot << q), half = (rn_u128)1 << (q - 1);
      if (quot >> 64) return 0;
      N = (uint64_t)quot;
      cmp = rem > half ? 2 : rem == half ? 1 : 0;
    } else {
      big b;
      b.w[0] = m;
      b.n = 1;
      int r = p;
      for (; r >= 19; r -= 19) big_mul(&b, pow10_u64[19]);
      if (r) big_mul(&b, pow10_u64[r]);
      if (64 * (b.n - 1) + bit_length(b.w[b.n - 1]) > q + 64)
        return 0; /* the quotient would exceed 64 bits */
      N = big_shift_round(&b, q, &cmp);
    }
  } else { /* m 2^e / 10^s, s = -p <= 19, m 2^e < 2^127 */
    const int s = -p;
    if (s > 19 || e > 74) return 0;
    rn_u128 v = (rn_u128)m << e, d = pow10_u64[s];
    rn_u128 quot = v / d, rem = v - quot * d;
    if (quot >> 64) return 0;
    N = (uint64_t)quot;
    cmp = 2 * rem > d ? 2 : 2 * rem == d ? 1 : 0;
  }
  return N + (cmp == 2 || (cmp == 1 && (N & 1u)));
}

/* The 8 decimal digits of v < 10^8, with leading zeros. */
static void eight_digits(uint32_t v, char *d) {
  static const char pairs[201] = "00010203040506070809101112131415161718192021222324"
                                 "25262728293031323334353637383940414243444546474849"
                                 "50515253545556575859606162636465666768697071727374"
                                 "75767778798081828384858687888990919293949596979899";
  for (int i = 6; i >= 0; i -= 2) {
    memcpy(d + i, pairs + 2 * (v % 100u), 2);
    v /= 100u;
  }
}

/* Lays out the 17 digits d of a value with decimal exponent k as %.17g does. */
static size_t layout(int negative, const char d[17], int k, char *buf) {
  char *s = buf;
  int last = 16; /* last significant digit kept (trailing zeros dropped) */
  while (last > 0 && d[last] == '0') last--;
  if (negative) *s++ = '-';
  if (k >= -4 && k < 17) {
    if (k >= 0) {
      for (int i = 0; i <= k; i++) *s++ = d[i];
      if (last > k) {
        *s++ = '.';
        for (int i = k + 1; i <= last; i++) *s++ = d[i];
      }
    } else {
      *s++ = '0';
      *s++ = '.';
      for (int i = 0; i < -k - 1; i++) *s++ = '0';
      for (int i = 0; i <= last; i++) *s++ = d[i];
    }
  } else {
    *s++ = d[0];
    if (last > 0) {
      *s++ = '.';
      for (int i = 1; i <= last; i++) *s++ = d[i];
    }
    *s++ = 'e';
    *s++ = k < 0 ? '-' : '+';
    int a = k < 0 ? -k : k;
    if (a >= 100) *s++ = (char)('0' + a / 100);
    *s++ = (char)('0' + a / 10 % 10);
    *s++ = (char)('0' + a % 10);
  }
  *s = '\0';
  return (size_t)(s - buf);
}

size_t rn_format_g17(double x, char *buf) {
  uint64_t bits;
  memcpy(&bits, &x, sizeof bits);
  const int negative = (int)(bits >> 63);
  const int biased = (int)((bits >> 52) & 0x7ffu);
  uint64_t m = bits & ((UINT64_C(1) << 52) - 1u);
  if (biased == 0x7ff) return (size_t)snprintf(buf, RN_NUM_BUF, "%.17g", x);
  if (biased == 0 && m == 0) {
    char *s = buf;
    if (negative) *s++ = '-';
    *s++ = '0';
    *s = '\0';
    return (size_t)(s - buf);
  }
  int e;
  if (biased) {
    m |= UINT64_C(1) << 52;
    e = biased - 1075;
  } else {
    e = -1074;
  }
  /* floor(log2 |x|), then k = floor(log10 |x|) or one less */
  if (fabs(x) < 9007199254740992.0) { /* integers below 2^53: "%.17g" is "%lld" */
    const long long i = (long long)x;
    if ((double)i == x) return rn_format_long((long)i, buf);
  }
  /* k from log2 |x| = e2 + log2(1 + f) ~ e2 + f + 0.3466 f (1 - f) (error < 0.005);
   * a wrong guess near a power of 10 is corrected by the digit count of N */
  const int mbits = bit_length(m), e2 = e + mbits - 1;
  const double f = (double)((m << (53 - mbits)) - (UINT64_C(1) << 52)) * 0x1p-52;
  const double t = ((double)e2 + f + 0.3466 * f * (1.0 - f)) * 0.30102999566398119521;
  int k = (int)t;
  if ((double)k > t) k -= 1; /* floor */
  uint64_t N = scaled(m, e, 16 - k);
  if (N >= pow10_u64[17]) { /* k one too small (or N rounded up to 10^17) */
    k += 1;
    N = scaled(m, e, 16 - k);
  } else if (N <= pow10_u64[16]) { /* k one too large: |x| 10^p below 10^16 (even if
                                       it rounds up to 10^16) */
    const uint64_t N1 = scaled(m, e, 17 - k);
    if (N1 >= pow10_u64[16] && N1 < pow10_u64[17]) {
      k -= 1;
      N = N1;
    }
  }
  if (N < pow10_u64[16] || N >= pow10_u64[17]) /* out of the exact range */
    return (size_t)snprintf(buf, RN_NUM_BUF, "%.17g", x);
  char d[17];
  const uint64_t hi = N / 100000000u;
  d[0] = (char)('0' + hi / 100000000u);
  eight_digits((uint32_t)(hi % 100000000u), d + 1);
  eight_digits((uint32_t)(N % 100000000u), d + 9);
  return layout(negative, d, k, buf);
}

size_t rn_format_long(long v, char *buf) {
  char tmp[24];
  int n = 0;
  unsigned long u = v < 0 ? 0ul - (unsigned long)v : (unsigned long)v;
  do {
    tmp[n++] = (char)('0' + u % 10u);
    u /= 10u;
  } while (u);
  char *s = buf;
  if (v < 0) *s++ = '-';
  while (n) *s++ = tmp[--n];
  *s = '\0';
  return (size_t)(s - buf);
}

int rn_num_checked(rn_num_check *chk, const char *field, double x) {
  if (isfinite(x)) return 1;
  if (!chk->bad) {
    chk->bad = 1;
    chk->value = x;
    snprintf(chk->field, sizeof chk->field, "%s", field ? field : "a number");
  }
  return 0;
}

const char *rn_num_check_message(const rn_num_check *chk, const char *path, char *buf,
                                 size_t n) {
  snprintf(buf, n, "%s: %s is %s (not a finite number); no file written",
           path ? path : "output", chk->field,
           isnan(chk->value) ? "nan"
           : chk->value > 0  ? "inf"
                             : "-inf");
  return buf;
}

void rn_put_json_string(FILE *f, const char *s) {
  fputc('"', f);
  for (const unsigned char *p = (const unsigned char *)(s ? s : ""); *p; p++) {
    if (*p == '"' || *p == '\\')
      fprintf(f, "\\%c", *p);
    else if (*p < 0x20)
      fprintf(f, "\\u%04x", *p);
    else
      fputc(*p, f);
  }
  fputc('"', f);
}
