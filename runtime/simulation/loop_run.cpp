// A model of bodies with closed loops: the partitioned formulation (default)
// or the augmented one (--formulation augmented), from a consistent initial
// state (or the equilibrium on the loops, for a static start); rows t, q, v,
// loop_residual and a <body>_drive per driven joint (docs/partitioning.md,
// "Closed loops").
#include <cmath>
#include <memory>
#include <sstream>

#include "runtime/errors/invalid_input.h"
#include "runtime/errors/multibody_errors.h"
#include "runtime/multibody/loop_systems.h"
#include "runtime/simulation/model_run.h"
#include "runtime/simulation/static_start.h"

namespace mbfe::runtime::detail {

namespace {

// A projected coordinate that moved less than this (relative) moved by round-off.
constexpr double kProjectionNoise = 1e-12;

// "3 rows of loop 'coupler_rocker' repeat ...": the rows the closure left out
// (LoopClosure), loop by loop in file order; empty when none.
std::string redundant_rows_notice(const LoopClosure& closure) {
  std::vector<std::pair<std::string, int>> per_loop;
  for (const std::string& loop : closure.redundant_row_loops()) {
    if (per_loop.empty() || per_loop.back().first != loop) per_loop.emplace_back(loop, 0);
    ++per_loop.back().second;
  }
  std::string text;
  for (const auto& [loop, rows] : per_loop)
    text += (text.empty() ? "" : "; ") + std::to_string(rows) + (rows == 1 ? " row" : " rows") + " of loop '" + loop +
            "' repeat" + (rows == 1 ? "s" : "") + " the conditions of the others";
  if (text.empty()) return text;
  return text + " at the initial state (as when every joint axis of a linkage is parallel) and " +
         (closure.redundant_rows().size() == 1 ? "is" : "are") +
         " left out of the closure; loop_residual still measures every row";
}

class LoopRun final : public ModelRun {
 public:
  LoopRun(const AssembledModel& model, const SimulationRequest& request) : model_(model) {
    const RigidCoordinates& c = model.coordinates();
    const bool augmented = request.formulation == CoupledFormulation::kAugmented;
    announce_scaled_quaternions(model.ir(), request.strict, notices_);
    Eigen::VectorXd q0, v0;
    model.initial_coordinates(q0, v0);
    // Loop rows that repeat the others are found at the initial state, as
    // given (every system of this run from the same).
    const Eigen::VectorXd q_given = q0;
    try {
      if (augmented) system_ = std::make_unique<LoopAugmentedSystem>(*model.kernels(), model.bodies(), c, q_given.data());
      else system_ = std::make_unique<LoopPartitionedSystem>(*model.kernels(), model.bodies(), c, q_given.data());
    } catch (const std::invalid_argument& e) {
      throw InvalidInput(model.ir().source_path + ": " + e.what());
    }
    if (const std::string text = redundant_rows_notice(system_->closure()); !text.empty()) notices_.push_back(text);
    system_->closure().impose_motion(0.0, q0.data(), v0.data());  // the motion fixes them: nothing to announce
    Eigen::VectorXd q = q0, v = v0;
    const bool static_start = request.static_start.value_or(model.ir().initial.static_start);
    try {
      system_->make_consistent(0.0, q, v);
      if (static_start) {
        // Found by the partitioned system whatever the formulation run.
        LoopPartitionedSystem partitioned(*model.kernels(), model.bodies(), c, q_given.data());
        loop_static_state(model.ir(), partitioned, q, v);
        v0.setZero();  // the velocities are the equilibrium's: nothing to announce
      }
      y0_ = system_->state_of(0.0, q, v);
    } catch (const ContactError& e) {
      throw InvalidInput(model.ir().source_path + ": inconsistent initial state: " + e.what());
    }
    // Velocities left at zero (not given) are completed from J v = nu without
    // a word; a velocity given and changed is announced.
    // A static start moves the positions on purpose: nothing to announce.
    const std::string moved = static_start ? "" : moves(q0, q, c.position_columns, c.position_quantity, 0, false);
    const std::string moved_rates = moves(v0, v, c.velocity_columns, c.velocity_quantity, 1, true);
    if (!moved.empty() || !moved_rates.empty()) {
      std::string text = "the initial state does not close the loops and was projected onto them:";
      if (!moved.empty()) text += " positions: " + moved + ";";
      if (!moved_rates.empty()) text += " velocities: " + moved_rates + ";";
      if (request.strict) throw InvalidInput(model.ir().source_path + ": " + text + " (strict)");
      notices_.push_back(text);
    }
    add_column("t", ir::Quantity::kTime);
    for (int i = 0; i < c.nq; ++i) add_column(c.position_columns[i], c.position_quantity[i]);
    for (int i = 0; i < c.nv; ++i) add_column(c.velocity_columns[i], c.velocity_quantity[i], 1);
    add_column("loop_residual", ir::Quantity::kLength);
    for (int d : system_->closure().driven_velocities()) {
      const ir::Body& body = model.ir().bodies[c.velocity_body[d]];
      add_column(body.name + "_drive", ir::joint_reaction(body.joint.type));
    }
    variant_ = augmented ? "augmented formulation" : "partitioned formulation";
  }

  OdeSystem& system() override { return *system_; }

  void row(double t, const Eigen::VectorXd& y, std::vector<double>& values, Eigen::VectorXd* q,
           Eigen::VectorXd* qd) override {
    system_->full_state(t, y, q_, v_);
    values[0] = t;
    std::size_t k = 1;
    for (Eigen::Index i = 0; i < q_.size(); ++i) values[k++] = q_[i];
    for (Eigen::Index i = 0; i < v_.size(); ++i) values[k++] = v_[i];
    values[k++] = system_->closure().residual(q_.data());
    if (system_->closure().driven_rows() > 0) {
      system_->drive_reactions(t, y, reactions_);
      for (Eigen::Index i = 0; i < reactions_.size(); ++i) values[k++] = reactions_[i];
    }
    if (q != nullptr) {
      *q = q_;
      *qd = v_;
    }
  }

  void full_state(double t, const Eigen::VectorXd& y, Eigen::VectorXd& q, Eigen::VectorXd& qd) override {
    system_->full_state(t, y, q, qd);
  }

  Eigen::VectorXd state_of(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd) override {
    const RigidCoordinates& c = model_.coordinates();
    if (q.size() != c.nq || qd.size() != c.nv)
      throw InvalidInput("the state has " + std::to_string(q.size()) + " / " + std::to_string(qd.size()) +
                         " coordinates, expected " + std::to_string(c.nq) + " / " + std::to_string(c.nv) +
                         " (position / velocity coordinates)");
    Eigen::VectorXd qc = q, vc = qd;
    system_->make_consistent(t, qc, vc);
    return system_->state_of(t, qc, vc);
  }

  std::optional<StepLimit> stable_limit(const IntegratorSpec&) override { return std::nullopt; }

 private:
  /// "coupler by -0.0012 rad, rod_qw by +1e-05": what the projection moved.
  static std::string moves(const Eigen::VectorXd& before, const Eigen::VectorXd& after,
                           const std::vector<std::string>& names, const std::vector<ir::Quantity>& quantities,
                           int rate, bool given_only) {
    std::ostringstream os;
    os.precision(6);
    for (Eigen::Index i = 0; i < before.size(); ++i) {
      if (given_only && before[i] == 0.0) continue;
      const double moved = after[i] - before[i];
      if (!(std::abs(moved) > kProjectionNoise * (1.0 + std::abs(before[i])))) continue;
      if (os.tellp() > 0) os << ", ";
      os << names[i] << " by " << std::showpos << moved << std::noshowpos;
      const std::string unit = ir::si_unit(quantities[i], rate);
      if (unit != "1") os << " " << unit;
    }
    return os.str();
  }

  const AssembledModel& model_;
  std::unique_ptr<LoopSystem> system_;
  Eigen::VectorXd q_, v_, reactions_;
};

}  // namespace

std::unique_ptr<ModelRun> make_loop_run(const AssembledModel& model, const SimulationRequest& request) {
  return std::make_unique<LoopRun>(model, request);
}

}  // namespace mbfe::runtime::detail
