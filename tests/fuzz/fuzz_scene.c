/* fuzz_scene.c - libFuzzer target for the JSON scene reader: every input goes
 * through rn_scene_parse and, if accepted, through one evaluation of
 * everything the library computes at the initial state (scene_check.h).  A
 * broken rule aborts, so libFuzzer keeps the input as a crash. */
#include <stdio.h>
#include <stdlib.h>

#include "scene_check.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  rn_fuzz_result res;
  if (rn_fuzz_scene_check(data, size, "fuzz.json", &res)) {
    fprintf(stderr, "fuzz_scene: %d broken rule(s); parse status %s: %s\n",
            res.violations, rn_status_name(res.status), res.message);
    abort();
  }
  return 0;
}
