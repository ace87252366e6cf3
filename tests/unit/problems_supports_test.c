/* problems_supports_test.c - free rigid-body motions (rn_network_free_motions,
 * rn_network_check_supports) of scenes (argv[1]: tests/data/supports, argv[2]:
 * problems/scenes):
 *  - a free rod with a tip force: 3 free translations and 3 free rotations,
 *    the force unbalanced, RN_ERR_BC naming them;
 *  - a rod pinned at its start under a couple: 3 free rotations, the couple
 *    unbalanced;
 *  - a free rod under balanced end forces and a pinned rod with a tip force
 *    (a pendulum): free motions, accepted;
 *  - the cantilever, the portal frame and the pinned column: nothing free
 *    (the column's supports leave no rigid motion). */
#include <stdio.h>
#include <string.h>

#include "scene/scene.h"
#include "testutil.h"

static void check(rn_context *ctx, const char *dir, const char *name, int nt, int nr,
                  int unbalanced_force, int unbalanced_moment) {
  char path[1024];
  snprintf(path, sizeof path, "%s/%s", dir, name);
  rn_scene *scene = NULL;
  CHECK_STATUS(rn_scene_load(ctx, path, &scene), RN_OK);
  if (!scene) return;
  const rn_network *net = rn_scene_network(scene);
  rn_free_motions fm;
  CHECK_STATUS(rn_network_free_motions(net, &fm), RN_OK);
  printf("%s: %d free translations, %d free rotations, unbalanced force %d moment %d\n",
         name, fm.num_translations, fm.num_rotations, fm.unbalanced_force,
         fm.unbalanced_moment);
  CHECK(fm.num_translations == nt);
  CHECK(fm.num_rotations == nr);
  CHECK(fm.unbalanced_force == unbalanced_force);
  CHECK(fm.unbalanced_moment == unbalanced_moment);
  rn_status st = rn_network_check_supports(net);
  CHECK_STATUS(st, unbalanced_force || unbalanced_moment ? RN_ERR_BC : RN_OK);
  if (st) {
    printf("  %s\n", rn_context_last_error(ctx));
    CHECK(strstr(rn_context_last_error(ctx), "rigid-body motions free") != NULL);
  }
  rn_scene_destroy(&scene);
}

int main(int argc, char **argv) {
  rn_context *ctx = NULL;
  CHECK_STATUS(rn_context_create(&ctx), RN_OK);
  CHECK(argc == 3);
  if (argc == 3) {
    check(ctx, argv[1], "free_rod_tip_force.json", 3, 3, 1, 0);
    check(ctx, argv[1], "free_rod_couple.json", 0, 3, 0, 1);
    check(ctx, argv[1], "free_rod_balanced.json", 3, 3, 0, 0);
    check(ctx, argv[1], "pendulum.json", 0, 3, 0, 0);
    check(ctx, argv[2], "cantilever.json", 0, 0, 0, 0);
    check(ctx, argv[2], "portal_frame.json", 0, 0, 0, 0);
    check(ctx, argv[2], "pinned_column.json", 0, 0, 0, 0);
  }
  CHECK_STATUS(rn_network_free_motions(NULL, NULL), RN_ERR_ARG);
  rn_context_destroy(&ctx);
  return rn_test_finish("problems_supports");
}
