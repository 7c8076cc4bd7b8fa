// A model of bodies only: y = [q; q'], y' = [q'; M^-1 (Q - F)].
#include <string>

#include "runtime/errors/invalid_input.h"
#include "runtime/multibody/quaternion_check.h"
#include "runtime/multibody/rigid_coordinates.h"
#include "runtime/multibody/rigid_system.h"
#include "runtime/simulation/model_run.h"
#include "runtime/simulation/static_start.h"

namespace mbfe::runtime::detail {

namespace {

class RigidRun final : public ModelRun {
 public:
  RigidRun(const AssembledModel& model, const SimulationRequest& request)
      : model_(model), system_(*model.kernels(), model.bodies(), model.coordinates()) {
    const RigidCoordinates& c = model.coordinates();
    Eigen::VectorXd q0, qd0;
    model.initial_coordinates(q0, qd0);
    y0_.resize(c.nq + c.nv);
    y0_ << q0, qd0;
    announce_scaled_quaternions(model.ir(), request.strict, notices_);
    if (c.has_quaternions()) {
      // The file's are unit already (and announced above); a model built by
      // a program may not be. Off by more than the file's may be, it was not
      // meant so: say that it was scaled.
      const double error = quaternion_norm_error(c, y0_.data());
      normalize_quaternions(c, y0_.data());
      if (error > kUnitQuaternionTol) {
        const std::string text =
            "the initial quaternions were scaled to unit length (the largest was off by " + std::to_string(error) + ")";
        if (request.strict) throw InvalidInput(model.ir().source_path + ": " + text + " (strict)");
        notices_.push_back(text);
      }
    }
    system_.impose_motion(0.0, y0_);
    if (request.static_start.value_or(model.ir().initial.static_start)) {
      if (c.has_quaternions()) quaternion_static_state(model.ir(), system_, y0_);
      else rigid_static_state(model.ir(), system_, y0_);
    }
    add_column("t", ir::Quantity::kTime);
    for (int i = 0; i < c.nq; ++i) add_column(system_.name(i), c.position_quantity[i]);
    for (int i = 0; i < c.nv; ++i) add_column(system_.name(c.nq + i), c.velocity_quantity[i], 1);
    for (int d : system_.driven()) {
      const ir::Body& body = model.ir().bodies[c.velocity_body[d]];
      add_column(body.name + "_drive", ir::joint_reaction(body.joint.type));
    }
  }

  OdeSystem& system() override { return system_; }

  void row(double t, const Eigen::VectorXd& y, std::vector<double>& values, Eigen::VectorXd* q,
           Eigen::VectorXd* qd) override {
    const int n = system_.num_coordinates(), nv = system_.num_velocities();
    y_out_ = y;
    system_.impose_motion(t, y_out_);
    values[0] = t;
    for (int i = 0; i < n + nv; ++i) values[1 + i] = y_out_[i];
    if (!system_.driven().empty()) {
      system_.drive_reactions(t, y_out_, reactions_);
      for (Eigen::Index k = 0; k < reactions_.size(); ++k) values[1 + n + nv + k] = reactions_[k];
    }
    if (q != nullptr) {
      *q = y_out_.head(n);
      *qd = y_out_.tail(nv);
    }
  }

  void full_state(double t, const Eigen::VectorXd& y, Eigen::VectorXd& q, Eigen::VectorXd& qd) override {
    const int n = system_.num_coordinates(), nv = system_.num_velocities();
    y_out_ = y;
    system_.impose_motion(t, y_out_);
    q = y_out_.head(n);
    qd = y_out_.tail(nv);
  }

  Eigen::VectorXd state_of(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd) override {
    const int n = system_.num_coordinates(), nv = system_.num_velocities();
    if (q.size() != n || qd.size() != nv)
      throw InvalidInput("the state has " + std::to_string(q.size()) + " / " + std::to_string(qd.size()) +
                         " coordinates, expected " + std::to_string(n) + " / " + std::to_string(nv) +
                         " (position / velocity coordinates)");
    Eigen::VectorXd y(n + nv);
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
  if (!model.ir().constraints.empty()) return make_loop_run(model, request);
  return std::make_unique<RigidRun>(model, request);
}

}  // namespace mbfe::runtime::detail
