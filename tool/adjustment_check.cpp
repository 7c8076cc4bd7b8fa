#include "tool/adjustment_check.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <tuple>
#include <utility>

namespace mbfe::tool {

namespace {

constexpr double kMinSteps = 2000.0;  // steps of the check over T
// h omega of the check's step at the fastest frequency the run resolves:
// generalized-alpha's relative phase error there is about (h omega)^2 / 12
// per radian, 2e-4, about 1e-3 of a period.
constexpr double kResolution = 0.05;
constexpr double kPeakShare = 0.01;  // columns whose peak is below this share of the largest of their kind are not compared

bool is_force(const std::string& name) { return name.rfind("force_", 0) == 0 || name.rfind("lambda_", 0) == 0; }

/// The reference's column c at time t, linear between its rows.
double at(const RowsUpTo& ref, std::size_t c, double t) {
  const std::vector<double>& times = ref.t();
  const auto it = std::lower_bound(times.begin(), times.end(), t);
  if (it == times.end()) return ref.rows().back()[c];
  const std::size_t k = static_cast<std::size_t>(it - times.begin());
  if (k == 0 || *it == t) return ref.rows()[k][c];
  const double a = (t - times[k - 1]) / (times[k] - times[k - 1]);
  return (1.0 - a) * ref.rows()[k - 1][c] + a * ref.rows()[k][c];
}

/// The worst contact force and displacement of `run` against `reference`,
/// each column against its own peak in the reference.
std::pair<ColumnDifference, ColumnDifference> compare(const Model& model, const RowsUpTo& run,
                                                      const RowsUpTo& reference) {
  std::pair<ColumnDifference, ColumnDifference> out;
  if (reference.t().empty()) return out;
  const std::vector<std::string>& names = run.layout().columns;
  const std::vector<std::string>& units = run.layout().units;
  const std::vector<std::string>& ref_names = reference.layout().columns;
  const double t_last = reference.t().back();
  // Per column: its largest difference and the reference's peak.
  struct Column {
    std::size_t c;
    bool force;
    double peak = 0.0, diff = 0.0;
  };
  std::vector<Column> columns;
  std::vector<std::string> driven;  // the coordinates of driven joints follow their motion in both runs
  for (const ir::Body& body : model.ir().bodies)
    if (body.joint.motion) driven.push_back(body.name);
  double force_peak = 0.0, displacement_peak = 0.0;
  for (std::size_t c = 0; c < names.size(); ++c) {
    const bool force = is_force(names[c]);
    const bool displacement = !force && c < units.size() && units[c] == "m" && names[c] != "phi_abs" &&
                              std::find(driven.begin(), driven.end(), names[c]) == driven.end();
    if (!force && !displacement) continue;
    const auto found = std::find(ref_names.begin(), ref_names.end(), names[c]);
    if (found == ref_names.end()) continue;
    const std::size_t r = static_cast<std::size_t>(found - ref_names.begin());
    Column col{c, force};
    for (const std::vector<double>& row : reference.rows()) col.peak = std::max(col.peak, std::abs(row[r]));
    for (std::size_t k = 0; k < run.t().size(); ++k)
      if (run.t()[k] <= t_last * (1.0 + 1e-12))
        col.diff = std::max(col.diff, std::abs(run.rows()[k][c] - at(reference, r, run.t()[k])));
    (force ? force_peak : displacement_peak) = std::max(force ? force_peak : displacement_peak, col.peak);
    columns.push_back(col);
  }
  for (const Column& col : columns) {
    // Each column against its own peak (the worst contact, the worst
    // displacement), but not one that hardly moves (below 1 % of the largest
    // of its kind: a contact that barely touched, the deflection under a
    // wheel on a stiff slab), where any difference would look large.
    const double largest = col.force ? force_peak : displacement_peak;
    const double scale = col.peak >= kPeakShare * largest ? col.peak : 0.0;
    if (!(scale > 0.0)) continue;
    ColumnDifference& d = col.force ? out.first : out.second;
    if (d.column.empty() || col.diff / scale > d.relative) d = {col.diff / scale, names[col.c]};
  }
  return out;
}

}  // namespace

double resolved_frequency(const ir::Model& model, const std::vector<runtime::AdjustmentEstimate::Limit>& limits) {
  double omega = 0.0;
  for (const runtime::AdjustmentEstimate::Limit& limit : limits) omega = std::max(omega, limit.omega_limit);
  for (const ir::Contact& c : model.contacts) {
    if (c.type != ir::ContactType::kSliderSpring || !(c.stiffness > 0.0) || c.body < 0) continue;
    const double mass = model.bodies[static_cast<std::size_t>(c.body)].mass;
    if (mass > 0.0) omega = std::max(omega, std::sqrt(c.stiffness / mass));
  }
  return omega;
}

double check_step(double run_step, double t_check, double omega) {
  double target = t_check / kMinSteps;
  if (omega > 0.0) target = std::min(target, kResolution / omega);
  const double k = std::max(1.0, std::ceil(run_step / target - 1e-9));
  return run_step / k;
}

AdjustmentCheck check_adjustment(const Model& model, const runtime::SimulationRequest& run,
                                 const runtime::SimulationReport& report, const RowsUpTo& adjusted, double t_check,
                                 const runtime::StepMonitor& keep_going) {
  AdjustmentCheck out;
  out.t_end = t_check;
  out.omega = resolved_frequency(
      model.ir(), report.adjustment_estimate ? report.adjustment_estimate->limits
                                             : std::vector<runtime::AdjustmentEstimate::Limit>{});
  runtime::SimulationRequest request = run;
  request.integrator = runtime::parse_integrator(out.integrator);
  request.adjust = false;
  request.t_end = t_check;
  request.step = out.step = check_step(run.step, t_check, out.omega);
  request.every = 1;
  request.state_in_rows = false;
  RowsUpTo reference(t_check);
  const runtime::SimulationReport original = model.simulate(request, reference, keep_going);
  out.message = original.message;
  out.interrupted = original.run.status == runtime::SimulationStatus::kInterrupted;
  std::tie(out.contact_force, out.displacement) = compare(model, adjusted, reference);
  if (reference.t().empty() || out.interrupted) return out;
  // The reference's own error: the same run at twice the step against it.
  request.step = 2.0 * out.step;
  RowsUpTo coarser(t_check);
  const runtime::SimulationReport coarse = model.simulate(request, coarser, keep_going);
  out.interrupted = coarse.run.status == runtime::SimulationStatus::kInterrupted;
  if (coarse.message.empty())
    std::tie(out.reference_contact_force, out.reference_displacement) = compare(model, coarser, reference);
  return out;
}

nlohmann::json adjustment_check_json(const AdjustmentCheck& check) {
  const auto difference = [](const ColumnDifference& d) {
    return d.column.empty() ? nlohmann::json() : nlohmann::json{{"relative", d.relative}, {"column", d.column}};
  };
  return {{"t_end", check.t_end},
          {"integrator", check.integrator},
          {"step", check.step},
          {"omega", check.omega},
          {"contact_force", difference(check.contact_force)},
          {"displacement", difference(check.displacement)},
          {"reference_change",
           {{"contact_force", difference(check.reference_contact_force)},
            {"displacement", difference(check.reference_displacement)}}},
          {"message", check.message}};
}

std::string adjustment_check_line(const AdjustmentCheck& check) {
  std::ostringstream line;
  line << std::setprecision(3) << "adjustment check over " << check.t_end << " s against the original model ("
       << check.integrator << ", step " << check.step << " s): ";
  const auto say = [&](const char* what, const ColumnDifference& d) {
    if (d.column.empty())
      line << "no " << what;
    else
      line << what << " differ by up to " << 100.0 * d.relative << " % of their peak (" << d.column << ")";
  };
  say("contact forces", check.contact_force);
  line << ", ";
  say("displacements", check.displacement);
  if (!check.reference_contact_force.column.empty() || !check.reference_displacement.column.empty()) {
    // What the reference itself is sure of: the figures above are only
    // meaningful where they exceed it.
    line << "; the reference moves by up to ";
    if (!check.reference_contact_force.column.empty())
      line << 100.0 * check.reference_contact_force.relative << " % (contact forces)";
    if (!check.reference_contact_force.column.empty() && !check.reference_displacement.column.empty()) line << " and ";
    if (!check.reference_displacement.column.empty())
      line << 100.0 * check.reference_displacement.relative << " % (displacements)";
    line << " at twice its step";
  }
  if (!check.message.empty()) line << "; the original model's run: " << check.message;
  return line.str();
}

}  // namespace mbfe::tool
