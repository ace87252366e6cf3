/* val_lattice_stretch.c - `rodnet generate` lattices under uniaxial stretch
 * with frictionless grips (--load stretch-x: face joints pinned along x only,
 * plus the component pins that remove the rigid motions) against grips
 * (--load grip-x: face joints pinned in x, y, z), solved through the scene
 * reader (lattice -> JSON scene -> rn_scene_load -> rn_solve):
 *  (1) square grid: the bars along x carry the strain, nothing bends and the
 *      lattice does not contract laterally (Poisson ratio 0), so
 *      E* = E A / a per unit width exactly, under both loads;
 *  (2) regular honeycomb: bending-dominated, it contracts laterally with an
 *      effective Poisson ratio near 1.  Gibson & Ashby's bending limit is
 *      nu = 1; axial stretching of the bars lowers it to
 *      nu_inf = (1 - d) / (1 + 3 d), d = K_bend / K_stretch = 12 I / (A l^2)
 *      (Masters & Evans 1996), for the infinite lattice.  Asserted: nu > 0
 *      (the sign: contraction), |nu - nu_inf| < 0.05 (the free zigzag edges
 *      of a few cells shift the extent-based nu by a few per cent: 0.971 at
 *      4 x 4, 1.005 at 6 x 6 cells), the faces themselves contract under
 *      stretch and not under grip, and the grip's energy is higher (more
 *      constraints with the same prescribed motion: minimum principle);
 *  (3) the out-of-plane motion stays zero (z-symmetry; the three z pins
 *      only remove the out-of-plane rigid motions). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "generate/lattice.h"
#include "generate/lattice_scene.h"
#include "scene/scene.h"
#include "testutil.h"
#include "valutil.h"

static const char *dir = ".";

typedef struct lattice_result {
  double energy;
  double strain[3];     /* change of the mean face-to-face distance / extent */
  double face_span0[3]; /* lateral span (along y) of the min-x face joints */
  double face_span1[3]; /* the same after the solve */
  double zmax;          /* largest |z| of a joint after the solve */
} lattice_result;

static void must(rn_context *ctx, rn_status st, const char *what) {
  if (st != RN_OK) {
    fprintf(stderr, "%s: %s: %s\n", what, rn_status_name(st), rn_context_last_error(ctx));
    exit(1);
  }
}

/* Generates kind with cells n x n (edges_per_rod 4, circle of radius a/50,
 * E = 1, nu = 0.3, elastic joints) loaded by load along x with strain eps,
 * solves it and measures. */
static lattice_result run(rn_context *ctx, rn_lattice_kind kind, int n,
                          rn_lattice_load_kind load, double eps) {
  int cells[3] = {n, n, n};
  rn_lattice *lat = NULL;
  rn_scene *s = NULL;
  char path[1024];
  rn_lattice_scene sc = {"val_lattice_stretch",
                         4,
                         RN_JOINT_ELASTIC,
                         1.0,
                         0.3,
                         RN_LSEC_CIRCLE,
                         {1.0 / 50, 0},
                         load,
                         0,
                         eps,
                         0.0,
                         NULL};
  lattice_result res = {0};
  snprintf(path, sizeof path, "%s/val_lattice_%s_%d.json", dir,
           rn_lattice_kind_name(kind), (int)load);
  must(ctx, rn_lattice_build(ctx, kind, cells, 1.0, &lat), "build");
  must(ctx, rn_lattice_write_scene(ctx, path, lat, &sc), "write");
  must(ctx, rn_scene_load(ctx, path, &s), "load");
  rn_network *net = rn_scene_network(s);
  val_solve(net, 0);
  size_t nd = rn_network_num_dofs(net);
  double *x = malloc(nd * sizeof(double));
  must(ctx, rn_network_get_dofs(net, x), "dofs");
  must(ctx, rn_network_energy(net, x, &res.energy), "energy");
  free(x);
  double lo0[3] = {0}, hi0[3] = {0}, lo1[3] = {0}, hi1[3] = {0}, cnt[3][2] = {{0}};
  double fmin0 = INFINITY, fmax0 = -INFINITY, fmin1 = INFINITY, fmax1 = -INFINITY;
  for (int j = 0; j < rn_lattice_num_nodes(lat); j++) {
    double p0[3], p1[3];
    rn_lattice_node(lat, j, p0);
    must(ctx, rn_network_joint_position(net, j, p1), "position");
    res.zmax = fmax(res.zmax, fabs(p1[2]));
    for (int d = 0; d < 2; d++) {
      int f = rn_lattice_face(lat, j, d);
      if (f < 0) lo0[d] += p0[d], lo1[d] += p1[d], cnt[d][0]++;
      if (f > 0) hi0[d] += p0[d], hi1[d] += p1[d], cnt[d][1]++;
    }
    if (rn_lattice_face(lat, j, 0) < 0) {
      fmin0 = fmin(fmin0, p0[1]), fmax0 = fmax(fmax0, p0[1]);
      fmin1 = fmin(fmin1, p1[1]), fmax1 = fmax(fmax1, p1[1]);
    }
  }
  for (int d = 0; d < 2; d++) {
    double L0 = hi0[d] / cnt[d][1] - lo0[d] / cnt[d][0];
    double L1 = hi1[d] / cnt[d][1] - lo1[d] / cnt[d][0];
    res.strain[d] = L1 / L0 - 1;
  }
  res.face_span0[1] = fmax0 - fmin0;
  res.face_span1[1] = fmax1 - fmin1;
  rn_scene_destroy(&s);
  rn_lattice_destroy(&lat);
  remove(path);
  return res;
}

int main(int argc, char **argv) {
  rn_context *ctx = NULL;
  const double eps = 1e-3, r = 1.0 / 50, E = 1.0, A = M_PI * r * r;
  if (argc > 1) dir = argv[1];
  CHECK_STATUS(rn_context_create(&ctx), RN_OK);

  /* (1) square grid, 3 x 3 cells of a = 1: E* = E A / a, nu = 0 */
  for (int load = RN_LLOAD_STRETCH; load <= RN_LLOAD_GRIP; load++) {
    lattice_result q = run(ctx, RN_LATTICE_SQUARE, 3, (rn_lattice_load_kind)load, eps);
    /* E = 1/2 E* eps^2 (length 3 a) (width 4 a): each row of x-bars owns a
     * strip of width a */
    double Estar = 2 * q.energy / (eps * eps * 3 * 4);
    printf("square 3x3 %s-x %.0e: E* %.10e (E A / a %.10e), lateral strain %.3e\n",
           load == RN_LLOAD_STRETCH ? "stretch" : "grip", eps, Estar, E * A, q.strain[1]);
    CHECK_REL(Estar, E * A, 1e-6);
    CHECK_REL(q.strain[0], eps, 1e-12);
    CHECK(fabs(q.strain[1]) < 1e-6 * eps); /* solver tolerance */
    CHECK(q.zmax < 1e-12);
  }

  /* (2) regular honeycomb, 4 x 4 cells */
  lattice_result hs = run(ctx, RN_LATTICE_HONEYCOMB, 4, RN_LLOAD_STRETCH, eps);
  lattice_result hg = run(ctx, RN_LATTICE_HONEYCOMB, 4, RN_LLOAD_GRIP, eps);
  double l = 1.0 / sqrt(3.0), I = M_PI * pow(r, 4) / 4;
  double dd = 12 * I / (A * l * l), nu_inf = (1 - dd) / (1 + 3 * dd);
  double nu = -hs.strain[1] / hs.strain[0], nu_grip = -hg.strain[1] / hg.strain[0];
  printf("honeycomb 4x4 stretch-x %.0e: nu %.6f (infinite lattice %.6f), energy %.6e; "
         "grip-x: nu %.6f, energy %.6e\n",
         eps, nu, nu_inf, hs.energy, nu_grip, hg.energy);
  printf("  min-x face span %.6f -> %.6f (stretch), %.6f (grip)\n", hs.face_span0[1],
         hs.face_span1[1], hg.face_span1[1]);
  CHECK_REL(hs.strain[0], eps, 1e-12);
  CHECK(nu > 0);
  CHECK(fabs(nu - nu_inf) < 0.05);
  CHECK(hs.face_span1[1] < hs.face_span0[1] * (1 - 0.5 * nu_inf * eps));
  CHECK(hg.face_span1[1] == hg.face_span0[1]);
  CHECK(hg.energy > hs.energy);
  CHECK(hs.zmax < 1e-12 && hg.zmax < 1e-12);
  rn_context_destroy(&ctx);
  return rn_test_finish("val_lattice_stretch");
}
