// A coupled model (bodies + beams + contacts) ready to simulate or linearise:
// the generated solver, the beams (original or with their modal adjustment of
// damping) and the CoupledDynamics of runtime/multibody/. Shared by
// `mbfe simulate`, `mbfe eval`, the stability advisor, the tests and the
// benchmark.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <optional>
#include <vector>

#include "runtime/damping/beam_model.h"
#include "ir/model.h"
#include "runtime/modal/state_spectrum.h"
#include "runtime/multibody/coupled_system.h"
#include "tool/simulate_options.h"
#include "tool/solver_cache.h"

namespace mbfe::tool {

struct CoupledModel {
  LoadedSolver solver;
  runtime::BeamModel beams;   // assembled and analysed (every mode), model order
  bool adjusted = false;      // beams carry their adjusted C and K
  std::shared_ptr<runtime::CoupledDynamics> dynamics;
  Eigen::VectorXd q0, qd0;    // initial [q_b; q_c] and rates (beams at rest, undeformed)
};

/// True for a model with bodies and beams (contacts optional).
bool is_coupled(const ir::Model& model);

/// Builds the coupled model. adjust: absent = adjusted when some beam has an
/// `adjustment:` block. @throws UsageError for --adjust on without a block,
/// std::invalid_argument for a beam the assembly rejects.
CoupledModel load_coupled(const ir::Model& model, std::optional<bool> adjust, bool quiet);

/// The beam's internal force C q' + K q, original (sparse Rayleigh) or adjusted
/// (low rank, method-notes section 3, for a uniform cap; eq (27) otherwise).
runtime::BeamForceFn beam_force(const runtime::BeamPart& beam, bool adjusted);

/// The beam's free acceleration M^-1 (P - C q' - K q) without a solve, for the
/// low-rank adjusted beam (M^-1 U = Phi_L: a = M^-1 P - (s_C q' + s_K q) -
/// Phi_L (d_C .* U^T q' + d_K .* U^T q)); empty for the others.
runtime::BeamForceFn beam_acceleration(const runtime::BeamPart& beam, bool adjusted);

/// The spectrum of the linearised, partitioned system at the model's initial
/// state (runtime/multibody/linearization.h), original or adjusted beams.
runtime::StateSpectrum coupled_spectrum(const ir::Model& model, bool adjusted, bool quiet = true);

/// `mbfe simulate` of a coupled model: partitioned (eqs (16)-(17)) or augmented
/// formulation (tool/simulate_coupled.cpp). Returns the exit status (0, 2 or 3).
int simulate_coupled(const ir::Model& model, const SimulateOptions& options, bool augmented);

/// CSV names of the multipliers, stacked like the constraint rows:
/// lambda_<contact>_1/_2 for a pin, lambda_<contact> for a slider_pin.
std::vector<std::string> coupled_multiplier_names(const ir::Model& model);

}  // namespace mbfe::tool
