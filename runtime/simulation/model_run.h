// What one kind of model gives a Simulator (simulator.h): the system the
// integrator steps and its initial state, the output layout and the values of
// a row, the full coordinates of a state and back, and what the run tells
// its report (variant, tallies, the stable limit a diagnosis compares with).
// rigid_run.cpp, beam_run.cpp and coupled_run.cpp implement it; make_model_run
// picks one by the model's kind and the request. Internal to runtime/simulation/.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "ir/quantity.h"
#include "runtime/integrators/ode_system.h"
#include "runtime/integrators/simulation_driver.h"
#include "runtime/simulation/assembled_model.h"
#include "runtime/simulation/simulation_types.h"
#include "runtime/stability/step_limits.h"

namespace mbfe::runtime::detail {

class ModelRun {
 public:
  virtual ~ModelRun() = default;

  /// The system the integrator steps, and where it starts (t = 0).
  virtual OdeSystem& system() = 0;
  const Eigen::VectorXd& initial_state() const { return y0_; }
  const OutputLayout& layout() const { return layout_; }
  /// What the user should hear before the run (a projection onto the contacts).
  const std::vector<std::string>& notices() const { return notices_; }
  /// The driver's options beyond step and end time: the divergence bound.
  const SimulationOptions& options() const { return options_; }
  const std::string& variant() const { return variant_; }
  /// The run integrates the adjusted beams.
  virtual bool adjusted() const { return false; }

  /// The row at (t, y) into `values` (layout order). When `q` is not null the
  /// full coordinates of the state go there too (q and qd; left empty when
  /// the run says they cost too much and were not asked for: see
  /// SimulationRequest::state_in_rows). @throws std::runtime_error for a
  /// fault met on the way (a contact report).
  virtual void row(double t, const Eigen::VectorXd& y, std::vector<double>& values, Eigen::VectorXd* q,
                   Eigen::VectorXd* qd) = 0;
  /// The full coordinates of y, and the y of full coordinates (projected onto
  /// the contacts where the model has some).
  virtual void full_state(double t, const Eigen::VectorXd& y, Eigen::VectorXd& q, Eigen::VectorXd& qd) = 0;
  virtual Eigen::VectorXd state_of(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd) = 0;
  /// After every accepted step (tallies).
  virtual void accepted(double /*t*/, const Eigen::VectorXd& /*y*/) {}
  /// Into the report: tallies.
  virtual void fill(SimulationReport& /*report*/) const {}
  /// The integrator's stable limit for this model as simulated, for the
  /// sentence of a run that did not complete; absent when unknown.
  virtual std::optional<StepLimit> stable_limit(const IntegratorSpec& integrator) = 0;
  /// A point load on a beam, value(t) in N, from now on (replacing one set
  /// before at the same beam and point). @throws InvalidInput where the
  /// model takes none or the place is not on the beam.
  virtual void set_beam_load(const std::string& beam, double s, std::function<double(double)> value);

 protected:
  /// A column of the layout: its name, what it measures and which time
  /// derivative of that (its unit follows, ir::si_unit).
  void add_column(std::string name, ir::Quantity quantity, int rate = 0) {
    layout_.columns.push_back(std::move(name));
    layout_.units.push_back(ir::si_unit(quantity, rate));
  }

  Eigen::VectorXd y0_;
  OutputLayout layout_;
  std::vector<std::string> notices_;
  SimulationOptions options_;
  std::string variant_;
};

/// The run `request` asks of `model`. @throws InvalidInput for a request this
/// model cannot run.
std::unique_ptr<ModelRun> make_model_run(const AssembledModel& model, const SimulationRequest& request);

/// A notice per quaternion of the file's initial.q given off unit length
/// (the parser scaled it): into `notices`, or with `strict` an InvalidInput
/// (file:line:col) at the first.
void announce_scaled_quaternions(const ir::Model& model, bool strict, std::vector<std::string>& notices);

std::unique_ptr<ModelRun> make_rigid_run(const AssembledModel& model, const SimulationRequest& request);
/// A model of bodies with closed loops (called by make_rigid_run).
std::unique_ptr<ModelRun> make_loop_run(const AssembledModel& model, const SimulationRequest& request);
std::unique_ptr<ModelRun> make_beam_run(const AssembledModel& model, const SimulationRequest& request);
std::unique_ptr<ModelRun> make_coupled_run(const AssembledModel& model, const SimulationRequest& request);

}  // namespace mbfe::runtime::detail
