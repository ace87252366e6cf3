/* atomic_file.c - write to "<path>.tmp.<pid>", then rename. */
#define _POSIX_C_SOURCE 200809L

#include "io/atomic_file.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static char *temp_name(const char *path) {
  size_t n = strlen(path) + 48;
  char *t = malloc(n);
  if (t) snprintf(t, n, "%s.tmp.%ld", path, (long)getpid());
  return t;
}

static rn_file_temp_hook temp_hook = NULL;

void rn_file_set_temp_hook(rn_file_temp_hook hook) { temp_hook = hook; }

/* Announce the temporary file before it exists, forget it once it is gone. */
static void temp_active(const char *tmp, int active) {
  if (temp_hook) temp_hook(tmp, active);
}

static rn_status io_error(rn_context *ctx, const char *path, const char *what, int err) {
  return rn_context_set_error(ctx, RN_ERR_IO, "%s: %s: %s", path, what, strerror(err));
}

/* 1 if path exists and is neither a regular file nor a directory (a device
 * such as /dev/null or /dev/stdout, a FIFO): such a target is written in
 * place, never replaced by a rename. */
static int is_special(const char *path) {
  struct stat sb;
  return stat(path, &sb) == 0 && !S_ISREG(sb.st_mode) && !S_ISDIR(sb.st_mode);
}

/* Runs write on the open file f and closes it.  On a flush or close failure
 * the status is RN_ERR_IO and *err the errno (0 otherwise). */
static rn_status write_and_close(FILE *f, rn_file_writer write, void *user,
                                 rn_context *ctx, int *err) {
  setvbuf(f, NULL, _IOFBF, (size_t)1 << 20); /* large files: fewer write calls */
  rn_status st = write(f, user, ctx);
  *err = 0;
  if (!st && (fflush(f) != 0 || ferror(f))) {
    *err = errno;
    st = RN_ERR_IO;
  }
  if (fclose(f) != 0 && !st) {
    *err = errno;
    st = RN_ERR_IO;
  }
  return st;
}

static rn_status write_in_place(rn_context *ctx, const char *path, rn_file_writer write,
                                void *user) {
  FILE *f = fopen(path, "wb");
  if (!f) return io_error(ctx, path, "cannot open for writing", errno);
  int err;
  rn_status st = write_and_close(f, write, user, ctx, &err);
  if (st == RN_ERR_IO && err) st = io_error(ctx, path, "write failed", err);
  return st;
}

rn_status rn_file_write_atomic(rn_context *ctx, const char *path, rn_file_writer write,
                               void *user) {
  if (!path || !write) return rn_context_set_error(ctx, RN_ERR_ARG, "write: no path");
  if (is_special(path)) return write_in_place(ctx, path, write, user);
  char *tmp = temp_name(path);
  if (!tmp) return rn_context_set_error(ctx, RN_ERR_ALLOC, "%s: out of memory", path);
  temp_active(tmp, 1);
  FILE *f = fopen(tmp, "wb");
  if (!f) {
    rn_status st = io_error(ctx, path, "cannot create the file", errno);
    temp_active(tmp, 0);
    free(tmp);
    return st;
  }
  int err;
  rn_status st = write_and_close(f, write, user, ctx, &err);
  if (!st && rename(tmp, path) != 0) {
    err = errno;
    st = io_error(ctx, path, "cannot rename the temporary file", err);
  } else if (st == RN_ERR_IO && err) {
    st = io_error(ctx, path, "write failed", err);
  }
  if (st) remove(tmp);
  temp_active(tmp, 0);
  free(tmp);
  return st;
}

rn_status rn_file_probe_writable(rn_context *ctx, const char *path) {
  struct stat sb;
  if (stat(path, &sb) == 0 && S_ISDIR(sb.st_mode))
    return rn_context_set_error(ctx, RN_ERR_IO, "%s: is a directory", path);
  if (is_special(path))
    return access(path, W_OK) == 0
               ? RN_OK
               : io_error(ctx, path, "cannot open for writing", errno);
  char *tmp = temp_name(path);
  if (!tmp) return rn_context_set_error(ctx, RN_ERR_ALLOC, "%s: out of memory", path);
  temp_active(tmp, 1);
  FILE *f = fopen(tmp, "wb");
  rn_status st = RN_OK;
  if (!f)
    st = io_error(ctx, path, "cannot create the file", errno);
  else {
    fclose(f);
    remove(tmp);
  }
  temp_active(tmp, 0);
  free(tmp);
  return st;
}
