// The public C++ API of mbfe (docs/api.md): load a model with its solver,
// evaluate its equations, get its spectrum and stable steps, simulate it
// (whole, with rows to an observer, or a step at a time with a Simulator:
// api/simulator.h), and write results (api/results_output.h,
// api/run_record.h, api/vtk_animation.h).
//
//   #include "api/mbfe.h"
//
//   const mbfe::Model model = mbfe::Model::load("models/paper_platform.yaml");
//   mbfe::runtime::SimulationRequest request = model.request();  // the model's `simulation:` block
//   request.integrator = mbfe::runtime::parse_integrator("rk4");
//   request.step = 2e-5;
//   MyObserver observer;  // a runtime::SimulationObserver: begin(layout), row(row)
//   const mbfe::runtime::SimulationReport report = model.simulate(request, observer);
//
// A Model is cheap to copy (it shares its immutable parts) and safe to use
// from several threads at once: every call builds the workspace it writes.
// The headers here include only the runtime's value types (requests, rows,
// reports, spectra, errors); the runtime's classes stay behind them.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "ir/model.h"
#include "ir/model_error.h"
#include "ir/model_override.h"
#include "runtime/abi/mbfe_model_abi.h"
#include "runtime/advisor/model_spectrum.h"
#include "runtime/damping/beam_analysis_options.h"
#include "runtime/errors/invalid_input.h"
#include "runtime/errors/multibody_errors.h"
#include "runtime/integrators/integrator_spec.h"
#include "runtime/simulation/model_kind.h"
#include "runtime/simulation/simulation_types.h"

namespace mbfe::runtime {
class AssembledModel;
}

namespace mbfe {

struct LoadOptions {
  /// No line on stderr about compiling or reusing the solver.
  bool quiet = true;
  /// How far the beams' modal analysis goes (simulation and the stability
  /// advisor need every mode: at most 2000 DOFs per beam by default).
  runtime::BeamAnalysisOptions beams;
  /// Find the cached solver by the generated sources instead of the file's
  /// SHA-256: files that differ only where the generated code does not look
  /// (a beam's damping, the simulation block) share one compiled solver, at
  /// the price of generating the sources on every load (what `mbfe sweep`
  /// does for its points).
  bool cache_by_sources = false;
  /// Keep the modes a large beam's cap keeps (spectrum slicing, seconds per
  /// beam) in the cache folder and reuse them (api/modal_cache.h), unless
  /// beams.modes_store already names a store.
  bool cache_modes = true;
  /// Values of the file replaced before it is validated (`--set PATH=VALUE`,
  /// ir/model_override.h), in order; an error at one says it came from --set.
  ir::ModelOverrides overrides;
  /// Called with the model as read, before its solver is compiled or loaded:
  /// a program refuses there what the file reveals (an output path onto one
  /// of the files the model reads) without waiting for a compile. What it
  /// throws leaves load or parse.
  std::function<void(const ir::Model&)> on_read;
};

/// M(q), F(q, q'), Q(q, q', t) of the rigid part at one state (M v' + F = Q
/// over the nv velocity coordinates) and, for a model
/// with contacts, the constraints Phi, J_b = dPhi/dq_b, J_c = dPhi/dq_c and
/// gamma = -(dJ/dt) q' (rows stacked over the contacts in file order: 2 per
/// pin, 1 per slider_pin; J_c over every beam coordinate); for a model with
/// closed loops (`constraints:`), their Phi, J = dPhi/dv and gamma with
/// J v' = gamma (the rows of `mbfe eval`'s "loops", docs/model-format.md).
struct Evaluation {
  Eigen::MatrixXd M;  // nv x nv (nb x nb in a planar model)
  Eigen::VectorXd F, Q;
  bool has_constraints = false;
  Eigen::VectorXd phi;    // m
  Eigen::MatrixXd jb;     // m x nb
  Eigen::MatrixXd jc;     // m x nc
  Eigen::VectorXd gamma;  // m
  bool has_loops = false;
  Eigen::VectorXd loop_phi;    // l (m, or a sine or cosine for an orientation row)
  Eigen::MatrixXd loop_j;      // l x nv
  Eigen::VectorXd loop_gamma;  // l
};

/// A state for evaluate(): rigid coordinates (nq positions; planar: one per
/// body) and rates (nv velocities; planar: one per body), model order, beam
/// coordinates and rates (every beam's free DOFs, model order), time. Empty
/// vectors mean zeros (and identity quaternions); a quaternion must be unit
/// (within runtime::kUnitQuaternionTol).
struct State {
  std::vector<double> q, qd, qc, qcd;
  double t = 0.0;  // s
};

class Model {
 public:
  /// Reads a model file and gets its solver: generated and compiled into the
  /// run-time cache on first use ($MBFE_CACHE_DIR, default ~/.cache/mbfe),
  /// loaded from it afterwards.
  /// @throws ir::ModelError (file:line:col) for a bad model file;
  ///         std::runtime_error with the compiler's message if compiling fails.
  static Model load(const std::string& path, const LoadOptions& options = {});

  /// The same from model text in memory; `display_path` names it in messages.
  static Model parse(const std::string& text, const std::string& display_path, const LoadOptions& options = {});

  /// A model file with a solver linked into the program (mbfe_add_model):
  /// `mbfe_model_<name>()`. @throws ir::ModelError for a bad file, or when the
  /// solver was generated from another model or another version of the file
  /// (its SHA-256 differs).
  static Model with_solver(const std::string& path, const mbfe_model_v1* solver);

  /// An IR built by the program itself, with its solver (null for a model
  /// without bodies). @throws runtime::InvalidInput if the solver does not fit.
  static Model from_ir(ir::Model model, const mbfe_model_v1* solver, const LoadOptions& options = {});

  const ir::Model& ir() const;
  runtime::ModelKind kind() const;
  /// The generated solver; null for a model without bodies.
  const mbfe_model_v1* solver() const;
  /// Where the solver was loaded from (empty when linked or absent), and
  /// whether this load compiled it.
  const std::string& solver_library() const;
  bool solver_compiled_now() const;

  /// The model assembled for the numerics (beams assembled and analysed on
  /// first use), for programs that reach into the runtime (include
  /// runtime/simulation/assembled_model.h). @throws runtime::InvalidInput for
  /// a beam the analysis refuses.
  const runtime::AssembledModel& assembled() const;
  /// The model assembled for a run with `adjust` (SimulationRequest::adjust):
  /// a run of a coupled model's original beams (false) does not
  /// need the modes a large beam's cap keeps, and gets a model assembled
  /// without them (once) unless assembled() was built already. Otherwise
  /// assembled(). @throws as assembled().
  const runtime::AssembledModel& assembled_for(std::optional<bool> adjust) const;

  /// M, F, Q and the constraints at `state`; driven coordinates and rates are
  /// the motion's at state.t. @throws runtime::InvalidInput for
  /// a model without bodies, vectors of the wrong size or a quaternion off
  /// unit length;
  /// runtime::SliderOffBeamError when a slider is off its beam.
  Evaluation evaluate(const State& state) const;

  /// The spectrum, original or adjusted (runtime/advisor/model_spectrum.h).
  /// @throws runtime::InvalidInput (adjusted without an adjustment block, a
  ///         fault at the initial state).
  runtime::ModelSpectrum spectrum(bool adjusted) const;

  /// The stable step of every integrator of the advisor, original and (when a
  /// beam has an adjustment block) adjusted.
  std::vector<runtime::StepLimitRow> step_limits() const;

  /// The request of the model's `simulation:` block (integrator, step, end
  /// time; the rest at its defaults): the one place a request starts from.
  /// Change its fields, then simulate. @throws runtime::InvalidInput naming
  /// the integrator when the block names an unknown one.
  runtime::SimulationRequest request() const;

  /// Runs `request` (runtime/simulation/simulate.h); rows go to `observer`.
  /// `keep_going` is asked before every step; false stops the run there
  /// (status interrupted: a caller's Ctrl-C).
  /// @throws runtime::InvalidRequest naming the field of `request` this model
  ///         cannot run, runtime::InvalidInput for other bad input.
  runtime::SimulationReport simulate(const runtime::SimulationRequest& request,
                                     runtime::SimulationObserver& observer,
                                     const runtime::StepMonitor& keep_going = {}) const;

 private:
  struct Shared;  // the IR, the solver and the assembled model (model.cpp)
  explicit Model(std::shared_ptr<const Shared> shared) : shared_(std::move(shared)) {}
  static Model make(ir::Model model, const mbfe_model_v1* solver, std::string library, bool compiled_now,
                    const LoadOptions& options);
  std::shared_ptr<const Shared> shared_;
};

}  // namespace mbfe
