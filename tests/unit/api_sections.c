/* api_sections.c - section constants and materials against closed forms and
 * the classic Saint-Venant table of rectangle torsion. */
#include <math.h>

#include "rodnet.h"
#include "testutil.h"

static const double pi = 3.14159265358979323846;

static void test_circles(void) {
  rn_section s;
  CHECK_STATUS(rn_section_circle(2.0, &s), RN_OK);
  CHECK_REL(s.A, 4.0 * pi, 1e-15);
  CHECK_REL(s.I11, 4.0 * pi, 1e-15);
  CHECK_REL(s.I22, 4.0 * pi, 1e-15);
  CHECK(s.I12 == 0.0);
  CHECK_REL(s.J, 8.0 * pi, 1e-15);
  CHECK_STATUS(rn_section_hollow_circle(2.0, 1.0, &s), RN_OK);
  CHECK_REL(s.A, 3.0 * pi, 1e-15);
  CHECK_REL(s.I11, 15.0 * pi / 4.0, 1e-15);
  CHECK_REL(s.J, 15.0 * pi / 2.0, 1e-15);
  CHECK_STATUS(rn_section_hollow_circle(2.0, 0.0, &s), RN_OK);
  CHECK_REL(s.J, 8.0 * pi, 1e-15);
  CHECK_STATUS(rn_section_validate(&s), RN_OK);
  /* bad input */
  CHECK_STATUS(rn_section_circle(0.0, &s), RN_ERR_ARG);
  CHECK_STATUS(rn_section_circle(-1.0, &s), RN_ERR_ARG);
  CHECK_STATUS(rn_section_circle(NAN, &s), RN_ERR_NOT_FINITE);
  CHECK_STATUS(rn_section_circle(1.0, NULL), RN_ERR_ARG);
  CHECK_STATUS(rn_section_hollow_circle(1.0, 1.0, &s), RN_ERR_ARG);
  CHECK_STATUS(rn_section_hollow_circle(1.0, 2.0, &s), RN_ERR_ARG);
  CHECK_STATUS(rn_section_hollow_circle(1.0, -0.1, &s), RN_ERR_ARG);
  CHECK_STATUS(rn_section_hollow_circle(INFINITY, 0.1, &s), RN_ERR_NOT_FINITE);
}

static void test_ellipse(void) {
  rn_section s, c;
  CHECK_STATUS(rn_section_ellipse(2.0, 1.0, &s), RN_OK);
  CHECK_REL(s.A, 2.0 * pi, 1e-15);
  CHECK_REL(s.I11, 2.0 * pi, 1e-15);     /* pi a^3 b / 4, a along d1 */
  CHECK_REL(s.I22, pi / 2.0, 1e-15);     /* pi a b^3 / 4 */
  CHECK_REL(s.J, 8.0 * pi / 5.0, 1e-15); /* pi a^3 b^3 / (a^2 + b^2) */
  /* J < I11 + I22 (the polar moment) for a != b; equal for a circle */
  CHECK(s.J < s.I11 + s.I22);
  CHECK_STATUS(rn_section_ellipse(0.3, 0.3, &s), RN_OK);
  CHECK_STATUS(rn_section_circle(0.3, &c), RN_OK);
  CHECK_REL(s.J, c.J, 1e-14);
  CHECK_REL(s.I11, c.I11, 1e-14);
  CHECK_STATUS(rn_section_ellipse(1.0, 0.0, &s), RN_ERR_ARG);
  CHECK_STATUS(rn_section_ellipse(NAN, 1.0, &s), RN_ERR_NOT_FINITE);
}

static void test_rectangle(void) {
  /* J = beta w h^3 (w >= h): the classic table (Timoshenko & Goodier). */
  static const double ratio[] = {1, 1.5, 2, 3, 4, 5, 10};
  static const double beta[] = {0.1406, 0.1958, 0.2287, 0.2633, 0.2808, 0.2913, 0.3123};
  rn_section s, t;
  for (int i = 0; i < 7; ++i) {
    double h = 0.02, w = ratio[i] * h;
    CHECK_STATUS(rn_section_rectangle(w, h, &s), RN_OK);
    CHECK_NEAR(s.J / (w * h * h * h), beta[i], 5.1e-5); /* table has 4 digits */
  }
  /* thin limit: beta -> 1/3 (1 - 0.630 h / w); the series constant is
   * 192/pi^5 sum_{n odd} n^-5 = 192/pi^5 * (31/32) zeta(5). */
  CHECK_STATUS(rn_section_rectangle(100.0, 1.0, &s), RN_OK);
  CHECK_REL(s.J / 100.0,
            (1.0 - 192.0 / pow(pi, 5) * (31.0 / 32.0) * 1.0369277551433699 / 100.0) / 3.0,
            1e-12);
  CHECK_STATUS(rn_section_rectangle(1e4, 1.0, &s), RN_OK);
  CHECK_NEAR(s.J / 1e4, 1.0 / 3.0, 3e-5);
  /* moments, width along d1 */
  CHECK_STATUS(rn_section_rectangle(3.0, 1.0, &s), RN_OK);
  CHECK_REL(s.A, 3.0, 1e-15);
  CHECK_REL(s.I11, 27.0 / 12.0, 1e-15);
  CHECK_REL(s.I22, 3.0 / 12.0, 1e-15);
  CHECK(s.I12 == 0.0);
  CHECK_STATUS(rn_section_rectangle(1.0, 3.0, &t), RN_OK);
  CHECK_REL(t.J, s.J, 1e-15);
  CHECK_REL(t.I11, s.I22, 1e-15);
  CHECK_REL(t.I22, s.I11, 1e-15);
  CHECK_STATUS(rn_section_rectangle(0.0, 1.0, &s), RN_ERR_ARG);
  CHECK_STATUS(rn_section_rectangle(1.0, -1.0, &s), RN_ERR_ARG);
  CHECK_STATUS(rn_section_rectangle(1.0, NAN, &s), RN_ERR_NOT_FINITE);
}

static void test_validate(void) {
  rn_section s = {1.0, 2.0, 3.0, 0.5, 1.0};
  CHECK_STATUS(rn_section_validate(&s), RN_OK);
  s.I12 = 3.0; /* I11 I22 - I12^2 < 0 */
  CHECK_STATUS(rn_section_validate(&s), RN_ERR_ARG);
  s.I12 = sqrt(6.0) * (1.0 + 1e-15);
  CHECK_STATUS(rn_section_validate(&s), RN_ERR_ARG);
  s.I12 = 0.0;
  s.J = 0.0;
  CHECK_STATUS(rn_section_validate(&s), RN_ERR_ARG);
  s.J = 1.0;
  s.A = -1.0;
  CHECK_STATUS(rn_section_validate(&s), RN_ERR_ARG);
  s.A = 1.0;
  s.I22 = NAN;
  CHECK_STATUS(rn_section_validate(&s), RN_ERR_NOT_FINITE);
  CHECK_STATUS(rn_section_validate(NULL), RN_ERR_ARG);
}

static void test_material(void) {
  rn_material m;
  CHECK_STATUS(rn_material_from_E_nu(200e9, 0.3, 7800.0, &m), RN_OK);
  CHECK_REL(m.E, 200e9, 0.0);
  CHECK_REL(m.G, 200e9 / 2.6, 1e-15);
  CHECK_REL(m.density, 7800.0, 0.0);
  CHECK_STATUS(rn_material_from_E_nu(1.0e7, 0.5, 0.0, &m), RN_OK);
  CHECK_REL(m.G, 1.0e7 / 3.0, 1e-15);
  CHECK_STATUS(rn_material_from_E_nu(1.0, 0.6, 0.0, &m), RN_ERR_ARG);
  CHECK_STATUS(rn_material_from_E_nu(1.0, -1.0, 0.0, &m), RN_ERR_ARG);
  CHECK_STATUS(rn_material_from_E_nu(0.0, 0.3, 0.0, &m), RN_ERR_ARG);
  CHECK_STATUS(rn_material_from_E_nu(-5.0, 0.3, 0.0, &m), RN_ERR_ARG);
  CHECK_STATUS(rn_material_from_E_nu(1.0, 0.3, -1.0, &m), RN_ERR_ARG);
  CHECK_STATUS(rn_material_from_E_nu(NAN, 0.3, 0.0, &m), RN_ERR_NOT_FINITE);
  CHECK_STATUS(rn_material_from_E_nu(1.0, 0.3, 0.0, NULL), RN_ERR_ARG);
}

int main(void) {
  test_circles();
  test_ellipse();
  test_rectangle();
  test_validate();
  test_material();
  return rn_test_finish("api_sections");
}
