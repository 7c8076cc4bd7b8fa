// mbfe simulate --check-adjustment T: after an adjusted run, the first T
// seconds again with the original model, implicitly (generalized_alpha), and
// how far the adjusted run's contact forces and displacements are from it
// (docs/damping-adjustment.md, "Checking a run").
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "api/mbfe.h"

namespace mbfe::tool {

/// Keeps the rows of a run up to a time (what the check compares).
class RowsUpTo : public runtime::SimulationObserver {
 public:
  explicit RowsUpTo(double t_max) : t_max_(t_max) {}
  void begin(const runtime::OutputLayout& layout) override { layout_ = layout; }
  void row(const runtime::OutputRow& row) override {
    if (row.t > t_max_ * (1.0 + 1e-12)) return;
    t_.push_back(row.t);
    rows_.push_back(row.values);
  }
  const runtime::OutputLayout& layout() const { return layout_; }
  const std::vector<double>& t() const { return t_; }
  const std::vector<std::vector<double>>& rows() const { return rows_; }

 private:
  double t_max_;
  runtime::OutputLayout layout_;
  std::vector<double> t_;
  std::vector<std::vector<double>> rows_;
};

/// The largest difference of one kind of column over the rows up to T,
/// relative to that column's peak in the reference; columns whose peak is
/// below 1 % of the largest of their kind are left out (a contact that
/// barely touched, the deflection under a wheel on a stiff slab).
struct ColumnDifference {
  double relative = 0.0;  // max |x - x_ref| / peak
  std::string column;     // the column where it is largest (empty: no such column)
};

struct AdjustmentCheck {
  double t_end = 0.0;  // s, T
  double step = 0.0;   // s, the original model's implicit step
  double omega = 0.0;  // rad/s, the fastest frequency the step resolves (check_step)
  std::string integrator = "generalized_alpha";
  ColumnDifference contact_force;  // force_* and lambda_* columns (N)
  ColumnDifference displacement;   // columns in m (rigid coordinates but driven ones, beam deflections, probes) but phi_abs
  /// The reference against the same run at twice its step, the same
  /// measures: an upper bound of the reference's own error (for a
  /// second-order method about three times it), which the figures above
  /// include. Empty columns when that run did not complete.
  ColumnDifference reference_contact_force;
  ColumnDifference reference_displacement;
  /// Empty when the original model's run completed; otherwise why not
  /// (the differences are then over the rows it reached).
  std::string message;
  /// A signal stopped the check (the monitor said stop): the figures are
  /// over the rows the original model's run reached.
  bool interrupted = false;
};

/// The fastest frequency (rad/s) an adjusted run of `model` represents and its
/// check must resolve: the largest omega_limit of its adjusted beams (`limits`,
/// as the run chose them) and the bounce of each body on a linear contact
/// spring, sqrt(k / m); 0 when it has neither.
double resolved_frequency(const ir::Model& model, const std::vector<runtime::AdjustmentEstimate::Limit>& limits);

/// The step of the check: the run's step divided by the smallest whole
/// number that gives at least 2000 steps over T and h omega <= 0.05 for
/// omega = resolved_frequency (generalized-alpha's phase error there is then
/// about 1e-4 a period; docs/damping-adjustment.md, "Checking a run").
double check_step(double run_step, double t_check, double omega);

/// Runs the original model over [0, t_check] with generalized_alpha at
/// check_step (the request's probes, start and formulation) and compares it
/// with `adjusted`, the rows of the adjusted run up to t_check (linear
/// interpolation of the reference at the adjusted run's times); then the
/// reference at twice its step against it, for the reference's own error.
/// `keep_going` is asked before each step of both runs, as Model::simulate
/// asks it; once it says stop, the check ends with what it has.
/// @throws as Model::simulate for a request the original model cannot run.
AdjustmentCheck check_adjustment(const Model& model, const runtime::SimulationRequest& run,
                                 const runtime::SimulationReport& report, const RowsUpTo& adjusted, double t_check,
                                 const runtime::StepMonitor& keep_going = {});

/// The sidecar's "adjustment_check": {t_end, integrator, step, omega,
/// contact_force: {relative, column}, displacement: {relative, column},
/// reference_change: {contact_force, displacement}, message}.
nlohmann::json adjustment_check_json(const AdjustmentCheck& check);

/// The line for stderr.
std::string adjustment_check_line(const AdjustmentCheck& check);

}  // namespace mbfe::tool
