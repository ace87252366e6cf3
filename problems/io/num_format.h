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
#include <stdio.h>

/* Writes s (NULL: "") to f as a JSON string: in double quotes, with '"' and
 * '\\' escaped and control characters as \\u00XX (every writer of rodnet's
 * JSON files; the text stays valid JSON whatever s holds). */
void rn_put_json_string(FILE *f, const char *s);

/* Room for any result of rn_format_g17 or rn_format_long, with the terminator. */
#define RN_NUM_BUF 40

/* Writes x as "%.17g" into buf (at least RN_NUM_BUF bytes, NUL-terminated);
 * returns the number of characters (without the NUL). */
size_t rn_format_g17(double x, char *buf);

/* Writes v as "%ld" into buf (at least RN_NUM_BUF bytes); returns the length. */
size_t rn_format_long(long v, char *buf);

/* The writers refuse non-finite numbers (issue 22): rn_format_g17 writes "nan"
 * or "inf" like printf, which is not JSON and not a number any reader of
 * rodnet's files takes.  A writer keeps an rn_num_check, passes every number
 * through rn_num_checked with the name of its field, and after the write
 * turns a recorded non-finite value into an error naming the file and the
 * first such field (rn_num_check_message); the file is then discarded
 * (atomic_file.h). */
typedef struct rn_num_check {
  int bad;         /* a non-finite number was met */
  double value;    /* the first one */
  char field[128]; /* its field */
} rn_num_check;

/* 1 if x is finite; otherwise records x and field (the first time) in *chk
 * and returns 0. */
int rn_num_checked(rn_num_check *chk, const char *field, double x);

/* "PATH: FIELD is nan (not a finite number); no file written" into buf[n]. */
const char *rn_num_check_message(const rn_num_check *chk, const char *path, char *buf,
                                 size_t n);

#endif
