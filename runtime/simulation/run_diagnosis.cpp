#include "runtime/simulation/run_diagnosis.h"

#include <cmath>
#include <cstdio>
#include <sstream>

namespace mbfe::runtime {

namespace {

std::string short_sci(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.4e", v);
  const std::string s = buf;
  const auto e = s.find('e');
  if (e == std::string::npos) return s;
  return s.substr(0, e) + "e" + std::to_string(std::stoi(s.substr(e + 1)));
}

}  // namespace

std::string eigenvalue_text(std::complex<double> lambda) {
  std::string s = short_sci(lambda.real());
  if (lambda.imag() != 0.0) s += (lambda.imag() > 0 ? " + " : " - ") + short_sci(std::abs(lambda.imag())) + "i";
  return s;
}

std::string diagnose_run(const SimulationResult& result, const std::optional<StepLimit>& limit,
                         const std::string& row_fault) {
  std::ostringstream msg;
  msg.precision(5);
  if (result.status == SimulationStatus::kCompleted && row_fault.empty()) return "";
  if (result.status == SimulationStatus::kInterrupted) {
    msg << "interrupted at t = " << result.t << " s";
    return msg.str();
  }
  const bool diverged = result.status == SimulationStatus::kDiverged;
  const bool finite = limit && limit->kind == StepLimit::Kind::kFinite;
  const bool beyond = finite && result.step > limit->h;
  const std::string fault = !row_fault.empty() ? row_fault : result.message;
  if (!diverged && !beyond) {
    // A fault that names its own time (a slider leaving its beam inside a
    // step) is said once, with that time.
    if (fault.find(" at t = ") != std::string::npos) return fault;
    msg << "failed at t = " << result.t << " s: " << fault;
    return msg.str();
  }
  // The state that failed the checks is one step after the last good one.
  msg << "diverged at t = " << (diverged ? result.t + result.step : result.t) << " s: step " << result.step;
  if (beyond)
    msg << " exceeds " << result.integrator << "'s stable limit " << limit->text() << " (fastest eigenvalue "
        << eigenvalue_text(limit->critical) << ")";
  else if (limit && limit->kind == StepLimit::Kind::kNone)
    msg << ": " << result.integrator << " has no stable step for this model (eigenvalue "
        << eigenvalue_text(limit->critical) << ")";
  else
    msg << " with " << result.integrator << (limit ? " (stable limit " + limit->text() + ")" : std::string());
  if (diverged)
    msg << ": |y| = " << result.norm << " exceeded the bound " << result.bound;
  else
    msg << "; the growing state broke a contact: " << fault;
  return msg.str();
}

}  // namespace mbfe::runtime
