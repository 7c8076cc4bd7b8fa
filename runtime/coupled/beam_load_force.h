// The loads of one beam that change with time (runtime/fem/beam_loads.h:
// point loads with an expression in t or a time window, moving loads) as a
// force element. They depend on t alone: no tangent, no coordinate read.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "runtime/coupled/force_element.h"
#include "runtime/fem/beam_loads.h"

namespace mbfe::runtime {

class BeamLoadForce final : public ForceElement {
 public:
  struct State final : ForceState {
    std::vector<NodalForce> nodal;  // the loads at the last evaluation
  };

  /// The time loads of `beam`, whose free DOFs start at `offset` in q_c.
  BeamLoadForce(std::shared_ptr<const BeamSystem> beam, int offset);

  const std::string& name() const override { return name_; }
  std::unique_ptr<ForceState> make_state() const override { return std::make_unique<State>(); }
  void add_force(const ForceArgs& x, ForceState& state, ForceSink& out) const override;
  void add_tangent(const ForceArgs&, const ForceState&, double, double, TangentSink&) const override {}
  void beam_dofs_read(const double*, std::vector<int>&) const override {}

 private:
  std::shared_ptr<const BeamSystem> beam_;
  int offset_;
  std::string name_;
};

}  // namespace mbfe::runtime
