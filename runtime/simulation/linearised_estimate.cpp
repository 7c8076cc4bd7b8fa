#include "runtime/simulation/linearised_estimate.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
#include <functional>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>

#include "runtime/errors/invalid_input.h"
#include "runtime/platform/thread_budget.h"
#include "runtime/simulation/limit_search.h"
#include "runtime/simulation/static_start.h"

namespace mbfe::runtime {

namespace {

// The search for omega_limit: auto, each probe one linearised run of the
// adjusted model: 10 grid points a decade, then 10 bisections (the grid
// ratio 10^0.1 to within 1e-4).
constexpr LimitSearchResolution kLinearisedSearch{10, 10};

/// Runs `a` and `b`, on two threads when the budget allows.
void both(const std::function<void()>& a, const std::function<void()>& b) {
  if (thread_budget() < 2) {
    a();
    b();
    return;
  }
  std::exception_ptr failure;
  std::thread other([&]() {
    try {
      b();
    } catch (...) {
      failure = std::current_exception();
    }
  });
  try {
    a();
  } catch (...) {
    other.join();
    throw;
  }
  other.join();
  if (failure) std::rethrow_exception(failure);
}

/// The worst relative change of a contact force under `adjusted` modes.
double worst_change(const LinearisedModel& lm, const LinearisedHistory& original, const ModalDynamicsSet& adjusted) {
  const LinearisedHistory a = run_linearised(lm.structure(), adjusted, lm.excitation(), lm.start());
  const LinearisedEstimate e = compare_contact_forces(lm.structure().contact_names, original, a);
  return e.worst >= 0 ? e.contacts[static_cast<std::size_t>(e.worst)].relative : 0.0;
}

}  // namespace

LinearisationPoint model_start(const AssembledModel& model) {
  LinearisationPoint point;
  model.initial_coordinates(point.q, point.qd);
  const std::shared_ptr<CoupledDynamics> dyn = model.make_dynamics(false);
  dyn->impose_motion(0.0, point.q, point.qd);
  point.static_start = model.ir().initial.static_start;
  if (point.static_start) coupled_static_start(model.ir(), dyn, point.q, point.qd);
  point.t_end = model.ir().simulation.t_end;
  return point;
}

LinearisedEstimate compare_contact_forces(const std::vector<std::string>& contacts, const LinearisedHistory& original,
                                          const LinearisedHistory& adjusted) {
  LinearisedEstimate out;
  double worst = -1.0;
  for (std::size_t i = 0; i < contacts.size(); ++i) {
    const std::vector<double>& o = original.force.at(i);
    const std::vector<double>& a = adjusted.force.at(i);
    LinearisedContactChange c;
    c.contact = contacts[i];
    double diff = 0.0, top_o = 0.0, top_a = 0.0, peak_a = 0.0;
    for (std::size_t k = 0; k < o.size() && k < a.size(); ++k) {
      diff = std::max(diff, std::abs(a[k] - o[k]));
      c.peak = std::max(c.peak, std::abs(o[k]));
      peak_a = std::max(peak_a, std::abs(a[k]));
      top_o = std::max(top_o, o[k]);
      top_a = std::max(top_a, a[k]);
    }
    const double scale = c.peak > 0.0 ? c.peak : peak_a;
    c.relative = scale > 0.0 ? diff / scale : 0.0;
    c.peak_change = top_o > 0.0 ? (top_a - top_o) / top_o : 0.0;
    if (scale > 0.0 && c.relative > worst) {
      worst = c.relative;
      out.worst = static_cast<int>(out.contacts.size());
    }
    out.contacts.push_back(c);
  }
  return out;
}

LinearisedEstimate linearised_estimate(const AssembledModel& model, const LinearisationPoint& point) {
  const auto start = std::chrono::steady_clock::now();
  const LinearisedModel lm(model, point);
  if (point.step_budget > 0 && lm.excitation().steps > point.step_budget)
    throw std::runtime_error("skipped: it would take " + std::to_string(lm.excitation().steps) + " steps, more than " +
                             std::to_string(point.step_budget) +
                             " (" + std::to_string(int(kLinearisedStepsPerRunStep)) + " times the run's) even at " +
                             std::to_string(int(kLinearisedLeastStepsPerPeriod)) +
                             " steps a period of its fastest excitation, and cost more than the run; the point "
                             "figures stand (a shorter step brings it back; the adjustment check measures)");
  const ModalDynamicsSet original = lm.original_modes(), adjusted = lm.adjusted_modes();
  LinearisedHistory o, a;
  both([&]() { o = run_linearised(lm.structure(), original, lm.excitation(), lm.start()); },
       [&]() { a = run_linearised(lm.structure(), adjusted, lm.excitation(), lm.start()); });
  LinearisedEstimate out = compare_contact_forces(lm.structure().contact_names, o, a);
  out.step = lm.excitation().step;
  out.steps = lm.excitation().steps;
  out.omega_excitation = lm.omega_excitation();
  out.unconverged_steps = o.unconverged_steps + a.unconverged_steps;
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

double choose_common_omega_limit(const AssembledModel& model, const std::vector<std::size_t>& auto_beams,
                                 const LinearisationPoint& point) {
  const ir::Model& ir = model.ir();
  if (auto_beams.empty()) throw std::invalid_argument("choose_common_omega_limit: no beam to choose for");
  const LinearisedModel lm(model, point);
  const LinearisedHistory original = run_linearised(lm.structure(), lm.original_modes(), lm.excitation(), lm.start());
  double tolerance = 1.0, fastest = 0.0, lowest = std::numeric_limits<double>::infinity();
  for (const std::size_t b : auto_beams) {
    tolerance = std::min(tolerance, ir.beams.at(b).adjustment.tolerance);
    const BeamPart& part = model.beams().beams.at(b);
    for (const ModalDynamics& mode : part.original) fastest = std::max(fastest, fastest_root(mode));
    lowest = std::min(lowest, part.basis.omega[0]);
  }
  std::vector<AdjustedModes> adjusted(model.beams().beams.size());
  const auto largest = [&](double omega_limit) {
    std::vector<const AdjustedModes*> given(adjusted.size(), nullptr);
    for (const std::size_t b : auto_beams) {
      ir::Adjustment a = ir.beams[b].adjustment;
      a.omega_limit_auto = false;
      a.omega_limit = omega_limit;
      adjusted[b] = adjust_modes(model.beams().beams[b].original, a);
      given[b] = &adjusted[b];
    }
    return worst_change(lm, original, lm.adjusted_modes(given));
  };
  const ir::Beam& first = ir.beams.at(auto_beams.front());
  const double top = 1.01 * fastest;
  if (const double floor_only = largest(top); floor_only > tolerance) {
    std::ostringstream os;
    os << ir.source_path << ":" << first.adjustment.omega_limit_loc.line << ":"
       << first.adjustment.omega_limit_loc.column << ": beam '" << first.name
       << "': omega_limit: auto finds no limit within tolerance " << tolerance
       << ": with nothing capped, the damping floor zeta_min alone changes a contact force by " << floor_only
       << " (a linearised run of both models); lower zeta_min or raise the tolerance";
    throw InvalidInput(os.str());
  }
  return lowest_limit_within(largest, tolerance, top, 0.5 * lowest, kLinearisedSearch);
}

}  // namespace mbfe::runtime
