/* registry_lists.c - the registries of preconditioners and solver kinds
 * (rodnet_registry.h): every row's value is its index, its name parses back to it
 * (rn_preconditioner_from_name, rn_solver_from_name), values outside the enums are
 * "unknown", rn_solver_is_distributed reads the flag, aliases stand for a real row;
 * the scene reader accepts exactly the rows' names (and names them all in its
 * "known:" list).  Prints the rows ("solver NAME FLAGS", "preconditioner NAME
 * FLAGS", "resolves NAME NAME") for check_registry_lists.py and
 * check_conformance_mpi.py; the first compares the command's help and errors
 * and the docs' tables with them.  Runs in the build without the solver too. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rodnet_registry.h"
#include "rodnet_scene.h"
#include "testutil.h"

/* A one-rod scene whose solver block is {"KEY": "NAME"}. */
static rn_status parse_with(rn_context *ctx, const char *key, const char *name,
                            rn_scene **out) {
  char text[1024];
  snprintf(text, sizeof text,
           "{\"materials\": {\"steel\": {\"E\": 1e7, \"nu\": 0.5}}, \"sections\": "
           "{\"wire\": {\"shape\": \"circle\", \"radius\": 0.01}}, \"rods\": "
           "[{\"name\": \"beam\", \"material\": \"steel\", \"section\": \"wire\", "
           "\"line\": {\"from\": [0, 0, 0], \"to\": [1, 0, 0], \"vertices\": 5}}], "
           "\"solver\": {\"%s\": \"%s\"}}",
           key, name);
  return rn_scene_parse(ctx, "registry.json", text, strlen(text), out);
}

/* The scene reader takes name for key, and the options it sets carry value. */
static void check_scene_accepts(rn_context *ctx, const char *key, const char *name,
                                int value) {
  rn_scene *s = NULL;
  CHECK_STATUS(parse_with(ctx, key, name, &s), RN_OK);
  if (!s) return;
  rn_solve_options opt;
  memset(&opt, 0, sizeof opt);
  opt.solver = (rn_solver_kind)-1;
  opt.preconditioner = (rn_preconditioner)-1;
  rn_scene_apply_solver(s, &opt);
  CHECK((strcmp(key, "method") == 0 ? (int)opt.solver : (int)opt.preconditioner) ==
        value);
  rn_scene_destroy(&s);
}

/* A bad name: refused, the message listing known exactly. */
static void check_scene_refuses(rn_context *ctx, const char *key, const char *known) {
  rn_scene *s = NULL;
  CHECK(parse_with(ctx, key, "no-such-name", &s) != RN_OK);
  char want[1024];
  snprintf(want, sizeof want, "\"no-such-name\" (known: %s)", known);
  const char *msg = rn_context_last_error(ctx);
  if (!strstr(msg, want)) printf("scene error '%s' does not contain '%s'\n", msg, want);
  CHECK(strstr(msg, want) != NULL);
  rn_scene_destroy(&s);
}

static void append(char *buf, size_t n, const char *sep, const char *name) {
  size_t len = strlen(buf);
  snprintf(buf + len, n - len, "%s%s", len ? sep : "", name);
}

static void check_preconditioners(rn_context *ctx) {
  char known[1024] = "";
  const size_t n = rn_preconditioner_count();
  CHECK(n > 0);
  CHECK(rn_preconditioner_info_at(n) == NULL);
  CHECK(rn_preconditioner_info_of((rn_preconditioner)-1) == NULL);
  CHECK(rn_preconditioner_info_of((rn_preconditioner)n) == NULL);
  CHECK(strcmp(rn_preconditioner_name((rn_preconditioner)n), "unknown") == 0);
  for (size_t i = 0; i < n; i++) {
    const rn_preconditioner_info *row = rn_preconditioner_info_at(i);
    CHECK(row && (size_t)row->value == i && row->name && row->help && *row->help);
    if (!row) continue;
    CHECK(rn_preconditioner_info_of(row->value) == row);
    CHECK(strcmp(rn_preconditioner_name(row->value), row->name) == 0);
    rn_preconditioner p = (rn_preconditioner)-1;
    CHECK_STATUS(rn_preconditioner_from_name(row->name, &p), RN_OK);
    CHECK(p == row->value);
    /* an alias stands for a row that is not one; the others for themselves */
    const rn_preconditioner_info *to = rn_preconditioner_info_of(row->resolves_to);
    CHECK(to != NULL);
    if (to)
      CHECK((row->flags & RN_PC_ALIAS) ? to != row && !(to->flags & RN_PC_ALIAS)
                                       : to == row);
    CHECK(!((row->flags & RN_PC_ONE_RANK) && (row->flags & RN_PC_MPI_RUNTIME)));
    check_scene_accepts(ctx, "preconditioner", row->name, (int)row->value);
    append(known, sizeof known, ", ", row->name);
    printf("preconditioner %s %u\n", row->name, row->flags);
    if (to) printf("resolves %s %s\n", row->name, to->name);
  }
  rn_preconditioner p;
  CHECK_STATUS(rn_preconditioner_from_name("no-such-name", &p), RN_ERR_ARG);
  CHECK_STATUS(rn_preconditioner_from_name(NULL, &p), RN_ERR_ARG);
  check_scene_refuses(ctx, "preconditioner", known);
}

static void check_solvers(rn_context *ctx) {
  char known[1024] = "";
  const size_t n = rn_solver_count();
  CHECK(n > 0);
  CHECK(rn_solver_info_at(n) == NULL);
  CHECK(rn_solver_info_of((rn_solver_kind)-1) == NULL);
  CHECK(strcmp(rn_solver_name((rn_solver_kind)n), "unknown") == 0);
  CHECK(rn_solver_is_distributed((rn_solver_kind)n) == 0);
  CHECK(rn_solver_is_distributed((rn_solver_kind)-1) == 0);
  for (size_t i = 0; i < n; i++) {
    const rn_solver_info *row = rn_solver_info_at(i);
    CHECK(row && (size_t)row->value == i && row->name && row->help && *row->help);
    if (!row) continue;
    CHECK(rn_solver_info_of(row->value) == row);
    CHECK(strcmp(rn_solver_name(row->value), row->name) == 0);
    rn_solver_kind k = (rn_solver_kind)-1;
    CHECK_STATUS(rn_solver_from_name(row->name, &k), RN_OK);
    CHECK(k == row->value);
    CHECK(rn_solver_is_distributed(row->value) ==
          ((row->flags & RN_SOLVER_CAN_DISTRIBUTE) ? 1 : 0));
    check_scene_accepts(ctx, "method", row->name, (int)row->value);
    append(known, sizeof known, ", ", row->name);
    printf("solver %s %u\n", row->name, row->flags);
  }
  rn_solver_kind k;
  CHECK_STATUS(rn_solver_from_name("no-such-name", &k), RN_ERR_ARG);
  check_scene_refuses(ctx, "method", known);
}

int main(void) {
  rn_context *ctx = NULL;
  CHECK_STATUS(rn_context_create(&ctx), RN_OK);
  /* today's rows (the enums are ABI: a value never moves) */
  CHECK(rn_preconditioner_count() == 9 && rn_solver_count() == 6);
  CHECK(strcmp(rn_preconditioner_name(RN_PRECOND_DD_AMG), "dd-amg") == 0);
  CHECK(strcmp(rn_solver_name(RN_SOLVER_ROL_LBFGS), "rol-lbfgs") == 0);
  CHECK(rn_solver_is_distributed(RN_SOLVER_TR_KRYLOV) &&
        rn_solver_is_distributed(RN_SOLVER_NOX) &&
        !rn_solver_is_distributed(RN_SOLVER_TR_MINRES));
  check_solvers(ctx);
  check_preconditioners(ctx);
  rn_context_destroy(&ctx);
  return rn_test_finish("registry_lists");
}
