/* cli_registry.c - the command's lists of solver kinds and preconditioners, read from
 * the library's registry (rodnet_registry.h), so that the help and the errors of
 * `rodnet solve` and `rodnet bench` name exactly its rows. */
#include <string.h>

#include "cli/cli_registry.h"
#include "rodnet_registry.h"

/* Appends sep and text to buf[n] (truncated at n - 1 characters). */
static void append(char *buf, size_t n, const char *sep, const char *text) {
  size_t len = strlen(buf);
  if (len + 1 < n) snprintf(buf + len, n - len, "%s%s", sep, text);
}

/* (the rows' values are their indices: rodnet_registry.h) */
void rn_cli_solver_names(char *buf, size_t n) {
  buf[0] = '\0';
  for (size_t i = 0; i < rn_solver_count(); i++)
    append(buf, n, i ? ", " : "", rn_solver_name((rn_solver_kind)i));
}

void rn_cli_preconditioner_names(char *buf, size_t n) {
  buf[0] = '\0';
  for (size_t i = 0; i < rn_preconditioner_count(); i++)
    append(buf, n, i ? ", " : "", rn_preconditioner_name((rn_preconditioner)i));
}

void rn_cli_preconditioned_solvers(char *buf, size_t n) {
  const rn_solver_info *row;
  size_t count = 0, k = 0;
  buf[0] = '\0';
  for (size_t i = 0; (row = rn_solver_info_at(i)) != NULL; i++)
    count += (row->flags & RN_SOLVER_TAKES_PRECONDITIONER) != 0;
  for (size_t i = 0; (row = rn_solver_info_at(i)) != NULL; i++) {
    if (!(row->flags & RN_SOLVER_TAKES_PRECONDITIONER)) continue;
    append(buf, n, k == 0 ? "" : k + 1 == count ? " and " : ", ", row->name);
    k++;
  }
}

enum { HELP_NAME_COL = 24, HELP_TEXT_COL = 39, HELP_WIDTH = 84 };

/* One row of a help list: its name at HELP_NAME_COL, its text (and remark) from
 * HELP_TEXT_COL, wrapped at word boundaries within HELP_WIDTH columns. */
static void print_row(FILE *out, const char *name, const char *help, const char *remark) {
  char text[256];
  snprintf(text, sizeof text, "%s%s", help, remark);
  int col = fprintf(out, "%*s%-*s ", HELP_NAME_COL, "", HELP_TEXT_COL - HELP_NAME_COL - 1,
                    name);
  const char *w = text;
  while (*w) {
    size_t len = strcspn(w, " ");
    if (col > HELP_TEXT_COL && col + 1 + (int)len > HELP_WIDTH)
      col = fprintf(out, "\n%*s", HELP_TEXT_COL, "") - 1;
    else if (col > HELP_TEXT_COL)
      col += fprintf(out, " ");
    col += fprintf(out, "%.*s", (int)len, w);
    w += len;
    while (*w == ' ') w++;
  }
  fputc('\n', out);
}

void rn_cli_print_solver_help(FILE *out) {
  char solvers[128];
  rn_cli_preconditioned_solvers(solvers, sizeof solvers);
  fputs("      --solver NAME   the solver kind (default tr-minres; under mpirun\n"
        "                      tr-krylov; docs/solvers.md):\n",
        out);
  const rn_solver_info *s;
  for (size_t i = 0; (s = rn_solver_info_at(i)) != NULL; i++)
    print_row(out, s->name, s->help,
              s->flags & RN_SOLVER_CAN_DISTRIBUTE ? "; any number of ranks" : "");
  fprintf(out,
          "      --preconditioner NAME  preconditioner of %s (it defines\n"
          "                      the trust-region norm; docs/solvers.md):\n",
          solvers);
  const rn_preconditioner_info *p;
  for (size_t i = 0; (p = rn_preconditioner_info_at(i)) != NULL; i++)
    print_row(out, p->name, p->help,
              p->flags & RN_PC_ONE_RANK      ? "; one rank"
              : p->flags & RN_PC_MPI_RUNTIME ? "; needs MPI"
                                             : "");
}
