/* cli_paths.c - the files a command reads and writes (cli.h, "Input and output
 * files"): no output may be one of the inputs or another output, compared as
 * files (device and inode when they exist, the resolved path when not:
 * "./a.json", symbolic and hard links, a prefix's derived names, a folder's
 * files), and every output is checked writable before any computation. */
#define _XOPEN_SOURCE 700 /* realpath, fnmatch */

#include <dirent.h>
#include <errno.h>
#include <stdarg.h>
#include <fnmatch.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "io/atomic_file.h"
#include "cli/cli.h"

/* One file resolved: its name (path + suffix), whether it exists (and its
 * device and inode), its canonical path (the real path when it exists, else
 * the real path of its folder with its base name; NULL if the folder does not
 * exist); for a family (a '*' in the suffix) the canonical folder and the
 * pattern of the base names. */
typedef struct resolved {
  char *name, *canon, *dir_canon;
  const char *glob;
  int exists, family;
  dev_t dev;
  ino_t ino;
} resolved;

/* The canonical form of p, which need not exist: the real path of its longest
 * existing ancestor followed by the rest of p, without "." components and with
 * ".." taking back one.  NULL when out of memory.  Caller frees. */
static char *canonical(const char *p) {
  size_t n = strlen(p);
  char *full = malloc(n + 3), *head = malloc(n + 3), *real = NULL, *out = NULL;
  if (!full || !head) {
    free(full);
    free(head);
    return NULL;
  }
  if (p[0] == '/')
    strcpy(full, p);
  else
    sprintf(full, "./%s", p);
  strcpy(head, full);
  size_t cut = strlen(head); /* full[0 .. cut) resolves, full + cut is the rest */
  for (;;) {
    head[cut] = '\0';
    if ((real = realpath(cut ? head : "/", NULL))) break;
    char *slash = strrchr(head, '/');
    if (!slash) break;
    cut = (size_t)(slash - head);
  }
  if (real && (out = malloc(strlen(real) + strlen(full + cut) + 2))) {
    strcpy(out, real);
    for (const char *q = full + cut; *q;) {
      while (*q == '/') q++;
      size_t len = strcspn(q, "/");
      if (len == 0) break;
      if (len == 2 && q[0] == '.' && q[1] == '.') {
        char *s = strrchr(out, '/');
        if (s && s != out)
          *s = '\0';
        else
          strcpy(out, "/");
      } else if (!(len == 1 && q[0] == '.')) {
        size_t m = strlen(out);
        if (m > 1) out[m++] = '/';
        memcpy(out + m, q, len);
        out[m + len] = '\0';
      }
      q += len;
    }
  }
  free(real);
  free(head);
  free(full);
  return out;
}

/* The folder part of p ("." for a bare name), allocated. */
static char *dir_of(const char *p) {
  const char *slash = strrchr(p, '/');
  size_t dlen = slash ? (size_t)(slash - p) : 0;
  char *dir = malloc(dlen + 2);
  if (!dir) return NULL;
  if (slash && dlen == 0)
    strcpy(dir, "/");
  else if (slash) {
    memcpy(dir, p, dlen);
    dir[dlen] = '\0';
  } else
    strcpy(dir, ".");
  return dir;
}

static int resolve(const rn_cli_file *f, resolved *r) {
  memset(r, 0, sizeof *r);
  const char *suffix = f->suffix ? f->suffix : "";
  r->name = malloc(strlen(f->path) + strlen(suffix) + 1);
  if (!r->name) return -1;
  sprintf(r->name, "%s%s", f->path, suffix);
  r->family = strchr(suffix, '*') != NULL;
  if (r->family) {
    const char *slash = strrchr(r->name, '/');
    char *dir = dir_of(r->name);
    r->glob = slash ? slash + 1 : r->name;
    r->dir_canon = dir ? canonical(dir) : NULL;
    free(dir);
    return 0;
  }
  struct stat sb;
  if (stat(r->name, &sb) == 0) {
    r->exists = 1;
    r->dev = sb.st_dev;
    r->ino = sb.st_ino;
    r->canon = realpath(r->name, NULL);
  }
  if (!r->canon) r->canon = canonical(r->name);
  return 0;
}

static void release(resolved *r) {
  free(r->name);
  free(r->canon);
  free(r->dir_canon);
}

/* 1 if the single file b is one of the family a's files: by name in a's
 * folder, or (b exists) as a link to one of the files there. */
static int in_family(const resolved *a, const resolved *b) {
  if (!a->dir_canon || !b->canon) return 0;
  const char *slash = strrchr(b->canon, '/');
  if (slash && (size_t)(slash - b->canon) == strlen(a->dir_canon) &&
      strncmp(b->canon, a->dir_canon, (size_t)(slash - b->canon)) == 0 &&
      fnmatch(a->glob, slash + 1, 0) == 0)
    return 1;
  if (strcmp(a->dir_canon, "/") == 0 && slash == b->canon &&
      fnmatch(a->glob, slash + 1, 0) == 0)
    return 1;
  if (!b->exists) return 0;
  DIR *d = opendir(a->dir_canon);
  int same = 0;
  for (struct dirent *e; d && !same && (e = readdir(d));) {
    if (fnmatch(a->glob, e->d_name, 0) != 0) continue;
    char *p = malloc(strlen(a->dir_canon) + strlen(e->d_name) + 2);
    struct stat sb;
    if (p) {
      sprintf(p, "%s/%s", a->dir_canon, e->d_name);
      same = stat(p, &sb) == 0 && sb.st_dev == b->dev && sb.st_ino == b->ino;
    }
    free(p);
  }
  if (d) closedir(d);
  return same;
}

/* 1 if a and b are the same file (or b one of the family a's). */
static int same_file(const resolved *a, const resolved *b) {
  if (a->family && b->family) return 0;
  if (a->family) return in_family(a, b);
  if (b->family) return in_family(b, a);
  if (a->exists && b->exists) return a->dev == b->dev && a->ino == b->ino;
  if (strcmp(a->name, b->name) == 0) return 1;
  return a->canon && b->canon && strcmp(a->canon, b->canon) == 0;
}

/* "OPTION PATH" or "OPTION PATH (its file PATH.vtu)" into buf. */
static const char *show(const rn_cli_file *f, const resolved *r, char *buf, size_t n) {
  if (f->suffix)
    snprintf(buf, n, "%s %s (%s %s)", f->what, f->path,
             r->family ? "its files" : "its file", r->name);
  else
    snprintf(buf, n, "%s %s", f->what, f->path);
  return buf;
}

/* A message of the checks, printed once under mpirun (by rank 0). */
#if defined(__GNUC__)
__attribute__((format(printf, 1, 2)))
#endif
static void
say(const char *fmt, ...) {
  va_list ap;
  if (rn_cli_quiet_rank()) return;
  va_start(ap, fmt);
  vfprintf(stderr, fmt, ap);
  va_end(ap);
}

int rn_cli_check_files(const char *cmd, const rn_cli_file *files, int n) {
  resolved *r = calloc((size_t)(n > 0 ? n : 1), sizeof *r);
  int rc = 0;
  if (!r) {
    say("rodnet %s: out of memory\n", cmd);
    return RN_EXIT_INTERNAL;
  }
  for (int i = 0; i < n && !rc; i++)
    if (files[i].path && resolve(&files[i], &r[i])) {
      say("rodnet %s: out of memory\n", cmd);
      rc = RN_EXIT_INTERNAL;
    }
  char a[4200];
  for (int i = 0; i < n && !rc; i++) {
    if (!files[i].path || files[i].role == RN_CLI_IN) continue;
    for (int j = 0; j < n && !rc; j++) {
      if (!files[j].path || j == i) continue;
      if (files[j].role == RN_CLI_IN && same_file(&r[i], &r[j]))
        rc = rn_cli_usage_error(cmd,
                                "%s is %s itself: the result would overwrite its "
                                "input; choose another name",
                                show(&files[i], &r[i], a, sizeof a), files[j].what);
      else if (files[j].role != RN_CLI_IN && j < i && same_file(&r[i], &r[j]))
        rc = rn_cli_usage_error(cmd,
                                "%s and %s name the same file (%s): one output would "
                                "overwrite the other; choose another name",
                                files[i].what, files[j].what,
                                r[i].family ? r[j].name : r[i].name);
    }
  }
  for (int i = 0; i < n; i++) release(&r[i]);
  free(r);
  return rc;
}

int rn_cli_probe_outputs(const char *cmd, const rn_cli_file *files, int n) {
  rn_context *ctx = NULL;
  if (rn_context_create(&ctx) != RN_OK) {
    say("rodnet %s: out of memory\n", cmd);
    return RN_EXIT_INTERNAL;
  }
  int rc = 0;
  for (int i = 0; i < n && !rc; i++) {
    const rn_cli_file *f = &files[i];
    if (!f->path || f->role == RN_CLI_IN || (f->suffix && f->suffix[0] == '/'))
      continue; /* a file in an output folder: the folder's probe covers it */
    if (f->role == RN_CLI_OUT_DIR) {
      struct stat sb;
      char *dir = NULL;
      int err = 0;
      if (stat(f->path, &sb) == 0) {
        if (!S_ISDIR(sb.st_mode)) {
          say("rodnet %s: %s %s: exists and is not a folder\n", cmd, f->what, f->path);
          rc = RN_EXIT_INPUT;
        } else if (access(f->path, W_OK | X_OK) != 0)
          err = errno;
      } else if (!(dir = dir_of(f->path)))
        err = ENOMEM;
      else if (stat(dir, &sb) != 0)
        err = ENOENT; /* its parent folder is missing */
      else if (access(dir, W_OK | X_OK) != 0)
        err = errno;
      free(dir);
      if (err) {
        say("rodnet %s: %s %s: cannot write the folder: %s\n", cmd, f->what, f->path,
            strerror(err));
        rc = RN_EXIT_INPUT;
      }
      continue;
    }
    char *name = malloc(strlen(f->path) + (f->suffix ? strlen(f->suffix) : 0) + 1);
    if (!name) {
      rc = RN_EXIT_INTERNAL;
      break;
    }
    sprintf(name, "%s%s", f->path, f->suffix ? f->suffix : "");
    if (rn_file_probe_writable(ctx, name) != RN_OK) {
      say("rodnet %s: %s %s\n", cmd, f->what, rn_context_last_error(ctx));
      rc = RN_EXIT_INPUT;
    }
    free(name);
  }
  rn_context_destroy(&ctx);
  return rc;
}
