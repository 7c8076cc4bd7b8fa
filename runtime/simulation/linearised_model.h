// A coupled model as the linearised moving-contact run sees it
// (linearised_run.h; docs/damping-adjustment.md, "The accuracy estimate"):
// every beam in its modes, the bodies linearised about a reference motion,
// the slider_spring contacts moving along their beams, the links and the
// dashpots of the beams' discrete parts, and the loads, all on one time grid.
//
// The reference motion is the run's initial state with the free rigid
// coordinates held and the driven ones following their motion; the bodies'
// M, C, K are the tangents of their equations there (rigid_tangents.h), and a
// contact's place, compression and gradient at t come from its own force
// element at the reference (coupled/slider_spring_force.h), so the profile,
// the camber and the side it presses from are the run's. The step resolves
// the fastest excitation of the contacts (each body bouncing on its contact
// spring, each contact crossing its beam's elements); modes far above it are
// taken quasi-static.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "runtime/damping/modal_adjustment.h"
#include "runtime/simulation/assembled_model.h"
#include "runtime/simulation/linearised_run.h"

namespace mbfe::runtime {

/// Steps per period of the fastest excitation: h = 2 pi / (this omega) (s).
constexpr double kLinearisedStepsPerPeriod = 24.0;
/// The fewest steps per period a run within a step budget may take: the
/// average-acceleration rule's period error is (omega h)^2 / 12, 2.3 % at
/// 12 steps a period against 0.6 % at 24, and both runs of an estimate share
/// it (measured against 24: docs/damping-adjustment.md, "Its cost").
constexpr double kLinearisedLeastStepsPerPeriod = 12.0;
/// Modes whose slowest root exceeds this many times the fastest excitation
/// are quasi-static (unless the adjustment changes them).
constexpr double kQuasiStaticFactor = 4.0;
/// The most steps a linearised run takes (its cost is linear in them).
constexpr int kLinearisedMaxSteps = 200000;
/// A run's estimate takes the linearised run only when its steps are at most
/// this many times the run's own: a step of the linearised run costs a third
/// to a half of an adjusted RK4 step (one pass over the modes against four
/// evaluations) and its two runs go on two threads, so within this budget
/// the estimate costs at most about twice the run's integration (measured:
/// docs/damping-adjustment.md, "Its cost"). It admits the catenaries at
/// their shipped 1e-3 s step at 12 steps a period of the strip crossing
/// their elements.
constexpr double kLinearisedStepsPerRunStep = 5.0;

/// Why the linearised run cannot stand for `model`'s adjusted runs, in a few
/// words ("a pin or slider_pin contact"), or empty when it can.
std::string linearised_run_unavailable(const AssembledModel& model);

/// Where the linearisation is made, and over what time.
struct LinearisationPoint {
  Eigen::VectorXd q, qd;     // [q_b; q_c] and rates: the run's initial state
  bool static_start = true;  // the run starts at its static equilibrium (the linear model starts at its own)
  double t_end = 0.0;        // s
  /// The most steps the linearised run may take for this estimate (0: no
  /// limit): beyond it the grid takes kLinearisedLeastStepsPerPeriod, and
  /// linearised_estimate refuses when even that does not fit.
  int step_budget = 0;
};

class LinearisedModel {
 public:
  /// @throws InvalidInput with linearised_run_unavailable's reason when it is
  /// not empty; std::invalid_argument for a point of the wrong size.
  LinearisedModel(const AssembledModel& model, const LinearisationPoint& point);

  const LinearisedStructure& structure() const { return structure_; }
  const LinearisedExcitation& excitation() const { return excitation_; }
  const LinearisedStart& start() const { return start_; }
  /// rad/s: the fastest excitation, and the quasi-static threshold.
  double omega_excitation() const { return omega_; }
  double omega_quasi_static() const { return kQuasiStaticFactor * omega_; }

  /// The modes of the original model: a mode is quasi-static when its
  /// slowest root exceeds omega_quasi_static().
  ModalDynamicsSet original_modes() const;
  /// The modes of the adjusted model, beam b's from adjusted[b] (null: the
  /// beam's own adjustment, part.adjusted): a mode the adjustment changes
  /// keeps its dynamics, one it keeps is quasi-static as in the original, one
  /// policy truncate removes is absent. @throws std::invalid_argument when an
  /// entry does not fit its beam.
  ModalDynamicsSet adjusted_modes(const std::vector<const AdjustedModes*>& adjusted = {}) const;

 private:
  const AssembledModel& model_;
  LinearisedStructure structure_;
  LinearisedExcitation excitation_;
  LinearisedStart start_;
  double omega_ = 0.0;
};

/// The dashpots of a beam's discrete parts, R = C - alpha M - beta K: its
/// diagonal entries (free DOF, N s/m) that are not round-off. The nodal C
/// is Rayleigh over the elements plus the discrete parts as they are
/// (runtime/fem/beam_system.cpp); the modes carry alpha + beta omega^2, so R
/// is what a modal model misses. @throws std::invalid_argument when R has an
/// entry off its diagonal (no discrete part makes one).
std::vector<std::pair<int, double>> discrete_damping(const BeamSystem& beam);

}  // namespace mbfe::runtime
