// A coupled model (bodies, beams and contacts), eqs (14)-(17) of the paper.
// The formulation is chosen from the request: the partitioned one (default)
// integrates y = [u; q_c; u'; q_c'] with the dependent rigid coordinates
// closed by Newton at every evaluation, in split coordinates when its adjusted
// beams allow; the augmented one y = [q_b; q_c; q_b'; q_c'] with the
// multipliers (a cross-check; |Phi| drifts); the implicit integrators the
// index-3 form. About 440 lines: the run (CoupledRun) holds the formulation,
// the output layout and the tallies of one run, which its observers read.
#include <algorithm>
#include <cmath>
#include <memory>
#include <sstream>

#include "runtime/coupled/augmented_system.h"
#include "runtime/coupled/coordinate_partitioning.h"
#include "runtime/coupled/coupled_implicit_system.h"
#include "runtime/coupled/coupled_tangents.h"
#include "runtime/coupled/linearization.h"
#include "runtime/coupled/split_beam_system.h"
#include "runtime/coupled/tangent_spectrum.h"
#include "runtime/errors/invalid_input.h"
#include "runtime/errors/multibody_errors.h"
#include "runtime/simulation/beam_probes.h"
#include "runtime/simulation/contact_tallies.h"
#include "runtime/simulation/model_run.h"
#include "runtime/simulation/static_start.h"

namespace mbfe::runtime::detail {

namespace {

// A projected coordinate that moved less than this (relative) moved by round-off.
constexpr double kProjectionNoise = 1e-12;

// The linearisation behind a diagnosis of a model with constraint contacts
// is a dense eigenproblem growing as n^3: a diagnosis should take seconds,
// and at 1,927 coordinates it takes 6 minutes (`mbfe stability` still gives
// the limits of larger models). Models without them go through their
// tangents and Arnoldi (seconds at any size).
constexpr int kMaxDiagnosedCoordinates = 1000;

/// Multiplier columns, stacked like the constraint rows: lambda_<contact>_1/_2
/// for a pin, lambda_<contact> for a slider_pin.
std::vector<std::string> multiplier_names(const ir::Model& model) {
  std::vector<std::string> out;
  for (const ir::Contact& c : model.contacts) {
    if (!c.is_constraint()) continue;  // a spring: force_<contact>, after the multipliers
    if (c.type == ir::ContactType::kPin) {
      out.push_back("lambda_" + c.name + "_1");
      out.push_back("lambda_" + c.name + "_2");
    } else {
      out.push_back("lambda_" + c.name);
    }
  }
  return out;
}

/// Per beam coordinate of q_c: whether it is a slope w' (an odd DOF of its
/// node), told by its place in the mesh, not by its name.
std::vector<bool> beam_slopes(const CoupledModel& model) {
  std::vector<bool> out(static_cast<std::size_t>(model.nc()), false);
  for (const CoupledBeam& b : model.beams())
    for (std::size_t full = 0; full < b.mesh.full_to_free.size(); ++full)
      if (const int f = b.mesh.full_to_free[full]; f >= 0) out[static_cast<std::size_t>(b.offset + f)] = full % 2 != 0;
  return out;
}

/// The integrators that step the index-3 form (coupled_implicit_system.h).
bool second_order_implicit(const IntegratorSpec& spec) {
  if (spec.kind == IntegratorKind::kBackwardEuler || spec.kind == IntegratorKind::kTrapezoid ||
      spec.kind == IntegratorKind::kGeneralizedAlpha)
    return true;
  return spec.kind == IntegratorKind::kLinearMultistep && spec.name == "bdf2";
}

class CoupledRun final : public ModelRun {
 public:
  bool adjusted() const override { return adjusted_; }
  CoupledRun(const AssembledModel& model, const SimulationRequest& request) : model_(model), request_(request) {
    index3_ = second_order_implicit(request.integrator);
    // The adjustment exists to widen explicit steps: an implicit integrator runs
    // the original model unless --adjust on asks otherwise (and is refused).
    adjusted_ = index3_ && !request.adjust ? false : model.resolve_adjusted(request.adjust);
    // The index-3 system takes low-rank adjusted beams (the static start uses
    // it), but Newton contracts slowly on them: the two-span catenary's 1.4 s
    // took 190 s against 3 s of adjusted RK4. Not offered until that is understood.
    if (index3_ && adjusted_)
      throw InvalidRequest("adjust", "on with " + request.integrator.name +
                                         ": the implicit integrators run the original model of a coupled model (the "
                                         "adjustment exists for explicit steps); use the original model (adjust off), "
                                         "or an explicit integrator such as rk4");
    const bool augmented = request.formulation == CoupledFormulation::kAugmented;
    dynamics_ = model.make_dynamics(adjusted_);
    probes_ = resolve_probes(request.probes, model.ir(), model.beams());
    // Low-rank adjusted beams step in split coordinates when nothing is
    // partitioned: the same ODE, without passes over their kept modes.
    // A beam's acceleration is read from the nodal q_c'' (split coordinates
    // hold s'' in its place).
    const bool beam_accelerations = std::any_of(probes_.begin(), probes_.end(), [](const BeamProbe& p) {
      return p.acceleration && p.body < 0;
    });
    split_ = !index3_ && !augmented && adjusted_ && !beam_accelerations && dynamics_->split_low_rank_beams();
    if (adjusted_ && !split_)
      model.refuse_truncation(true, augmented            ? "the augmented formulation steps the nodal form"
                                    : beam_accelerations ? "a beam acceleration probe needs the nodal form"
                                                         : "this model cannot be split");
    if (split_) {
      system_ = std::make_unique<SplitBeamSystem>(dynamics_);
    } else if (index3_) {
      try {
        system_ = std::make_unique<CoupledImplicitSystem>(dynamics_);
      } catch (const std::invalid_argument& e) {
        throw InvalidInput(model.ir().source_path + ": " + e.what());
      }
    } else if (augmented) {
      system_ = std::make_unique<AugmentedSystem>(dynamics_);
    } else {
      system_ = std::make_unique<PartitionedSystem>(dynamics_);
    }
    const int n = dynamics_->n();
    model.initial_coordinates(q0_, qd0_);
    dynamics_->impose_motion(0.0, q0_, qd0_);
    if (request.static_start.value_or(model.ir().initial.static_start))
      coupled_static_start(model.ir(), dynamics_, q0_, qd0_);
    try {
      y0_ = state_of(0.0, q0_, qd0_);
    } catch (const ContactError& e) {
      throw InvalidInput(model.ir().source_path + ": inconsistent initial state: " + e.what());
    }
    names_ = dynamics_->model().coordinate_names();
    slopes_ = beam_slopes(dynamics_->model());
    {
      // An initial state off the constraints is projected onto them: say so.
      Eigen::VectorXd q(n), qd(n);
      system_->full_state(0.0, y0_, q, qd);
      // A truncated beam starts at its projection on the kept modes
      // (docs/damping-adjustment.md, "Policy truncate"), not on the contacts.
      std::string truncated;
      if (split_) {
        for (int k : dynamics_->split_structures()) {
          const LowRankStructure& st = *dynamics_->model().structures()[static_cast<std::size_t>(k)];
          if (!st.truncated()) continue;
          const LowRankStructure::Range& r = st.ranges().front();
          const int off = dynamics_->nb() + r.offset;
          std::ostringstream os;
          os << (truncated.empty() ? "" : "; ") << "'" << st.name() << "' (" << st.rank() << " of " << r.size
             << " modes), largest change of a coordinate "
             << (q.segment(off, r.size) - q0_.segment(off, r.size)).cwiseAbs().maxCoeff();
          truncated += os.str();
          q.segment(off, r.size) = q0_.segment(off, r.size);
          qd.segment(off, r.size) = qd0_.segment(off, r.size);
        }
      }
      if (!truncated.empty())
        notices_.push_back("policy truncate: the initial state projected on the kept modes of the beams: " + truncated);
      const std::string moved = projection_moves(q0_, q);
      const std::string moved_rates = projection_moves(qd0_, qd);
      if (!moved.empty() || !moved_rates.empty()) {
        std::string text = "the initial state violates the contacts and was projected onto them:";
        if (!moved.empty()) text += " positions: " + moved + ";";
        if (!moved_rates.empty()) text += " velocities (per s): " + moved_rates + ";";
        if (request.strict) throw InvalidInput(model.ir().source_path + ": " + text + " (strict)");
        notices_.push_back(text);
      }
    }
    build_layout();
    // An unstable beam mode drags the contacts along; catch it while the Newton
    // closure can still follow (a state 1e4 times the largest seen).
    options_.divergence_factor = 1.0e4;
    // What the beams are: a truncation (policy truncate) is no adjustment of damping.
    int truncated_beams = 0, adjusted_beams = 0;
    for (const ir::Beam& b : model.ir().beams) {
      if (!b.adjustment.active()) continue;
      ++(b.adjustment.policy == ir::AdjustmentPolicy::kTruncate ? truncated_beams : adjusted_beams);
    }
    const std::string beams = !adjusted_              ? "original damping"
                              : truncated_beams == 0 ? "adjusted damping"
                              : adjusted_beams == 0  ? "truncated modes"
                                                     : "adjusted damping and truncated modes";
    variant_ = beams + ", " + (index3_ ? "index-3" : augmented ? "augmented" : "partitioned") + " formulation" +
               (split_ ? ", low-rank beams in split coordinates" : "");
    if (adjusted_)
      for (const JoinedStructure& s : model.joined())
        variant_ += ", joined structure " + joined_name(model.ir(), s.beams) + " (" +
                    std::to_string(s.adjusted.modes.size() - s.adjusted.adjusted) + " of " + std::to_string(s.dof) +
                    " modes kept)";
    // The beam DOFs the probes read: with split beams and probes, a row needs
    // only those nodal (unless the observer reads every coordinate).
    rows_at_probes_ = split_ && !probes_.empty() && !request.state_in_rows;
    for (const BeamProbe& p : probes_)
      for (int a = 0; a < 4; ++a)
        if (p.body < 0 && p.weights.free_index[a] >= 0) probe_dofs_.push_back(p.offset + p.weights.free_index[a]);
    tallies_ = std::make_unique<ContactTallies>(dynamics_->model(), model.ir());
  }

  OdeSystem& system() override { return *system_; }

  void row(double t, const Eigen::VectorXd& y, std::vector<double>& values, Eigen::VectorXd* q_out,
           Eigen::VectorXd* qd_out) override {
    const int nb = dynamics_->nb(), n = dynamics_->n(), m = dynamics_->m();
    if (rows_at_probes_)
      system_->full_state_at(t, y, probe_dofs_, q_, qd_);
    else
      system_->full_state(t, y, q_, qd_);
    const ContactReport& contacts = system_->report(t, y);
    dynamics_->impose_motion(t, q_, qd_);
    std::size_t k = 0;
    values[k++] = t;
    for (const Eigen::VectorXd* x : {&q_, &qd_}) {
      for (int i = 0; i < nb; ++i) values[k++] = (*x)[i];
      if (probes_.empty()) {
        for (int i = nb; i < n; ++i) values[k++] = (*x)[i];
      } else {
        for (const BeamProbe& p : probes_)
          if (!p.acceleration) values[k++] = p.value(x->data() + nb);
      }
    }
    for (int r = 0; r < m; ++r) values[k++] = contacts.lambda[r];
    values[k++] = contacts.phi_max;
    const int springs = static_cast<int>(dynamics_->model().slider_springs().size());
    const int links = static_cast<int>(dynamics_->model().links().size());
    for (int s = 0; s < springs; ++s) values[k++] = dynamics_->spring_state(s).force;
    for (int s = 0; s < springs; ++s) values[k++] = dynamics_->spring_state(s).w;
    for (int l = 0; l < links; ++l) values[k++] = dynamics_->link_state(l).tension;
    if (!dynamics_->driven().empty()) {
      dynamics_->drive_reactions(contacts.qdd, reactions_);
      for (Eigen::Index i = 0; i < reactions_.size(); ++i) values[k++] = reactions_[i];
    }
    for (const BeamProbe& p : probes_)
      if (p.acceleration) values[k++] = p.body >= 0 ? contacts.qdd[p.body] : p.value(contacts.qdd.data() + nb);
    if (q_out == nullptr) return;
    if (rows_at_probes_) {
      q_out->resize(0);
      qd_out->resize(0);
    } else {
      *q_out = q_;
      *qd_out = qd_;
    }
  }

  void full_state(double t, const Eigen::VectorXd& y, Eigen::VectorXd& q, Eigen::VectorXd& qd) override {
    system_->full_state(t, y, q, qd);
    dynamics_->impose_motion(t, q, qd);
  }

  Eigen::VectorXd state_of(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd) override {
    const int n = dynamics_->n();
    if (q.size() != n || qd.size() != n)
      throw InvalidInput("the state has " + std::to_string(q.size()) + " / " + std::to_string(qd.size()) +
                         " coordinates, expected " + std::to_string(n) + " ([q_b; q_c])");
    if (!index3_) return system_->initial_state(t, q, qd);
    // Projected onto the contacts as the partitioned formulation does, then
    // handed over in full coordinates.
    PartitionedSystem projection(dynamics_);
    Eigen::VectorXd qp(n), qdp(n);
    projection.full_state(t, projection.initial_state(t, q, qd), qp, qdp);
    return system_->initial_state(t, qp, qdp);
  }

  void accepted(double t, const Eigen::VectorXd& y) override {
    if (tallies_->empty()) return;
    system_->report(t, y);  // evaluates the springs and links at this state
    tallies_->count(t, *dynamics_);
    last_t_ = t;
    last_y_ = y;
    if (!placed_) place(t, y);
  }

  // Where the springs' points are at (t, y) (the tallies' start and end).
  void place(double t, const Eigen::VectorXd& y) const {
    system_->full_state_at(t, y, {}, place_q_, place_qd_);
    dynamics_->impose_motion(t, place_q_, place_qd_);
    tallies_->place(*dynamics_, place_q_);
    placed_ = true;
  }

  void fill(SimulationReport& report) const override {
    // The points at the last accepted state serve only the warnings of a
    // completed run: a state that broke the run keeps the last place found.
    if (placed_ && last_y_.allFinite()) {
      try {
        place(last_t_, last_y_);
      } catch (const std::exception&) {
      }
    }
    report.springs = tallies_->springs();
    report.links = tallies_->links();
  }

  std::optional<StepLimit> stable_limit(const IntegratorSpec& integrator) override {
    // The stable limit of the linearised system at the initial state tells an
    // instability of the integrator from a fault of the model: the
    // eigenvalues `mbfe stability` takes (runtime/advisor/model_spectrum.h),
    // zero modes and round-off growth told from growth of the motion.
    try {
      const std::shared_ptr<CoupledDynamics> dynamics = model_.make_dynamics(adjusted_);
      StateSpectrum spectrum;
      std::vector<std::complex<double>> middle;
      if (dynamics->model().m() == 0) {
        CoupledTangents tangents(*dynamics, 0.0, q0_, qd0_);
        spectrum = tangent_spectrum(tangents);
        middle = middle_of_spectrum(spectrum, adjusted_ ? model_.beams().adjusted : model_.beams().original);
      } else {
        if (dynamics_->n() > kMaxDiagnosedCoordinates) return std::nullopt;
        spectrum = linearized_spectrum(dynamics, 0.0, q0_, qd0_);
      }
      std::vector<std::complex<double>> limiting = split_growing(with_zero_modes(spectrum)).limiting.eigenvalues;
      limiting.insert(limiting.end(), middle.begin(), middle.end());
      return stable_step(integrator, limiting);
    } catch (const std::exception&) {
      return std::nullopt;  // no limit known: the message says only what happened
    }
  }

  void set_beam_load(const std::string& beam, double s, std::function<double(double)> value) override {
    const auto& beams = model_.ir().beams;
    int b = -1;
    for (std::size_t i = 0; i < beams.size(); ++i)
      if (beams[i].name == beam) b = static_cast<int>(i);
    if (b < 0) throw InvalidInput("no beam named '" + beam + "'");
    try {
      dynamics_->set_applied_load(b, s, std::move(value));
    } catch (const std::invalid_argument& e) {
      throw InvalidInput(e.what());
    }
  }

 private:
  /// "link1 by +0.0012 rad, beam_w3 by -1e-05 m": the coordinates the
  /// projection onto the contacts moved (beyond round-off), for the notice.
  std::string projection_moves(const Eigen::VectorXd& before, const Eigen::VectorXd& after) const {
    std::ostringstream os;
    os.precision(6);
    const int nb = static_cast<int>(model_.ir().bodies.size());
    for (Eigen::Index i = 0; i < before.size(); ++i) {
      const double moved = after[i] - before[i];
      if (!(std::abs(moved) > kProjectionNoise * (1.0 + std::abs(before[i])))) continue;
      if (os.tellp() > 0) os << ", ";
      const std::string& name = names_.empty() ? dynamics_->model().coordinate_names()[i] : names_[i];
      os << name << " by " << std::showpos << moved << std::noshowpos;
      const std::string unit = ir::si_unit(quantity(i));
      if (unit != "1") os << " " << unit;
    }
    return os.str();
  }

  /// What coordinate i of [q_b; q_c] measures: a joint's angle or length,
  /// a beam's deflection or slope.
  ir::Quantity quantity(Eigen::Index i) const {
    const int nb = dynamics_->nb();
    return i < nb ? ir::joint_coordinate(model_.ir().bodies[i].joint.type)
                  : ir::beam_dof(slopes_[static_cast<std::size_t>(i - nb)]);
  }

  void build_layout() {
    const int n = dynamics_->n();
    // The positions written (the bodies', then every beam DOF or the
    // displacement probes), each followed later by its rate.
    std::vector<std::pair<std::string, ir::Quantity>> positions;
    for (int i = 0; i < n; ++i)
      if (i < dynamics_->nb() || probes_.empty()) positions.emplace_back(names_[i], quantity(i));
    for (const BeamProbe& p : probes_)
      if (!p.acceleration) positions.emplace_back(p.label, ir::Quantity::kLength);  // accelerations: at the end
    add_column("t", ir::Quantity::kTime);
    for (const auto& [name, quantity] : positions) add_column(name, quantity);
    for (const auto& [name, quantity] : positions) add_column(name + "_dot", quantity, 1);
    for (const std::string& l : multiplier_names(model_.ir())) add_column(l, ir::Quantity::kForce);
    add_column("phi_abs", ir::Quantity::kLength);
    const CoupledModel& cm = dynamics_->model();
    for (const SliderSpringForce* s : cm.slider_springs()) add_column("force_" + s->name(), ir::Quantity::kForce);
    for (const SliderSpringForce* s : cm.slider_springs())
      add_column("deflection_" + s->name(), ir::Quantity::kLength);
    for (const LinkForce* l : cm.links()) add_column("tension_" + l->name(), ir::Quantity::kForce);
    for (int d : dynamics_->driven())
      add_column(model_.ir().bodies[d].name + "_drive", ir::joint_reaction(model_.ir().bodies[d].joint.type));
    // Acceleration probes last: a beam's or a body coordinate's.
    for (const BeamProbe& p : probes_)
      if (p.acceleration) add_column(p.label, p.body >= 0 ? quantity(p.body) : ir::Quantity::kLength, 2);
  }

  const AssembledModel& model_;
  SimulationRequest request_;
  bool index3_ = false, adjusted_ = false, split_ = false, rows_at_probes_ = false;
  std::shared_ptr<CoupledDynamics> dynamics_;
  std::unique_ptr<CoupledSystem> system_;
  std::vector<BeamProbe> probes_;
  std::vector<int> probe_dofs_;
  std::vector<std::string> names_;
  std::vector<bool> slopes_;  // per beam coordinate
  Eigen::VectorXd q0_, qd0_, q_, qd_, reactions_;
  std::unique_ptr<ContactTallies> tallies_;
  // The last accepted state, and scratch for the springs' points there.
  double last_t_ = 0.0;
  Eigen::VectorXd last_y_;
  mutable Eigen::VectorXd place_q_, place_qd_;
  mutable bool placed_ = false;
};

}  // namespace

std::unique_ptr<ModelRun> make_coupled_run(const AssembledModel& model, const SimulationRequest& request) {
  return std::make_unique<CoupledRun>(model, request);
}

}  // namespace mbfe::runtime::detail
