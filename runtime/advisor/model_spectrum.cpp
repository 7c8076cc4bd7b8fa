#include "runtime/advisor/model_spectrum.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <functional>
#include <memory>
#include <vector>

#include "runtime/coupled/coupled_tangents.h"
#include "runtime/coupled/linearization.h"
#include "runtime/coupled/tangent_spectrum.h"
#include "runtime/coupled/truncated_tangents.h"
#include "runtime/errors/multibody_errors.h"
#include "runtime/errors/invalid_input.h"
#include "runtime/multibody/loop_systems.h"
#include "runtime/multibody/tangent_linearization.h"
#include "runtime/simulation/assembled_model.h"
#include "runtime/simulation/settled_state.h"
#include "runtime/simulation/static_start.h"
#include "runtime/structure/low_rank_structure.h"

namespace mbfe::runtime {

namespace {

ModelSpectrum from_linearization(const StateSpectrum& linearized, int coordinates) {
  ModelSpectrum out;
  out.full = with_zero_modes(linearized);
  out.limiting = split_growing(out.full).limiting;
  out.limiting.complete = out.full.complete;
  out.growing = growing_beyond_noise(out.full);
  out.coordinates = coordinates;
  out.linearized = true;
  return out;
}

// A modulus below this share of the largest is a zero mode's round-off (a
// free spin, a neutral direction), not a scale of the motion: a relaxation
// damped and timed by it would take forever to settle.
constexpr double kZeroModeShare = 1e-6;

// The smallest and largest moduli of the eigenvalues of `spectrum` that are
// not zero modes: the scales of its modes, for a dynamic relaxation (false
// when there is none).
bool mode_scales(const ModelSpectrum& spectrum, double& omega_min, double& omega_max) {
  omega_min = 0.0;
  omega_max = 0.0;
  for (const auto& l : spectrum.full.eigenvalues) omega_max = std::max(omega_max, std::abs(l));
  for (const auto& l : spectrum.full.eigenvalues) {
    const double w = std::abs(l);
    if (!(w > kZeroModeShare * omega_max)) continue;
    omega_min = omega_min == 0.0 ? w : std::min(omega_min, w);
  }
  return omega_min > 0.0;
}

// The spectrum at an equilibrium the motion settles into, when it is a
// stable one; otherwise `at_start` (an unstable equilibrium, an inverted
// pendulum, tells less than the state the run starts from).
ModelSpectrum settled_or_start(ModelSpectrum at_start, const std::function<bool(double, double)>& settle,
                               const std::function<ModelSpectrum()>& linearize_settled) {
  double omega_min, omega_max;
  if (at_start.growing == 0 || !mode_scales(at_start, omega_min, omega_max)) return at_start;
  if (!settle(omega_min, omega_max)) return at_start;
  ModelSpectrum out = linearize_settled();
  if (out.growing > 0) return at_start;
  out.at_equilibrium = true;
  out.growing_at_start = at_start.growing;
  return out;
}

// A model with closed loops, linearised as it is integrated: the partitioned
// system y = [q; v_u] in its independent coordinates at the consistent
// initial state, the dependent ones closed by Newton at every evaluation;
// released away from equilibrium, at the equilibrium it settles into.
ModelSpectrum loop_spectrum(const AssembledModel& model, Eigen::VectorXd q, Eigen::VectorXd v, bool static_start) {
  std::unique_ptr<LoopPartitionedSystem> system;
  try {
    system = std::make_unique<LoopPartitionedSystem>(*model.kernels(), model.bodies(), model.coordinates(), q.data());
  } catch (const std::invalid_argument& e) {
    throw InvalidInput(model.ir().source_path + ": " + e.what());
  }
  system->make_consistent(0.0, q, v);
  if (static_start) loop_static_state(model.ir(), *system, q, v);
  const auto linearize = [&]() {
    const Eigen::VectorXd y0 = system->state_of(0.0, q, v);
    const std::vector<int> independent = system->partition().independent;
    if (independent.empty()) {
      // The loops and the drives fix every coordinate: a kinematic model,
      // nothing for an integrator to make unstable.
      ModelSpectrum out;
      out.linearized = true;
      return out;
    }
    const Eigen::MatrixXd a = tangent_jacobian(*system, model.coordinates(), independent, 0.0, y0);
    return from_linearization(balanced_spectrum(a), static_cast<int>(independent.size()));
  };
  ModelSpectrum at_start = linearize();
  if (static_start) return at_start;
  return settled_or_start(
      std::move(at_start),
      [&](double omega_min, double omega_max) {
        return loop_settled_state(model.ir(), *system, omega_min, omega_max, q, v);
      },
      linearize);
}

// A tree with spherical or free joints: y = [q; v] in the three rotation
// increments of each quaternion (not its four components); released away
// from equilibrium, at the equilibrium it settles into.
ModelSpectrum quaternion_spectrum(const AssembledModel& model, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                                  bool static_start) {
  const RigidCoordinates& c = model.coordinates();
  RigidSystem system(*model.kernels(), model.bodies(), c);
  Eigen::VectorXd y0(c.nq + c.nv);
  y0 << q, v;
  normalize_quaternions(c, y0.data());
  system.impose_motion(0.0, y0);
  if (static_start) quaternion_static_state(model.ir(), system, y0);
  std::vector<int> all(c.nv);
  for (int i = 0; i < c.nv; ++i) all[i] = i;
  const auto linearize = [&]() {
    return from_linearization(balanced_spectrum(tangent_jacobian(system, c, all, 0.0, y0)), c.nv);
  };
  ModelSpectrum at_start = linearize();
  if (static_start) return at_start;
  return settled_or_start(
      std::move(at_start),
      [&](double omega_min, double omega_max) {
        return quaternion_settled_state(model.ir(), system, omega_min, omega_max, y0);
      },
      linearize);
}

bool truncated_beams(const CoupledDynamics& dynamics) {
  for (const auto& st : dynamics.model().structures())
    if (st->truncated()) return true;
  return false;
}

bool every_beam_truncated(const ir::Model& model) {
  for (const ir::Beam& b : model.beams)
    if (!b.adjustment.active() || b.adjustment.policy != ir::AdjustmentPolicy::kTruncate) return false;
  return true;
}

// A coupled model with truncated beams (policy truncate), linearised as it is
// integrated: in the kept modes of each beam, from the run's initial state,
// the beams' coordinates projected on those modes as the run projects them.
ModelSpectrum truncated_spectrum(CoupledDynamics& dynamics, Eigen::VectorXd q, Eigen::VectorXd qd) {
  const int nb = dynamics.nb();
  for (const auto& st : dynamics.model().structures()) {
    const LowRankStructure::Range& r = st->ranges().front();
    for (Eigen::VectorXd* x : {&q, &qd}) {
      auto block = x->segment(nb + r.offset, r.size);
      const Eigen::VectorXd eta = st->phi().transpose() * (st->M() * block);
      block = st->phi() * eta;
    }
  }
  CoupledTangents tangents(dynamics, 0.0, q, qd);
  TruncatedTangents reduced(tangents);
  ModelSpectrum out = from_linearization(tangent_spectrum(reduced), reduced.size());
  // Between the two ends of a large spectrum: the kept modes alone, each
  // the roots of m s^2 + c s + k (as the nodal path takes the beams' own).
  std::vector<ModalDynamics> modes;
  const Eigen::Index rigid = reduced.size() - static_cast<Eigen::Index>(reduced.modal_size());
  for (Eigen::Index i = rigid; i < reduced.size(); ++i) {
    ModalDynamics mode;
    mode.m = reduced.mass()(i, i);
    mode.c = reduced.damping()(i, i);
    mode.k = reduced.stiffness()(i, i);
    modes.push_back(mode);
  }
  const std::vector<std::complex<double>> middle = middle_of_spectrum(out.full, state_spectrum(modes));
  if (middle.empty()) return out;
  std::vector<std::complex<double>> limiting = out.limiting.eigenvalues;
  limiting.insert(limiting.end(), middle.begin(), middle.end());
  out.limiting = spectrum_from_eigenvalues(std::move(limiting));
  out.limiting.complete = false;
  out.middle_from_beams = static_cast<int>(middle.size());
  return out;
}

}  // namespace

ModelSpectrum model_spectrum(const AssembledModel& model, bool adjusted) {
  adjusted = model.resolve_adjusted(adjusted);
  if (model.kind() != ModelKind::kCoupled)
    model.refuse_truncation(adjusted, "the stability advisor linearises the nodal model");
  // Linearised where a run starts: the static equilibrium when the model asks for it.
  const bool static_start = model.ir().initial.static_start;
  Eigen::VectorXd q0, qd0;
  model.initial_coordinates(q0, qd0);
  try {
    switch (model.kind()) {
      case ModelKind::kBeams: {
        ModelSpectrum out;
        out.full = adjusted ? model.beams().adjusted : model.beams().original;
        out.limiting = out.full;
        out.coordinates = model.beams().dof;
        return out;
      }
      case ModelKind::kRigid: {
        if (!model.ir().constraints.empty()) return loop_spectrum(model, q0, qd0, static_start);
        if (model.coordinates().has_quaternions()) return quaternion_spectrum(model, q0, qd0, static_start);
        RigidSystem system(*model.kernels(), model.bodies(), model.coordinates());
        const int n = system.num_coordinates();
        Eigen::VectorXd y0(2 * n);
        y0 << q0, qd0;
        system.impose_motion(0.0, y0);
        if (static_start) rigid_static_state(model.ir(), system, y0);
        ModelSpectrum at_start = from_linearization(linearized_spectrum(system, 0.0, y0), n);
        if (static_start) return at_start;
        // Not an equilibrium: the motion swings about the nearest one. None
        // (a mechanism, a free body): the local estimate is all there is.
        Eigen::VectorXd equilibrium = y0;
        return settled_or_start(
            std::move(at_start),
            [&](double omega_min, double omega_max) {
              return rigid_settled_state(model.ir(), system, omega_min, omega_max, equilibrium);
            },
            [&]() { return from_linearization(linearized_spectrum(system, 0.0, equilibrium), n); });
      }
      case ModelKind::kCoupled: {
        const std::shared_ptr<CoupledDynamics> dynamics = model.make_dynamics(adjusted);
        const int n_coupled = dynamics->n();
        const bool from_tangents = linearized_from_tangents(*dynamics);
        if (!from_tangents && n_coupled > kMaxLinearizedCoordinates)
          throw InvalidInput(model.ir().source_path + ": the coupled system has " + std::to_string(n_coupled) +
                             " coordinates and constraint contacts; its linearisation is a dense eigenproblem and "
                             "handles at most " + std::to_string(kMaxLinearizedCoordinates) +
                             " (each beam's own spectrum: mbfe modal; runs: an implicit integrator needs no limit)");
        dynamics->impose_motion(0.0, q0, qd0);
        if (static_start) coupled_static_start(model.ir(), dynamics, q0, qd0);
        if (truncated_beams(*dynamics)) {
          if (!from_tangents || !dynamics->model().splittable())
            model.refuse_truncation(true, "this model cannot be split");
          if (!every_beam_truncated(model.ir()))
            model.refuse_truncation(true, "the stability advisor linearises truncated beams in their kept modes "
                                          "only when every beam of the model is truncated");
          return truncated_spectrum(*dynamics, q0, qd0);
        }
        if (from_tangents) {
          CoupledTangents tangents(*dynamics, 0.0, q0, qd0);
          ModelSpectrum out = from_linearization(tangent_spectrum(tangents), n_coupled);
          std::vector<std::complex<double>> limiting = out.limiting.eigenvalues;
          const std::vector<std::complex<double>> middle =
              middle_of_spectrum(out.full, adjusted ? model.beams().adjusted : model.beams().original);
          if (middle.empty()) return out;
          limiting.insert(limiting.end(), middle.begin(), middle.end());
          out.limiting = spectrum_from_eigenvalues(std::move(limiting));
          out.limiting.complete = false;
          out.middle_from_beams = static_cast<int>(middle.size());
          return out;
        }
        const StateSpectrum full = linearized_spectrum(dynamics, 0.0, q0, qd0);
        return from_linearization(full, static_cast<int>(full.eigenvalues.size()) / 2);
      }
    }
  } catch (const ContactError& e) {
    throw InvalidInput(model.ir().source_path + ": at the initial state: " + e.what());
  } catch (const SingularMassMatrixError& e) {
    throw InvalidInput(model.ir().source_path + ": at the initial state: " + e.what());
  }
  throw InvalidInput("unknown kind of model");
}

bool linearized_from_tangents(const CoupledDynamics& dynamics) { return dynamics.model().m() == 0; }

bool linearized_from_tangents(const AssembledModel& model) {
  return model.kind() == ModelKind::kCoupled && linearized_from_tangents(*model.make_dynamics(false));
}

std::vector<StepLimitRow> step_limit_table(const ModelSpectrum& original, const ModelSpectrum* adjusted) {
  std::vector<StepLimitRow> rows;
  for (const IntegratorSpec& integrator : advisor_integrators()) {
    StepLimitRow row;
    row.integrator = integrator;
    row.original = stable_step(integrator, original.limiting.eigenvalues);
    if (adjusted) row.adjusted = stable_step(integrator, adjusted->limiting.eigenvalues);
    rows.push_back(row);
  }
  return rows;
}

}  // namespace mbfe::runtime
