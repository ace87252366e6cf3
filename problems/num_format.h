/* num_format.h - fast number formatting for the writers (result JSON, VTK).
 *
 * rn_format_g17 writes exactly the characters printf("%.17g", x) writes (so the
 * writers' output is unchanged byte for byte and every double round-trips through
 * strtod), about 10x faster than glibc's printf: the 17 significant digits are
 * the exactly rounded (ties to even) integer N = round(|x| 10^p), computed with a
 * small multi-word integer, with snprintf as the fallback above 2^127 and for
 * non-finite values.  Checked against snprintf on millions of values by the test
 * problems_num_format. */
#ifndef RN_NUM_FORMAT_H
#define RN_NUM_FORMAT_H

#include <stddef.h>

/* Room for any result of rn_format_g17 or rn_format_long, with the terminator. */
#define RN_NUM_BUF 40

/* Writes x as "%.17g" into buf (at least RN_NUM_BUF bytes, NUL-terminated);
 * returns the number of characters (without the NUL). */
size_t rn_format_g17(double x, char *buf);

/* Writes v as "%ld" into buf (at least RN_NUM_BUF bytes); returns the length. */
size_t rn_format_long(long v, char *buf);

#endif
