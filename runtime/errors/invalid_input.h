// The runtime's errors for a request it cannot run as asked: bad user input
// found after parsing (an --adjust on without an adjustment block, a probe on
// an unknown beam, a beam too large for every mode, an initial state that
// violates the contacts). The command-line tool prints what() and exits with
// status 2; numerical faults during a run are not this (they end the run with a
// status, see runtime/simulation/simulate.h).
#pragma once

#include <stdexcept>
#include <string>

namespace mbfe::runtime {

class InvalidInput : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

/// A field of a SimulationRequest (runtime/simulation/simulation_types.h)
/// that cannot be run as given: what() is "<field> <what is wrong>"
/// ("step must be > 0 s, got -1"), so a caller that knows the field by
/// another name (the command line's --step, Python's step=) can say it its
/// way: `field()` names it, `detail()` is the rest.
class InvalidRequest : public InvalidInput {
 public:
  InvalidRequest(std::string field, std::string detail)
      : InvalidInput(field + " " + detail), field_(std::move(field)), detail_(std::move(detail)) {}
  const std::string& field() const { return field_; }
  const std::string& detail() const { return detail_; }

 private:
  std::string field_, detail_;
};

}  // namespace mbfe::runtime
