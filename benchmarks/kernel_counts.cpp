// kernel_counts.cpp - a counting build of the rod kernels: kernels/rod.c
// compiled as C++ with every double replaced by a type that counts its
// arithmetic, so that bench_kernels reports counted (not estimated)
// floating-point operations per vertex.  The loops are branch-free, so the
// count of one evaluation is the count of every evaluation of that size.
//
// Counted: + - * (1 flop each), / and sqrt (1 flop each, also reported apart).
// Not counted: comparisons, selects, sign changes, loads and stores.  The
// libm fallback for |theta/2| > 1e5 and the degenerate-stencil search never
// run on the benchmark's rods.
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <vector>

namespace rn_count {
struct op_counts {
  double addmul = 0.0, divsqrt = 0.0;
};
extern op_counts counts; // of the evaluation being counted (benchmark-only state)

struct cd {
  double v;
  cd() = default;
  cd(double x) : v(x) {} // NOLINT: implicit, as double literals mix in freely
  explicit operator double() const { return v; }
};
inline cd operator+(cd a, cd b) {
  counts.addmul += 1.0;
  return cd(a.v + b.v);
}
inline cd operator-(cd a, cd b) {
  counts.addmul += 1.0;
  return cd(a.v - b.v);
}
inline cd operator*(cd a, cd b) {
  counts.addmul += 1.0;
  return cd(a.v * b.v);
}
inline cd operator/(cd a, cd b) {
  counts.divsqrt += 1.0;
  return cd(a.v / b.v);
}
inline cd operator-(cd a) { return cd(-a.v); }
inline cd &operator+=(cd &a, cd b) { return a = a + b; }
inline cd &operator-=(cd &a, cd b) { return a = a - b; }
inline cd &operator*=(cd &a, cd b) { return a = a * b; }
inline bool operator<(cd a, cd b) { return a.v < b.v; }
inline bool operator>(cd a, cd b) { return a.v > b.v; }
inline bool operator<=(cd a, cd b) { return a.v <= b.v; }
inline bool operator>=(cd a, cd b) { return a.v >= b.v; }
inline bool operator==(cd a, cd b) { return a.v == b.v; }
inline bool operator!=(cd a, cd b) { return a.v != b.v; }
} // namespace rn_count
using rn_count::cd;
using rn_count::counts;

static inline cd sqrt(cd a) {
  rn_count::counts.divsqrt += 1.0;
  return cd(::sqrt(a.v));
}
static inline cd fabs(cd a) { return cd(::fabs(a.v)); }
static inline cd cos(cd a) { return cd(::cos(a.v)); }
static inline cd sin(cd a) { return cd(::sin(a.v)); }

// The kernels' external names, renamed so that this copy does not clash with
// the library's.
#define rnk_bendtwist_energy cnt_rnk_bendtwist_energy
#define rnk_bendtwist_grad cnt_rnk_bendtwist_grad
#define rnk_bendtwist_hess cnt_rnk_bendtwist_hess
#define rnk_bendtwist_hvp cnt_rnk_bendtwist_hvp
#define rnk_bend_energy cnt_rnk_bend_energy
#define rnk_bend_grad cnt_rnk_bend_grad
#define rnk_bend_hess cnt_rnk_bend_hess
#define rnk_bend_hvp cnt_rnk_bend_hvp
#define rnk_twist_energy cnt_rnk_twist_energy
#define rnk_twist_grad cnt_rnk_twist_grad
#define rnk_twist_hess cnt_rnk_twist_hess
#define rnk_twist_hvp cnt_rnk_twist_hvp
#define rnk_strains cnt_rnk_strains
#define rnk_reference_twist cnt_rnk_reference_twist
#define rnk_rod_energy cnt_rnk_rod_energy
#define rnk_rod_grad cnt_rnk_rod_grad
#define rnk_rod_hvp cnt_rnk_rod_hvp
#define rnk_rod_hess cnt_rnk_rod_hess
#define rnk_stretch_energy cnt_rnk_stretch_energy
#define RN_NO_TARGET_CLONES 1

#define double cd
#include "../kernels/rod.c"

// Only reached for degenerate edges (never on the benchmark's rods).
int cnt_rnk_stretch_energy(const cd q[7], const rnk_stretch_param *p, cd *E) {
  (void)q;
  (void)p;
  *E = 0.0;
  return RNK_OK;
}
#undef double

#include "kernel_counts.h"

rn_count::op_counts rn_count::counts;

int rn_bench_kernel_counts(int op, int nv, double *addmul, double *divsqrt) {
  if (nv < 3) return 1;
  size_t ne = (size_t)nv - 1, n = 4 * ne + 3;
  std::vector<cd> x(n), v(n), out(n * (op == RN_COUNT_HESS ? RNK_BAND : 1));
  std::vector<rnk_frame> ref(ne);
  std::vector<rnk_stretch_param> sp(ne);
  std::vector<rnk_bend_param> bp(ne - 1);
  std::vector<rnk_twist_param> tp(ne - 1);
  std::vector<cd> m(ne - 1);
  for (size_t i = 0; i <= ne; ++i) { // a helix, slightly twisted
    double s = (double)i / (double)ne;
    x[4 * i] = 0.05 * ::cos(4.0 * M_PI * s);
    x[4 * i + 1] = 0.05 * ::sin(4.0 * M_PI * s);
    x[4 * i + 2] = s;
    if (i < ne) x[4 * i + 3] = 0.01 * (double)i;
  }
  for (size_t i = 0; i < n; ++i) v[i] = ::sin(0.37 * (double)i);
  for (size_t j = 0; j < ne; ++j) {
    double e[3], l = 0.0, a[3] = {0.0, 0.0, 0.0}, d = 0.0;
    for (int k = 0; k < 3; ++k) {
      e[k] = x[4 * j + 4 + k].v - x[4 * j + k].v;
      l += e[k] * e[k];
    }
    l = ::sqrt(l);
    for (int k = 0; k < 3; ++k) e[k] /= l;
    a[0] = 1.0;
    for (int k = 0; k < 3; ++k) d += a[k] * e[k];
    for (int k = 0; k < 3; ++k) a[k] -= d * e[k];
    double na = ::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    for (int k = 0; k < 3; ++k) {
      ref[j].t[k] = e[k];
      ref[j].a1[k] = a[k] / na;
    }
    sp[j].k = 3000.0;
    sp[j].lbar = 0.99 * l;
  }
  for (size_t k = 0; k + 1 < ne; ++k) {
    bp[k].B[0] = 1.0;
    bp[k].B[1] = 0.1;
    bp[k].B[2] = 2.0;
    bp[k].kbar[0] = 0.01;
    bp[k].kbar[1] = 0.0;
    bp[k].vlen = 1.0 / (double)ne;
    tp[k].beta = 0.7;
    tp[k].taubar = 0.0;
    tp[k].vlen = bp[k].vlen;
    tp[k].ref_twist = 0.0;
    m[k] = 0.0;
  }
  rnk_rod_seg s = {(int)ne, x.data(),  ref.data(), sp.data(), 0,
                   (int)ne, bp.data(), tp.data(),  m.data()};
  cd E[3];
  int bad[2], rc;
  counts = rn_count::op_counts();
  switch (op) {
  case RN_COUNT_ENERGY:
    rc = cnt_rnk_rod_energy(&s, E, bad);
    break;
  case RN_COUNT_GRAD:
    rc = cnt_rnk_rod_grad(&s, E, out.data(), bad);
    break;
  case RN_COUNT_HVP:
    rc = cnt_rnk_rod_hvp(&s, v.data(), out.data(), bad);
    break;
  default:
    rc = cnt_rnk_rod_hess(&s, out.data(), bad);
    break;
  }
  *addmul = counts.addmul / nv;
  *divsqrt = counts.divsqrt / nv;
  return rc;
}
