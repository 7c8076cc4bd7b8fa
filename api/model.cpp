#include <mutex>

#include "api/mbfe.h"

#include "api/modal_cache.h"
#include "api/solver_cache.h"
#include "frontend/parse_model.h"
#include "ir/coordinate_layout.h"
#include "runtime/fem/beam_system.h"
#include "runtime/coupled/contact_constraints.h"
#include "runtime/multibody/quaternion_check.h"
#include "runtime/multibody/rigid_system.h"
#include "runtime/simulation/assembled_model.h"
#include "runtime/simulation/simulate.h"
#include "runtime/structure/coupled_beam.h"

namespace mbfe {

struct Model::Shared {
  ir::Model ir;
  runtime::ModelKind kind = runtime::ModelKind::kRigid;
  const mbfe_model_v1* solver = nullptr;
  std::string solver_library;
  bool compiled_now = false;
  runtime::BeamAnalysisOptions beam_options;
  // Built on first use: the beams' modal analysis is the expensive part, and
  // evaluate() does not need it.
  mutable std::mutex assembled_mutex;
  mutable std::shared_ptr<const runtime::AssembledModel> assembled;
  // Assembled for runs of the original model only (assembled_for(false)).
  mutable std::shared_ptr<const runtime::AssembledModel> original_only;
};

Model Model::make(ir::Model model, const mbfe_model_v1* solver, std::string library, bool compiled_now,
                  const LoadOptions& options) {
  auto shared = std::make_shared<Shared>();
  shared->kind = runtime::model_kind(model);
  if (!model.bodies.empty()) {
    if (!solver) throw runtime::InvalidInput("model '" + model.name + "' has bodies: it needs its generated solver");
    if (solver->abi_version != MBFE_MODEL_ABI_VERSION)
      throw runtime::InvalidInput("the solver of '" + model.name + "' has ABI version " +
                                  std::to_string(solver->abi_version) + ", expected " +
                                  std::to_string(MBFE_MODEL_ABI_VERSION) + " (regenerate it)");
    const int positions = ir::coordinate_layout(model).num_positions;
    if (solver->model_name != model.name || solver->num_coordinates != positions)
      throw runtime::InvalidInput("the solver '" + std::string(solver->model_name) + "' (" +
                                  std::to_string(solver->num_coordinates) +
                                  " coordinates) is not the solver of model '" + model.name + "' (" +
                                  std::to_string(positions) + " position coordinates)");
    // A model read from a file is paired only with the solver generated from
    // those bytes (an IR built in memory has no file to compare).
    const std::string solver_sha256 = solver->model_sha256 ? solver->model_sha256 : "";
    if (!model.source_sha256.empty() && model.source_sha256 != solver_sha256)
      throw runtime::InvalidInput("the solver of '" + model.name +
                                  "' was generated from another version of the model (sha256 " + solver_sha256 +
                                  ", the model's is " + model.source_sha256 + "); rebuild it");
    shared->solver = solver;
  }
  shared->ir = std::move(model);
  shared->solver_library = std::move(library);
  shared->compiled_now = compiled_now;
  shared->beam_options = options.beams;
  if (options.cache_modes && !shared->beam_options.modes_store)
    shared->beam_options.modes_store = disk_modal_store(options.quiet);
  return Model(std::move(shared));
}

namespace {

// The solver of a model with bodies, from the run-time cache.
LoadedSolver cached_solver(const ir::Model& model, const LoadOptions& options) {
  if (model.bodies.empty()) return {};
  return load_solver(model, options.quiet, options.cache_by_sources);
}

}  // namespace

Model Model::load(const std::string& path, const LoadOptions& options) {
  ir::Model model = frontend::load_model_file(path, {}, options.overrides);
  if (options.on_read) options.on_read(model);
  const LoadedSolver solver = cached_solver(model, options);
  return make(std::move(model), solver.model, solver.library_path, solver.compiled_now, options);
}

Model Model::parse(const std::string& text, const std::string& display_path, const LoadOptions& options) {
  ir::Model model = frontend::parse_model_text(text, display_path, {}, options.overrides);
  if (options.on_read) options.on_read(model);
  const LoadedSolver solver = cached_solver(model, options);
  return make(std::move(model), solver.model, solver.library_path, solver.compiled_now, options);
}

Model Model::with_solver(const std::string& path, const mbfe_model_v1* solver) {
  ir::Model model = frontend::load_model_file(path);
  if (solver && model.source_sha256 != solver->model_sha256)
    throw ir::ModelError(path, {},
                         "the linked solver '" + std::string(solver->model_name) +
                             "' was generated from another version of this file (sha256 " + solver->model_sha256 +
                             ", the file's is " + model.source_sha256 + "); rebuild it");
  return make(std::move(model), solver, "", false, {});
}

Model Model::from_ir(ir::Model model, const mbfe_model_v1* solver, const LoadOptions& options) {
  return make(std::move(model), solver, "", false, options);
}

const ir::Model& Model::ir() const { return shared_->ir; }
runtime::ModelKind Model::kind() const { return shared_->kind; }
const mbfe_model_v1* Model::solver() const { return shared_->solver; }
const std::string& Model::solver_library() const { return shared_->solver_library; }
bool Model::solver_compiled_now() const { return shared_->compiled_now; }

const runtime::AssembledModel& Model::assembled() const {
  std::lock_guard<std::mutex> lock(shared_->assembled_mutex);
  if (!shared_->assembled)
    shared_->assembled =
        std::make_shared<const runtime::AssembledModel>(shared_->ir, shared_->solver, shared_->beam_options);
  return *shared_->assembled;
}

const runtime::AssembledModel& Model::assembled_for(std::optional<bool> adjust) const {
  if (adjust.value_or(true) || shared_->kind != runtime::ModelKind::kCoupled) return assembled();
  std::lock_guard<std::mutex> lock(shared_->assembled_mutex);
  if (shared_->assembled) return *shared_->assembled;
  if (!shared_->original_only) {
    runtime::BeamAnalysisOptions options = shared_->beam_options;
    options.original_only = true;
    shared_->original_only = std::make_shared<const runtime::AssembledModel>(shared_->ir, shared_->solver, options);
  }
  return *shared_->original_only;
}

namespace {

Eigen::VectorXd state_vector(const std::vector<double>& values, int n, const char* name, const char* what) {
  if (values.empty()) return Eigen::VectorXd::Zero(n);
  if (static_cast<int>(values.size()) != n)
    throw runtime::InvalidInput(std::string(name) + " has " + std::to_string(values.size()) + " entries, expected " +
                                std::to_string(n) + " (" + what + ")");
  return Eigen::Map<const Eigen::VectorXd>(values.data(), n);
}

}  // namespace

Evaluation Model::evaluate(const State& state) const {
  const ir::Model& model = shared_->ir;
  if (!shared_->solver)
    throw runtime::InvalidInput("model '" + model.name + "' has no bodies: nothing to evaluate (try mbfe modal)");
  const ir::CoordinateLayout layout = ir::coordinate_layout(model);
  Eigen::VectorXd q = state_vector(state.q, layout.num_positions, "q", "position coordinates, in model order");
  Eigen::VectorXd qd = state_vector(state.qd, layout.num_velocities, "qd", "velocity coordinates, in model order");
  if (state.q.empty()) {  // zeros, and identity quaternions
    for (std::size_t b = 0; b < model.bodies.size(); ++b) {
      const ir::JointType type = model.bodies[b].joint.type;
      if (type == ir::JointType::kSpherical || type == ir::JointType::kFree)
        q[layout.first_position[b] + (type == ir::JointType::kFree ? 3 : 0)] = 1.0;
    }
  }
  if (const std::string wrong = runtime::non_unit_quaternion(model, q.data()); !wrong.empty())
    throw runtime::InvalidInput("q: " + wrong);
  const mbfe_model_v1& solver = *shared_->solver;
  if (solver.num_driven > 0) {
    // Driven coordinates are the motion's at t, whatever the state says.
    std::vector<double> dq(solver.num_driven), dqd(solver.num_driven), dqdd(solver.num_driven);
    solver.motion(state.t, dq.data(), dqd.data(), dqdd.data());
    for (int k = 0; k < solver.num_driven; ++k) {
      q[solver.driven_positions ? solver.driven_positions[k] : solver.driven_coordinates[k]] = dq[k];
      qd[solver.driven_coordinates[k]] = dqd[k];
    }
  }
  Evaluation out;
  runtime::RigidTerms terms;
  runtime::evaluate_rigid_terms(*shared_->solver, q, qd, state.t, terms);
  out.M = terms.M;
  out.F = terms.F;
  out.Q = terms.Q;
  if (solver.num_loop_rows > 0) {
    const int rows = solver.num_loop_rows, nv = layout.num_velocities;
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> j(rows, nv);
    out.loop_phi.resize(rows);
    out.loop_gamma.resize(rows);
    solver.loop_constraints(q.data(), out.loop_phi.data());
    solver.loop_jacobian(q.data(), j.data());
    solver.loop_gamma(q.data(), qd.data(), out.loop_gamma.data());
    out.loop_j = j;
    out.has_loops = true;
  }
  if (model.contacts.empty()) {
    if (!state.qc.empty() || !state.qcd.empty())
      throw runtime::InvalidInput("qc/qcd: model '" + model.name +
                                  "' has no contacts (no beam coordinates to evaluate)");
    return out;
  }
  std::vector<runtime::BeamMesh> meshes;
  for (const ir::Beam& b : model.beams) meshes.push_back(runtime::beam_mesh(runtime::assemble_beam(b, model.gravity)));
  const runtime::ContactConstraints constraints(*shared_->solver, meshes);
  const int nc = constraints.num_beam_dofs();
  const Eigen::VectorXd qc = state_vector(state.qc, nc, "qc", "beam coordinates in contract order");
  const Eigen::VectorXd qcd = state_vector(state.qcd, nc, "qcd", "beam coordinates in contract order");
  runtime::ConstraintValues cv;
  constraints.evaluate(state.t, q.data(), qc.data(), qd.data(), qcd.data(), cv);
  out.has_constraints = true;
  out.phi = cv.phi;
  out.jb = cv.jb;
  out.jc = cv.jc_dense(nc);
  out.gamma = cv.gamma;
  return out;
}

runtime::ModelSpectrum Model::spectrum(bool adjusted) const { return runtime::model_spectrum(assembled(), adjusted); }

std::vector<runtime::StepLimitRow> Model::step_limits() const {
  const runtime::ModelSpectrum original = spectrum(false);
  if (!assembled().has_adjustment()) return runtime::step_limit_table(original, nullptr);
  const runtime::ModelSpectrum adjusted = spectrum(true);
  return runtime::step_limit_table(original, &adjusted);
}

runtime::SimulationRequest Model::request() const {
  const ir::Model& model = shared_->ir;
  runtime::SimulationRequest request;
  try {
    request.integrator = runtime::parse_integrator(model.simulation.integrator);
  } catch (const std::invalid_argument& e) {
    throw runtime::InvalidRequest("integrator", e.what());
  }
  request.step = model.simulation.step;
  request.t_end = model.simulation.t_end;
  return request;
}

runtime::SimulationReport Model::simulate(const runtime::SimulationRequest& request,
                                          runtime::SimulationObserver& observer,
                                          const runtime::StepMonitor& keep_going) const {
  runtime::check_request_early(ir(), request);  // before seconds of assembly
  return runtime::simulate(assembled_for(request.adjust), request, observer, keep_going);
}

}  // namespace mbfe
