#include "tool/adjustment_check.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

namespace mbfe::tool {

namespace {

constexpr double kMinSteps = 2000.0;  // steps of the check over T
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

}  // namespace

double check_step(double run_step, double t_check) {
  const double k = std::max(1.0, std::ceil(run_step * kMinSteps / t_check - 1e-9));
  return run_step / k;
}

AdjustmentCheck check_adjustment(const Model& model, const runtime::SimulationRequest& run, const RowsUpTo& adjusted,
                                 double t_check) {
  AdjustmentCheck out;
  out.t_end = t_check;
  runtime::SimulationRequest request = run;
  request.integrator = runtime::parse_integrator(out.integrator);
  request.adjust = false;
  request.t_end = t_check;
  request.step = out.step = check_step(run.step, t_check);
  request.every = 1;
  request.state_in_rows = false;
  RowsUpTo reference(t_check);
  const runtime::SimulationReport report = model.simulate(request, reference);
  out.message = report.message;
  if (reference.t().empty()) return out;
  const std::vector<std::string>& names = adjusted.layout().columns;
  const std::vector<std::string>& units = adjusted.layout().units;
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
    for (std::size_t k = 0; k < adjusted.t().size(); ++k)
      if (adjusted.t()[k] <= t_last * (1.0 + 1e-12))
        col.diff = std::max(col.diff, std::abs(adjusted.rows()[k][c] - at(reference, r, adjusted.t()[k])));
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
    ColumnDifference& d = col.force ? out.contact_force : out.displacement;
    if (d.column.empty() || col.diff / scale > d.relative) d = {col.diff / scale, names[col.c]};
  }
  return out;
}

nlohmann::json adjustment_check_json(const AdjustmentCheck& check) {
  const auto difference = [](const ColumnDifference& d) {
    return d.column.empty() ? nlohmann::json() : nlohmann::json{{"relative", d.relative}, {"column", d.column}};
  };
  return {{"t_end", check.t_end},
          {"integrator", check.integrator},
          {"step", check.step},
          {"contact_force", difference(check.contact_force)},
          {"displacement", difference(check.displacement)},
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
  if (!check.message.empty()) line << "; the original model's run: " << check.message;
  return line.str();
}

}  // namespace mbfe::tool
