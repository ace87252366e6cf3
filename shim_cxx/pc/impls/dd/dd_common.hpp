// dd_common.hpp - helpers shared by the files of the rod-level domain decomposition
// (pc/impls/dd/): reductions over the ranks, the ladder of diagonal shifts, block
// work vectors, entry lookup in a fill-complete matrix.
#ifndef RODNET_SHIM_DD_COMMON_HPP
#define RODNET_SHIM_DD_COMMON_HPP

#include <cmath>
#include <string>

#include <Teuchos_CommHelpers.hpp>

#include "base/shim_error.hpp"
#include "system/system.hpp"

namespace rodnet {
namespace dd {

using Comm = Teuchos::Comm<int>;

constexpr size_t kNone = static_cast<size_t>(-1);

// Global sum of a count over the ranks.
inline long long sum_over_ranks(const Comm &comm, long long v) {
  long long s = 0;
  Teuchos::reduceAll(comm, Teuchos::REDUCE_SUM, v, Teuchos::outArg(s));
  return s;
}

// Throws Error on every rank if any rank reports a failure (never on one only).
inline void throw_if_any(const Comm &comm, bool failed, rn_status status,
                         const std::string &what) {
  int f = failed ? 1 : 0, any = 0;
  Teuchos::reduceAll(comm, Teuchos::REDUCE_MAX, f, Teuchos::outArg(any));
  if (any) throw Error(status, what);
}

// Smallest shift s in {0} u {1e-10, 1e-9, ..., 1e10} for which try_factor(s)
// succeeds (bisection on the exponent; the factorisation of the returned shift is
// the last one made).  Returns -1 if none does.  zero_failed: 0 is known to fail.
// hint (an exponent in [-10, 10], e.g. the last set-up's shift): 10^(hint-1) and
// 10^hint are tried first, two factorisations where the shift has not changed by a
// decade (the bisection takes six).
template <class F>
double smallest_shift(F &&try_factor, bool zero_failed = false, int hint = 99) {
  if (!zero_failed && try_factor(0.0)) return 0.0;
  int lo = -11, hi = 11; // 10^lo fails (-11 stands for 0), 10^hi works (11: unknown)
  bool last_hi = false;  // the last factorisation made is that of 10^hi
  const auto test = [&](int e) {
    last_hi = try_factor(std::pow(10.0, e));
    (last_hi ? hi : lo) = e;
  };
  if (hint >= -10 && hint <= 10) {
    if (hint > -10) test(hint - 1);
    if (hi == 11) test(hint);
  }
  if (hi == 11) {
    test(10);
    if (hi == 11) return -1.0;
  }
  while (hi - lo > 1) test((lo + hi) / 2);
  const double s = std::pow(10.0, hi);
  if (!last_hi) try_factor(s); // leave the factorisation of the returned shift
  return s;
}

// v with k columns on map, made anew where it has another column count (the work
// vectors of a block application: one halo exchange and one coarse solve for all the
// block's columns instead of one per column).
inline void ensure_columns(Teuchos::RCP<TMV> &v, const Teuchos::RCP<const TMap> &map,
                           size_t k) {
  if (v.is_null() || v->getNumVectors() != k) v = Teuchos::rcp(new TMV(map, k));
}

// Position of local column lc in row row of a fill-complete local matrix (sorted rows).
template <class Local>
size_t find_entry(const Local &lcl, LO row, LO lc) {
  const size_t beg = lcl.graph.row_map(row), end = lcl.graph.row_map(row + 1);
  size_t lo = beg, hi = end;
  while (lo < hi) {
    const size_t mid = (lo + hi) / 2;
    if (lcl.graph.entries(mid) < lc)
      lo = mid + 1;
    else
      hi = mid;
  }
  if (lo == end || lcl.graph.entries(lo) != lc)
    throw Error(RN_ERR_INTERNAL, "dd preconditioner: coarse matrix entry missing");
  return lo;
}

} // namespace dd
} // namespace rodnet

#endif
