/* fuzz_regressions.c - every input the scene fuzzer found (one file each in
 * tests/data/fuzz_regressions/) keeps the reader's contract (scene_check.h)
 * and gives the outcome its manifest line states.
 *
 *   fuzz_regressions MANIFEST.tsv FILE...
 * MANIFEST lines: "NAME<TAB>STATUS<TAB>TEXT" (# starts a comment): the file
 * NAME (next to the manifest) parses with status STATUS ("RN_OK",
 * "RN_ERR_PARSE", ...) and, unless TEXT is "-", a message containing TEXT.
 * Every FILE given must have a manifest line and every line a file. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene_check.h"
#include "testutil.h"

enum { MAX_ENTRIES = 256 };

typedef struct entry {
  char name[256], status[64], text[512];
  int seen;
} entry;

static const char *base_name(const char *path) {
  const char *s = strrchr(path, '/');
  return s ? s + 1 : path;
}

static int read_manifest(const char *path, entry *e) {
  FILE *f = fopen(path, "r");
  char line[1024];
  int n = 0;
  CHECK(f != NULL);
  if (!f) return 0;
  while (fgets(line, sizeof line, f) && n < MAX_ENTRIES) {
    line[strcspn(line, "\r\n")] = '\0';
    if (line[0] == '#' || line[0] == '\0') continue;
    char *name = strtok(line, "\t"), *status = strtok(NULL, "\t"),
         *text = strtok(NULL, "");
    CHECK(name && status && text);
    if (!(name && status && text)) continue;
    snprintf(e[n].name, sizeof e[n].name, "%s", name);
    snprintf(e[n].status, sizeof e[n].status, "%s", status);
    snprintf(e[n].text, sizeof e[n].text, "%s", text);
    e[n++].seen = 0;
  }
  fclose(f);
  return n;
}

static unsigned char *read_bytes(const char *path, size_t *len) {
  FILE *f = fopen(path, "rb");
  if (!f) return NULL;
  size_t cap = 1 << 16, n = 0, got;
  unsigned char *buf = malloc(cap);
  while (buf && (got = fread(buf + n, 1, cap - n, f)) > 0) {
    n += got;
    if (n == cap) {
      unsigned char *nb = realloc(buf, cap *= 2);
      if (!nb) free(buf);
      buf = nb;
    }
  }
  fclose(f);
  *len = n;
  return buf;
}

static void check_file(const char *path, entry *e, int n) {
  const char *name = base_name(path);
  entry *x = NULL;
  for (int i = 0; i < n && !x; i++)
    if (strcmp(e[i].name, name) == 0) x = &e[i];
  if (!x) {
    rn_test_fail(__FILE__, __LINE__, "%s has no line in the manifest", name);
    return;
  }
  x->seen = 1;
  size_t len = 0;
  unsigned char *data = read_bytes(path, &len);
  CHECK(data != NULL);
  if (!data) return;
  /* exactly len bytes (libFuzzer's inputs are not NUL-terminated) */
  unsigned char *copy = malloc(len ? len : 1);
  memcpy(copy, data, len);
  free(data);
  rn_fuzz_result res;
  int broken = rn_fuzz_scene_check(copy, len, name, &res);
  free(copy);
  if (broken) rn_test_fail(__FILE__, __LINE__, "%s: %d broken rule(s)", name, broken);
  CHECK(!res.skipped);
  if (strcmp(rn_status_name(res.status), x->status) != 0)
    rn_test_fail(__FILE__, __LINE__, "%s: status %s, expected %s (%s)", name,
                 rn_status_name(res.status), x->status, res.message);
  if (strcmp(x->text, "-") != 0 && !strstr(res.message, x->text))
    rn_test_fail(__FILE__, __LINE__, "%s: message \"%s\" lacks \"%s\"", name, res.message,
                 x->text);
  printf("%-40s %-16s %s\n", name, rn_status_name(res.status), res.message);
}

int main(int argc, char **argv) {
  static entry e[MAX_ENTRIES];
  if (argc < 2) {
    fprintf(stderr, "usage: %s MANIFEST.tsv FILE...\n", argv[0]);
    return 2;
  }
  int n = read_manifest(argv[1], e);
  for (int i = 2; i < argc; i++) check_file(argv[i], e, n);
  for (int i = 0; i < n; i++)
    if (!e[i].seen)
      rn_test_fail(__FILE__, __LINE__, "no file for manifest line %s", e[i].name);
  CHECK(n > 0);
  return rn_test_finish("fuzz_regressions");
}
