// A model of bodies only: y = [q; q'], y' = [q'; M^-1 (Q - F)].
#include "runtime/errors/invalid_input.h"
#include "runtime/multibody/rigid_system.h"
#include "runtime/simulation/model_run.h"
#include "runtime/simulation/static_start.h"

namespace mbfe::runtime::detail {

namespace {

class RigidRun final : public ModelRun {
 public:
  RigidRun(const AssembledModel& model, const SimulationRequest& request)
      : model_(model), system_(*model.kernels(), model.bodies()) {
    const int n = system_.num_coordinates();
    Eigen::VectorXd q0, qd0;
    model.initial_coordinates(q0, qd0);
    y0_.resize(2 * n);
    y0_ << q0, qd0;
    system_.impose_motion(0.0, y0_);
    if (request.static_start.value_or(model.ir().initial.static_start))
      rigid_static_state(model.ir(), system_, y0_);
    layout_.columns.push_back("t");
    layout_.units.push_back("s");
    for (int i = 0; i < 2 * n; ++i) {
      layout_.columns.push_back(system_.name(i));
      const ir::Body& body = model.ir().bodies[i % n];
      layout_.units.push_back(i < n ? coordinate_unit(body) : rate_unit(body));
    }
    for (int d : system_.driven()) {
      layout_.columns.push_back(model.ir().bodies[d].name + "_drive");
      layout_.units.push_back(model.ir().bodies[d].joint.type == ir::JointType::kRevolute ? "N m" : "N");
    }
  }

  OdeSystem& system() override { return system_; }

  void row(double t, const Eigen::VectorXd& y, std::vector<double>& values, Eigen::VectorXd* q,
           Eigen::VectorXd* qd) override {
    const int n = system_.num_coordinates();
    y_out_ = y;
    system_.impose_motion(t, y_out_);
    values[0] = t;
    for (int i = 0; i < 2 * n; ++i) values[1 + i] = y_out_[i];
    if (!system_.driven().empty()) {
      system_.drive_reactions(t, y_out_, reactions_);
      for (Eigen::Index k = 0; k < reactions_.size(); ++k) values[1 + 2 * n + k] = reactions_[k];
    }
    if (q != nullptr) {
      *q = y_out_.head(n);
      *qd = y_out_.tail(n);
    }
  }

  void full_state(double t, const Eigen::VectorXd& y, Eigen::VectorXd& q, Eigen::VectorXd& qd) override {
    const int n = system_.num_coordinates();
    y_out_ = y;
    system_.impose_motion(t, y_out_);
    q = y_out_.head(n);
    qd = y_out_.tail(n);
  }

  Eigen::VectorXd state_of(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd) override {
    const int n = system_.num_coordinates();
    if (q.size() != n || qd.size() != n)
      throw InvalidInput("the state has " + std::to_string(q.size()) + " / " + std::to_string(qd.size()) +
                         " coordinates, expected " + std::to_string(n) + " (one per body)");
    Eigen::VectorXd y(2 * n);
    y << q, qd;
    system_.impose_motion(t, y);
    return y;
  }

  std::optional<StepLimit> stable_limit(const IntegratorSpec&) override { return std::nullopt; }

 private:
  const AssembledModel& model_;
  RigidSystem system_;
  Eigen::VectorXd y_out_, reactions_;
};

}  // namespace

std::unique_ptr<ModelRun> make_rigid_run(const AssembledModel& model, const SimulationRequest& request) {
  if (request.integrator.kind == IntegratorKind::kGeneralizedAlpha)
    throw InvalidRequest("integrator", "generalized_alpha needs a linear second-order (beam) model; for rigid models "
                                       "use rk4, trapezoid, backward_euler, ...");
  if (request.adjust)
    throw InvalidRequest("adjust", "applies to beam models only ('" + model.ir().name + "' has no beams)");
  if (!request.probes.empty())
    throw InvalidRequest("probes", "apply to beam models only ('" + model.ir().name + "' has no beams)");
  return std::make_unique<RigidRun>(model, request);
}

}  // namespace mbfe::runtime::detail
