/* check.c - derivative self-test: gradient and HVP against central
 * differences with an h-sweep, CSR Hessian against the HVP, CSR symmetry.
 *
 * Directions and perturbations are scaled per DOF: positions (of vertices
 * and joints) by the mean rest edge length L, material angles and joint
 * rotation vectors by 1 (radian), so that h and perturb are relative sizes.
 * Directions d have entries L r or r with r uniform in [-1, 1) (splitmix64
 * from the seed: deterministic).  For each point and
 * direction and h in 1e-2 .. 1e-5 (half decades):
 *   gradient: e(h) = |(E(x+hd) - E(x-hd)) / 2h - g.d| / max(|g.d|, |g| |d| / sqrt(n)),
 *             |H d| |d| instead when that is below 1e3 eps |H d| |d| (a
 *             gradient at round-off, as at rest)
 *   HVP:      e(h) = |(g(x+hd) - g(x-hd)) / 2h - H d| / |H d|
 * (absolute when the denominator is 0).  The error of a case is its minimum
 * over h (the best h); the report holds the worst case.  The observed order
 * is the least-squares slope of log e against log h over the leading part of
 * the sweep where e still decreases (by at least a factor 2 per half decade)
 * and stays above 100 eps M / (h den), M the size of the energy terms (of
 * the gradient entries for the HVP): there truncation, not round-off,
 * dominates.  The report holds the smallest order over the cases, NaN if no
 * case had two such points (e.g. an energy quadratic along every d).
 *
 * Truncation against a wrong derivative: the signed error of the differences
 * is D(h) = c + a h^2 + O(h^4) + round-off, c = 0 for a correct derivative.
 * Richardson's extrapolation of two neighbouring steps,
 *   c(h1, h2) = (D(h2) h1^2 - D(h1) h2^2) / (h1^2 - h2^2),
 * removes the h^2 term (componentwise for the HVP; norms as for e(h)).  Its
 * minimum over the neighbouring pairs of a case is the error extrapolated to
 * h -> 0; the report holds the worst case.  A large error that is truncation
 * (a state where the gradient is small against the third derivative, e.g. a
 * rest state under small loads) extrapolates to round-off, a wrong derivative
 * to c.  rn_check_fd_passes judges with both.
 *
 * The generic rn_objective_check_derivatives runs the same sweeps on any
 * objective given by callbacks; rn_network_check_derivatives adds the
 * assembled Hessian's checks. */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/network_internal.h"
#include "rodnet_couple.h"

static const char *where = "rn_network_check_derivatives";

enum { N_SWEEP = 7, N_DIRECTIONS = 2 };

typedef struct check_work {
  size_t n;
  const rn_objective *obj;
  double *scale, *x, *xp, *xm, *d, *g, *gp, *gm, *hv, *y, *vals, *rprev, *x0;
  uint64_t rng;
  double eabs; /* sum of |energy terms| at the point */
  double gabs; /* |g| + |H d| L: size of the gradient entries near it */
} check_work;

static double uniform(uint64_t *state) { /* splitmix64, [-1, 1) */
  uint64_t z = (*state += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  z ^= z >> 31;
  return (double)(z >> 11) * (2.0 / 9007199254740992.0) - 1.0;
}

static double norm2(size_t n, const double *v) {
  double s = 0.0;
  for (size_t i = 0; i < n; ++i) s += v[i] * v[i];
  return sqrt(s);
}

static double dot(size_t n, const double *a, const double *b) {
  double s = 0.0;
  for (size_t i = 0; i < n; ++i) s += a[i] * b[i];
  return s;
}

/* Per reduced DOF: mean rest edge length for positions, 1 for angles. */
static void dof_scales(const rn_network *net, double *scale) {
  double lsum = 0.0;
  size_t ne = 0;
  for (int ir = 0; ir < net->nrods; ++ir)
    for (int j = 0; j < net->rods[ir].ne; ++j, ++ne) lsum += net->rods[ir].lbar[j];
  for (int ir = 0; ir < net->nrods; ++ir) {
    const rn_rod *r = &net->rods[ir];
    for (int v = 0; v < r->nv; ++v)
      for (int k = 0; k < RN_DOFS_PER_VERTEX; ++k) {
        int64_t m = net->map[rn_dof_vertex(r->off, v) + (size_t)k];
        if (m >= 0) scale[m] = lsum / (double)ne;
      }
    for (int j = 0; j < r->ne; ++j) {
      int64_t m = net->map[rn_dof_theta(r->off, j)];
      if (m >= 0) scale[m] = 1.0;
    }
  }
  for (int ij = 0; ij < net->njoints; ++ij) { /* position: L; rotation: 1 rad */
    const rn_joint *J = &net->joints[ij];
    for (int k = 0; k < 3; ++k) {
      int64_t m = net->map[rn_dof_joint_position(J->off) + (size_t)k];
      if (m >= 0) scale[m] = lsum / (double)ne;
      if (!rn_joint_has_rotation(J)) continue;
      m = net->map[rn_dof_joint_rotation(J->off) + (size_t)k];
      if (m >= 0) scale[m] = 1.0;
    }
  }
  for (size_t v = 0; v < rn_cell_full_count(net); ++v) { /* strain moving an image
                                                          by one edge length */
    int64_t m = net->map[net->cell->off + v];
    if (m >= 0)
      scale[m] = lsum / (double)ne / pow(net->cell->measure, 1.0 / net->cell->dim);
  }
}

static void random_scaled(check_work *w, double *v) {
  for (size_t i = 0; i < w->n; ++i) v[i] = w->scale[i] * uniform(&w->rng);
}

/* Least-squares slope of log e against log h over the leading run of the
 * sweep where e decreases and stays above the round-off level rnd[k]; NaN
 * with fewer than two points. */
static double sweep_order(const double *h, const double *e, const double *rnd) {
  int m = 1;
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  if (!(e[0] > rnd[0]) || !isfinite(e[0])) return NAN;
  while (m < N_SWEEP && e[m] > rnd[m] && isfinite(e[m]) && e[m] < 0.5 * e[m - 1]) m++;
  if (m < 2) return NAN;
  for (int i = 0; i < m; ++i) {
    double lx = log(h[i]), ly = log(e[i]);
    sx += lx;
    sy += ly;
    sxx += lx * lx;
    sxy += lx * ly;
  }
  return ((double)m * sxy - sx * sy) / ((double)m * sxx - sx * sx);
}

static void record(const double *h, const double *e, const double *rnd, const double *ex,
                   double *worst, double *order, double *worst_ex) {
  double best = INFINITY, best_ex = INFINITY, p = sweep_order(h, e, rnd);
  for (int k = 0; k < N_SWEEP; ++k) {
    if (e[k] < best) best = e[k];
    if (ex[k] < best_ex) best_ex = ex[k];
  }
  if (isfinite(best) && best > *worst) *worst = best;
  if (isfinite(best_ex) && best_ex > *worst_ex) *worst_ex = best_ex;
  if (!isnan(p) && (isnan(*order) || p < *order)) *order = p;
}

/* Richardson's weights of D(h_prev) and D(h) removing the h^2 term. */
static void richardson(double hp, double h, double *wp, double *w) {
  double den = hp * hp - h * h;
  *wp = -h * h / den;
  *w = hp * hp / den;
}

static void shifted(const check_work *w, double h, double *xp, double *xm) {
  for (size_t i = 0; i < w->n; ++i) {
    xp[i] = w->x[i] + h * w->d[i];
    xm[i] = w->x[i] - h * w->d[i];
  }
}

/* One direction: gradient and HVP sweeps.  Trial points where the energy is
 * degenerate count as infinite error at that h. */
static rn_status check_direction(check_work *w, rn_check_report *rep) {
  size_t n = w->n;
  const rn_objective *o = w->obj;
  double h[N_SWEEP], eg[N_SWEEP], eh[N_SWEEP], rg[N_SWEEP], rh[N_SWEEP];
  double xg[N_SWEEP], xh[N_SWEEP], dg_prev = 0.0;
  int have_prev = 0;
  double gd = dot(n, w->g, w->d), hvn = norm2(n, w->hv);
  double den_g = fmax(fabs(gd), norm2(n, w->g) * norm2(n, w->d) / sqrt((double)n));
  /* a gradient at round-off (at rest: the kernels' rounding, ~eps times the
   * stiffness) is zero: then the scale is |H d| |d|, the energy's curvature
   * along d */
  double hd = hvn * norm2(n, w->d);
  if (den_g <= 1e3 * DBL_EPSILON * hd) den_g = hd;
  if (!(den_g > 0.0)) den_g = 1.0;
  if (!(hvn > 0.0)) hvn = 1.0;
  for (int k = 0; k < N_SWEEP; ++k) {
    double Ep, Em, diff = 0.0;
    h[k] = pow(10.0, -2.0 - 0.5 * k);
    double wp = 0.0, wk = 0.0, dg;
    eg[k] = eh[k] = xg[k] = xh[k] = INFINITY;
    rg[k] = rh[k] = 0.0;
    shifted(w, h[k], w->xp, w->xm);
    if (o->gradient(o->user, w->xp, &Ep, w->gp) != RN_OK ||
        o->gradient(o->user, w->xm, &Em, w->gm) != RN_OK) {
      have_prev = 0;
      continue;
    }
    dg = (Ep - Em) / (2.0 * h[k]) - gd;
    eg[k] = fabs(dg) / den_g;
    if (have_prev) {
      richardson(h[k - 1], h[k], &wp, &wk);
      xg[k] = fabs(wp * dg_prev + wk * dg) / den_g;
    }
    /* round-off level: 100 eps times the size of the energy terms (of the
     * gradient entries) over h; below it the sweep no longer shows order */
    rg[k] = 100.0 * DBL_EPSILON * w->eabs / (h[k] * den_g);
    rh[k] = 100.0 * DBL_EPSILON * w->gabs / (h[k] * hvn);
    double xdiff = 0.0;
    for (size_t i = 0; i < n; ++i) {
      double r = (w->gp[i] - w->gm[i]) / (2.0 * h[k]) - w->hv[i],
             c = wp * w->rprev[i] + wk * r;
      diff += r * r;
      xdiff += c * c;
      w->rprev[i] = r;
    }
    eh[k] = sqrt(diff) / hvn;
    if (have_prev) xh[k] = sqrt(xdiff) / hvn;
    dg_prev = dg;
    have_prev = 1;
  }
  record(h, eg, rg, xg, &rep->grad_rel_err, &rep->grad_order,
         &rep->grad_extrapolated_err);
  record(h, eh, rh, xh, &rep->hvp_rel_err, &rep->hvp_order, &rep->hvp_extrapolated_err);
  return RN_OK;
}

/* Largest |H_ij - H_ji| relative to the largest |H_ij|. */
static double csr_asymmetry(const rn_network *net, const double *vals) {
  double amax = 0.0, dmax = 0.0;
  for (size_t r = 0; r < net->nred; ++r)
    for (int64_t p = net->rowptr[r]; p < net->rowptr[r + 1]; ++p) {
      int64_t c = net->col[p], q;
      amax = fmax(amax, fabs(vals[p]));
      for (q = net->rowptr[c]; q < net->rowptr[c + 1] && net->col[q] != (int64_t)r; ++q) {
      }
      dmax = fmax(dmax, q < net->rowptr[c + 1] ? fabs(vals[p] - vals[q]) : fabs(vals[p]));
    }
  return amax > 0.0 ? dmax / amax : dmax;
}

/* CSR Hessian at w->x against the HVP along w->d; symmetry. */
static rn_status check_csr(const rn_network *net, check_work *w, rn_check_report *rep) {
  rn_status st;
  double diff = 0.0, hvn;
  if ((st = rn_network_hessian_values(net, w->x, w->vals))) return st;
  for (size_t r = 0; r < w->n; ++r) {
    double s = 0.0;
    for (int64_t p = net->rowptr[r]; p < net->rowptr[r + 1]; ++p)
      s += w->vals[p] * w->d[net->col[p]];
    w->y[r] = s;
    diff += (s - w->hv[r]) * (s - w->hv[r]);
  }
  hvn = norm2(w->n, w->hv);
  rep->hess_hvp_err = fmax(rep->hess_hvp_err, hvn > 0.0 ? sqrt(diff) / hvn : sqrt(diff));
  rep->hess_sym_err = fmax(rep->hess_sym_err, csr_asymmetry(net, w->vals));
  return RN_OK;
}

/* The network as an rn_objective (user: a net_user). */
typedef struct net_user {
  const rn_network *net;
} net_user;

static rn_status network_gradient(void *user, const double *x, double *E, double *g) {
  return rn_network_gradient(((const net_user *)user)->net, x, E, g);
}

static rn_status network_hvp(void *user, const double *x, const double *v, double *hv) {
  return rn_network_hvp(((const net_user *)user)->net, x, v, hv);
}

/* The size of the network's energy terms (their round-off). */
static double network_energy_size(void *user, const double *x) {
  double terms[RN_TERM_COUNT], s = 0.0;
  if (rn_network_energy_terms(((const net_user *)user)->net, x, terms) != RN_OK)
    return NAN;
  for (int t = 0; t < RN_TERM_COUNT; ++t) s += fabs(terms[t]);
  return s;
}

/* net: also the assembled Hessian's checks (NULL for a generic objective). */
static rn_status check_point(const rn_network *net, check_work *w, rn_check_report *rep) {
  const rn_objective *o = w->obj;
  rn_status st;
  double E = 0.0;
  if ((st = o->gradient(o->user, w->x, &E, w->g))) return st;
  w->eabs = o->energy_size ? o->energy_size(o->user, w->x) : fabs(E);
  if (!isfinite(w->eabs)) return RN_DEGENERATE;
  for (int dir = 0; dir < N_DIRECTIONS; ++dir) {
    random_scaled(w, w->d);
    if ((st = o->hvp(o->user, w->x, w->d, w->hv))) return st;
    /* force ~ sqrt(2 energy stiffness), stiffness ~ |H d| / |d| */
    w->gabs = norm2(w->n, w->g) +
              sqrt(2.0 * w->eabs * norm2(w->n, w->hv) / fmax(norm2(w->n, w->d), DBL_MIN));
    if (net && dir == 0 && (st = check_csr(net, w, rep))) return st;
    if ((st = check_direction(w, rep))) return st;
  }
  rep->n_points++;
  return RN_OK;
}

static rn_status work_alloc(size_t nvar, size_t nnz, check_work *w) {
  size_t n = nvar + 1;
  double **arrays[] = {&w->scale, &w->x,  &w->xp, &w->xm, &w->d,     &w->g,
                       &w->gp,    &w->gm, &w->hv, &w->y,  &w->rprev, &w->x0};
  memset(w, 0, sizeof(*w));
  w->n = nvar;
  for (size_t i = 0; i < sizeof(arrays) / sizeof(arrays[0]); ++i)
    if (!(*arrays[i] = malloc(n * sizeof(double)))) return RN_ERR_ALLOC;
  w->vals = malloc((nnz + 1) * sizeof(double));
  return w->vals ? RN_OK : RN_ERR_ALLOC;
}

static void work_free(check_work *w) {
  free(w->scale);
  free(w->x);
  free(w->xp);
  free(w->xm);
  free(w->d);
  free(w->g);
  free(w->gp);
  free(w->gm);
  free(w->hv);
  free(w->y);
  free(w->rprev);
  free(w->x0);
  free(w->vals);
}

/* x0: the state to test (never NULL here). */
static rn_status run_points(const rn_network *net, const double *x0, int n_random,
                            double perturb, check_work *w, rn_check_report *rep) {
  rn_status st;
  for (int p = 0; p <= n_random; ++p) {
    memcpy(w->x, x0, w->n * sizeof(double));
    for (size_t i = 0; p > 0 && i < w->n; ++i)
      w->x[i] += perturb * w->scale[i] * uniform(&w->rng);
    st = check_point(net, w, rep);
    if (st < 0 || (st > 0 && p == 0))
      return st; /* degenerate perturbed points are skipped */
  }
  return RN_OK;
}

rn_status rn_network_check_derivatives(const rn_network *net, const double *x,
                                       int n_random, double perturb, uint64_t seed,
                                       rn_check_report *rep) {
  check_work w;
  rn_status st;
  if (!net) return RN_ERR_ARG;
  if ((st = rn_net_check_final(net, where))) return st;
  if (!rep) return rn_fail(net->ctx, RN_ERR_ARG, where, "rep is NULL");
  if (n_random < 0 || !isfinite(perturb) || perturb < 0.0)
    return rn_fail(net->ctx, RN_ERR_ARG, where,
                   "need n_random >= 0 and finite perturb >= 0");
  if (x && !rn_all_finite(net->nred, x))
    return rn_fail(net->ctx, RN_ERR_NOT_FINITE, where, "x has NaN or infinite entries");
  if (net->nfixed_couples > 0) { /* no energy: its gradient is not a derivative */
    char which[160];
    return rn_fail(net->ctx, RN_ERR_ARG, where,
                   "the moment on %s is a couple fixed in space (no energy): the "
                   "gradient and Hessian checks against the energy do not apply (its "
                   "force and Jacobian are checked in the unit tests)",
                   rn_network_fixed_couple_where(net, which, sizeof which));
  }
  memset(rep, 0, sizeof(*rep));
  rep->grad_order = rep->hvp_order = NAN;
  if (net->nred == 0) return RN_OK;
  if (work_alloc(net->nred, net->nnz, &w)) {
    work_free(&w);
    return rn_fail(net->ctx, RN_ERR_ALLOC, where, "out of memory");
  }
  net_user nu = {net};
  rn_objective obj = {net->nred,           NULL, network_gradient, network_hvp,
                      network_energy_size, &nu};
  w.obj = &obj;
  w.rng = seed;
  dof_scales(net, w.scale);
  if (x)
    memcpy(w.x0, x, w.n * sizeof(double));
  else
    rn_network_get_dofs(net, w.x0);
  st = run_points(net, w.x0, n_random, perturb, &w, rep);
  work_free(&w);
  return st;
}

rn_status rn_objective_check_derivatives(rn_context *ctx, const rn_objective *obj,
                                         const double *x, int n_random, double perturb,
                                         uint64_t seed, rn_check_report *rep) {
  static const char *const here = "rn_objective_check_derivatives";
  check_work w;
  rn_status st;
  if (!ctx) return RN_ERR_ARG;
  if (!obj || !obj->gradient || !obj->hvp || !x || !rep)
    return rn_context_set_error(ctx, RN_ERR_ARG, "%s: NULL objective, callback, x or rep",
                                here);
  if (n_random < 0 || !isfinite(perturb) || perturb < 0.0)
    return rn_context_set_error(ctx, RN_ERR_ARG,
                                "%s: need n_random >= 0 and finite perturb >= 0", here);
  if (!rn_all_finite(obj->n, x))
    return rn_context_set_error(ctx, RN_ERR_NOT_FINITE,
                                "%s: x has NaN or infinite entries", here);
  memset(rep, 0, sizeof(*rep));
  rep->grad_order = rep->hvp_order = NAN;
  if (obj->n == 0) return RN_OK;
  if (work_alloc(obj->n, 0, &w)) {
    work_free(&w);
    return rn_context_set_error(ctx, RN_ERR_ALLOC, "%s: out of memory", here);
  }
  w.obj = obj;
  w.rng = seed;
  for (size_t i = 0; i < w.n; ++i)
    w.scale[i] = obj->scale && obj->scale[i] > 0.0 ? obj->scale[i] : 1.0;
  memcpy(w.x0, x, w.n * sizeof(double));
  st = run_points(NULL, w.x0, n_random, perturb, &w, rep);
  work_free(&w);
  if (st < 0) return rn_context_set_error(ctx, st, "%s: a callback failed", here);
  if (st > 0)
    return rn_context_set_error(ctx, st, "%s: the objective is degenerate at x", here);
  return RN_OK;
}

int rn_check_fd_passes(double rel_err, double extrapolated_err, double tol) {
  return rel_err <= tol || extrapolated_err <= tol; /* NaN fails */
}
