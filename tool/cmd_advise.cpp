// mbfe advise MODEL.yaml --tolerance TOL: the lowest omega_limit of every
// adjusted beam whose accuracy estimate stays below TOL, the stable step of
// each explicit integrator there, and the wall time a run would take against
// the original model's implicit run.
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "api/mbfe.h"
#include "ir/model_error.h"
#include "runtime/advisor/model_spectrum.h"
#include "runtime/simulation/adjustment_estimate.h"
#include "runtime/simulation/assembled_model.h"
#include "tool/cli_args.h"
#include "tool/commands.h"
#include "tool/model_warnings_notice.h"

namespace mbfe::tool {

namespace {

constexpr const char* kHelp = R"(Usage: mbfe advise MODEL.yaml --tolerance TOL [--steps N] [--set PATH=VALUE]

Chooses, for every beam with an adjustment block, the lowest omega_limit
whose accuracy estimate stays at or below TOL, as `adjustment: {omega_limit:
auto, tolerance: TOL}` would (docs/damping-adjustment.md, "The accuracy
estimate"): where it applies (slider_spring contacts, every beam's modes,
no pin or slider_pin), the largest change the adjustment makes in a contact
force over the model's t_end, by a linearised run of both models, with one
limit common to the beams; elsewhere the largest relative change it makes
in the compliance where contacts, links and loads act, beam by beam. Prints each beam's limit and its estimate, the
stable step of each explicit integrator of the model so adjusted (mbfe
stability's advisor), and an estimate of the wall time to the model's t_end:
each explicit integrator at 0.9 of its stable step, against the original
model integrated implicitly (generalized_alpha) at RK4's step, the step that
resolves what the adjusted run resolves. Each wall time is the time per step
of N timed steps (default 200) times the steps to t_end.

Options:
  --tolerance TOL   the largest estimate allowed, relative (0 < TOL < 1), e.g. 0.01
  --steps N         steps timed per integrator (default 200)
  --set PATH=VALUE  replace a value of the model file first (repeatable; as
                    mbfe simulate --set)

A limit is printed rounded up to four digits, and the rounded value is the one
the estimate was checked at: copied into the model file as omega_limit, it
gives the same estimate.

Exit status: 0 done; 2 bad input (no adjustment block, a TOL outside (0, 1),
a beam whose limit cannot be chosen: file:line:col at its omega_limit).

Example:
  mbfe advise models/vehicle_bridge_30m.yaml --tolerance 0.01
)";

/// Drops the rows: only the run's wall time is wanted.
class NoRows : public runtime::SimulationObserver {
 public:
  void row(const runtime::OutputRow& /*row*/) override {}
};

/// Seconds per step of `steps` steps of `request` (or fewer to t_end), or
/// NaN when the run does not complete.
double seconds_per_step(const Model& model, runtime::SimulationRequest request, long steps) {
  request.t_end = std::min(request.t_end, request.step * static_cast<double>(steps));
  request.every = std::max<std::int64_t>(1, steps);
  NoRows rows;
  const runtime::SimulationReport report = model.simulate(request, rows);
  if (!report.message.empty() || report.run.steps == 0) return NAN;
  return report.run.wall_seconds / static_cast<double>(report.run.steps);
}

std::string seconds(double s) {
  if (!std::isfinite(s)) return "-";
  std::ostringstream o;
  o << std::setprecision(3) << s << " s";
  return o.str();
}

}  // namespace

int cmd_advise(const Args& args) {
  const ParsedArgs parsed(args, {"tolerance", "steps", "set"}, {"help", "quiet"});
  if (parsed.has("help")) {
    std::cout << kHelp;
    return 0;
  }
  if (parsed.positional().size() != 1) throw UsageError("expected one model file (see --help)");
  const auto tolerance = parsed.number("tolerance");
  if (!tolerance) throw UsageError("--tolerance TOL is required, e.g. --tolerance 0.01 (see --help)");
  if (!(*tolerance > 0.0 && *tolerance < 1.0))
    throw UsageError("--tolerance: expected a relative change in (0, 1), got '" + *parsed.value("tolerance") + "'");
  const double steps = parsed.number("steps").value_or(200.0);
  if (!(steps >= 1.0) || steps != std::floor(steps)) throw UsageError("--steps must be a positive whole number");

  LoadOptions load;
  load.quiet = parsed.has("quiet");
  load.overrides = model_overrides(parsed);
  const Model given = Model::load(parsed.positional()[0], load);
  announce_model_warnings(given.ir());
  ir::Model ir = given.ir();
  bool any = false;
  for (const ir::Beam& beam : ir.beams)
    if (beam.adjustment.active() && beam.adjustment.policy == ir::AdjustmentPolicy::kTruncate)
      throw ir::ModelError(ir.source_path, beam.adjustment.loc,
                           "beam '" + beam.name + "' has policy truncate: mbfe advise chooses an adjustment's "
                           "omega_limit by its estimated change of the structure's compliance, and a truncation, "
                           "which removes modes, has no such estimate (docs/catenary.md, \"Modal truncation\", "
                           "measures its accuracy; mbfe stability gives its stable steps)");
  for (ir::Beam& beam : ir.beams)
    if (beam.adjustment.active()) {
      beam.adjustment.omega_limit_auto = true;
      beam.adjustment.tolerance = *tolerance;
      any = true;
    }
  if (!any)
    throw UsageError("model '" + ir.name + "' has no beam with an active adjustment block: there is no omega_limit "
                     "to choose");
  const Model model = Model::from_ir(ir, given.solver(), load);
  const runtime::AdjustmentEstimate estimate = runtime::estimate_adjustment(model.assembled(), {});

  std::cout << "model '" << ir.name << "', tolerance " << 100.0 * *tolerance << " %:\n";
  for (const runtime::AdjustmentEstimate::Limit& limit : estimate.limits) {
    double worst = 0.0;
    std::string where = "no contact, link or load on it";
    if (estimate.linearised) {
      // One figure for the whole model: the worst contact force of the run.
      worst = estimate.max;
      where = estimate.where.empty() ? "no contact pressing" : estimate.where;
      where += " (the whole model, a linearised run over t_end)";
    } else {
      for (const runtime::AdjustmentEstimatePoint& p : estimate.points)
        if (p.beam == limit.beam && (where.rfind("no ", 0) == 0 || p.estimate > worst)) {
          worst = p.estimate;
          where = p.what;
        }
    }
    std::cout << "  beam '" << limit.beam << "': omega_limit " << std::setprecision(4) << limit.omega_limit
              << " rad/s; estimate " << std::setprecision(3) << 100.0 * worst << " % at " << where << "\n";
  }
  if (!estimate.linearised && !estimate.linearised_unavailable.empty())
    std::cout << "  by the point figures: the linearised run does not apply (" << estimate.linearised_unavailable
              << ")\n";
  for (const std::string& text : estimate.not_estimated) std::cout << "  not estimated: " << text << "\n";

  const runtime::SimulationRequest base = model.request();
  const double t_end = base.t_end;
  std::cout << "\nintegrator          stable step (adjusted)   wall time to t_end = " << t_end
            << " s (estimated)\n";
  double rk4_step = NAN;
  for (const runtime::StepLimitRow& row : model.step_limits()) {
    const std::string& name = row.integrator.name;
    if (name != "forward_euler" && name != "rk4" && name != "explicit_midpoint" && name != "ab2") continue;
    const runtime::StepLimit& limit = *row.adjusted;
    std::string wall = "-";
    if (limit.kind == runtime::StepLimit::Kind::kFinite) {
      runtime::SimulationRequest r = base;
      r.integrator = row.integrator;
      r.step = 0.9 * limit.h;
      r.adjust = true;
      if (name == "rk4") rk4_step = r.step;
      wall = seconds(seconds_per_step(model, r, static_cast<long>(steps)) * std::ceil(t_end / r.step));
    }
    std::ostringstream cell;
    cell << limit.text() << (limit.kind == runtime::StepLimit::Kind::kFinite ? " s" : "");
    std::cout << std::left << std::setw(20) << name << std::setw(25) << cell.str() << wall << "\n";
  }
  if (std::isfinite(rk4_step)) {
    runtime::SimulationRequest r = base;
    r.integrator = runtime::parse_integrator("generalized_alpha");
    r.step = rk4_step;
    r.adjust = false;
    const double wall = seconds_per_step(model, r, static_cast<long>(steps)) * std::ceil(t_end / r.step);
    std::cout << std::left << std::setw(20) << "generalized_alpha" << std::setw(25)
              << "original model, at rk4's" << seconds(wall) << "\n";
  }
  return 0;
}

}  // namespace mbfe::tool
