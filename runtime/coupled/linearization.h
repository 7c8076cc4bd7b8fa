// The linearised, partitioned coupled system at one state: what `mbfe stability`
// and `mbfe modal` analyse for a coupled model.
//
// The partitioned system (eqs (16)-(17)) is y' = f(t, y), y = [z; z'],
// z = [u; q_c]. Its Jacobian is
//
//   A = df/dy = [[0, I], [da/dz, da/dz']]
//
// with a(z, z') the accelerations (v closed by Newton and v' projected inside
// every evaluation, so A is the Jacobian on the constraint manifold). The top
// block is exact; the bottom one is formed by central differences, column by
// column, with steps scaled to each entry (the beam part of a is linear in
// q_c and q_c', so there the differences are exact up to round-off). The
// eigenvalues of A (dense; the paper's platform has 394 states) go to the
// stability advisor (stability/step_limits.h) like a beam's spectrum.
//
// A rigid-only model (RigidSystem, y = [q; q'], a = M(q)^-1 (Q - F)) has the
// same block form and goes through the same OdeSystem overloads.
#pragma once

#include <Eigen/Core>
#include <complex>
#include <vector>

#include "runtime/integrators/ode_system.h"
#include "runtime/modal/state_spectrum.h"
#include "runtime/coupled/coupled_dynamics.h"

namespace mbfe::runtime {

struct LinearizationOptions {
  /// Central-difference step of entry j: rel_step * max(1, |y_j|).
  double rel_step = 1e-6;
  /// Newton closure tolerance (m) while differencing: tighter than the
  /// simulation's 1e-10, so that closure residuals do not pollute the quotients.
  double closure_tol = 1e-13;
};

/// A = df/dy of a second-order `system` (y = [z; z'], see ode_system.h) at
/// (t, y) (size x size). A system with state between calls (the partitioned
/// system's Newton start) is left where an evaluation at y puts it.
/// @throws what system.rhs throws.
Eigen::MatrixXd rhs_jacobian(OdeSystem& system, double t, const Eigen::VectorXd& y,
                             const LinearizationOptions& options = {});

/// Eigenvalues of a dense real matrix, sorted and paired as StateSpectrum does;
/// imaginary parts below 1e-10 |lambda| (rounding of repeated real eigenvalues)
/// are set to zero.
StateSpectrum dense_spectrum(const Eigen::MatrixXd& a);

/// The eigenvalues of a state matrix A = [[A11, A12], [A21, A22]] (2 n x 2 n,
/// positions then rates), balanced first by the similarity diag(I, sigma I),
/// sigma = sqrt(max |A21|) (rates measured in units of sigma). Same
/// eigenvalues, less rounding in the QR iteration.
StateSpectrum balanced_spectrum(Eigen::MatrixXd a);

/// The spectrum of a second-order `system` linearised at (t, y): A from
/// rhs_jacobian, balanced (rates rescaled by sqrt(max |da/dz|)) before the
/// eigenvalues. @throws what system.rhs throws.
StateSpectrum linearized_spectrum(OdeSystem& system, double t, const Eigen::VectorXd& y,
                                  const LinearizationOptions& options = {});

/// The spectrum of the linearised partitioned system at the consistent state
/// y0 = system.initial_state(t, q, qd), A formed with options.closure_tol.
StateSpectrum linearized_spectrum(const std::shared_ptr<CoupledDynamics>& dynamics, double t,
                                  const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                                  const LinearizationOptions& options = {});

/// A linearisation's spectrum split for the stability advisor. Away from an
/// equilibrium (a pendulum released above its pivot, a platform under gravity)
/// the linearisation has eigenvalues with Re > 0: the motion itself leaves the
/// state, and every method follows that growth for small h. Absolute stability
/// concerns the other eigenvalues, so only they set the limits.
struct SplitSpectrum {
  StateSpectrum limiting;  // Re <= 0 (after the rounding below)
  int growing = 0;         // Re > 0, left out
};

/// Relative size of the real part that a conservative system's imaginary
/// eigenvalues pick up from the QR iteration and the differencing (~1e-16 to
/// ~1e-10 |lambda|); a damping ratio this small is no damping, and a growth
/// rate this small is rounding: such real parts are set to 0.
constexpr double kRoundingRe = 1e-9;

SplitSpectrum split_growing(const StateSpectrum& spectrum);

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
/// nothing a step limit depends on. (The tangents' spectrum,
/// tangent_spectrum.h, has the driven coordinates' pairs exactly zero. A free
/// coordinate with neither stiffness nor damping is a defective zero pair,
/// which round-off splits into +-sqrt(eps) ~ 1e-8 max |lambda|: above this,
/// but below kLinearizationNoiseRel, so not counted as growing, and its
/// mirror image sets no limit the fast modes do not set first.)
inline constexpr double kZeroModeRel = 1e-10;

/// The spectrum with every |lambda| <= kZeroModeRel max |lambda| set to 0.
StateSpectrum with_zero_modes(const StateSpectrum& spectrum);

/// The eigenvalues with Re > kLinearizationNoiseRel max |lambda|: the motion's
/// own growth, beyond the linearisation's noise.
int growing_beyond_noise(const StateSpectrum& spectrum);

}  // namespace mbfe::runtime
