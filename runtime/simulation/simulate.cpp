#include "runtime/simulation/simulate.h"

#include <algorithm>
#include <stdexcept>

#include "runtime/simulation/simulator.h"

namespace mbfe::runtime {

SimulationReport simulate(const AssembledModel& model, const SimulationRequest& request,
                          SimulationObserver& observer, const StepMonitor& keep_going) {
  Simulator sim(model, request);
  for (const std::string& text : sim.notices()) observer.notice(text);
  observer.begin(sim.layout());
  // Every `every`-th step, or automatically at most about 10,000 rows.
  constexpr std::int64_t kMaxRows = 10000;
  const std::int64_t total = sim.total_steps();
  const std::int64_t every = request.every > 0 ? request.every : std::max<std::int64_t>(1, (total + kMaxRows - 1) / kMaxRows);
  // A fault met writing a row: the step after it fails the same way; no
  // more rows, and the report names the fault.
  bool rows = true;
  std::int64_t emitted = 0;
  const auto emit = [&]() {
    if (!rows) return;
    try {
      observer.row(sim.row());
      ++emitted;
    } catch (const std::runtime_error& e) {
      sim.note_row_fault(e.what());
      rows = false;
    }
  };
  emit();
  bool last_emitted = true;
  while (!sim.finished()) {
    const std::int64_t before = sim.steps();
    sim.advance_steps(1, keep_going);
    if (sim.steps() == before) break;  // stopped
    last_emitted = sim.steps() % every == 0 || sim.steps() == total;
    if (last_emitted) emit();
  }
  if (!last_emitted) emit();
  SimulationReport report = sim.report();
  report.run.rows = emitted;
  return report;
}

}  // namespace mbfe::runtime
