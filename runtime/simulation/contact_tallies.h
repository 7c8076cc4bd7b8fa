// Lift-offs of the slider_spring contacts and slackenings of the links over
// a run (SpringContactTally, LinkSlackTally in simulation_types.h): an
// observer of the accepted steps, reading the force elements' states.
#pragma once

#include <array>
#include <vector>

#include <Eigen/Core>

#include "ir/model.h"
#include "runtime/coupled/coupled_dynamics.h"
#include "runtime/simulation/simulation_types.h"

namespace mbfe::runtime {

class ContactTallies {
 public:
  /// One tally per slider_spring and per link that can go slack of `model`,
  /// whose model file is `ir` (the springs' bodies and points).
  ContactTallies(const CoupledModel& model, const ir::Model& ir);
  /// Nothing to count.
  bool empty() const { return springs_.empty() && links_.empty(); }
  /// Counts the accepted state at t, whose forces `dynamics` has just
  /// evaluated (its spring and link states).
  void count(double t, const CoupledDynamics& dynamics);
  /// Records where each spring's contact point is at the accepted state of
  /// full coordinates q (driven joints imposed): the first call sets the
  /// start, every call the end.
  void place(const CoupledDynamics& dynamics, const Eigen::VectorXd& q);
  const std::vector<SpringContactTally>& springs() const { return springs_; }
  const std::vector<LinkSlackTally>& links() const { return links_; }

 private:
  std::vector<SpringContactTally> springs_;
  std::vector<LinkSlackTally> links_;
  std::vector<int> link_index_;  // per tally: the model's link
  std::vector<std::array<int, 2>> spring_point_;  // per spring: its body and point
  double t_prev_ = 0.0;
};

}  // namespace mbfe::runtime
