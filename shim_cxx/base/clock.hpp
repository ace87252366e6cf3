// clock.hpp - the wall clock of the shim's timings (the preconditioners' set-up and
// apply seconds, the Problem's evaluation seconds, the studies in benchmarks/).
#ifndef RODNET_SHIM_CLOCK_HPP
#define RODNET_SHIM_CLOCK_HPP

#include <chrono>

namespace rodnet {

using Clock = std::chrono::steady_clock;

// Seconds from t0 to now.
inline double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

} // namespace rodnet

#endif
