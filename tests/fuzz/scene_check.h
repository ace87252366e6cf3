/* scene_check.h - the contract the JSON scene reader and the library keep on
 * ANY input, checked on one input by the libFuzzer target (fuzz_scene.c) and
 * by the regression test of the inputs it found (fuzz_regressions.c).
 *
 * The bytes go to rn_scene_parse as they are (not NUL-terminated).  Then:
 *  - rejected: no scene, a negative status, and ONE non-empty line of message
 *    that starts with the label;
 *  - accepted: the network is finalized and at its initial state every
 *    evaluation (energy split, energy + gradient, Hessian-vector product,
 *    Hessian values, also at load factor 1/2) and every per-rod result
 *    (vertices, angles, frames, strains, rest lengths, stencil fields) either
 *    succeeds with finite values only or returns RN_DEGENERATE (> 0) with a
 *    message; never a negative status; a periodic cell's description is
 *    consistent and its strain, stress and relative density are finite or
 *    RN_DEGENERATE.
 * Each broken rule is printed to stderr (with the input's label). */
#ifndef RN_FUZZ_SCENE_CHECK_H
#define RN_FUZZ_SCENE_CHECK_H

#include <stddef.h>
#include <stdint.h>

#include "rodnet.h"

/* Inputs whose "line" asks for more vertices than this are skipped: valid
 * scenes, but too big to evaluate at fuzzing speed (the instrumented
 * evaluations take about 1 ms per vertex; the reader's own limit is 1e8
 * vertices per rod, which a fuzzer reaches in a few bytes).  The reader's
 * paths do not depend on the size beyond a few vertices. */
#define RN_FUZZ_MAX_LINE_VERTICES 1000

typedef struct rn_fuzz_result {
  int skipped;      /* the input was skipped (see above) */
  rn_status status; /* of rn_scene_parse */
  char message[1024];
  int violations; /* broken rules (0: the input keeps the contract) */
} rn_fuzz_result;

/* Check one input; label names it in the messages.  Returns res->violations. */
int rn_fuzz_scene_check(const uint8_t *data, size_t size, const char *label,
                        rn_fuzz_result *res);

#endif
