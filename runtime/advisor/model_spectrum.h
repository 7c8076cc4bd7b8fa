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

#include "runtime/integrators/integrator.h"
#include "runtime/modal/state_spectrum.h"
#include "runtime/stability/step_limits.h"

namespace mbfe::runtime {

class AssembledModel;

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
};

/// A linearisation's eigenvalues carry the error of its difference quotients
/// (runtime/coupled/linearization.h: central differences with a relative
/// step of 1e-6, so about eps / 1e-6 = 2e-10 of the terms an acceleration is
/// summed from, amplified where those terms cancel: the adjusted beams'
/// low-rank operators subtract terms k* / omega_1^2 ~ 1e4 times the result).
/// The eigenvalues inherit it relative to the largest |lambda|: an undamped
/// mode of the shipped vehicle models comes out with Re up to +6.7e-9
/// max |lambda| (adjusted). A positive real part up to this share of
/// max |lambda| is that noise, not growth of the motion: it is not counted as
/// growing (the eigenvalue is still left out of the limits, as every Re > 0
/// is). The constant is 15 times the largest measured; a true growth that slow
/// is not what step limits are about: at RK4's limit (~2.8 / max |lambda|) it
/// grows by exp(2.8e-7 N) over N steps, 3 % in 1e5.
inline constexpr double kLinearizationNoiseRel = 1e-7;

/// A zero mode (a driven coordinate, a rigid-body motion, a neutral
/// equilibrium) has an exactly zero Jacobian column and comes out of the
/// eigen-solver at ~1e-16 max |lambda| (measured on the shipped vehicle
/// models); an eigenvalue below this share of max |lambda| is set to 0. A
/// physical mode that slow turns by 2.8e-10 rad per step at RK4's limit:
/// nothing a step limit depends on.
inline constexpr double kZeroModeRel = 1e-10;

/// The spectrum with every |lambda| <= kZeroModeRel max |lambda| set to 0.
StateSpectrum with_zero_modes(const StateSpectrum& spectrum);

/// The eigenvalues with Re > kLinearizationNoiseRel max |lambda|: the motion's
/// own growth, beyond the linearisation's noise.
int growing_beyond_noise(const StateSpectrum& spectrum);

/// The largest coupled model (coordinates) model_spectrum linearises: its
/// dense eigenproblem of twice the coordinates takes hours and gigabytes
/// beyond a few thousand.
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
