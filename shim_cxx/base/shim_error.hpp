// shim_error.hpp - the exception used inside the solver shim.
//
// Inside shim_cxx/ a failing rodnet call or a solver failure throws rodnet::Error;
// every extern "C" entry catches it (and any other exception) and turns it into an
// rn_status with the message stored in the network's context.
#ifndef RODNET_SHIM_ERROR_HPP
#define RODNET_SHIM_ERROR_HPP

#include <stdexcept>
#include <string>

#include "rodnet.h"

namespace rodnet {

class Error : public std::runtime_error {
public:
  // recorded: the C layer already stored the message in the context.
  Error(rn_status status, const std::string &what, bool recorded = false)
      : std::runtime_error(what), status_(status), recorded_(recorded) {}
  rn_status status() const { return status_; }
  bool recorded() const { return recorded_; }

private:
  rn_status status_;
  bool recorded_;
};

// Throws Error if a rodnet call returned an error (negative) status; returns
// the status otherwise (RN_OK or a positive, recoverable one).
inline rn_status check_status(rn_status s, const char *where) {
  if (s < 0) throw Error(s, where, true);
  return s;
}

} // namespace rodnet

#endif
