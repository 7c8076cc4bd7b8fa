#include "runtime/simulation/simulate.h"

#include <algorithm>
#include <stdexcept>

#include "runtime/errors/invalid_input.h"
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

void check_request_early(const ir::Model& model, const SimulationRequest& request) {
  if (model.bodies.empty() || model.beams.empty()) return;  // truncation runs in coupled models only
  const bool any_adjustment =
      std::any_of(model.beams.begin(), model.beams.end(), [](const ir::Beam& b) { return b.adjustment.active(); });
  // As CoupledRun decides (coupled_run.cpp): the implicit integrators run the
  // original model unless asked otherwise (and then refuse).
  const IntegratorKind kind = request.integrator.kind;
  const bool implicit = kind == IntegratorKind::kBackwardEuler || kind == IntegratorKind::kTrapezoid ||
                        kind == IntegratorKind::kGeneralizedAlpha ||
                        (kind == IntegratorKind::kLinearMultistep && request.integrator.name == "bdf2");
  const bool adjusted = implicit ? request.adjust.value_or(false) : request.adjust.value_or(any_adjustment);
  if (!adjusted) return;
  const auto truncated = [](const ir::Beam& b) {
    return b.adjustment.active() && b.adjustment.policy == ir::AdjustmentPolicy::kTruncate;
  };
  for (const ProbeSpec& probe : request.probes) {
    if (!probe.acceleration || probe.body) continue;
    // The probe's own beam when it is truncated, else the first that is: a
    // beam acceleration keeps every beam in nodal coordinates (coupled_run.cpp).
    const ir::Beam* refused = nullptr;
    for (const ir::Beam& b : model.beams)
      if (truncated(b) && (!refused || b.name == probe.beam)) refused = &b;
    if (!refused) return;
    const ir::SourceLoc at = refused->adjustment.loc;
    const std::string place = probe.label.substr(0, probe.label.size() - 4);  // BEAM@S without ":acc"
    const std::string where =
        model.source_path + ":" + std::to_string(at.line) + ":" + std::to_string(at.column) + ": ";
    const std::string fixes = "probe the displacement ('" + place +
                              "') or a body's acceleration (BODY:acc), or run "
                              "the original model (adjust off)";
    if (refused->name == probe.beam)
      throw InvalidInput(where + "probe '" + probe.label + "': beam '" + probe.beam +
                         "' has policy truncate: it moves in its kept modes alone, in split coordinates, which hold "
                         "no nodal acceleration; " +
                         fixes);
    throw InvalidInput(where + "probe '" + probe.label +
                       "': a beam's acceleration needs every beam in nodal "
                       "coordinates, and beam '" +
                       refused->name +
                       "' has policy truncate, which steps in split "
                       "coordinates only; " +
                       fixes);
  }
}

}  // namespace mbfe::runtime
