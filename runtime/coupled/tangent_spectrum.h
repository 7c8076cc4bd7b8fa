// The eigenvalues of a coupled model linearised from its own tangents
// (coupled_tangents.h), or from their projection on truncated structures'
// kept modes (truncated_tangents.h): A = [[0, I], [-M^-1 K_t, -M^-1 C_t]]
// over the free coordinates, and an exact zero pair for every driven
// coordinate.
//
// Small models: A formed column by column (n_f products and solves) and the
// balanced dense eigen-decomposition, every eigenvalue. Large models (the
// catenaries: thousands of beam DOFs, where that decomposition takes many
// minutes and gigabytes) get the two ends of the spectrum by the implicitly
// restarted Arnoldi method (Spectra), with nothing of size n x n formed:
//
//   the fastest   the largest |lambda| of A, from products by A; they set the
//                 stable steps of the explicit methods (|h lambda| within a
//                 region of size ~2 to 2.8 around the origin)
//   the slowest   the largest |mu| of (A - sigma I)^-1 (shifted solves,
//                 sigma = 0 unless that is singular), lambda = sigma + 1/mu:
//                 the zero modes, the motion's own growth away from an
//                 equilibrium and the slow, lightly damped modes that make
//                 forward Euler and AB2 "none" when undamped
//
// The middle of the spectrum is not computed (StateSpectrum::complete is
// false): a mode there whose damping ratio is far below those of both ends
// would lower forward Euler's limit (-2 Re / |lambda|^2) without being seen.
// With Rayleigh or modally adjusted damping that ratio is smallest at one end
// (docs/damping-adjustment.md, "The stability advisor").
#pragma once

#include <complex>
#include <vector>

#include "runtime/coupled/coupled_tangents.h"
#include "runtime/coupled/state_operator.h"
#include "runtime/modal/state_spectrum.h"

namespace mbfe::runtime {

/// Models with up to this many state eigenvalues (2 n_f) get the dense,
/// complete spectrum (the shipped vehicle models have 164 to 254 states and
/// decompose in well under a second; the dense QR grows as states^3).
inline constexpr int kMaxDenseTangentStates = 1200;

/// Eigenvalues computed at each end of a large model's spectrum (conjugate
/// pairs count twice). The fastest few set the explicit methods' limits; more
/// cost restarts on the cluster at the top (a beam mesh's top modes, an
/// adjusted structure's capped root repeated for every capped mode). The
/// slowest hold the zero modes, the motion's own growth and the slow modes.
inline constexpr int kFastestEigenvalues = 8;
inline constexpr int kSlowestEigenvalues = 12;

struct TangentSpectrumOptions {
  int max_dense_states = kMaxDenseTangentStates;
  int fastest = kFastestEigenvalues;
  int slowest = kSlowestEigenvalues;
};

/// The spectrum of `tangents`' A, plus 2 exact zeros per driven coordinate;
/// eigenvalues below 1e-6 of the stiffness scale (~omega_max) are zero modes
/// and set to 0 (tangent_spectrum.cpp says why).
/// complete = false for the two ends of a large model. Leaves `tangents`
/// factored at the last shift used.
/// @throws std::runtime_error when the Arnoldi iteration does not converge
///         (the message says at which end).
StateSpectrum tangent_spectrum(StateOperator& tangents, const TangentSpectrumOptions& options = {});

/// What fills the middle of a partial spectrum: the eigenvalues of `source`
/// (the beams' own modes, as the model's adjustment leaves them) with Re <= 0
/// and a modulus strictly between the two ends of `partial` (its last
/// `fastest` entries by modulus are the fast end). A lightly damped mode there
/// sets forward Euler's and AB2's limits; uncoupled, its eigenvalue estimates
/// the coupled one (the contacts and links move it), where leaving it out
/// overstated forward Euler's limit 8 times on the two-span catenary
/// (docs/damping-adjustment.md, "The stability advisor"). Empty for a complete
/// `partial`.
std::vector<std::complex<double>> middle_of_spectrum(const StateSpectrum& partial, const StateSpectrum& source,
                                                     int fastest = kFastestEigenvalues);

}  // namespace mbfe::runtime
