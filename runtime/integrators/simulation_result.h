// How a fixed-step run ended: plain values that a report carries to the
// caller (api/mbfe.h), apart from the driver that produces them
// (simulation_driver.h), so that the public headers need no integrator.
#pragma once

#include <cstdint>
#include <string>

namespace mbfe::runtime {

/// What a Newton-based stepper did over a run (reported by `mbfe simulate`).
struct NewtonStatistics {
  long iterations = 0;      // Newton iterations, every step
  long factorizations = 0;  // iteration matrices formed and factored
  long steps = 0;           // steps taken
};

enum class SimulationStatus { kCompleted, kDiverged, kInterrupted, kFailed };

struct SimulationResult {
  SimulationStatus status = SimulationStatus::kCompleted;
  double t = 0.0;            // s: time of the last state that passed the checks
                             // (kDiverged: t of the step that failed them is t + step)
  std::int64_t steps = 0;    // accepted steps
  double step = 0.0;         // s, as asked
  std::string integrator;    // canonical integrator name
  double norm = 0.0;         // |y| at the failing step (kDiverged; may be inf or nan)
  double bound = 0.0;        // the bound it exceeded (kDiverged)
  std::string message;       // kFailed: what the system threw
  std::int64_t rows = 0;     // rows handed to the sink
  double wall_seconds = 0.0;
  NewtonStatistics newton;   // implicit second-order steppers: iterations, factorisations
};

}  // namespace mbfe::runtime
