#include "runtime/simulation/simulation_types.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "runtime/errors/invalid_input.h"

namespace mbfe::runtime {

ProbeSpec parse_probe(const std::string& text) {
  static const std::string kAcc = ":acc";
  const bool acc = text.size() > kAcc.size() && text.compare(text.size() - kAcc.size(), kAcc.size(), kAcc) == 0;
  const std::string place = acc ? text.substr(0, text.size() - kAcc.size()) : text;
  const auto at = place.find('@');
  ProbeSpec spec;
  spec.label = text;
  spec.acceleration = acc;
  if (at == std::string::npos) {
    if (!acc || place.empty())
      throw InvalidRequest("probes", "'" + text +
                                         "': expected BEAM@S (S in m along the beam), BEAM@S:acc (its acceleration) "
                                         "or BODY:acc, e.g. beam1@0.5, beam1@0.5:acc, wheel:acc");
    spec.beam = place;
    spec.body = true;
    return spec;
  }
  spec.beam = place.substr(0, at);
  const std::string number = place.substr(at + 1);
  char* end = nullptr;
  errno = 0;
  spec.s = std::strtod(number.c_str(), &end);
  if (number.empty() || end != number.c_str() + number.size() || errno == ERANGE || !std::isfinite(spec.s)) {
    const auto colon = number.find(':');
    if (colon != std::string::npos)
      throw InvalidRequest("probes", "'" + text + "': unknown suffix '" + number.substr(colon) +
                                         "'; the only one is :acc (the acceleration, m/s^2): BEAM@S is the "
                                         "displacement (m), BEAM@S:acc its acceleration, e.g. " +
                                         spec.beam + "@" + number.substr(0, colon) + ":acc");
    throw InvalidRequest("probes", "'" + text + "': expected a number after '@', got '" + number + "'");
  }
  return spec;
}

void check_request(const SimulationRequest& request) {
  const auto got = [](double v) {
    std::ostringstream os;
    os.precision(17);
    os << v;
    return os.str();
  };
  if (!(request.step > 0.0) || !std::isfinite(request.step))
    throw InvalidRequest("step", "must be > 0 s, got " + got(request.step));
  if (!(request.t_end > 0.0) || !std::isfinite(request.t_end))
    throw InvalidRequest("t_end", "must be > 0 s, got " + got(request.t_end));
  if (request.every < 0)
    throw InvalidRequest("every", "must be a positive integer (or 0, automatic), got " + std::to_string(request.every));
}

const char* status_name(const SimulationReport& report) {
  switch (report.run.status) {
    case SimulationStatus::kDiverged:
      return "diverged";
    case SimulationStatus::kInterrupted:
      return "interrupted";
    case SimulationStatus::kFailed:
      // A fault at a step beyond the stable limit is the run diverging
      // (run_diagnosis.h says it so).
      return report.message.rfind("diverged", 0) == 0 ? "diverged" : "failed";
    case SimulationStatus::kCompleted:
      return report.message.empty() ? "completed" : "failed";  // the last row failed
  }
  return "failed";
}

}  // namespace mbfe::runtime
