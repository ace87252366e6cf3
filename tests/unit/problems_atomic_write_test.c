/* problems_atomic_write_test.c - output files are written completely or not
 * at all: a failing writer, an impossible rename or a missing directory
 * leave no partial file and no temporary file behind, and an existing file
 * keeps its old content.  argv[1]: a scratch directory (created). */
#define _POSIX_C_SOURCE 200809L

#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "io/atomic_file.h"
#include "testutil.h"

static rn_status write_hello(FILE *f, void *user, rn_context *ctx) {
  (void)user;
  (void)ctx;
  fputs("hello\n", f);
  return RN_OK;
}

/* Writes part of the content, then fails. */
static rn_status write_then_fail(FILE *f, void *user, rn_context *ctx) {
  (void)user;
  fputs("{\"partial\": ", f);
  return rn_context_set_error(ctx, RN_ERR_NOT_FINITE, "writer: NaN in the result");
}

static int file_is(const char *path, const char *content) {
  char buf[256] = {0};
  FILE *f = fopen(path, "rb");
  if (!f) return 0;
  size_t n = fread(buf, 1, sizeof buf - 1, f);
  fclose(f);
  return n == strlen(content) && memcmp(buf, content, n) == 0;
}

static int exists(const char *path) {
  struct stat sb;
  return stat(path, &sb) == 0;
}

/* Number of entries of dir whose name contains ".tmp.". */
static int temp_files(const char *dir) {
  int n = 0;
  DIR *d = opendir(dir);
  if (!d) return -1;
  for (struct dirent *e; (e = readdir(d));)
    if (strstr(e->d_name, ".tmp.")) n++;
  closedir(d);
  return n;
}

/* A device target is written in place and stays a device: /dev/full (every
 * write fails with ENOSPC: an error, no temporary file in /dev) and
 * /dev/null (success).  Skipped where they are not character devices. */
static void check_devices(rn_context *ctx) {
  struct stat sb;
  if (stat("/dev/full", &sb) == 0 && S_ISCHR(sb.st_mode)) {
    CHECK_STATUS(rn_file_write_atomic(ctx, "/dev/full", write_hello, NULL), RN_ERR_IO);
    CHECK(strstr(rn_context_last_error(ctx), "/dev/full: write failed") != NULL);
    CHECK(stat("/dev/full", &sb) == 0 && S_ISCHR(sb.st_mode));
    CHECK(temp_files("/dev") == 0);
    CHECK_STATUS(rn_file_probe_writable(ctx, "/dev/full"), RN_OK);
  }
  if (stat("/dev/null", &sb) == 0 && S_ISCHR(sb.st_mode)) {
    CHECK_STATUS(rn_file_write_atomic(ctx, "/dev/null", write_hello, NULL), RN_OK);
    CHECK(stat("/dev/null", &sb) == 0 && S_ISCHR(sb.st_mode));
  }
}

int main(int argc, char **argv) {
  if (argc < 2) {
    fprintf(stderr, "usage: %s SCRATCH_DIR\n", argv[0]);
    return 2;
  }
  const char *dir = argv[1];
  char ok[512], old[512], sub[512], missing[512];
  mkdir(dir, 0755);
  snprintf(ok, sizeof ok, "%s/ok.txt", dir);
  snprintf(old, sizeof old, "%s/old.txt", dir);
  snprintf(sub, sizeof sub, "%s/subdir", dir);
  snprintf(missing, sizeof missing, "%s/no/such/dir/out.json", dir);
  remove(ok);
  remove(old);
  mkdir(sub, 0755);
  rn_context *ctx = NULL;
  CHECK_STATUS(rn_context_create(&ctx), RN_OK);
  check_devices(ctx);

  /* success */
  CHECK_STATUS(rn_file_write_atomic(ctx, ok, write_hello, NULL), RN_OK);
  CHECK(file_is(ok, "hello\n"));
  CHECK(temp_files(dir) == 0);

  /* a failing writer: no file, and an existing file keeps its content */
  CHECK_STATUS(rn_file_write_atomic(ctx, ok, write_then_fail, NULL), RN_ERR_NOT_FINITE);
  CHECK(file_is(ok, "hello\n"));
  CHECK(strcmp(rn_context_last_error(ctx), "writer: NaN in the result") == 0);
  CHECK_STATUS(rn_file_write_atomic(ctx, old, write_then_fail, NULL), RN_ERR_NOT_FINITE);
  CHECK(!exists(old));
  CHECK(temp_files(dir) == 0);

  /* rename over a directory fails after a complete write */
  CHECK_STATUS(rn_file_write_atomic(ctx, sub, write_hello, NULL), RN_ERR_IO);
  CHECK(strstr(rn_context_last_error(ctx), "cannot rename") != NULL);
  CHECK(temp_files(dir) == 0);
  struct stat sb;
  CHECK(stat(sub, &sb) == 0 && S_ISDIR(sb.st_mode));

  /* a missing directory */
  CHECK_STATUS(rn_file_write_atomic(ctx, missing, write_hello, NULL), RN_ERR_IO);
  CHECK(strstr(rn_context_last_error(ctx), missing) == rn_context_last_error(ctx));
  CHECK(strstr(rn_context_last_error(ctx), "cannot create the file") != NULL);

  /* the early probe */
  CHECK_STATUS(rn_file_probe_writable(ctx, ok), RN_OK);
  CHECK(file_is(ok, "hello\n"));
  CHECK(temp_files(dir) == 0);
  CHECK_STATUS(rn_file_probe_writable(ctx, sub), RN_ERR_IO);
  CHECK(strstr(rn_context_last_error(ctx), "is a directory") != NULL);
  CHECK_STATUS(rn_file_probe_writable(ctx, missing), RN_ERR_IO);
  CHECK(temp_files(dir) == 0);

  rn_context_destroy(&ctx);
  remove(ok);
  rmdir(sub);
  return rn_test_finish("problems_atomic_write");
}
