// A model of beams only, integrated in mass-normalised modal coordinates
// (every mode; the same model as the nodal one, see runtime/damping/beam_ode.h),
// original or adjusted; rows in nodal coordinates: t, then the beam
// coordinates in contract order (<beam>_w<node>, <beam>_dw<node>, free DOFs
// only), or the probe columns.
#include "runtime/errors/invalid_input.h"
#include "runtime/fem/beam_loads.h"
#include "runtime/simulation/beam_probes.h"
#include "runtime/simulation/model_run.h"

namespace mbfe::runtime::detail {

namespace {

class BeamRun final : public ModelRun {
 public:
  bool adjusted() const override { return adjusted_; }
  BeamRun(const AssembledModel& model, const SimulationRequest& request)
      : beams_(model.beams()), state_in_rows_(request.state_in_rows) {
    adjusted_ = model.resolve_adjusted(request.adjust);
    model.refuse_truncation(adjusted_, "this is a model of beams alone");
    try {
      ode_ = modal_beam_ode(beams_, adjusted_);
    } catch (const std::invalid_argument& e) {
      throw InvalidInput(e.what());
    }
    n_ = beams_.dof;
    const Eigen::VectorXd y_static = modal_static_state(beams_, adjusted_, *ode_);
    probes_ = resolve_probes(request.probes, model.ir(), beams_);
    add_column("t", ir::Quantity::kTime);
    if (probes_.empty()) {
      for (const BeamPart& b : beams_.beams)
        for (int f : b.system.free_dof) {
          const bool slope = f % 2 != 0;
          add_column(b.system.name + (slope ? "_dw" : "_w") + std::to_string(f / 2), ir::beam_dof(slope));
        }
    } else {
      for (const BeamProbe& p : probes_) {
        add_column(p.label, ir::Quantity::kLength, p.acceleration ? 2 : 0);
        any_acceleration_ = any_acceleration_ || p.acceleration;
      }
    }
    // A probe is a fixed linear map of q = Phi eta: fold it into one row of
    // modal weights, so a probe column costs n flops per row, not n^2.
    probe_rows_.resize(static_cast<Eigen::Index>(probes_.size()), n_);
    for (std::size_t k = 0; k < probes_.size(); ++k) {
      probe_rows_.row(k).setZero();
      for (int e = 0; e < 4; ++e)
        if (probes_[k].weights.free_index[e] >= 0)
          probe_rows_.row(k) +=
              probes_[k].weights.w[e] * ode_->phi().row(probes_[k].offset + probes_[k].weights.free_index[e]);
    }
    options_.reference_norm = y_static.norm();
    // Beams start at rest, undeformed, or in static equilibrium under the loads at t = 0.
    y0_ = request.static_start.value_or(model.ir().initial.static_start) ? y_static : Eigen::VectorXd::Zero(2 * n_);
    variant_ = adjusted_ ? "adjusted damping" : "original damping";
  }

  OdeSystem& system() override { return *ode_; }

  void row(double t, const Eigen::VectorXd& y, std::vector<double>& values, Eigen::VectorXd* q,
           Eigen::VectorXd* qd) override {
    values[0] = t;
    // Nodal coordinates cost n^2 per row: only when a column or the observer
    // needs them.
    const bool state = q != nullptr && state_in_rows_;
    if (probes_.empty() || state) ode_->positions(y, q_);
    if (probes_.empty()) {
      for (int i = 0; i < n_; ++i) values[1 + i] = q_[i];
    } else {
      probe_values_.noalias() = probe_rows_ * y.head(n_);
      // Accelerations: the modal ODE's eta'' at this state (one more
      // evaluation of its right-hand side per row).
      if (any_acceleration_) {
        ode_->rhs(t, y, ydot_);
        probe_accelerations_.noalias() = probe_rows_ * ydot_.tail(n_);
      }
      for (std::size_t k = 0; k < probes_.size(); ++k)
        values[1 + k] = probes_[k].acceleration ? probe_accelerations_[k] : probe_values_[k];
    }
    if (q == nullptr) return;
    if (state) {
      *q = q_;
      qd->noalias() = ode_->phi() * y.tail(n_);
    } else {
      q->resize(0);
      qd->resize(0);
    }
  }

  void full_state(double, const Eigen::VectorXd& y, Eigen::VectorXd& q, Eigen::VectorXd& qd) override {
    ode_->positions(y, q);
    qd.noalias() = ode_->phi() * y.tail(n_);
  }

  Eigen::VectorXd state_of(double, const Eigen::VectorXd& q, const Eigen::VectorXd& qd) override {
    if (q.size() != n_ || qd.size() != n_)
      throw InvalidInput("the state has " + std::to_string(q.size()) + " / " + std::to_string(qd.size()) +
                         " coordinates, expected " + std::to_string(n_) + " (every beam's free DOFs)");
    Eigen::VectorXd nodal(2 * n_);
    nodal << q, qd;
    return ode_->from_nodal(nodal);
  }

  std::optional<StepLimit> stable_limit(const IntegratorSpec& integrator) override {
    return stable_step(integrator, (adjusted_ ? beams_.adjusted : beams_.original).eigenvalues);
  }

  void set_beam_load(const std::string& beam, double s, std::function<double(double)> value) override {
    int b = -1;
    for (std::size_t i = 0; i < beams_.beams.size(); ++i)
      if (beams_.beams[i].system.name == beam) b = static_cast<int>(i);
    if (b < 0) throw InvalidInput("no beam named '" + beam + "'");
    const BeamPart& part = beams_.beams[static_cast<std::size_t>(b)];
    BeamPointWeights w;
    try {
      w = point_weights(part.system, s);
    } catch (const std::invalid_argument& e) {
      throw InvalidInput("beam '" + beam + "': " + e.what());
    }
    applied_.erase(std::remove_if(applied_.begin(), applied_.end(),
                                  [&](const Applied& a) { return a.beam == b && a.s == s; }),
                   applied_.end());
    applied_.push_back({b, s, w, std::move(value)});
    // The modal ODE's time loads: the model's own, then the applied ones.
    ode_->set_time_loads([this, scratch = std::vector<NodalForce>()](double t, std::vector<NodalForce>& out) mutable {
      out.clear();
      for (const BeamPart& p : beams_.beams) {
        if (!p.system.has_time_loads()) continue;
        time_dependent_loads(p.system, t, scratch);
        for (const NodalForce& f : scratch) out.push_back({p.offset + f.index, f.value});
      }
      for (const Applied& a : applied_) {
        const double v = a.value(t);
        const int offset = beams_.beams[static_cast<std::size_t>(a.beam)].offset;
        for (int e = 0; e < 4; ++e)
          if (a.weights.free_index[e] >= 0 && a.weights.w[e] != 0.0)
            out.push_back({offset + a.weights.free_index[e], v * a.weights.w[e]});
      }
    });
  }

 private:
  struct Applied {
    int beam;
    double s;
    BeamPointWeights weights;
    std::function<double(double)> value;
  };
  const BeamModel& beams_;
  bool state_in_rows_;
  bool adjusted_ = false;
  int n_ = 0;
  std::unique_ptr<ModalBeamOde> ode_;
  std::vector<BeamProbe> probes_;
  Eigen::MatrixXd probe_rows_;
  Eigen::VectorXd probe_values_, probe_accelerations_, ydot_, q_;
  bool any_acceleration_ = false;
  std::vector<Applied> applied_;
};

}  // namespace

std::unique_ptr<ModelRun> make_beam_run(const AssembledModel& model, const SimulationRequest& request) {
  return std::make_unique<BeamRun>(model, request);
}

}  // namespace mbfe::runtime::detail
