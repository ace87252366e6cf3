/* val_couple_fixed.c - a clamped isotropic rod (B1 = B2) under a tip couple
 * fixed in space (rodnet_couple.h, RN_COUPLE_FIXED) and no force, solved by
 * the NOX path on the residual (docs/model.md, "Loads").
 *
 * Closed form (Kirchhoff): with no force the internal moment is the applied
 * couple M along the whole rod; m = B t x t' + C tau t gives t' = (M / B) x t:
 * the tangent turns about the fixed axis n = M / |M| at the rate w = |M| / B,
 * at a constant angle to M (curvature |M x t| / B, twist rate M . t / C), so
 * the centreline is a helix about n.  From the clamp (s = 0, tangent t0):
 *   x(s) = (t0 . n) n s + sin(w s) / w u + (1 - cos(w s)) / w (n x u),
 *   u = t0 - (t0 . n) n.
 * Asserted: the tip against x(L) with second-order convergence in the number
 * of edges (mid-edge clamp convention of VALIDATION.md); the clamp's reaction
 * moment is -M and every edge's internal moment is M, to round-off (relative
 * 1e-9 of |M|, the solver's residual); the conservative couple on the same
 * scene gives a measurably different tip (it applies f x (M x f) / |n x f|^2,
 * which departs from M as the end turns out of the plane normal to M); the
 * energy minimisers refuse the fixed couple; and in a plane (couple normal to
 * it) both models give the same state.
 *
 * The same couple on a joint of valence 1 at the tip (rigid: a rotational
 * spring from the terminal edge to the joint rotation; elastic: the rotation
 * fit follows the terminal frame), "model": "fixed" on the joint: the joint
 * is massless, so its spring hands the terminal edge the spatial moment M
 * (its energy is invariant under a common rotation) and the rod's equilibrium
 * equations are those of the couple on the rod's last edge.  Asserted: the
 * rod's state equals the rod-vertex solution to 1e-8 L at every n (so the
 * helix at second order), the clamp reaction is -M, the applied resultant
 * counts M, and the energy minimisers refuse it naming the joint.  The
 * conservative couple on the rigid joint: the reactions balance the applied
 * resultant, which counts the spatial moment m (not M) it applies there. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rodnet_couple.h"
#include "testutil.h"
#include "valutil.h"

static rn_network *rod_with_couple(rn_context *ctx, int n, double L, const rn_material *m,
                                   const rn_section *s, const double M[3],
                                   rn_couple_model model) {
  rn_network *net = val_clamped_rod(ctx, n, L, m, s, NULL, NULL, 0);
  CHECK_STATUS(rn_network_add_moment_model(net, 0, -1, M, model), RN_OK);
  CHECK_STATUS(rn_network_finalize(net), RN_OK);
  return net;
}

/* The clamped rod ending at joint "tip" of valence 1 and model jm, the couple
 * M on the joint. */
static rn_network *rod_with_joint_couple(rn_context *ctx, int n, double L,
                                         const rn_material *m, const rn_section *s,
                                         const double M[3], rn_joint_model jm,
                                         rn_couple_model model) {
  rn_network *net = val_clamped_rod(ctx, n, L, m, s, NULL, NULL, 0);
  int rods[1] = {0}, ends[1] = {RN_END}, j = -1;
  CHECK_STATUS(rn_network_add_joint(net, "tip", jm, 1, rods, ends, &j), RN_OK);
  CHECK_STATUS(rn_network_add_joint_moment_model(net, j, M, model), RN_OK);
  CHECK_STATUS(rn_network_finalize(net), RN_OK);
  return net;
}

static rn_solve_report solve_nox(rn_network *net) {
  rn_solve_options opt;
  rn_solve_report rep;
  rn_solve_options_default(&opt);
  opt.solver = RN_SOLVER_NOX;
  opt.gtol_rel = 1e-11;
  rn_status st = rn_solve(net, &opt, &rep);
  CHECK_STATUS(st, RN_OK);
  if (st) printf("rn_solve: %s\n", rn_context_last_error(rn_network_context(net)));
  CHECK(rep.converged);
  CHECK(!rep.stability.checked); /* not applicable: no energy */
  return rep;
}

/* the helix tip x(L), clamp at the origin with tangent +x */
static void helix_tip(const double M[3], double B, double L, double x[3]) {
  double mm = sqrt(M[0] * M[0] + M[1] * M[1] + M[2] * M[2]), w = mm / B;
  double n[3] = {M[0] / mm, M[1] / mm, M[2] / mm}, t0[3] = {1, 0, 0};
  double tn = n[0], u[3], nu[3];
  for (int k = 0; k < 3; ++k) u[k] = t0[k] - tn * n[k];
  nu[0] = n[1] * u[2] - n[2] * u[1];
  nu[1] = n[2] * u[0] - n[0] * u[2];
  nu[2] = n[0] * u[1] - n[1] * u[0];
  for (int k = 0; k < 3; ++k)
    x[k] = tn * n[k] * L + sin(w * L) / w * u[k] + (1.0 - cos(w * L)) / w * nu[k];
}

static double dist3(const double a[3], const double b[3]) {
  return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
              (a[2] - b[2]) * (a[2] - b[2]));
}

int main(void) {
  rn_context *ctx;
  CHECK_STATUS(rn_context_create(&ctx), RN_OK);
  rn_material mat;
  rn_section sec;
  CHECK_STATUS(rn_material_from_E_nu(1e7, 0.5, 0.0, &mat), RN_OK);
  CHECK_STATUS(rn_section_circle(0.01, &sec), RN_OK);
  const double B = mat.E * sec.I11, L = 1.0;
  /* |M| L / B = 2: the tangent turns by 2 rad about n, tilted against the rod */
  double M[3] = {0.5, 0.6, 0.9};
  {
    double s = 2.0 * B / L / sqrt(M[0] * M[0] + M[1] * M[1] + M[2] * M[2]);
    for (int k = 0; k < 3; ++k) M[k] *= s;
  }
  const double mm = sqrt(M[0] * M[0] + M[1] * M[1] + M[2] * M[2]);
  double exact[3];
  helix_tip(M, B, L, exact);

  int ns[4] = {10, 20, 40, 80};
  double hs[4], err[4];
  for (int i = 0; i < 4; ++i) {
    rn_network *net = rod_with_couple(ctx, ns[i], L, &mat, &sec, M, RN_COUPLE_FIXED);
    rn_solve_report rep = solve_nox(net);
    double tip[3];
    val_vertex(net, -1, tip);
    hs[i] = L / (ns[i] - 0.5);
    err[i] = dist3(tip, exact) / L;
    printf("fixed couple, n = %d: tip (%.9f, %.9f, %.9f), exact (%.9f, %.9f, %.9f), "
           "error/L %.4e, %d Newton, %ld GMRES iterations\n",
           ns[i], tip[0], tip[1], tip[2], exact[0], exact[1], exact[2], err[i],
           rep.iterations, rep.krylov_iterations);
    /* reaction of the clamp: -M (no force); internal moment M on every edge */
    int nsup = rn_network_num_supports(net);
    CHECK(nsup == 1);
    rn_reaction R[1];
    double *x = malloc(sizeof(double) * rn_network_num_dofs(net));
    CHECK_STATUS(rn_network_get_dofs(net, x), RN_OK);
    CHECK_STATUS(rn_network_reactions(net, x, R, 1), RN_OK);
    for (int k = 0; k < 3; ++k) {
      CHECK_NEAR(R[0].moment[k], -M[k], 1e-9 * mm);
      CHECK_NEAR(R[0].force[k], 0.0, 1e-9 * mm / L);
    }
    int ne = ns[i];
    double *fi = malloc(sizeof(double) * 3 * (size_t)ne),
           *mi = malloc(sizeof(double) * 3 * (size_t)ne), worst = 0.0;
    CHECK_STATUS(rn_network_rod_internal_forces(net, 0, fi, mi), RN_OK);
    /* edge 0 is clamped; the couple acts on the whole last edge (a cut at its
     * midpoint splits it), so edges 1 .. ne - 2 */
    for (int j = 1; j < ne - 1; ++j)
      for (int k = 0; k < 3; ++k) worst = fmax(worst, fabs(mi[3 * j + k] - M[k]));
    printf("  clamp reaction moment (%.12g, %.12g, %.12g) vs -M; internal moment "
           "max |m - M| / |M| = %.2e\n",
           R[0].moment[0], R[0].moment[1], R[0].moment[2], worst / mm);
    CHECK(worst <= 1e-9 * mm);
    free(fi);
    free(mi);
    free(x);

    /* the couple on a joint at the tip: the same rod state */
    for (int jm = 0; jm < 2; ++jm) {
      rn_joint_model model = jm ? RN_JOINT_RIGID : RN_JOINT_ELASTIC;
      rn_network *nj =
          rod_with_joint_couple(ctx, ns[i], L, &mat, &sec, M, model, RN_COUPLE_FIXED);
      rn_solve_report rj = solve_nox(nj);
      double tj[3], F[3], Ma[3], dmax = 0.0;
      val_vertex(nj, -1, tj);
      size_t nd = rn_network_num_dofs(nj);
      double *xj = malloc(sizeof(double) * nd);
      rn_reaction Rj[1];
      CHECK(rn_network_num_supports(nj) == 1);
      CHECK_STATUS(rn_network_get_dofs(nj, xj), RN_OK);
      CHECK_STATUS(rn_network_reactions(nj, xj, Rj, 1), RN_OK);
      CHECK_STATUS(rn_network_applied_resultant(nj, F, Ma), RN_OK);
      for (int v = 0; v < ns[i] + 1; ++v) { /* every vertex of the rod */
        double a[3], b[3];
        val_vertex(nj, v, a);
        val_vertex(net, v, b);
        dmax = fmax(dmax, dist3(a, b));
      }
      printf("  fixed couple on the %s joint at the tip: tip (%.9f, %.9f, %.9f), max "
             "|x - x_rod| / L = %.2e, %d Newton; reaction moment + M = %.1e |M|\n",
             jm ? "rigid" : "elastic", tj[0], tj[1], tj[2], dmax / L, rj.iterations,
             sqrt(pow(Rj[0].moment[0] + M[0], 2) + pow(Rj[0].moment[1] + M[1], 2) +
                  pow(Rj[0].moment[2] + M[2], 2)) /
                 mm);
      CHECK(dmax < 1e-8 * L);
      for (int k = 0; k < 3; ++k) {
        CHECK_NEAR(Rj[0].moment[k], -M[k], 1e-9 * mm);
        CHECK_NEAR(Rj[0].force[k], 0.0, 1e-9 * mm / L);
        CHECK(F[k] == 0.0);
      }
      CHECK_NEAR(Ma[0], M[0], 1e-12 * mm);
      CHECK_NEAR(Ma[1], M[1], 1e-12 * mm);
      CHECK_NEAR(Ma[2], M[2], 1e-12 * mm);
      if (i == 0 && jm == 1) { /* the energy minimisers refuse it, naming the joint */
        rn_solve_options opt;
        rn_solve_report r2;
        rn_solve_options_default(&opt);
        CHECK_STATUS(rn_solve(nj, &opt, &r2), RN_ERR_ARG);
        const char *msg = rn_context_last_error(ctx);
        CHECK(strstr(msg, "joint 'tip' is a couple fixed in space") &&
              strstr(msg, "--solver nox"));
        printf("  refused: %s\n", msg);
      }
      free(xj);
      rn_network_destroy(&nj);
    }

    if (i == 1) {
      /* the conservative couple on the same scene: a different answer */
      /* (NOX: the trust region winds the end through the couple's axis, where the
       * conservative potential gains 2 pi |M| per passage at no elastic cost, and
       * does not converge; docs/model.md) */
      rn_network *nc =
          rod_with_couple(ctx, ns[i], L, &mat, &sec, M, RN_COUPLE_CONSERVATIVE);
      rn_solve_options oc;
      rn_solve_report rc;
      rn_solve_options_default(&oc);
      oc.solver = RN_SOLVER_NOX;
      CHECK_STATUS(rn_solve(nc, &oc, &rc), RN_OK);
      CHECK(rc.converged);
      double tc[3];
      val_vertex(nc, -1, tc);
      printf("  conservative couple, same scene: tip (%.6f, %.6f, %.6f), %.3e from the "
             "fixed couple's\n",
             tc[0], tc[1], tc[2], dist3(tc, tip) / L);
      CHECK(dist3(tc, tip) > 0.03 * L);
      rn_network_destroy(&nc);
      /* the conservative couple on a rigid joint at the tip: the applied
       * resultant counts the moment m it applies, which the reactions balance */
      nc = rod_with_joint_couple(ctx, ns[i], L, &mat, &sec, M, RN_JOINT_RIGID,
                                 RN_COUPLE_CONSERVATIVE);
      CHECK_STATUS(rn_solve(nc, &oc, &rc), RN_OK);
      CHECK(rc.converged);
      {
        double F[3], Ma[3], *xc = malloc(sizeof(double) * rn_network_num_dofs(nc));
        rn_reaction Rc[1];
        CHECK_STATUS(rn_network_get_dofs(nc, xc), RN_OK);
        CHECK_STATUS(rn_network_reactions(nc, xc, Rc, 1), RN_OK);
        CHECK_STATUS(rn_network_applied_resultant(nc, F, Ma), RN_OK);
        double bal = 0.0, dev = 0.0;
        for (int k = 0; k < 3; ++k) {
          bal = fmax(bal, fabs(Rc[0].moment[k] + Ma[k]));
          dev = fmax(dev, fabs(Ma[k] - M[k]));
        }
        printf("  conservative couple on a rigid joint: applied moment (%.6g, %.6g, "
               "%.6g), |m - M| = %.3f |M|; reaction + applied = %.1e |M|\n",
               Ma[0], Ma[1], Ma[2], dev / mm, bal / mm);
        CHECK(bal < 1e-8 * mm);
        CHECK(dev > 1e-2 * mm);
        free(xc);
      }
      rn_network_destroy(&nc);
      /* the energy minimisers refuse the fixed couple, naming it */
      rn_solve_options opt;
      rn_solve_report r2;
      rn_solve_options_default(&opt);
      CHECK_STATUS(rn_solve(net, &opt, &r2), RN_ERR_ARG);
      const char *msg = rn_context_last_error(ctx);
      CHECK(strstr(msg, "rod 'rod' vertex 20") && strstr(msg, "fixed in space") &&
            strstr(msg, "--solver nox"));
      printf("  refused: %s\n", msg);
    }
    rn_network_destroy(&net);
  }
  double order = rn_test_loglog_slope(4, hs, err);
  printf("fixed couple helix: tip convergence order %.3f\n", order);
  CHECK(order > 1.85 && order < 2.15);
  CHECK(err[3] < 2e-3);

  /* in a plane (couple along z, rod along x): both models coincide */
  {
    /* below the lateral-torsional buckling moment of the round rod, so the
     * trust region stays in the plane too */
    double Mz[3] = {0.0, 0.0, 0.5 * B / L}, a[3], b[3];
    rn_network *nf = rod_with_couple(ctx, 20, L, &mat, &sec, Mz, RN_COUPLE_FIXED);
    rn_network *nc = rod_with_couple(ctx, 20, L, &mat, &sec, Mz, RN_COUPLE_CONSERVATIVE);
    solve_nox(nf);
    val_solve(nc, 0);
    val_vertex(nf, -1, a);
    val_vertex(nc, -1, b);
    printf(
        "planar: fixed tip (%.12f, %.12f, %.12f), conservative (%.12f, %.12f, %.12f)\n",
        a[0], a[1], a[2], b[0], b[1], b[2]);
    CHECK(dist3(a, b) < 1e-8 * L);
    rn_network_destroy(&nf);
    rn_network_destroy(&nc);
  }
  rn_context_destroy(&ctx);
  return rn_test_finish("val_couple_fixed");
}
