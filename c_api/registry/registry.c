/* registry.c - the tables of preconditioners and solver kinds (rodnet_registry.h)
 * and the name functions of rodnet_solve.h that read them.  In every build (no
 * MPI, no Trilinos): the scene reader and the command parse names without the
 * solver too. */
#include <string.h>

#include "rodnet_registry.h"

/* ---- the tables: the rows of rodnet_registry.h, in enum order ------------------- */

#define RN_PC_ROW(value, name, resolves_to, flags, help) \
  {value, name, resolves_to, flags, help},
static const rn_preconditioner_info preconditioners[] = {
    RN_PRECONDITIONER_LIST(RN_PC_ROW)};
#undef RN_PC_ROW

#define RN_SOLVER_ROW(value, name, flags, help) {value, name, flags, help},
static const rn_solver_info solvers[] = {RN_SOLVER_LIST(RN_SOLVER_ROW)};
#undef RN_SOLVER_ROW

/* Every row's value is its index, so that a value finds its row by indexing: the
 * enum of rodnet_solve.h and the lists agree (a row out of order or a value
 * skipped does not compile). */
#define RN_PC_INDEX(value, ...) rn_pc_index_##value,
#define RN_SOLVER_INDEX(value, ...) rn_solver_index_##value,
enum { RN_PRECONDITIONER_LIST(RN_PC_INDEX) rn_pc_rows };
enum { RN_SOLVER_LIST(RN_SOLVER_INDEX) rn_solver_rows };
#undef RN_PC_INDEX
#undef RN_SOLVER_INDEX
#define RN_PC_CHECK(value, ...)                          \
  _Static_assert((int)value == (int)rn_pc_index_##value, \
                 #value " is not at its index in RN_PRECONDITIONER_LIST");
#define RN_SOLVER_CHECK(value, ...)                          \
  _Static_assert((int)value == (int)rn_solver_index_##value, \
                 #value " is not at its index in RN_SOLVER_LIST");
RN_PRECONDITIONER_LIST(RN_PC_CHECK)
RN_SOLVER_LIST(RN_SOLVER_CHECK)
#undef RN_PC_CHECK
#undef RN_SOLVER_CHECK

enum {
  N_PRECONDITIONERS = (int)(sizeof preconditioners / sizeof preconditioners[0]),
  N_SOLVERS = (int)(sizeof solvers / sizeof solvers[0])
};

/* ---- accessors ------------------------------------------------------------------- */

size_t rn_preconditioner_count(void) { return N_PRECONDITIONERS; }

const rn_preconditioner_info *rn_preconditioner_info_at(size_t i) {
  return i < N_PRECONDITIONERS ? &preconditioners[i] : NULL;
}

/* (a C caller may store any int in the enum) */
const rn_preconditioner_info *rn_preconditioner_info_of(rn_preconditioner p) {
  const int v = (int)p;
  return v >= 0 ? rn_preconditioner_info_at((size_t)v) : NULL;
}

size_t rn_solver_count(void) { return N_SOLVERS; }

const rn_solver_info *rn_solver_info_at(size_t i) {
  return i < N_SOLVERS ? &solvers[i] : NULL;
}

const rn_solver_info *rn_solver_info_of(rn_solver_kind k) {
  const int v = (int)k;
  return v >= 0 ? rn_solver_info_at((size_t)v) : NULL;
}

/* ---- the name functions of rodnet_solve.h ----------------------------------------- */

static const char *pc_name_at(size_t i) { return preconditioners[i].name; }
static const char *solver_name_at(size_t i) { return solvers[i].name; }

/* The index of name among name_at(0), ..., name_at(count - 1); -1 if absent. */
static int index_of(const char *name, size_t count, const char *(*name_at)(size_t)) {
  for (size_t i = 0; name && i < count; i++)
    if (strcmp(name, name_at(i)) == 0) return (int)i;
  return -1;
}

const char *rn_preconditioner_name(rn_preconditioner p) {
  const rn_preconditioner_info *row = rn_preconditioner_info_of(p);
  return row ? row->name : "unknown";
}

rn_status rn_preconditioner_from_name(const char *name, rn_preconditioner *p) {
  const int i = index_of(name, N_PRECONDITIONERS, pc_name_at);
  if (i < 0 || !p) return RN_ERR_ARG;
  *p = preconditioners[i].value;
  return RN_OK;
}

const char *rn_solver_name(rn_solver_kind k) {
  const rn_solver_info *row = rn_solver_info_of(k);
  return row ? row->name : "unknown";
}

rn_status rn_solver_from_name(const char *name, rn_solver_kind *k) {
  const int i = index_of(name, N_SOLVERS, solver_name_at);
  if (i < 0 || !k) return RN_ERR_ARG;
  *k = solvers[i].value;
  return RN_OK;
}

int rn_solver_is_distributed(rn_solver_kind k) {
  const rn_solver_info *row = rn_solver_info_of(k);
  return row && (row->flags & RN_SOLVER_CAN_DISTRIBUTE) ? 1 : 0;
}
