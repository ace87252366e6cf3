/* jet.h - second-order jets: a value with its exact gradient and Hessian with
 * respect to up to JET_MAX local variables (internal to kernels/).
 *
 * The kernels evaluate each energy as a composition of a few elementary
 * operations (products, quotients, sqrt, atan2, sin/cos) on jets; each
 * operation applies the exact first and second derivative rules, so the
 * result carries the analytic gradient and Hessian of the composition.
 * `n` is the number of active variables and `ord` the highest derivative
 * carried (0: value, 1: gradient, 2: Hessian); only the upper triangle of
 * the Hessian (j >= i) is maintained.  Outputs may alias inputs. */
#ifndef RODNET_JET_H
#define RODNET_JET_H

#include <math.h>
#include <string.h>

#define JET_MAX 9

typedef struct jet {
  int n, ord;
  double v;
  double g[JET_MAX];
  double h[JET_MAX][JET_MAX];
} jet;

typedef struct jvec {
  jet c[3];
} jvec;

/* Copy only the active part of a jet (jets are large; whole-struct copies
 * would dominate the cost of value-only evaluation). */
static inline void jet_copy(jet *r, const jet *a) {
  int n = a->n, ord = a->ord;
  if (r == a) return;
  r->n = n;
  r->ord = ord;
  r->v = a->v;
  if (ord >= 1)
    for (int i = 0; i < n; ++i) r->g[i] = a->g[i];
  if (ord >= 2)
    for (int i = 0; i < n; ++i)
      for (int j = i; j < n; ++j) r->h[i][j] = a->h[i][j];
}

static inline void jet_const(jet *r, int n, int ord, double v) {
  r->n = n;
  r->ord = ord;
  r->v = v;
  if (ord >= 1)
    for (int i = 0; i < n; ++i) r->g[i] = 0.0;
  if (ord >= 2)
    for (int i = 0; i < n; ++i)
      for (int j = i; j < n; ++j) r->h[i][j] = 0.0;
}

static inline void jet_var(jet *r, int n, int ord, double v, int k) {
  jet_const(r, n, ord, v);
  if (ord >= 1) r->g[k] = 1.0;
}

/* r = sa * a + sb * b */
static inline void jet_lin(jet *r, double sa, const jet *a, double sb, const jet *b) {
  int n = a->n, ord = a->ord;
  r->n = n;
  r->ord = ord;
  r->v = sa * a->v + sb * b->v;
  if (ord >= 1)
    for (int i = 0; i < n; ++i) r->g[i] = sa * a->g[i] + sb * b->g[i];
  if (ord >= 2)
    for (int i = 0; i < n; ++i)
      for (int j = i; j < n; ++j) r->h[i][j] = sa * a->h[i][j] + sb * b->h[i][j];
}

static inline void jet_add(jet *r, const jet *a, const jet *b) {
  jet_lin(r, 1.0, a, 1.0, b);
}
static inline void jet_sub(jet *r, const jet *a, const jet *b) {
  jet_lin(r, 1.0, a, -1.0, b);
}

static inline void jet_scale(jet *r, double s, const jet *a) {
  int n = a->n, ord = a->ord;
  r->n = n;
  r->ord = ord;
  r->v = s * a->v;
  if (ord >= 1)
    for (int i = 0; i < n; ++i) r->g[i] = s * a->g[i];
  if (ord >= 2)
    for (int i = 0; i < n; ++i)
      for (int j = i; j < n; ++j) r->h[i][j] = s * a->h[i][j];
}

static inline void jet_add_const(jet *r, const jet *a, double c) {
  jet_copy(r, a);
  r->v += c;
}

/* r = a * b */
static inline void jet_mul(jet *r, const jet *a, const jet *b) {
  int n = a->n, ord = a->ord;
  jet t;
  t.n = n;
  t.ord = ord;
  t.v = a->v * b->v;
  if (ord >= 1)
    for (int i = 0; i < n; ++i) t.g[i] = a->g[i] * b->v + a->v * b->g[i];
  if (ord >= 2)
    for (int i = 0; i < n; ++i)
      for (int j = i; j < n; ++j)
        t.h[i][j] =
            a->h[i][j] * b->v + a->v * b->h[i][j] + a->g[i] * b->g[j] + b->g[i] * a->g[j];
  jet_copy(r, &t);
}

/* r += a * b (fused, saves a temporary) */
static inline void jet_fma(jet *r, const jet *a, const jet *b) {
  jet t;
  jet_mul(&t, a, b);
  jet_add(r, r, &t);
}

/* r = f(a) given f(a.v) = f0, f'(a.v) = f1, f''(a.v) = f2. */
static inline void jet_chain(jet *r, const jet *a, double f0, double f1, double f2) {
  int n = a->n, ord = a->ord;
  jet t;
  t.n = n;
  t.ord = ord;
  t.v = f0;
  if (ord >= 1)
    for (int i = 0; i < n; ++i) t.g[i] = f1 * a->g[i];
  if (ord >= 2)
    for (int i = 0; i < n; ++i)
      for (int j = i; j < n; ++j) t.h[i][j] = f1 * a->h[i][j] + f2 * a->g[i] * a->g[j];
  jet_copy(r, &t);
}

static inline void jet_inv(jet *r, const jet *a) {
  double x = a->v, i1 = 1.0 / x;
  jet_chain(r, a, i1, -i1 * i1, 2.0 * i1 * i1 * i1);
}

static inline void jet_div(jet *r, const jet *a, const jet *b) {
  jet ib;
  jet_inv(&ib, b);
  jet_mul(r, a, &ib);
}

static inline void jet_sqrt(jet *r, const jet *a) {
  double s = sqrt(a->v);
  jet_chain(r, a, s, 0.5 / s, -0.25 / (s * a->v));
}

static inline void jet_sin(jet *r, const jet *a) {
  double s = sin(a->v), c = cos(a->v);
  jet_chain(r, a, s, c, -s);
}

static inline void jet_cos(jet *r, const jet *a) {
  double s = sin(a->v), c = cos(a->v);
  jet_chain(r, a, c, -s, -c);
}

/* r = atan2(y, x) */
static inline void jet_atan2(jet *r, const jet *y, const jet *x) {
  int n = x->n, ord = x->ord;
  double X = x->v, Y = y->v, r2 = X * X + Y * Y, r4 = r2 * r2;
  double fx = -Y / r2, fy = X / r2;
  double fxx = 2.0 * X * Y / r4, fyy = -fxx, fxy = (Y * Y - X * X) / r4;
  jet t;
  t.n = n;
  t.ord = ord;
  t.v = atan2(Y, X);
  if (ord >= 1)
    for (int i = 0; i < n; ++i) t.g[i] = fx * x->g[i] + fy * y->g[i];
  if (ord >= 2)
    for (int i = 0; i < n; ++i)
      for (int j = i; j < n; ++j)
        t.h[i][j] = fx * x->h[i][j] + fy * y->h[i][j] + fxx * x->g[i] * x->g[j] +
                    fyy * y->g[i] * y->g[j] +
                    fxy * (x->g[i] * y->g[j] + y->g[i] * x->g[j]);
  jet_copy(r, &t);
}

/* Copy a jet over n_from variables into one over n_to >= n_from variables,
 * variable k going to k + offset. */
static inline void jet_embed(jet *r, const jet *a, int n_to, int offset) {
  int n = a->n, ord = a->ord;
  jet t;
  jet_const(&t, n_to, ord, a->v);
  if (ord >= 1)
    for (int i = 0; i < n; ++i) t.g[i + offset] = a->g[i];
  if (ord >= 2)
    for (int i = 0; i < n; ++i)
      for (int j = i; j < n; ++j) t.h[i + offset][j + offset] = a->h[i][j];
  jet_copy(r, &t);
}

/* ---- 3-vectors of jets ---- */
static inline void jvec_const(jvec *r, int n, int ord, const double v[3]) {
  for (int k = 0; k < 3; ++k) jet_const(&r->c[k], n, ord, v[k]);
}

static inline void jvec_dot(jet *r, const jvec *a, const jvec *b) {
  jet t;
  jet_mul(&t, &a->c[0], &b->c[0]);
  jet_fma(&t, &a->c[1], &b->c[1]);
  jet_fma(&t, &a->c[2], &b->c[2]);
  jet_copy(r, &t);
}

static inline void jvec_cross(jvec *r, const jvec *a, const jvec *b) {
  jvec t;
  jet p;
  for (int k = 0; k < 3; ++k) {
    int k1 = (k + 1) % 3, k2 = (k + 2) % 3;
    jet_mul(&t.c[k], &a->c[k1], &b->c[k2]);
    jet_mul(&p, &a->c[k2], &b->c[k1]);
    jet_sub(&t.c[k], &t.c[k], &p);
  }
  for (int k = 0; k < 3; ++k) jet_copy(&r->c[k], &t.c[k]);
}

/* r = a . v with v a constant vector (linear: no product rule needed) */
static inline void jvec_dot_const(jet *r, const jvec *a, const double v[3]) {
  jet t;
  jet_lin(&t, v[0], &a->c[0], v[1], &a->c[1]);
  jet_lin(r, 1.0, &t, v[2], &a->c[2]);
}

/* r = v x a with v a constant vector */
static inline void jvec_cross_const(jvec *r, const double v[3], const jvec *a) {
  jvec t;
  for (int k = 0; k < 3; ++k) {
    int k1 = (k + 1) % 3, k2 = (k + 2) % 3;
    jet_lin(&t.c[k], v[k1], &a->c[k2], -v[k2], &a->c[k1]);
  }
  for (int k = 0; k < 3; ++k) jet_copy(&r->c[k], &t.c[k]);
}

/* r = s * a with s a jet */
static inline void jvec_mul(jvec *r, const jet *s, const jvec *a) {
  for (int k = 0; k < 3; ++k) jet_mul(&r->c[k], s, &a->c[k]);
}

/* r = sa * a + sb * b (constant scalars) */
static inline void jvec_lin(jvec *r, double sa, const jvec *a, double sb, const jvec *b) {
  for (int k = 0; k < 3; ++k) jet_lin(&r->c[k], sa, &a->c[k], sb, &b->c[k]);
}

/* r = sa * a + sb * b (jet scalars) */
static inline void jvec_comb(jvec *r, const jet *sa, const jvec *a, const jet *sb,
                             const jvec *b) {
  jvec t;
  jet p;
  for (int k = 0; k < 3; ++k) {
    jet_mul(&t.c[k], sa, &a->c[k]);
    jet_mul(&p, sb, &b->c[k]);
    jet_add(&t.c[k], &t.c[k], &p);
  }
  for (int k = 0; k < 3; ++k) jet_copy(&r->c[k], &t.c[k]);
}

/* r = a . b with a over variables 0..na-1 and b over variables 0..nb-1 of a
 * second block: r is a jet over na + nb variables (a's block first). */
static inline void jvec_dot_blocks(jet *r, const jvec *a, const jvec *b) {
  int ord = a->c[0].ord, na = a->c[0].n, nb = b->c[0].n;
  r->n = na + nb;
  r->ord = ord;
  r->v = a->c[0].v * b->c[0].v + a->c[1].v * b->c[1].v + a->c[2].v * b->c[2].v;
  if (ord >= 1) {
    for (int i = 0; i < na; ++i)
      r->g[i] =
          a->c[0].g[i] * b->c[0].v + a->c[1].g[i] * b->c[1].v + a->c[2].g[i] * b->c[2].v;
    for (int i = 0; i < nb; ++i)
      r->g[na + i] =
          a->c[0].v * b->c[0].g[i] + a->c[1].v * b->c[1].g[i] + a->c[2].v * b->c[2].g[i];
  }
  if (ord >= 2) {
    for (int i = 0; i < na; ++i) {
      for (int j = i; j < na; ++j)
        r->h[i][j] = a->c[0].h[i][j] * b->c[0].v + a->c[1].h[i][j] * b->c[1].v +
                     a->c[2].h[i][j] * b->c[2].v;
      for (int j = 0; j < nb; ++j)
        r->h[i][na + j] = a->c[0].g[i] * b->c[0].g[j] + a->c[1].g[i] * b->c[1].g[j] +
                          a->c[2].g[i] * b->c[2].g[j];
    }
    for (int i = 0; i < nb; ++i)
      for (int j = i; j < nb; ++j)
        r->h[na + i][na + j] = a->c[0].v * b->c[0].h[i][j] + a->c[1].v * b->c[1].h[i][j] +
                               a->c[2].v * b->c[2].h[i][j];
  }
}

static inline void jvec_embed(jvec *r, const jvec *a, int n_to, int offset) {
  for (int k = 0; k < 3; ++k) jet_embed(&r->c[k], &a->c[k], n_to, offset);
}

#endif
