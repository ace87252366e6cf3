/* scene_supercell.c - the supercell of a periodic cell scene as a study past its
 * first instability needs it (rn_scene_load_supercell, rn_scene_supercell_copies;
 * rodnet_scene.h; docs/homogenization.md, "Post-buckling"): the cell's file with
 * "periodic": {"repeat"} set, its strain and stress control dropped, and for an
 * in-plane study of a 2D cell the out-of-plane pins. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cjson/cJSON.h>

#include "io/text_file.h"
#include "rodnet_scene.h"

/* One constraint object {"type": type, key: name} appended to cons, with
 * "components": ["z"] if z; NULL out of memory. */
static cJSON *add_constraint(cJSON *cons, const char *type, const char *key,
                             const char *name, int z) {
  cJSON *c = cJSON_CreateObject();
  if (!c) return NULL;
  cJSON_AddItemToArray(cons, c);
  if (!cJSON_AddStringToObject(c, "type", type) || !cJSON_AddStringToObject(c, key, name))
    return NULL;
  if (z) {
    const char *comp[] = {"z"};
    cJSON *a = cJSON_CreateStringArray(comp, 1);
    if (!a || !cJSON_AddItemToObject(c, "components", a)) return NULL;
  }
  return c;
}

/* Out-of-plane pins for an in-plane study of a 2D supercell: z of every joint
 * and interior rod vertex, every material angle, the first joint fully (the
 * anchor the periodic cell would otherwise add).  0, or -1 out of memory. */
static int add_pins(cJSON *root, const rn_network *net) {
  cJSON *cons = cJSON_GetObjectItemCaseSensitive(root, "constraints");
  if (!cons && !(cons = cJSON_AddArrayToObject(root, "constraints"))) return -1;
  for (int j = 0; j < rn_network_num_joints(net); ++j)
    if (!add_constraint(cons, "pin", "joint", rn_network_joint_name(net, j), j > 0))
      return -1;
  for (int r = 0; r < rn_network_num_rods(net); ++r) {
    int nv = rn_network_rod_num_vertices(net, r);
    const char *name = rn_network_rod_name(net, r);
    for (int v = 1; v + 1 < nv; ++v) {
      cJSON *c = add_constraint(cons, "pin", "rod", name, 1);
      if (!c || !cJSON_AddNumberToObject(c, "vertex", v)) return -1;
    }
    for (int e = 0; e + 1 < nv; ++e) {
      cJSON *c = add_constraint(cons, "fix_theta", "rod", name, 0);
      if (!c || !cJSON_AddNumberToObject(c, "edge", e)) return -1;
    }
  }
  return 0;
}

rn_status rn_scene_load_supercell(rn_context *ctx, const char *path, int dim,
                                  const int rep[3], int pin_out_of_plane,
                                  rn_scene **out) {
  char *text = NULL, *json = NULL;
  size_t len = 0;
  rn_status st;
  cJSON *root = NULL;
  rn_scene *sc = NULL;
  if (!out) return rn_context_set_error(ctx, RN_ERR_ARG, "no output scene");
  *out = NULL;
  if (!path || !rep || (dim != 2 && dim != 3))
    return rn_context_set_error(ctx, RN_ERR_ARG, "a supercell needs a file and %s",
                                rep ? "a dimension 2 or 3" : "its copies per direction");
  for (int d = 0; d < dim; ++d)
    if (rep[d] < 1 || rep[d] > 1000)
      return rn_context_set_error(ctx, RN_ERR_ARG,
                                  "%s: %d copies in direction %d (1 to 1000)", path,
                                  rep[d], d + 1);
  if (pin_out_of_plane && dim != 2)
    return rn_context_set_error(ctx, RN_ERR_ARG,
                                "%s: out-of-plane pins are for a 2D cell", path);
  if ((st = rn_text_file_read(ctx, path, 1 << 28, &text, &len))) return st;
  if (!(root = cJSON_Parse(text))) { /* the reader's message: file, line, reason */
    st = rn_scene_parse(ctx, path, text, len, &sc);
    if (!st) st = rn_context_set_error(ctx, RN_ERR_PARSE, "%s: not valid JSON", path);
    goto done;
  }
  cJSON *per = cJSON_GetObjectItemCaseSensitive(root, "periodic");
  if (!cJSON_IsObject(per) || cJSON_GetObjectItemCaseSensitive(per, "repeat")) {
    st = rn_context_set_error(ctx, RN_ERR_ARG,
                              "%s: a supercell needs a periodic scene without \"repeat\"",
                              path);
    goto done;
  }
  cJSON_DeleteItemFromObjectCaseSensitive(per, "stress");
  cJSON_DeleteItemFromObjectCaseSensitive(per, "strain");
  cJSON *r = cJSON_CreateIntArray(rep, dim);
  if (!r || !cJSON_AddItemToObject(per, "repeat", r)) goto fail_alloc;
  if (!(json = cJSON_PrintUnformatted(root))) goto fail_alloc;
  if ((st = rn_scene_parse(ctx, path, json, strlen(json), &sc))) goto done;
  if (pin_out_of_plane) {
    if (add_pins(root, rn_scene_network(sc))) goto fail_alloc;
    rn_scene_destroy(&sc);
    free(json);
    if (!(json = cJSON_PrintUnformatted(root))) goto fail_alloc;
    if ((st = rn_scene_parse(ctx, path, json, strlen(json), &sc))) goto done;
  }
  *out = sc;
  sc = NULL;
  goto done;
fail_alloc:
  st = rn_context_set_error(ctx, RN_ERR_ALLOC, "out of memory");
done:
  rn_scene_destroy(&sc);
  free(json);
  free(text);
  cJSON_Delete(root);
  return st;
}

rn_status rn_scene_supercell_copies(const rn_scene *s, int *rod_base, int *rod_cell) {
  const rn_network *net = s ? rn_scene_network(s) : NULL;
  if (!net || !rod_base || !rod_cell) return RN_ERR_ARG;
  int nrod = rn_network_num_rods(net);
  for (int r = 0; r < nrod; ++r) {
    const char *name = rn_network_rod_name(net, r), *at = strchr(name, '@');
    int *c = rod_cell + 3 * r;
    c[0] = c[1] = c[2] = 0;
    rod_base[r] = at ? -1 : r;
    if (!at || sscanf(at + 1, "%d,%d,%d", &c[0], &c[1], &c[2]) < 2) continue;
    size_t len = (size_t)(at - name);
    for (int r0 = 0; r0 < nrod; ++r0) {
      const char *n0 = rn_network_rod_name(net, r0);
      if (strlen(n0) == len && strncmp(n0, name, len) == 0) {
        rod_base[r] = r0;
        break;
      }
    }
  }
  return RN_OK;
}
