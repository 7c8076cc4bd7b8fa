// The spectrum of a whole model and the stable step of every integrator for
// it: what `mbfe stability` reports and `mbfe modal` prints for a coupled
// model.
//
//   beams    the eigenvalues of eq (28) of every beam (modal, exact)
//   rigid    y' = f(t, y), y = [q; q'], linearised at the initial state, or
//            at the static equilibrium when the initial state is not one
//            (below)
//   coupled  the partitioned system (eqs (16)-(17)) linearised at the initial
//            state (runtime/coupled/linearization.h)
//
// A linearisation away from an equilibrium has eigenvalues with Re > 0 (the
// motion itself leaves that state); they are counted and left out of the
// limits (split_growing). For a rigid model that is not where its limits are
// set: released from rest away from equilibrium, it swings about the
// equilibrium, and there its modes oscillate (an undamped one gives forward
// Euler no stable step at all, which the mirror image -sigma of a growing
// eigenvalue +sigma at the initial state hides). So a rigid model whose
// initial state has growing eigenvalues is linearised at its static
// equilibrium instead, when it has one (docs/damping-adjustment.md).
#pragma once

#include <optional>
#include <vector>

#include "runtime/integrators/integrator_spec.h"
#include "runtime/modal/state_spectrum.h"
#include "runtime/stability/step_limits.h"

namespace mbfe::runtime {

class AssembledModel;
class CoupledDynamics;

struct ModelSpectrum {
  StateSpectrum full;      // every eigenvalue
  StateSpectrum limiting;  // those that set the step limits (Re <= 0 after rounding; == full for beams)
  /// Eigenvalues that grow beyond the linearisation's noise (growing_beyond_noise);
  /// they and those with Re > 0 within the noise are left out of `limiting`.
  int growing = 0;
  /// Coordinates behind the spectrum: bodies (rigid), beam DOFs (beams), or
  /// the independent coordinates of the partitioned system (coupled).
  int coordinates = 0;
  bool linearized = false;  // rigid and coupled: local, at the initial state
  /// Rigid: linearised at the static equilibrium, not at the initial state,
  /// which has `growing_at_start` eigenvalues with Re > 0.
  bool at_equilibrium = false;
  int growing_at_start = 0;
  /// Coupled, partial spectrum: eigenvalues of the beams' own modes (as the
  /// model's adjustment leaves them) added to `limiting` between the two ends
  /// Arnoldi computes. A lightly damped mode in that middle sets forward
  /// Euler's and AB2's limits; uncoupled, its eigenvalue is an estimate of
  /// the coupled one (the coupling moves it), far closer than none.
  int middle_from_beams = 0;
};

/// A coupled model without constraint contacts is linearised from its own
/// tangents (runtime/coupled/coupled_tangents.h, tangent_spectrum.h): exact
/// but for its force elements' small difference quotients, dense up to
/// kMaxDenseTangentStates states, the two ends of the spectrum by Arnoldi
/// beyond (seconds for the ten-span catenary). One with constraint contacts
/// is linearised on their manifold by differences of the partitioned
/// system's right-hand side (runtime/coupled/linearization.h), dense.
bool linearized_from_tangents(const CoupledDynamics& dynamics);
/// The same for an assembled model (false unless coupled).
bool linearized_from_tangents(const AssembledModel& model);

/// The largest coupled model with constraint contacts (coordinates) that
/// model_spectrum linearises: its dense eigenproblem of twice the
/// coordinates takes hours and gigabytes beyond a few thousand.
inline constexpr int kMaxLinearizedCoordinates = 3000;

/// The spectrum of `model`, original or with its adjusted beams.
/// @throws InvalidInput if adjusted beams are asked for and no beam has an
///         active adjustment block, or the linearisation fails at the initial
///         state (a contact fault, a singular mass matrix: the message says so).
ModelSpectrum model_spectrum(const AssembledModel& model, bool adjusted);

/// The stable step of one integrator for the original and, if known, the
/// adjusted model.
struct StepLimitRow {
  IntegratorSpec integrator;
  StepLimit original;
  std::optional<StepLimit> adjusted;
};

/// One row per integrator of advisor_integrators(), in that order; `adjusted`
/// may be null (no adjustment block).
std::vector<StepLimitRow> step_limit_table(const ModelSpectrum& original, const ModelSpectrum* adjusted);

}  // namespace mbfe::runtime
