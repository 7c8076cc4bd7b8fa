// Lift-offs of the slider_spring contacts and slackenings of the links over
// a run (SpringContactTally, LinkSlackTally in simulation_types.h): an
// observer of the accepted steps, reading the force elements' states.
#pragma once

#include <vector>

#include "runtime/coupled/coupled_dynamics.h"
#include "runtime/simulation/simulation_types.h"

namespace mbfe::runtime {

class ContactTallies {
 public:
  /// One tally per slider_spring and per link that can go slack of `model`.
  explicit ContactTallies(const CoupledModel& model);
  /// Nothing to count.
  bool empty() const { return springs_.empty() && links_.empty(); }
  /// Counts the accepted state at t, whose forces `dynamics` has just
  /// evaluated (its spring and link states).
  void count(double t, const CoupledDynamics& dynamics);
  const std::vector<SpringContactTally>& springs() const { return springs_; }
  const std::vector<LinkSlackTally>& links() const { return links_; }

 private:
  std::vector<SpringContactTally> springs_;
  std::vector<LinkSlackTally> links_;
  std::vector<int> link_index_;  // per tally: the model's link
  double t_prev_ = 0.0;
};

}  // namespace mbfe::runtime
