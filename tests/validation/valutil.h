/* valutil.h - helpers shared by the validation tests: straight rods with the
 * mid-edge clamp convention of VALIDATION.md, solving, reading tips. */
#ifndef RN_VALUTIL_H
#define RN_VALUTIL_H

#include "rodnet.h"
#include "rodnet_solve.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* A straight rod along +x with n edges whose first edge is clamped and whose
 * continuum clamp sits at the midpoint of that edge (x = 0): the physical
 * length is L = (n - 1/2) h, so the rod runs from x = -h/2 to x = L.
 * Section and material as given; d1 = +y.  Returns the finalized network in
 * *net (aborts the test on error). */
rn_network *val_clamped_rod(rn_context *ctx, int n, double L, const rn_material *m,
                            const rn_section *s, const double *tip_force,
                            const double *tip_moment, int finalize);

/* Solve with default options (quiet) and return the report; fails the test
 * if the solve does not converge. */
rn_solve_report val_solve(rn_network *net, int load_steps);

/* Position of vertex v (negative: from the end) of rod 0. */
void val_vertex(const rn_network *net, int v, double x[3]);

/* Complete elliptic integrals K(k), E(k) (AGM) and incomplete F(phi, k),
 * E(phi, k) (Carlson symmetric forms), modulus k. */
double val_ellK(double k);
double val_ellE(double k);
double val_ellF(double phi, double k);
double val_ellEinc(double phi, double k);

#endif
