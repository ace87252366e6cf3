/* lattice_scene.c - lattice -> JSON scene writer (lattice_scene.h). */
#include "generate/lattice_scene.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/atomic_file.h"
#include "generate/lattice_check.h"
#include "io/num_format.h"

typedef struct scene_out {
  FILE *f;
  const rn_lattice *lat;
  const rn_lattice_scene *opt;
  int *first, *inc; /* bars at each node: inc[first[n] .. first[n+1]) = 2 b + end */
} scene_out;

static void put_vec(FILE *f, const double *v) {
  fprintf(f, "[%.17g, %.17g, %.17g]", v[0], v[1], v[2]);
}

static void put_header(scene_out *o) {
  const rn_lattice_scene *opt = o->opt;
  FILE *f = o->f;
  fputs("{\n  \"description\": ", f);
  rn_put_json_string(f, opt->description ? opt->description : "rodnet lattice");
  if (opt->model) {
    fputs(",\n  \"model\": ", f);
    rn_put_json_string(f, opt->model);
  }
  fprintf(f, ",\n  \"materials\": {\"material\": {\"E\": %.17g, \"nu\": %.17g}},\n",
          opt->E, opt->nu);
  fputs("  \"sections\": {\"section\": ", f);
  if (opt->shape == RN_LSEC_CIRCLE)
    fprintf(f, "{\"shape\": \"circle\", \"radius\": %.17g}", opt->section[0]);
  else if (opt->shape == RN_LSEC_RECTANGLE)
    fprintf(f, "{\"shape\": \"rectangle\", \"width\": %.17g, \"height\": %.17g}",
            opt->section[0], opt->section[1]);
  else
    fprintf(f, "{\"shape\": \"ellipse\", \"a\": %.17g, \"b\": %.17g}", opt->section[0],
            opt->section[1]);
  fputs("},\n", f);
}

static void put_rods(scene_out *o) {
  FILE *f = o->f;
  int nb = rn_lattice_num_bars(o->lat);
  int planar = rn_lattice_kind_dimension(rn_lattice_get_kind(o->lat)) == 2;
  fputs("  \"rods\": [\n", f);
  for (int b = 0; b < nb; b++) {
    int n[2];
    double p[3], q[3];
    rn_lattice_bar(o->lat, b, n);
    rn_lattice_node(o->lat, n[0], p);
    rn_lattice_node(o->lat, n[1], q);
    fprintf(f,
            "    {\"name\": \"e%d\", \"material\": \"material\", \"section\": "
            "\"section\",\n     \"line\": {\"from\": ",
            b + 1);
    put_vec(f, p);
    fputs(", \"to\": ", f);
    put_vec(f, q);
    fprintf(f, ", \"vertices\": %d}%s}%s\n", o->opt->edges_per_rod + 1,
            planar ? ", \"d1\": [0, 0, 1]" : "", b + 1 < nb ? "," : "");
  }
  fputs("  ],\n", f);
}

/* Incident bar ends of every node (counting sort). */
static int build_incidence(scene_out *o) {
  int nn = rn_lattice_num_nodes(o->lat), nb = rn_lattice_num_bars(o->lat);
  o->first = calloc((size_t)nn + 1, sizeof *o->first);
  o->inc = malloc(2 * (size_t)(nb ? nb : 1) * sizeof *o->inc);
  if (!o->first || !o->inc) return 0;
  for (int n = 0; n < nn; n++)
    o->first[n + 1] = o->first[n] + rn_lattice_valence(o->lat, n);
  int *fill = malloc((size_t)(nn ? nn : 1) * sizeof *fill);
  if (!fill) return 0;
  memcpy(fill, o->first, (size_t)nn * sizeof *fill);
  for (int b = 0; b < nb; b++) {
    int e[2];
    rn_lattice_bar(o->lat, b, e);
    for (int k = 0; k < 2; k++) o->inc[fill[e[k]]++] = 2 * b + k;
  }
  free(fill);
  return 1;
}

static void put_joints(scene_out *o) {
  FILE *f = o->f;
  int nn = rn_lattice_num_nodes(o->lat);
  const char *model = o->opt->joint_model == RN_JOINT_RIGID ? "rigid" : "elastic";
  fputs("  \"joints\": [\n", f);
  for (int n = 0; n < nn; n++) {
    fprintf(f, "    {\"name\": \"v%d\", \"model\": \"%s\", \"ends\": [", n + 1, model);
    for (int k = o->first[n]; k < o->first[n + 1]; k++)
      fprintf(f, "%s{\"rod\": \"e%d\", \"end\": \"%s\"}", k > o->first[n] ? ", " : "",
              o->inc[k] / 2 + 1, o->inc[k] % 2 ? "end" : "start");
    fprintf(f, "]}%s\n", n + 1 < nn ? "," : "");
  }
  fputs("  ]", f);
}

/* The node of the minimum face along axis nearest the face's centroid. */
static int face_centre_node(const rn_lattice *lat, int axis) {
  int nn = rn_lattice_num_nodes(lat), count = 0, best = -1;
  double c[3] = {0, 0, 0}, x[3], dbest = INFINITY;
  for (int n = 0; n < nn; n++)
    if (rn_lattice_face(lat, n, axis) < 0) {
      rn_lattice_node(lat, n, x);
      for (int d = 0; d < 3; d++) c[d] += x[d];
      count++;
    }
  for (int d = 0; d < 3; d++) c[d] /= count;
  for (int n = 0; n < nn; n++)
    if (rn_lattice_face(lat, n, axis) < 0) {
      rn_lattice_node(lat, n, x);
      double dd = 0;
      for (int d = 0; d < 3; d++) dd += (x[d] - c[d]) * (x[d] - c[d]);
      if (dd < dbest) {
        dbest = dd;
        best = n;
      }
    }
  return best;
}

/* Separator before the next entry of a list. */
static void next_entry(FILE *f, int *count) {
  fputs(*count ? ",\n    " : "\n    ", f);
  (*count)++;
}

/* Distance of x from the point p (component `skip` ignored, -1: none) or,
 * when line is set, from the line through p and q. */
typedef struct node_metric {
  double p[3], q[3];
  int skip, line;
} node_metric;

static double node_distance(const node_metric *m, const double x[3]) {
  double a[3], b[3], s = 0;
  for (int d = 0; d < 3; d++) {
    a[d] = d == m->skip ? 0 : x[d] - m->p[d];
    b[d] = m->q[d] - m->p[d];
  }
  if (!m->line) return sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
  double c[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                 a[0] * b[1] - a[1] * b[0]};
  for (int d = 0; d < 3; d++) s += b[d] * b[d];
  return sqrt((c[0] * c[0] + c[1] * c[1] + c[2] * c[2]) / s);
}

/* The node farthest from m among the face nodes along axis (the first one on
 * ties), or among all nodes if every face node is at distance 0. */
static int farthest_node(const rn_lattice *lat, int axis, const node_metric *m) {
  int nn = rn_lattice_num_nodes(lat), best = -1;
  for (int all = 0; all < 2 && best < 0; all++) {
    double dbest = 0;
    for (int n = 0; n < nn; n++) {
      double x[3], dist;
      if (!all && !rn_lattice_face(lat, n, axis)) continue;
      rn_lattice_node(lat, n, x);
      dist = node_distance(m, x);
      if (dist > dbest) {
        dbest = dist;
        best = n;
      }
    }
  }
  return best;
}

/* Component pins (RN_FIX_* bits in mask[node]) beyond the faces' axis pins
 * that remove the remaining rigid motions (docs/lattices.md): the centre
 * joint A of the minimum face is held laterally; a 3D block gets one more
 * lateral pin at the node B farthest from the axis through A (rotation about
 * the axis); a planar lattice (z = 0) has z pinned at A, at the node farthest
 * from A and at the node farthest from the line through those two. */
/* The out-of-plane rigid motions of a planar lattice: z pinned at the centre
 * node A of the minimum face normal to axis, at the node farthest from A and
 * at the node farthest from the line through those two. */
static void planar_z_pins(const rn_lattice *lat, int axis, int *mask) {
  int a = face_centre_node(lat, axis);
  node_metric m = {{0, 0, 0}, {0, 0, 0}, axis, 0};
  rn_lattice_node(lat, a, m.p);
  mask[a] |= RN_FIX_Z;
  m.skip = -1;
  int n2 = farthest_node(lat, axis, &m);
  rn_lattice_node(lat, n2, m.q);
  m.line = 1;
  mask[n2] |= RN_FIX_Z;
  mask[farthest_node(lat, axis, &m)] |= RN_FIX_Z;
}

static void rigid_motion_pins(const rn_lattice *lat, int axis, int *mask) {
  int a = face_centre_node(lat, axis), b = (axis + 1) % 3, c = (axis + 2) % 3;
  node_metric m = {{0, 0, 0}, {0, 0, 0}, axis, 0};
  rn_lattice_node(lat, a, m.p);
  if (rn_lattice_kind_dimension(rn_lattice_get_kind(lat)) == 3) {
    mask[a] |= RN_FIX_X << b | RN_FIX_X << c;
    int n = farthest_node(lat, axis, &m);
    double x[3];
    rn_lattice_node(lat, n, x);
    mask[n] |= fabs(x[b] - m.p[b]) >= fabs(x[c] - m.p[c]) ? RN_FIX_X << c : RN_FIX_X << b;
    return;
  }
  mask[a] |= RN_FIX_X << (1 - axis);
  planar_z_pins(lat, axis, mask);
}

static void put_components(FILE *f, int mask) {
  int first = 1;
  fputs(", \"components\": [", f);
  for (int k = 0; k < 3; k++)
    if (mask & (1 << k)) {
      fprintf(f, "%s\"%c\"", first ? "" : ", ", "xyz"[k]);
      first = 0;
    }
  fputc(']', f);
}

/* The pins of the joints n with mask[n] (RN_FIX_* bits) as constraints. */
static void put_pins(FILE *f, int nn, const int *mask, int *count) {
  for (int n = 0; n < nn; n++)
    if (mask[n]) {
      next_entry(f, count);
      fprintf(f, "{\"type\": \"pin\", \"joint\": \"v%d\"", n + 1);
      if (mask[n] != RN_FIX_XYZ) put_components(f, mask[n]);
      fputc('}', f);
    }
}

/* stretch (uniaxial, frictionless grips) and grip (gripped faces). */
static rn_status put_stretch(scene_out *o, rn_context *ctx) {
  FILE *f = o->f;
  int axis = o->opt->load_axis, nn = rn_lattice_num_nodes(o->lat), count = 0;
  int grip = o->opt->load == RN_LLOAD_GRIP;
  double d[3] = {0, 0, 0};
  int *mask = calloc((size_t)nn, sizeof *mask);
  if (!mask) return rn_context_set_error(ctx, RN_ERR_ALLOC, "generate: out of memory");
  d[axis] = o->opt->load_value * rn_lattice_extent(o->lat, axis);
  for (int n = 0; n < nn; n++)
    if (rn_lattice_face(o->lat, n, axis)) mask[n] = grip ? RN_FIX_XYZ : RN_FIX_X << axis;
  if (!grip) rigid_motion_pins(o->lat, axis, mask);
  fputs(",\n  \"constraints\": [", f);
  put_pins(f, nn, mask, &count);
  for (int n = 0; n < nn; n++)
    if (rn_lattice_face(o->lat, n, axis) > 0) {
      next_entry(f, &count);
      fprintf(f, "{\"type\": \"displace\", \"joint\": \"v%d\", \"value\": ", n + 1);
      put_vec(f, d);
      if (!grip) put_components(f, RN_FIX_X << axis);
      fputc('}', f);
    }
  fputs("\n  ]", f);
  free(mask);
  return RN_OK;
}

/* Pins (mask) and displacements (d, 3 per node, components dmask) of the
 * biaxial and shear loads of a planar lattice. */
static void planar_load(const scene_out *o, int *mask, int *dmask, double *d) {
  const rn_lattice *lat = o->lat;
  int nn = rn_lattice_num_nodes(lat), shear = o->opt->load == RN_LLOAD_SHEAR;
  double ex = rn_lattice_extent(lat, 0), ey = rn_lattice_extent(lat, 1);
  for (int n = 0; n < nn; n++) {
    int fx = rn_lattice_face(lat, n, 0), fy = rn_lattice_face(lat, n, 1);
    if (shear) {
      if (!fy) continue;
      mask[n] |= RN_FIX_X | RN_FIX_Y;
      if (fy > 0) {
        dmask[n] = RN_FIX_X | RN_FIX_Y;
        d[3 * n] = o->opt->load_value * ey;
      }
      continue;
    }
    if (fx) mask[n] |= RN_FIX_X;
    if (fy) mask[n] |= RN_FIX_Y;
    if (fx > 0) {
      dmask[n] |= RN_FIX_X;
      d[3 * n] = o->opt->load_value * ex;
    }
    if (fy > 0) {
      dmask[n] |= RN_FIX_Y;
      d[3 * n + 1] = o->opt->load_value2 * ey;
    }
  }
  planar_z_pins(lat, 0, mask);
}

/* biaxial and shear (planar lattices). */
static rn_status put_planar_load(scene_out *o, rn_context *ctx) {
  FILE *f = o->f;
  int nn = rn_lattice_num_nodes(o->lat), count = 0;
  int *mask = calloc((size_t)nn, sizeof *mask),
      *dmask = calloc((size_t)nn, sizeof *dmask);
  double *d = calloc(3 * (size_t)nn, sizeof *d);
  if (!mask || !dmask || !d) {
    free(mask);
    free(dmask);
    free(d);
    return rn_context_set_error(ctx, RN_ERR_ALLOC, "generate: out of memory");
  }
  planar_load(o, mask, dmask, d);
  fputs(",\n  \"constraints\": [", f);
  put_pins(f, nn, mask, &count);
  for (int n = 0; n < nn; n++)
    if (dmask[n]) {
      next_entry(f, &count);
      fprintf(f, "{\"type\": \"displace\", \"joint\": \"v%d\", \"value\": ", n + 1);
      put_vec(f, d + 3 * n);
      put_components(f, dmask[n]);
      fputc('}', f);
    }
  fputs("\n  ]", f);
  free(mask);
  free(dmask);
  free(d);
  return RN_OK;
}

static void put_pull(scene_out *o) {
  FILE *f = o->f;
  int axis = o->opt->load_axis, nn = rn_lattice_num_nodes(o->lat), count = 0;
  int nmin = 0, nmax = 0, fixed = face_centre_node(o->lat, axis);
  for (int n = 0; n < nn; n++) {
    nmin += rn_lattice_face(o->lat, n, axis) < 0;
    nmax += rn_lattice_face(o->lat, n, axis) > 0;
  }
  fprintf(f, ",\n  \"constraints\": [{\"type\": \"clamp\", \"joint\": \"v%d\"}],\n",
          fixed + 1);
  fputs("  \"loads\": [", f);
  for (int n = 0; n < nn; n++) {
    int face = rn_lattice_face(o->lat, n, axis);
    if (!face || n == fixed) continue;
    double F[3] = {0, 0, 0};
    F[axis] = face > 0 ? o->opt->load_value / nmax : -o->opt->load_value / nmin;
    next_entry(f, &count);
    fprintf(f, "{\"type\": \"force\", \"joint\": \"v%d\", \"value\": ", n + 1);
    put_vec(f, F);
    fputc('}', f);
  }
  fputs("\n  ]", f);
}

static rn_status write_scene(FILE *f, void *user, rn_context *ctx) {
  scene_out *o = user;
  o->f = f;
  if (!build_incidence(o))
    return rn_context_set_error(ctx, RN_ERR_ALLOC, "generate: out of memory");
  put_header(o);
  put_rods(o);
  put_joints(o);
  rn_status st = RN_OK;
  if (o->opt->load == RN_LLOAD_STRETCH || o->opt->load == RN_LLOAD_GRIP)
    st = put_stretch(o, ctx);
  if (o->opt->load == RN_LLOAD_PULL) put_pull(o);
  if (o->opt->load == RN_LLOAD_BIAXIAL || o->opt->load == RN_LLOAD_SHEAR)
    st = put_planar_load(o, ctx);
  fputs("\n}\n", f);
  return st;
}

rn_status rn_lattice_write_scene(rn_context *ctx, const char *path, const rn_lattice *lat,
                                 const rn_lattice_scene *opt) {
  if (!lat || !opt || opt->edges_per_rod < 1)
    return rn_context_set_error(ctx, RN_ERR_ARG, "generate: bad arguments");
  int planar_load = opt->load == RN_LLOAD_BIAXIAL || opt->load == RN_LLOAD_SHEAR;
  if (planar_load && rn_lattice_kind_dimension(rn_lattice_get_kind(lat)) != 2)
    return rn_context_set_error(ctx, RN_ERR_ARG,
                                "generate: biaxial and shear loads of a finite lattice "
                                "need a planar lattice (or --periodic)");
  if (opt->load != RN_LLOAD_NONE && !planar_load &&
      (opt->load_axis < 0 || opt->load_axis > 2 ||
       !(rn_lattice_extent(lat, opt->load_axis) > 0)))
    return rn_context_set_error(
        ctx, RN_ERR_ARG,
        "generate: the %s lattice is flat along %c: it cannot "
        "be loaded along that axis",
        rn_lattice_kind_name(rn_lattice_get_kind(lat)),
        "xyz"[opt->load_axis < 0 || opt->load_axis > 2 ? 0 : opt->load_axis]);
  /* a scene with "nan" or "inf" is not JSON (issue 22): refuse it */
  rn_num_check chk = {0, 0.0, ""};
  rn_lattice_scene_finite(opt, &chk);
  for (int k = 0; k < 3; k++) {
    const double ext = rn_lattice_extent(lat, k);
    rn_num_checked(&chk, "the lattice's extent (joint positions)", ext);
    rn_num_checked(&chk, "the load (value times extent)", opt->load_value * ext);
    rn_num_checked(&chk, "the load (value times extent)", opt->load_value2 * ext);
  }
  if (chk.bad) {
    char msg[512];
    return rn_context_set_error(ctx, RN_ERR_NOT_FINITE, "generate: %s",
                                rn_num_check_message(&chk, path, msg, sizeof msg));
  }
  scene_out o = {NULL, lat, opt, NULL, NULL};
  rn_status st = rn_file_write_atomic(ctx, path, write_scene, &o);
  free(o.first);
  free(o.inc);
  return st;
}
