/* problems_generate_test.c - lattice scenes (problems/generate/lattice.h,
 * lattice_scene.h): for a small instance of every lattice the node and bar
 * counts, the valence histogram and the bar length follow the closed forms
 * of docs/lattices.md, and the written scene, read back by the scene reader,
 * has those rods and joints, the DOF count they imply, and the prescribed
 * motions and forces of the loading options.
 * argv[1]: a scratch folder for the scene files. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "generate/lattice.h"
#include "generate/lattice_check.h"
#include "generate/lattice_scene.h"
#include "generate/periodic_cell.h"
#include "scene/scene.h"
#include "testutil.h"

static const char *scratch;
static const double a = 2.0; /* lattice period */

typedef struct lattice_case {
  rn_lattice_kind kind;
  int cells[3];
  int nodes, bars;
  int hist[13]; /* number of nodes of valence 0 .. 12 */
  double bar;   /* bar length / period */
} lattice_case;

/* Closed forms (docs/lattices.md) for the instances below. */
static void expected(lattice_case *c) {
  int nx = c->cells[0], ny = c->cells[1], nz = c->cells[2];
  memset(c->hist, 0, sizeof c->hist);
  switch (c->kind) {
  case RN_LATTICE_SQUARE: /* nx x ny squares */
    c->nodes = (nx + 1) * (ny + 1);
    c->bars = nx * (ny + 1) + ny * (nx + 1);
    c->hist[2] = 4;
    c->hist[3] = 2 * (nx - 1) + 2 * (ny - 1);
    c->hist[4] = (nx - 1) * (ny - 1);
    c->bar = 1;
    break;
  case RN_LATTICE_TRIANGULAR: /* ny + 1 rows of nx + 1 nodes */
    c->nodes = (nx + 1) * (ny + 1);
    c->bars = nx * (ny + 1) + ny * (2 * nx + 1);
    c->hist[6] = (nx - 1) * (ny - 1);
    c->bar = 1;
    break;
  case RN_LATTICE_HONEYCOMB: /* ny rows of nx hexagons; Euler: E = V + F - 1 */
    c->nodes = 2 * (2 * nx + 1) + (ny - 1) * (2 * nx + 2);
    c->bars = c->nodes + nx * ny - 1;
    c->hist[2] = 3 * c->nodes - 2 * c->bars; /* valences are 2 and 3 */
    c->hist[3] = c->nodes - c->hist[2];
    c->bar = 1 / sqrt(3.0);
    break;
  case RN_LATTICE_KAGOME: /* hexagons sharing corners, each edge in one */
    c->bars = 6 * nx * ny;
    c->hist[4] = ny * (nx - 1) + (ny - 1) * (2 * nx - 1); /* shared corners */
    c->nodes = 6 * nx * ny - c->hist[4];
    c->hist[2] = c->nodes - c->hist[4];
    c->bar = 0.5;
    break;
  case RN_LATTICE_CUBIC:
    c->nodes = (nx + 1) * (ny + 1) * (nz + 1);
    c->bars =
        nx * (ny + 1) * (nz + 1) + ny * (nx + 1) * (nz + 1) + nz * (nx + 1) * (ny + 1);
    c->hist[3] = 8;
    c->hist[6] = (nx - 1) * (ny - 1) * (nz - 1);
    c->bar = 1;
    break;
  case RN_LATTICE_BCC: /* corners + centres, centre-corner struts */
    c->nodes = (nx + 1) * (ny + 1) * (nz + 1) + nx * ny * nz;
    c->bars = 8 * nx * ny * nz;
    c->hist[1] = 8;
    c->hist[8] = nx * ny * nz + (nx - 1) * (ny - 1) * (nz - 1);
    c->bar = sqrt(3.0) / 2;
    break;
  default: { /* octet: corners + face centres (FCC), nearest neighbours */
    int faces = (nx + 1) * ny * nz + nx * (ny + 1) * nz + nx * ny * (nz + 1);
    c->nodes = (nx + 1) * (ny + 1) * (nz + 1) + faces;
    c->bars = 4 * faces + 12 * nx * ny * nz;
    c->hist[3] = 8;
    c->hist[12] = (nx - 1) * (ny - 1) * (nz - 1) + (nx - 1) * ny * nz +
                  nx * (ny - 1) * nz + nx * ny * (nz - 1);
    c->bar = 1 / sqrt(2.0);
    break;
  }
  }
}

/* Histogram entries the closed forms give (others are not asserted, but the
 * histogram must sum to the node count and the valences to twice the bars). */
static int hist_known(const lattice_case *c, int v) { return c->hist[v] != 0 || v == 0; }

static void check_lattice(rn_context *ctx, const lattice_case *c) {
  rn_lattice *lat = NULL;
  CHECK_STATUS(rn_lattice_build(ctx, c->kind, c->cells, a, &lat), RN_OK);
  if (!lat) return;
  const char *name = rn_lattice_kind_name(c->kind);
  int nn = rn_lattice_num_nodes(lat), nb = rn_lattice_num_bars(lat), hist[64] = {0};
  int sum = 0;
  for (int n = 0; n < nn; n++) {
    int v = rn_lattice_valence(lat, n);
    hist[v < 63 ? v : 63]++;
    sum += v;
  }
  int ok = nn == c->nodes && nb == c->bars && sum == 2 * nb;
  for (int v = 0; v <= 12; v++) ok &= !hist_known(c, v) || hist[v] == c->hist[v];
  CHECK(ok);
  if (!ok)
    fprintf(stderr, "%s: %d nodes (want %d), %d bars (want %d)\n", name, nn, c->nodes, nb,
            c->bars);
  double worst = 0;
  for (int b = 0; b < nb; b++) {
    int e[2];
    double p[3], q[3];
    rn_lattice_bar(lat, b, e);
    rn_lattice_node(lat, e[0], p);
    rn_lattice_node(lat, e[1], q);
    double l = sqrt((q[0] - p[0]) * (q[0] - p[0]) + (q[1] - p[1]) * (q[1] - p[1]) +
                    (q[2] - p[2]) * (q[2] - p[2]));
    worst = fmax(worst, fabs(l / (c->bar * a) - 1));
  }
  CHECK(worst < 1e-14);
  rn_lattice_destroy(&lat);
  CHECK(lat == NULL);
}

static rn_scene *write_and_load(rn_context *ctx, rn_lattice_kind kind, const int *cells,
                                const rn_lattice_scene *opt, const char *file) {
  char path[1024];
  snprintf(path, sizeof path, "%s/%s", scratch, file);
  rn_lattice *lat = NULL;
  rn_scene *s = NULL;
  CHECK_STATUS(rn_lattice_build(ctx, kind, cells, a, &lat), RN_OK);
  CHECK_STATUS(rn_lattice_write_scene(ctx, path, lat, opt), RN_OK);
  CHECK_STATUS(rn_scene_load(ctx, path, &s), RN_OK);
  if (!s) fprintf(stderr, "%s: %s\n", file, rn_context_last_error(ctx));
  rn_lattice_destroy(&lat);
  return s;
}

static rn_lattice_scene default_options(void) {
  rn_lattice_scene o;
  memset(&o, 0, sizeof o);
  o.edges_per_rod = 3;
  o.joint_model = RN_JOINT_RIGID;
  o.E = 10;
  o.nu = 0.25;
  o.shape = RN_LSEC_CIRCLE;
  o.section[0] = 0.05;
  return o;
}

/* The scene read back: one rod per bar with edges_per_rod edges, one rigid
 * joint per node with the bar count as valence, and the DOFs that implies. */
static void check_scene(rn_context *ctx, const lattice_case *c) {
  rn_lattice_scene opt = default_options();
  char file[64];
  snprintf(file, sizeof file, "%s.json", rn_lattice_kind_name(c->kind));
  rn_scene *s = write_and_load(ctx, c->kind, c->cells, &opt, file);
  if (!s) return;
  rn_network *net = rn_scene_network(s);
  int nr = rn_network_num_rods(net), nj = rn_network_num_joints(net), hist[64] = {0};
  CHECK(nr == c->bars && nj == c->nodes);
  for (int j = 0; j < nj; j++) {
    int v = rn_network_joint_valence(net, j);
    hist[v >= 0 && v < 63 ? v : 63]++;
    CHECK(rn_network_joint_model(net, j) == RN_JOINT_RIGID);
  }
  for (int v = 1; v <= 12; v++) CHECK(!hist_known(c, v) || hist[v] == c->hist[v]);
  int nv_ok = 1;
  for (int r = 0; r < nr; r++) nv_ok &= rn_network_rod_num_vertices(net, r) == 4;
  CHECK(nv_ok);
  /* per rod: 2 interior vertices and 3 angles; per rigid joint 6 */
  CHECK(rn_network_num_dofs(net) == (size_t)(9 * nr + 6 * nj));
  rn_scene_destroy(&s);
}

/* Joint positions along axis: count of joints at the min / max and extent. */
static void faces(rn_scene *s, int axis, int *nmin, int *nmax, double *lo, double *hi) {
  rn_network *net = rn_scene_network(s);
  int nj = rn_network_num_joints(net);
  *lo = INFINITY;
  *hi = -INFINITY;
  *nmin = *nmax = 0;
  for (int j = 0; j < nj; j++) {
    double x[3];
    rn_scene_joint_initial_position(s, j, x);
    *lo = fmin(*lo, x[axis]);
    *hi = fmax(*hi, x[axis]);
  }
  for (int j = 0; j < nj; j++) {
    double x[3];
    rn_scene_joint_initial_position(s, j, x);
    *nmin += x[axis] == *lo;
    *nmax += x[axis] == *hi;
  }
}

/* stretch-x and grip-x on a 3 x 3 honeycomb (elastic joints): the joints of
 * both x faces are pinned (grip: fully; stretch: along x only, plus 4
 * component pins for the rigid motions: y of the min face's centre joint and
 * z of three joints), those of the max face moved by strain * extent along x. */
static void check_stretch(rn_context *ctx) {
  for (int grip = 0; grip < 2; grip++) {
    rn_lattice_scene opt = default_options();
    opt.joint_model = RN_JOINT_ELASTIC;
    opt.load = grip ? RN_LLOAD_GRIP : RN_LLOAD_STRETCH;
    opt.load_axis = 0;
    opt.load_value = 0.01;
    int cells[3] = {3, 3, 1}, nmin, nmax;
    rn_scene *s = write_and_load(ctx, RN_LATTICE_HONEYCOMB, cells, &opt,
                                 grip ? "grip.json" : "stretch.json");
    if (!s) continue;
    rn_network *net = rn_scene_network(s);
    double lo, hi;
    faces(s, 0, &nmin, &nmax, &lo, &hi);
    CHECK(nmin == 4 && nmax == 2); /* rows 0, 2 on the left; row 1 on the right */
    CHECK_NEAR(hi - lo, 3.5 * a, 1e-14);
    int nr = rn_network_num_rods(net), nj = rn_network_num_joints(net);
    size_t fixed_dofs = grip ? 3 * (size_t)(nmin + nmax) : (size_t)(nmin + nmax) + 4;
    CHECK(rn_network_num_dofs(net) == (size_t)(9 * nr + 3 * nj) - fixed_dofs);
    int moved = 0, fixed = 0;
    for (int j = 0; j < nj; j++) {
      double x[3], x0[3];
      CHECK_STATUS(rn_network_joint_position(net, j, x), RN_OK);
      rn_scene_joint_initial_position(s, j, x0);
      if (x0[0] == hi)
        moved += fabs(x[0] - x0[0] - 0.01 * (hi - lo)) < 1e-15 && x[1] == x0[1];
      else
        fixed += x[0] == x0[0] && x[1] == x0[1] && x[2] == x0[2];
    }
    CHECK(moved == nmax && fixed == nj - nmax);
    rn_scene_destroy(&s);
  }
}

/* compress-z (stretch with a negative value) and pull-z on a 2 x 2 x 2 cubic
 * block: the prescribed motion, and for pull one clamped joint and forces F and
 * -F on the two faces (load energy 0 at rest: measured from the initial state). */
static void check_3d_loads(rn_context *ctx) {
  int cells[3] = {2, 2, 2}, nmin, nmax;
  double lo, hi;
  rn_lattice_scene opt = default_options();
  opt.load = RN_LLOAD_STRETCH;
  opt.load_axis = 2;
  opt.load_value = -0.02;
  rn_scene *s = write_and_load(ctx, RN_LATTICE_CUBIC, cells, &opt, "compress.json");
  if (s) {
    rn_network *net = rn_scene_network(s);
    faces(s, 2, &nmin, &nmax, &lo, &hi);
    CHECK(nmin == 9 && nmax == 9);
    int nr = rn_network_num_rods(net), nj = rn_network_num_joints(net);
    /* z of the 18 face joints; x, y of the min face's centre joint; one
     * lateral component of the joint farthest from the z axis through it */
    CHECK(rn_network_num_dofs(net) == (size_t)(9 * nr + 6 * nj - 18 - 3));
    double x[3];
    CHECK_STATUS(rn_network_joint_position(net, nj - 1, x), RN_OK); /* a top corner */
    CHECK_NEAR(x[2], hi - 0.02 * (hi - lo), 1e-15);
    rn_scene_destroy(&s);
  }
  opt.load = RN_LLOAD_PULL;
  opt.load_value = 1.5;
  s = write_and_load(ctx, RN_LATTICE_CUBIC, cells, &opt, "pull.json");
  if (s) {
    rn_network *net = rn_scene_network(s);
    int nr = rn_network_num_rods(net), nj = rn_network_num_joints(net);
    CHECK(rn_network_num_dofs(net) == (size_t)(9 * nr + 6 * nj - 6));
    size_t n = rn_network_num_dofs(net);
    double *x = malloc(n * sizeof *x), E[RN_TERM_COUNT];
    CHECK_STATUS(rn_network_get_dofs(net, x), RN_OK);
    CHECK_STATUS(rn_network_energy_terms(net, x, E), RN_OK);
    /* the load potential is measured from the initial state: 0 at rest */
    CHECK(E[RN_TERM_LOAD] == 0.0);
    CHECK_NEAR(E[RN_TERM_STRETCH] + E[RN_TERM_BEND] + E[RN_TERM_TWIST], 0, 1e-30);
    /* no elastic force at rest: the reduced gradient is minus the loads on free
     * DOFs, 1.5 along z spread over the nmax joints of the max face and -1.5 over
     * the nmin joints of the min face, less the share of its clamped joint */
    double *g = malloc(n * sizeof *g), gsum = 0.0, gabs = 0.0;
    const double clamped_share = 1.5 / nmin;
    CHECK_STATUS(rn_network_gradient(net, x, NULL, g), RN_OK);
    for (size_t i = 0; i < n; i++) {
      gsum += g[i];
      gabs += fabs(g[i]);
    }
    CHECK_NEAR(gabs, 2 * 1.5 - clamped_share, 1e-12);
    CHECK_NEAR(gsum, -clamped_share, 1e-12);
    free(g);
    free(x);
    rn_scene_destroy(&s);
  }
}

static void check_errors(rn_context *ctx) {
  rn_lattice *lat = NULL;
  int bad[3] = {0, 2, 2}, ok[3] = {2, 2, 2}, flat[3] = {2, 2, 0};
  int huge[3] = {100000, 100000, 1};
  CHECK_STATUS(rn_lattice_build(ctx, RN_LATTICE_SQUARE, bad, a, &lat), RN_ERR_ARG);
  CHECK(strstr(rn_context_last_error(ctx), "cell count 0 outside") != NULL);
  CHECK_STATUS(rn_lattice_build(ctx, RN_LATTICE_SQUARE, ok, -1, &lat), RN_ERR_ARG);
  CHECK_STATUS(rn_lattice_build(ctx, RN_LATTICE_OCTET, flat, a, &lat), RN_ERR_ARG);
  CHECK_STATUS(rn_lattice_build(ctx, RN_LATTICE_SQUARE, huge, a, &lat), RN_ERR_RANGE);
  CHECK(strstr(rn_context_last_error(ctx), "too many") != NULL);
  CHECK(lat == NULL);
  CHECK_STATUS(rn_lattice_build(ctx, RN_LATTICE_KAGOME, ok, a, &lat), RN_OK);
  rn_lattice_scene opt = default_options();
  opt.load = RN_LLOAD_STRETCH;
  opt.load_axis = 2;
  opt.load_value = 0.1;
  char path[1024];
  snprintf(path, sizeof path, "%s/flat.json", scratch);
  remove(path);
  CHECK_STATUS(rn_lattice_write_scene(ctx, path, lat, &opt), RN_ERR_ARG);
  CHECK(strstr(rn_context_last_error(ctx), "flat along z") != NULL);
  FILE *f = fopen(path, "rb");
  CHECK(f == NULL); /* nothing written */
  if (f) fclose(f);
  rn_lattice_destroy(&lat);
  rn_lattice_kind k;
  CHECK(rn_lattice_kind_from_name("octet", &k) == 0 && k == RN_LATTICE_OCTET);
  CHECK(rn_lattice_kind_from_name("hexagonal", &k) != 0);
}

/* Issue 22 item 4: writing a periodic supercell lists each joint's rod ends
 * from an index of the bar ends (4 visits per bar), not by a scan of every bar
 * for every joint (4 nodes x bars visits: 100^2 honeycomb cells took 5.5 s,
 * 400^2 more than 9 minutes).  The count of visited ends is linear. */
static void check_pcell_write_linear(rn_context *ctx) {
  long per_bar[2] = {0, 0};
  for (int k = 0; k < 2; k++) {
    int cells[3] = {10 << k, 10 << k, 1};
    rn_pcell c;
    CHECK_STATUS(rn_pcell_from_lattice(ctx, RN_LATTICE_HONEYCOMB, cells, 1.0, &c), RN_OK);
    CHECK(c.nbars == 3 * cells[0] * cells[1] && c.nnodes == 2 * cells[0] * cells[1]);
    long work = 0;
    c.work = &work;
    rn_lattice_scene opt = default_options();
    char path[1024];
    snprintf(path, sizeof path, "%s/pcell_linear_%d.json", scratch, k);
    CHECK_STATUS(rn_pcell_write_scene(ctx, path, &c, &opt, NULL), RN_OK);
    CHECK(work == 4L * c.nbars); /* two passes over each joint's own ends */
    per_bar[k] = work / c.nbars;
    rn_pcell_free(&c);
  }
  CHECK(per_bar[0] == per_bar[1]);
}

/* Issue 22 item 1: the bounds of lattice_check.h on cells with closed forms
 * (docs/lattices.md, "Admissible sections"), square struts t x t (half width
 * r = t/2), density L t / V.  Square cell a x a: density 2t/a, joints of 90
 * degrees, zones r cot 45 = r, joint factor a/t.  Honeycomb (bars a/sqrt3,
 * 120 degrees): density 2t/a, zones r cot 60 = r/sqrt3, joint factor a/t.
 * Re-entrant (60 degrees at every joint, inclined bars l = a/sqrt3): zones
 * r cot 30 = r sqrt3, joint factor l / (sqrt3 t) on an inclined bar. */
static void check_strut_bounds(rn_context *ctx) {
  const double t = 0.1;
  for (int kind = 0; kind < 3; kind++) {
    int cells[3] = {2, 2, 1};
    rn_pcell c;
    if (kind == 2)
      CHECK_STATUS(rn_pcell_reentrant(ctx, cells, a, &c), RN_OK);
    else
      CHECK_STATUS(rn_pcell_from_lattice(ctx,
                                         kind ? RN_LATTICE_HONEYCOMB : RN_LATTICE_SQUARE,
                                         cells, a, &c),
                   RN_OK);
    int *uv = malloc(2 * (size_t)c.nbars * sizeof *uv);
    double *d = malloc(3 * (size_t)c.nbars * sizeof *d), L, V;
    for (int e = 0; e < c.nbars; e++) {
      const int *o = c.bar + 5 * e;
      uv[2 * e] = o[0];
      uv[2 * e + 1] = o[1];
      for (int k = 0; k < 3; k++) {
        d[3 * e + k] = c.xyz[3 * o[1] + k] - c.xyz[3 * o[0] + k];
        for (int m = 0; m < 2; m++) d[3 * e + k] += o[2 + m] * c.vec[3 * m + k];
      }
    }
    rn_pcell_measures(&c, &L, &V);
    rn_lattice_scene sec = default_options();
    sec.shape = RN_LSEC_RECTANGLE;
    sec.section[0] = sec.section[1] = t;
    rn_strut_bounds b;
    CHECK(rn_strut_bounds_compute(2, c.nnodes, c.nbars, uv, d, NULL, &sec, V, &b) == 0);
    const double l = a / sqrt(3.0);
    const double joint = kind == 0 ? a / t : kind == 1 ? a / t : l / (sqrt(3.0) * t);
    CHECK_NEAR(b.density, L * t / V, 1e-12);
    CHECK_NEAR(b.density, kind < 2 ? 2 * t / a : b.density, 1e-12);
    CHECK_NEAR(b.joint_factor, joint, 1e-9 * joint);
    CHECK_NEAR(b.factor, fmin(joint, 1.0 / b.density), 1e-9 * joint);
    CHECK(b.coincident_node < 0 && b.zero_bar < 0);
    free(uv);
    free(d);
    rn_pcell_free(&c);
  }
}

int main(int argc, char **argv) {
  if (argc < 2) {
    fprintf(stderr, "usage: problems_generate_test SCRATCH_DIR\n");
    return 2;
  }
  scratch = argv[1];
  rn_context *ctx = NULL;
  CHECK_STATUS(rn_context_create(&ctx), RN_OK);
  lattice_case cases[] = {
      {RN_LATTICE_SQUARE, {3, 2, 1}, 0, 0, {0}, 0},
      {RN_LATTICE_TRIANGULAR, {3, 3, 1}, 0, 0, {0}, 0},
      {RN_LATTICE_HONEYCOMB, {3, 3, 1}, 0, 0, {0}, 0},
      {RN_LATTICE_HONEYCOMB, {4, 1, 1}, 0, 0, {0}, 0},
      {RN_LATTICE_KAGOME, {3, 3, 1}, 0, 0, {0}, 0},
      {RN_LATTICE_CUBIC, {2, 2, 2}, 0, 0, {0}, 0},
      {RN_LATTICE_CUBIC, {3, 1, 2}, 0, 0, {0}, 0},
      {RN_LATTICE_BCC, {2, 2, 2}, 0, 0, {0}, 0},
      {RN_LATTICE_OCTET, {1, 1, 1}, 0, 0, {0}, 0},
      {RN_LATTICE_OCTET, {2, 2, 2}, 0, 0, {0}, 0},
  };
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
    expected(&cases[i]);
    check_lattice(ctx, &cases[i]);
    check_scene(ctx, &cases[i]);
  }
  check_stretch(ctx);
  check_3d_loads(ctx);
  check_errors(ctx);
  check_pcell_write_linear(ctx); /* issue 22 item 4 */
  check_strut_bounds(ctx);       /* issue 22 item 1 */
  rn_context_destroy(&ctx);
  return rn_test_finish("problems_generate");
}
