/* scene.c - an outside program using the installed scene library
 * (rodnet_scene.h, librodnet_scene): reads the scene SCENE.json, solves it with
 * the scene's solver settings, writes OUT.json and OUT.vtu and checks them;
 * also that a missing scene file is a clear RN_ERR_IO naming the file.
 * Usage: consumer_scene SCENE.json OUT_PREFIX.  Exit 0 on success. */
#include <rodnet.h>
#include <rodnet_scene.h>
#include <rodnet_solve.h>
#include <stdio.h>
#include <string.h>

static int fail(const char *what, rn_context *ctx) {
  fprintf(stderr, "consumer_scene: %s failed: %s\n", what,
          ctx ? rn_context_last_error(ctx) : "");
  return 1;
}

/* 1 if the file at path holds the text needle (files here are small). */
static int file_has(const char *path, const char *needle) {
  static char buf[1 << 16];
  FILE *f = fopen(path, "rb");
  if (!f) return 0;
  size_t n = fread(buf, 1, sizeof buf - 1, f);
  fclose(f);
  buf[n] = '\0';
  return strstr(buf, needle) != NULL;
}

int main(int argc, char **argv) {
  if (argc != 3) {
    fprintf(stderr, "usage: consumer_scene SCENE.json OUT_PREFIX\n");
    return 2;
  }
  char json[4096], vtu[4096];
  snprintf(json, sizeof json, "%s.json", argv[2]);
  snprintf(vtu, sizeof vtu, "%s.vtu", argv[2]);
  rn_context *ctx = NULL;
  rn_scene *scene = NULL;
  if (rn_context_create(&ctx) != RN_OK) return fail("context_create", NULL);
  int rc = 0;
  if (rn_scene_load(ctx, "no/such/scene.json", &scene) != RN_ERR_IO || scene ||
      !strstr(rn_context_last_error(ctx), "no/such/scene.json"))
    rc = fail("a missing file is RN_ERR_IO naming it", ctx);
  if (!rc && rn_scene_load(ctx, argv[1], &scene) != RN_OK)
    rc = fail("rn_scene_load", ctx);
  if (!rc) {
    rn_solve_options opt;
    rn_solve_report rep;
    rn_solve_options_default(&opt);
    rn_scene_apply_solver(scene, &opt);
    if (rn_solve(rn_scene_network(scene), &opt, &rep) != RN_OK || !rep.converged)
      rc = fail("rn_solve", ctx);
    else if (rn_scene_write_json(ctx, scene, &opt, &rep, json) != RN_OK)
      rc = fail("rn_scene_write_json", ctx);
    else if (rn_scene_write_vtu(ctx, scene, vtu) != RN_OK)
      rc = fail("rn_scene_write_vtu", ctx);
    else if (!file_has(json, "\"converged\": true") || !file_has(vtu, "<VTKFile"))
      rc = fail("the written files", ctx);
    else if (rn_scene_write_json(ctx, scene, &opt, NULL, json) != RN_ERR_ARG)
      rc = fail("a NULL report is RN_ERR_ARG", ctx);
    if (!rc)
      printf("consumer_scene: %s: %ld vertices, %d Newton iterations, energy %.10g\n",
             rn_scene_label(scene), rn_scene_num_vertices(scene), rep.iterations,
             rep.energy);
  }
  rn_scene_destroy(&scene);
  rn_context_destroy(&ctx);
  if (rc == 0) printf("consumer_scene: ok\n");
  return rc;
}
