// A model's simulation a step at a time (runtime/simulation/simulator.h
// behind it): advance to a time, read or set the state, read the outputs,
// set a load, go on.
//
//   const mbfe::Model model = mbfe::Model::load("models/bridge_moving_mass.yaml");
//   mbfe::Simulator sim(model, model.request());
//   sim.advance_to(0.3);
//   sim.set_beam_load("deck", 10.0, [](double t) { return -5e3 * std::sin(40.0 * (t - 0.3)); });
//   sim.advance_to(sim.t_end());
//   std::cout << sim.outputs()[sim.column("force_tyre")] << "\n";
//
// It holds the model (a Model is a shared handle), so it may outlive the
// Model it was made from. One thread at a time.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "api/mbfe.h"

namespace mbfe {

namespace runtime {
class Simulator;
}

class Simulator {
 public:
  /// The run `request` asks of `model`, at its initial state (the static
  /// start and the projection onto the contacts done; notices() says what
  /// moved). @throws runtime::InvalidRequest / runtime::InvalidInput as
  /// Model::simulate.
  Simulator(const Model& model, const runtime::SimulationRequest& request);
  ~Simulator();
  Simulator(Simulator&&) noexcept;
  Simulator& operator=(Simulator&&) noexcept;

  const runtime::OutputLayout& layout() const;
  /// The index of an output column. @throws runtime::InvalidInput naming the
  /// columns when there is none of that name.
  int column(const std::string& name) const;
  const std::vector<std::string>& notices() const;
  const std::string& variant() const;

  double time() const;   // s
  double step() const;   // s
  double t_end() const;  // s
  std::int64_t steps() const;
  std::int64_t total_steps() const;
  bool finished() const;
  runtime::SimulationStatus status() const;

  /// Steps to the last step time at or before t (and t_end); `keep_going`
  /// is asked before every step. Returns the status.
  runtime::SimulationStatus advance_to(double t, const runtime::StepMonitor& keep_going = {});
  runtime::SimulationStatus advance_steps(std::int64_t n, const runtime::StepMonitor& keep_going = {});

  /// Full coordinates [q_b; q_c] and rates at the current state, and back
  /// (projected onto the contacts).
  void state(Eigen::VectorXd& q, Eigen::VectorXd& qd);
  void set_state(const Eigen::VectorXd& q, const Eigen::VectorXd& qd);
  /// The output values at the current state (layout() order).
  const std::vector<double>& outputs();
  /// The row at the current state, for an observer (api/results_output.h).
  runtime::OutputRow row();
  /// A point load on a beam (N at t, the beam's transverse direction), from now on.
  void set_beam_load(const std::string& beam, double s, std::function<double(double)> value);
  /// The run so far; for a run that stopped early, why.
  runtime::SimulationReport report();
  /// A fault met evaluating a row, for the report.
  void note_row_fault(const std::string& fault);

 private:
  Model model_;
  std::unique_ptr<runtime::Simulator> sim_;
};

}  // namespace mbfe
