#include "runtime/simulation/linearised_model.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>

#include "runtime/errors/invalid_input.h"
#include "runtime/fem/beam_loads.h"
#include "runtime/multibody/rigid_system.h"
#include "runtime/multibody/rigid_tangents.h"

namespace mbfe::runtime {

namespace {

constexpr double kTwoPi = 6.283185307179586;
// An entry of C - alpha M - beta K below this share of the terms it is made
// of is round-off of the assembly, not a discrete part's damping.
constexpr double kRemainderRoundOff = 1e-10;
// Times at which a contact's speed along its beam is sampled over the run
// (the fastest sets the step).
constexpr int kSpeedSamples = 64;
// s: the interval of the difference that gives that speed.
constexpr double kSpeedInterval = 1e-6;
// The step resolves at least this many periods per run (a model whose
// contacts neither move nor bounce).
constexpr double kLeastPeriods = 20.0;

using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

/// The rigid state of the reference motion at t: q0 with the driven
/// coordinates at their motion; velocities those of the motion, 0 elsewhere.
class ReferenceMotion {
 public:
  ReferenceMotion(const CoupledModel& coupled, const Eigen::VectorXd& q0)
      : driven_(coupled.driven()), nb_(coupled.nb()), q0_(q0.head(coupled.nb())), motion_(driven_.make_motion()) {}
  void at(double t, Eigen::VectorXd& q, Eigen::VectorXd& v, Eigen::VectorXd& a) {
    q = q0_;
    v.setZero(nb_);
    a.setZero(nb_);
    if (driven_.empty()) return;
    driven_.motion(t, motion_);
    for (int k = 0; k < driven_.count(); ++k) {
      const int i = driven_.indices()[static_cast<std::size_t>(k)];
      q[i] = motion_.q[k];
      v[i] = motion_.qd[k];
      a[i] = motion_.qdd[k];
    }
  }

 private:
  const DrivenCoordinates& driven_;
  int nb_;
  Eigen::VectorXd q0_;
  DrivenCoordinates::Motion motion_;
};

/// The slowest root's modulus of m r^2 + c r + k = 0 (rad/s).
double slowest_root(const ModalDynamics& mode) {
  const auto roots = modal_roots(mode.c / mode.m, mode.k / mode.m);
  return std::min(std::abs(roots.first), std::abs(roots.second));
}

}  // namespace

std::string linearised_run_unavailable(const AssembledModel& model) {
  const ir::Model& ir = model.ir();
  if (model.kind() != ModelKind::kCoupled) return "no slider_spring contact (a model without bodies)";
  bool springs = false;
  for (const ir::Contact& c : ir.contacts) {
    if (c.is_constraint()) return "a pin or slider_pin contact, whose force is a multiplier, not a spring";
    springs = true;
  }
  if (!springs) return "no slider_spring contact";
  if (!ir.constraints.empty()) return "closed loops between the bodies";
  if (model.coordinates().nq != model.coordinates().nv) return "bodies with quaternion coordinates";
  for (std::size_t i = 0; i < ir.beams.size(); ++i) {
    const ir::Beam& b = ir.beams[i];
    if (b.adjustment.active() && b.adjustment.scope == ir::AdjustmentScope::kJoined)
      return "beam '" + b.name + "' is adjusted in a joined structure (scope joined)";
    const BeamPart& part = model.beams().beams.at(i);
    if (!part.basis.complete)
      return "beam '" + b.name + "' has " + std::to_string(part.system.M.rows()) +
             " DOFs, beyond the dense modal analysis: no complete modal basis";
  }
  return {};
}

std::vector<std::pair<int, double>> discrete_damping(const BeamSystem& beam) {
  const double alpha = beam.rayleigh_alpha, beta = beam.rayleigh_beta;
  const Eigen::SparseMatrix<double> R = beam.C - alpha * beam.M - beta * beam.K;
  std::vector<std::pair<int, double>> out;
  for (int col = 0; col < R.outerSize(); ++col)
    for (Eigen::SparseMatrix<double>::InnerIterator it(R, col); it; ++it) {
      const double scale = std::abs(beam.C.coeff(it.row(), it.col())) +
                           std::abs(alpha * beam.M.coeff(it.row(), it.col())) +
                           std::abs(beta * beam.K.coeff(it.row(), it.col()));
      if (!(std::abs(it.value()) > kRemainderRoundOff * scale)) continue;
      if (it.row() != it.col())
        throw std::invalid_argument("beam '" + beam.name + "': its damping beyond Rayleigh couples DOFs " +
                                    std::to_string(it.row()) + " and " + std::to_string(it.col()));
      out.emplace_back(static_cast<int>(it.row()), it.value());
    }
  return out;
}

LinearisedModel::LinearisedModel(const AssembledModel& model, const LinearisationPoint& point) : model_(model) {
  if (const std::string why = linearised_run_unavailable(model); !why.empty()) throw InvalidInput(why);
  const ir::Model& ir = model.ir();
  const std::shared_ptr<const CoupledModel> coupled = model.coupled_model(false);
  const mbfe_model_v1& kernels = coupled->kernels();
  const int nb = coupled->nb(), nc = coupled->nc();
  if (point.q.size() != nb + nc || point.qd.size() != nb + nc)
    throw std::invalid_argument("linearisation point: " + std::to_string(point.q.size()) + " coordinates, expected " +
                                std::to_string(nb + nc));
  if (!(point.t_end > 0.0)) throw std::invalid_argument("linearisation point: t_end must be positive");

  // The beams' modes.
  const BeamModel& beams = model.beams();
  structure_.dofs = nc;
  for (const BeamPart& part : beams.beams) {
    structure_.blocks.push_back({&part.basis.phi, part.offset, structure_.modes});
    structure_.modes += static_cast<int>(part.basis.phi.cols());
  }
  // The free rigid coordinates and the reference motion.
  std::vector<int> free;
  for (int i = 0; i < nb; ++i)
    if (!coupled->driven().is_driven(i)) free.push_back(i);
  const int nr = static_cast<int>(free.size());
  ReferenceMotion reference(*coupled, point.q);
  Eigen::VectorXd qb, vb, ab;
  reference.at(0.0, qb, vb, ab);
  {
    RowMajor M(nb, nb);
    Eigen::VectorXd F(nb), Q(nb);
    evaluate_dynamics(kernels, qb.data(), vb.data(), 0.0, M.data(), F.data(), Q.data());
    Eigen::MatrixXd K, C;
    rigid_dynamics_tangents(kernels, 0.0, qb.data(), vb.data(), ab.data(), K, C);
    structure_.mass.resize(nr, nr);
    structure_.damping.resize(nr, nr);
    structure_.stiffness.resize(nr, nr);
    for (int i = 0; i < nr; ++i)
      for (int j = 0; j < nr; ++j) {
        structure_.mass(i, j) = M(free[i], free[j]);
        structure_.damping(i, j) = C(free[i], free[j]);
        structure_.stiffness(i, j) = K(free[i], free[j]);
      }
  }
  // Links, and the dashpots of the discrete parts.
  for (const LinkForce* link : coupled->links()) {
    FixedElement e;
    e.name = link->name();
    const LinkGradient& g = link->gradient();
    for (int i = 0; i < g.size; ++i) e.dofs.emplace_back(g.cols[i], g.values[i]);
    e.offset = -link->rest();
    e.law.stiffness = link->stiffness();
    e.law.damping = link->damping();
    e.law.no_pull = link->can_go_slack();
    structure_.fixed.push_back(std::move(e));
  }
  for (const BeamPart& part : beams.beams)
    for (const auto& [dof, c] : discrete_damping(part.system)) {
      FixedElement e;
      e.name = "discrete damping of '" + part.system.name + "'";
      e.dofs.emplace_back(part.offset + dof, 1.0);
      e.law.damping = c;
      structure_.fixed.push_back(std::move(e));
    }
  // The contacts and their laws.
  const std::vector<const SliderSpringForce*>& springs = coupled->slider_springs();
  std::vector<double> bounce;
  std::vector<std::unique_ptr<ForceState>> states;
  for (const SliderSpringForce* spring : springs) {
    const ir::Contact& c = ir.contacts.at(static_cast<std::size_t>(spring->contact()));
    structure_.contact_names.push_back(spring->name());
    ElementLaw law;
    law.damping = spring->damping();
    if (spring->law().hertz) {
      law.hertz = spring->law().coefficient;
      law.compression_only = true;
      law.no_pull = c.unilateral;
    } else {
      law.stiffness = spring->stiffness();
      law.compression_only = law.no_pull = c.unilateral;
    }
    structure_.contact_laws.push_back(law);
    states.push_back(spring->make_state());
  }
  const int ncontacts = static_cast<int>(springs.size());
  Eigen::VectorXd fb_scratch = Eigen::VectorXd::Zero(nb), fc_scratch = Eigen::VectorXd::Zero(nc);
  const Eigen::VectorXd qc0 = point.q.tail(nc), vc0 = Eigen::VectorXd::Zero(nc);
  // One contact at the reference at t (its state left in states[i]).
  const auto contact_at = [&](int i, double t, const Eigen::VectorXd& q,
                              const Eigen::VectorXd& v) -> const SliderSpringForce::State& {
    const ForceArgs args{t, q.data(), v.data(), qc0.data(), vc0.data()};
    ForceSink sink{fb_scratch.data(), fc_scratch.data()};
    springs[static_cast<std::size_t>(i)]->add_force(args, *states[static_cast<std::size_t>(i)], sink);
    return static_cast<const SliderSpringForce::State&>(*states[static_cast<std::size_t>(i)]);
  };

  // The fastest excitation: each body bouncing on its contact spring (the
  // body's own mass, the structure rigid), each contact crossing elements.
  double omega = 0.0;
  for (int i = 0; i < ncontacts; ++i) {
    const SliderSpringForce& spring = *springs[static_cast<std::size_t>(i)];
    const ir::Contact& c = ir.contacts.at(static_cast<std::size_t>(spring.contact()));
    const double mass = ir.bodies.at(static_cast<std::size_t>(c.body)).mass;
    const auto& st = contact_at(i, 0.0, qb, vb);
    const double k = spring.law().hertz ? spring.law_stiffness(st.contact.delta) : spring.stiffness();
    if (mass > 0.0 && k > 0.0) omega = std::max(omega, std::sqrt(k / mass));
    const BeamSystem& beam = beams.beams.at(static_cast<std::size_t>(c.beam)).system;
    Eigen::VectorXd q1, v1, a1;
    for (int j = 0; j < kSpeedSamples; ++j) {
      const double t = point.t_end * j / kSpeedSamples;
      reference.at(t, qb, vb, ab);
      const double s0 = contact_at(i, t, qb, vb).contact.s;
      reference.at(t + kSpeedInterval, q1, v1, a1);
      const double s1 = contact_at(i, t + kSpeedInterval, q1, v1).contact.s;
      omega = std::max(omega, kTwoPi * std::abs(s1 - s0) / kSpeedInterval / beam.element_length);
    }
  }
  for (const BeamPart& part : beams.beams)
    for (const ir::BeamMovingLoad& load : part.system.moving_loads)
      omega = std::max(omega, kTwoPi * std::abs(load.speed) / part.system.element_length);
  omega = std::max(omega, kTwoPi * kLeastPeriods / point.t_end);
  omega_ = omega;

  // The grid and what acts on it.
  const double periods = point.t_end * omega / kTwoPi;
  int steps = static_cast<int>(std::ceil(periods * kLinearisedStepsPerPeriod));
  if (point.step_budget > 0 && steps > point.step_budget)
    steps = static_cast<int>(std::ceil(periods * kLinearisedLeastStepsPerPeriod));
  steps = std::clamp(steps, 1, kLinearisedMaxSteps);
  excitation_.steps = steps;
  excitation_.step = point.t_end / steps;
  excitation_.constant_load.setZero(nc);
  bool timed = false;
  for (const BeamPart& part : beams.beams) {
    excitation_.constant_load.segment(part.offset, part.system.P.size()) = part.system.P;
    timed = timed || part.system.has_time_loads();
  }
  const std::size_t points = static_cast<std::size_t>(steps) + 1;
  excitation_.geometry.resize(points * static_cast<std::size_t>(ncontacts));
  excitation_.rigid_gradients.setZero(nr, static_cast<Eigen::Index>(points) * ncontacts);
  excitation_.rigid_loads.setZero(nr, static_cast<Eigen::Index>(points));
  if (timed) excitation_.timed_loads.resize(points);
  RowMajor M(nb, nb);
  Eigen::VectorXd F(nb), Q(nb), f(nb);
  std::vector<NodalForce> nodal;
  for (std::size_t k = 0; k < points; ++k) {
    const double t = k == points - 1 ? point.t_end : static_cast<double>(k) * excitation_.step;
    reference.at(t, qb, vb, ab);
    // The bodies' loads at the reference: Q - F less the driven coordinates' inertia.
    evaluate_dynamics(kernels, qb.data(), vb.data(), t, M.data(), F.data(), Q.data());
    f = Q - F - M * ab;
    for (int i = 0; i < nr; ++i) excitation_.rigid_loads(i, static_cast<Eigen::Index>(k)) = f[free[i]];
    for (int i = 0; i < ncontacts; ++i) {
      const auto& st = contact_at(i, t, qb, vb);
      ContactGeometry& g = excitation_.geometry[k * static_cast<std::size_t>(ncontacts) + static_cast<std::size_t>(i)];
      if (!st.contact.on_beam) continue;
      g.active = true;
      // delta = offset + g^T q_c + r^T y, exact for the kernel's w = N q_e.
      g.offset = st.contact.delta;
      for (int a = 0; a < 4; ++a) {
        g.dofs[a] = st.gradient.cols[a];
        g.weights[a] = st.gradient.je[a];
        if (g.dofs[a] >= 0) g.offset -= g.weights[a] * qc0[g.dofs[a]];
      }
      const Eigen::Index column = static_cast<Eigen::Index>(k) * ncontacts + i;
      for (int j = 0; j < nr; ++j)
        excitation_.rigid_gradients(j, column) = st.gradient.jb[static_cast<std::size_t>(free[j])];
    }
    if (timed) {
      auto& loads = excitation_.timed_loads[k];
      for (const BeamPart& part : beams.beams) {
        if (!part.system.has_time_loads()) continue;
        time_dependent_loads(part.system, t, nodal);
        for (const NodalForce& n : nodal) loads.emplace_back(part.offset + n.index, n.value);
      }
    }
  }

  // Where the runs start.
  start_.static_start = point.static_start;
  if (!point.static_start) {
    start_.eta.resize(structure_.modes);
    start_.eta_dot.resize(structure_.modes);
    for (const BeamPart& part : beams.beams) {
      const Eigen::Index n = part.system.M.rows(), mb = part.basis.phi.cols();
      const int mode_offset = structure_.blocks[static_cast<std::size_t>(&part - beams.beams.data())].mode_offset;
      start_.eta.segment(mode_offset, mb) =
          part.basis.phi.transpose() * (part.system.M * point.q.segment(nb + part.offset, n));
      start_.eta_dot.segment(mode_offset, mb) =
          part.basis.phi.transpose() * (part.system.M * point.qd.segment(nb + part.offset, n));
    }
    start_.y = Eigen::VectorXd::Zero(nr);
    start_.y_dot.resize(nr);
    for (int i = 0; i < nr; ++i) start_.y_dot[i] = point.qd[free[i]];
  }
}

ModalDynamicsSet LinearisedModel::original_modes() const {
  ModalDynamicsSet out;
  const int n = structure_.modes;
  out.m.resize(n);
  out.c.resize(n);
  out.k.resize(n);
  out.kind.assign(static_cast<std::size_t>(n), ModalDynamicsSet::kDynamic);
  int j = 0;
  for (const BeamPart& part : model_.beams().beams)
    for (const ModalDynamics& mode : part.original) {
      out.m[j] = mode.m;
      out.c[j] = mode.c;
      out.k[j] = mode.k;
      if (slowest_root(mode) > omega_quasi_static())
        out.kind[static_cast<std::size_t>(j)] = ModalDynamicsSet::kQuasiStatic;
      ++j;
    }
  return out;
}

ModalDynamicsSet LinearisedModel::adjusted_modes(const std::vector<const AdjustedModes*>& adjusted) const {
  ModalDynamicsSet out = original_modes();
  const auto& parts = model_.beams().beams;
  int j = 0;
  for (std::size_t b = 0; b < parts.size(); ++b) {
    const BeamPart& part = parts[b];
    const AdjustedModes* given = b < adjusted.size() ? adjusted[b] : nullptr;
    const AdjustedModes& a = given ? *given : part.adjusted;
    if (a.modes.size() != part.original.size() || a.change.size() != part.original.size())
      throw std::invalid_argument("linearised run: beam '" + part.system.name + "' has " +
                                  std::to_string(part.original.size()) + " modes, its adjustment " +
                                  std::to_string(a.modes.size()));
    const bool truncate = a.policy == ir::AdjustmentPolicy::kTruncate;
    for (std::size_t i = 0; i < a.modes.size(); ++i, ++j) {
      if (a.change[i] == ModeChange::kKept) continue;
      const auto at = static_cast<std::size_t>(j);
      if (truncate && a.change[i] == ModeChange::kAdjusted) {
        out.kind[at] = ModalDynamicsSet::kAbsent;
        continue;
      }
      out.m[j] = a.modes[i].m;
      out.c[j] = a.modes[i].c;
      out.k[j] = a.modes[i].k;
      out.kind[at] = ModalDynamicsSet::kDynamic;
    }
  }
  return out;
}

}  // namespace mbfe::runtime
