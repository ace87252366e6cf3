/* problems_cli_commands_test.c - the command's help lists exactly the rows of
 * its subcommand table (problems/cli/cli.c), in order, each with its synopsis
 * and help lines; every row dispatches to a handler whose --help succeeds; a
 * name outside the table is an unknown command. */
#define _POSIX_C_SOURCE 200809L /* dup, mkstemp */
#include "cli/cli.h"
#include "testutil.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* Run the command with stdout (and stderr) captured; returns its exit status,
 * the output in *out (malloc'd). */
static int run_captured(int argc, char **argv, char **out) {
  char path[] = "/tmp/rn_cli_commands_XXXXXX";
  int fd = mkstemp(path);
  CHECK(fd >= 0);
  fflush(stdout);
  fflush(stderr);
  int saved_out = dup(1), saved_err = dup(2);
  dup2(fd, 1);
  dup2(fd, 2);
  int rc = rn_cli_main(argc, argv);
  fflush(stdout);
  fflush(stderr);
  dup2(saved_out, 1);
  dup2(saved_err, 2);
  close(saved_out);
  close(saved_err);
  long size = lseek(fd, 0, SEEK_END);
  *out = calloc((size_t)size + 1, 1);
  lseek(fd, 0, SEEK_SET);
  if (size > 0) CHECK(read(fd, *out, (size_t)size) == size);
  close(fd);
  unlink(path);
  return rc;
}

int main(void) {
  int n = 0;
  const rn_cli_command *rows = rn_cli_commands(&n);
  CHECK(n > 0);

  char *help = NULL;
  char *help_argv[] = {"rodnet", "--help", NULL};
  CHECK(run_captured(2, help_argv, &help) == RN_EXIT_OK);
  const char *list = strstr(help, "\nCommands:\n");
  CHECK(list != NULL);
  /* the lines of the list up to the blank line: "  NAME ..." starts a row,
   * deeper indented lines continue its help */
  int row = 0;
  for (const char *p = list ? list + strlen("\nCommands:\n") : ""; *p && *p != '\n';) {
    size_t len = strcspn(p, "\n");
    if (len > 2 && p[2] != ' ') {
      CHECK(row < n);
      if (row < n) {
        size_t name = strcspn(p + 2, " ");
        if (name != strlen(rows[row].name) || strncmp(p + 2, rows[row].name, name) != 0)
          rn_test_fail(__FILE__, __LINE__, "help row %d is '%.*s', the table's '%s'", row,
                       (int)name, p + 2, rows[row].name);
        CHECK(strncmp(p + 2, rows[row].synopsis, strlen(rows[row].synopsis)) == 0);
        /* the first help line ends the row's first line */
        size_t first = strcspn(rows[row].help, "\n");
        CHECK(len >= first && strncmp(p + len - first, rows[row].help, first) == 0);
      }
      row++;
    }
    p += len + (p[len] == '\n');
  }
  if (row != n)
    rn_test_fail(__FILE__, __LINE__, "help lists %d commands, the table %d", row, n);
  free(help);

  /* every row dispatches: its --help succeeds and prints its usage */
  for (int i = 0; i < n; i++) {
    char *out = NULL;
    char name[64];
    snprintf(name, sizeof name, "%s", rows[i].name);
    char *argv[] = {"rodnet", name, "--help", NULL};
    int rc = run_captured(3, argv, &out);
    if (rc != RN_EXIT_OK)
      rn_test_fail(__FILE__, __LINE__, "rodnet %s --help: exit %d", rows[i].name, rc);
    char usage[64];
    snprintf(usage, sizeof usage, "Usage: rodnet %s", rows[i].name);
    if (!strstr(out, usage))
      rn_test_fail(__FILE__, __LINE__, "rodnet %s --help does not say '%s'", rows[i].name,
                   usage);
    free(out);
  }

  char *out = NULL;
  char *bad_argv[] = {"rodnet", "frobnicate", NULL};
  CHECK(run_captured(2, bad_argv, &out) == RN_EXIT_USAGE);
  CHECK(strstr(out, "rodnet: unknown command 'frobnicate'\nTry 'rodnet --help'.\n") !=
        NULL);
  free(out);
  return rn_test_finish("problems_cli_commands");
}
