/* text_file.c - bounded whole-file reader. */
#define _POSIX_C_SOURCE 200809L

#include "io/text_file.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

/* Read at most max_bytes + 1 bytes of f into a growing buffer. */
static rn_status read_stream(FILE *f, size_t max_bytes, char **text, size_t *len) {
  size_t cap = 1 << 16, n = 0;
  char *buf = malloc(cap);
  if (!buf) return RN_ERR_ALLOC;
  for (;;) {
    if (n + 1 >= cap) {
      char *nb = realloc(buf, cap * 2);
      if (!nb) {
        free(buf);
        return RN_ERR_ALLOC;
      }
      buf = nb;
      cap *= 2;
    }
    size_t got = fread(buf + n, 1, cap - 1 - n, f);
    n += got;
    if (n > max_bytes) break;
    if (got == 0) {
      if (ferror(f)) {
        free(buf);
        return RN_ERR_IO;
      }
      break;
    }
  }
  buf[n] = '\0';
  *text = buf;
  *len = n;
  return RN_OK;
}

rn_status rn_text_file_read(rn_context *ctx, const char *path, size_t max_bytes,
                            char **text, size_t *len) {
  *text = NULL;
  *len = 0;
  FILE *f = fopen(path, "rb");
  if (!f)
    return rn_context_set_error(ctx, RN_ERR_IO, "%s: cannot open: %s", path,
                                strerror(errno));
  struct stat sb;
  if (fstat(fileno(f), &sb) != 0 || !S_ISREG(sb.st_mode)) {
    fclose(f);
    return rn_context_set_error(ctx, RN_ERR_IO, "%s: not a regular file", path);
  }
  rn_status st = read_stream(f, max_bytes, text, len);
  int err = errno;
  fclose(f);
  if (st == RN_ERR_ALLOC)
    return rn_context_set_error(ctx, st, "%s: out of memory reading the file", path);
  if (st)
    return rn_context_set_error(ctx, st, "%s: cannot read: %s", path, strerror(err));
  if (*len > max_bytes) {
    free(*text);
    *text = NULL;
    *len = 0;
    return rn_context_set_error(ctx, RN_ERR_IO, "%s: larger than %zu bytes", path,
                                max_bytes);
  }
  return RN_OK;
}
