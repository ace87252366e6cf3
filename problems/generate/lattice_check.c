/* lattice_check.c - the geometric and numeric bounds of generated lattices
 * (lattice_check.h; the argument in docs/lattices.md, "Admissible sections"). */
#include "generate/lattice_check.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

static const double pi = 3.14159265358979323846;

void rn_strut_section_size(int dim, const rn_lattice_scene *sec, double *half_width,
                           double *area) {
  const double p = sec->section[0], q = sec->section[1];
  switch (sec->shape) {
  case RN_LSEC_RECTANGLE: /* width p along d1 (+z in 2D), height q */
    *half_width = dim == 2 ? 0.5 * q : 0.5 * sqrt(p * p + q * q);
    *area = dim == 2 ? q : p * q;
    break;
  case RN_LSEC_ELLIPSE: /* semi-axis p along d1 */
    *half_width = dim == 2 ? q : fmax(p, q);
    *area = dim == 2 ? 2.0 * q : pi * p * q;
    break;
  default:
    *half_width = p;
    *area = dim == 2 ? 2.0 * p : pi * p * p;
    break;
  }
}

/* The joint zone of every node into zone (calloc'd): node n's bar ends are
 * list[start[n] .. start[n + 1]) (2 e + end), the bars' vectors d, lengths
 * len, section scales scale (NULL: 1) and half width r0; a node where two
 * ends leave in one direction has an infinite zone (out->coincident_node). */
static void joint_zones(int nnodes, const int *start, const int *list, const double *d,
                        const double *len, const double *scale, double r0, double *zone,
                        rn_strut_bounds *out) {
  /* joint zone z_n = r_max cot(theta_min / 2): along a strut of half width r
   * leaving the node at angle theta from another of half width r, the two
   * overlap up to the distance r (1 + cos theta) / sin theta = r cot(theta/2)
   * from the node (the far corner of their rhombus of intersection) */
  for (int n = 0; n < nnodes && out->zero_bar < 0; n++) {
    double cmax = -1.0, rmax = 0.0; /* cos of the smallest angle */
    for (int i = start[n]; i < start[n + 1]; i++) {
      const int e = list[i] >> 1;
      const double s = scale ? scale[e] : 1.0;
      rmax = fmax(rmax, r0 * s);
      for (int j = start[n]; j < i; j++) {
        const int f = list[j] >> 1;
        const double sg = ((list[i] & 1) == (list[j] & 1)) ? 1.0 : -1.0;
        const double *a = d + 3 * e, *b = d + 3 * f;
        const double c =
            sg * (a[0] * b[0] + a[1] * b[1] + a[2] * b[2]) / (len[e] * len[f]);
        cmax = fmax(cmax, c);
      }
    }
    if (cmax >= 1.0 - 1e-12) {
      if (out->coincident_node < 0) out->coincident_node = n;
      zone[n] = HUGE_VAL;
    } else if (cmax > -1.0) {
      zone[n] = rmax * (1.0 + cmax) / sqrt(1.0 - cmax * cmax);
    }
  }
}

int rn_strut_bounds_compute(int dim, int nnodes, int nbars, const int *uv,
                            const double *d, const double *scale,
                            const rn_lattice_scene *sec, double measure,
                            rn_strut_bounds *out) {
  double r0, a0;
  rn_strut_section_size(dim, sec, &r0, &a0);
  memset(out, 0, sizeof *out);
  out->joint_factor = HUGE_VAL;
  out->joint_bar = out->coincident_node = out->zero_bar = -1;
  /* the bar ends at each node (counting sort), as unit directions away from it */
  int *start = calloc((size_t)nnodes + 1, sizeof(int));
  int *list = malloc(2 * (size_t)(nbars ? nbars : 1) * sizeof(int));
  double *len = malloc((size_t)(nbars ? nbars : 1) * sizeof(double));
  double *zone = calloc((size_t)(nnodes ? nnodes : 1), sizeof(double));
  if (!start || !list || !len || !zone) {
    free(start);
    free(list);
    free(len);
    free(zone);
    return -1;
  }
  double volume = 0.0;
  for (int e = 0; e < nbars; e++) {
    const double *v = d + 3 * e, s = scale ? scale[e] : 1.0;
    len[e] = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (!(len[e] > 0.0) && out->zero_bar < 0) out->zero_bar = e;
    volume += a0 * (dim == 2 ? s : s * s) * len[e];
    start[uv[2 * e] + 1]++;
    start[uv[2 * e + 1] + 1]++;
  }
  out->density = volume / measure;
  for (int n = 0; n < nnodes; n++) start[n + 1] += start[n];
  for (int e = 0; e < nbars; e++) /* 2 e leaves u along d, 2 e + 1 leaves v along -d */
    for (int end = 0; end < 2; end++) list[start[uv[2 * e + end]]++] = 2 * e + end;
  for (int n = nnodes; n > 0; n--) start[n] = start[n - 1]; /* undo the fill */
  start[0] = 0;
  joint_zones(nnodes, start, list, d, len, scale, r0, zone, out);
  for (int e = 0; e < nbars && out->zero_bar < 0; e++) {
    const double z = zone[uv[2 * e]] + zone[uv[2 * e + 1]];
    if (z > 0.0 && len[e] / z < out->joint_factor) {
      out->joint_factor = len[e] / z;
      out->joint_bar = e;
    }
  }
  const double fd = out->density > 0.0
                        ? (dim == 2 ? 1.0 / out->density : 1.0 / sqrt(out->density))
                        : HUGE_VAL;
  out->factor = fmin(fd, out->joint_factor);
  if (out->zero_bar >= 0 || out->coincident_node >= 0) out->factor = 0.0;
  free(start);
  free(list);
  free(len);
  free(zone);
  return 0;
}

/* x finite and of magnitude at least DBL_MIN (not subnormal, not 0). */
static int normal(double x) { return isfinite(x) && fabs(x) >= DBL_MIN; }

static rn_status section_of(const rn_lattice_scene *sec, double k, rn_section *s) {
  const double p = k * sec->section[0], q = k * sec->section[1];
  return sec->shape == RN_LSEC_CIRCLE      ? rn_section_circle(p, s)
         : sec->shape == RN_LSEC_RECTANGLE ? rn_section_rectangle(p, q, s)
                                           : rn_section_ellipse(p, q, s);
}

rn_status rn_generate_check_range(rn_context *ctx, const rn_lattice_scene *sec,
                                  double min_len, double max_len, double extent,
                                  double smin, double smax) {
  const double lo = RN_GEN_MIN_LENGTH, hi = RN_GEN_MAX_LENGTH;
  if (!(min_len >= lo) || !(max_len <= hi))
    return rn_context_set_error(ctx, RN_ERR_RANGE,
                                "bar lengths from %.6g to %.6g: every bar "
                                "length must lie in [%g, %g] (the scale of --cell-size "
                                "and --cells)",
                                min_len, max_len, lo, hi);
  if (!(extent <= hi))
    return rn_context_set_error(ctx, RN_ERR_RANGE,
                                "the lattice extends to %.6g: coordinates "
                                "must stay within %g (--cell-size times --cells)",
                                extent, hi);
  const int two = sec->shape != RN_LSEC_CIRCLE;
  for (int k = 0; k < 1 + two; k++) {
    const double lo_d = smin * sec->section[k], hi_d = smax * sec->section[k];
    if (!(lo_d >= lo) || !(hi_d <= hi))
      return rn_context_set_error(ctx, RN_ERR_RANGE,
                                  "a section dimension of %.6g: section "
                                  "dimensions must lie in [%g, %g]",
                                  lo_d < lo ? lo_d : hi_d, lo, hi);
  }
  rn_material m;
  if (rn_material_from_E_nu(sec->E, sec->nu, 0.0, &m) != RN_OK)
    return rn_context_set_error(ctx, RN_ERR_RANGE, "--material %g,%g is invalid", sec->E,
                                sec->nu);
  for (int k = 0; k < 2; k++) {
    rn_section s;
    if (section_of(sec, k ? smax : smin, &s) != RN_OK ||
        rn_section_validate(&s) != RN_OK || !normal(m.E * s.A) || !normal(m.E * s.I11) ||
        !normal(m.E * s.I22) || !normal(m.G * s.J))
      return rn_context_set_error(
          ctx, RN_ERR_RANGE,
          "the section's stiffnesses E A, E I, G J (E = %g, section "
          "dimension %g) are not representable doubles: scale the section or "
          "--material",
          sec->E, (k ? smax : smin) * sec->section[0]);
  }
  return RN_OK;
}

int rn_lattice_scene_finite(const rn_lattice_scene *opt, rn_num_check *chk) {
  rn_num_checked(chk, "materials.material.E", opt->E);
  rn_num_checked(chk, "materials.material.nu", opt->nu);
  rn_num_checked(chk, "sections.section (first dimension)", opt->section[0]);
  rn_num_checked(chk, "sections.section (second dimension)", opt->section[1]);
  rn_num_checked(chk, "the load value", opt->load_value);
  rn_num_checked(chk, "the load value", opt->load_value2);
  return !chk->bad;
}

double rn_pcell_bar_vectors(const rn_pcell *c, int *uv, double *d) {
  double ext = 0.0, span = 0.0;
  for (int e = 0; e < c->nbars; e++) {
    const int *o = c->bar + 5 * e;
    uv[2 * e] = o[0];
    uv[2 * e + 1] = o[1];
    for (int k = 0; k < 3; k++) {
      d[3 * e + k] = c->xyz[3 * o[1] + k] - c->xyz[3 * o[0] + k];
      for (int m = 0; m < c->dim; m++) d[3 * e + k] += o[2 + m] * c->vec[3 * m + k];
    }
  }
  for (int k = 0; k < 3 * c->nnodes; k++) ext = fmax(ext, fabs(c->xyz[k]));
  for (int k = 0; k < 9; k++) span += fabs(c->vec[k]); /* image ends reach x + a_m */
  return ext + span;
}

int rn_pcell_strut_bounds(const rn_pcell *c, const rn_lattice_scene *sec,
                          rn_strut_bounds *out, double *extent) {
  size_t nb1 = (size_t)(c->nbars ? c->nbars : 1);
  int *uv = malloc(2 * nb1 * sizeof(int));
  double *d = malloc(3 * nb1 * sizeof(double)), L, V;
  int rc = -1;
  if (uv && d) {
    double ext = rn_pcell_bar_vectors(c, uv, d);
    rn_pcell_measures(c, &L, &V);
    rc = rn_strut_bounds_compute(c->dim, c->nnodes, c->nbars, uv, d, c->section_scale,
                                 sec, V, out);
    if (extent) *extent = ext;
  }
  free(uv);
  free(d);
  return rc;
}
