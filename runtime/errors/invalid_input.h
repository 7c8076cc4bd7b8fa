// The runtime's error for a request it cannot run as asked: bad user input
// found after parsing (an --adjust on without an adjustment block, a probe on
// an unknown beam, a beam too large for every mode, an initial state that
// violates the contacts). The command-line tool prints what() and exits with
// status 2; numerical faults during a run are not this (they end the run with a
// status, see simulate.h).
#pragma once

#include <stdexcept>
#include <string>

namespace mbfe::runtime {

class InvalidInput : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

}  // namespace mbfe::runtime
