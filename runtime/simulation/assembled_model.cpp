#include "runtime/simulation/assembled_model.h"

#include <limits>
#include <string>

#include "runtime/errors/invalid_input.h"
#include "runtime/simulation/adjustment_estimate.h"
#include "runtime/simulation/linearised_estimate.h"
#include "runtime/simulation/static_start_hints.h"
#include "runtime/structure/adjusted_structures.h"

namespace mbfe::runtime {

ModelKind model_kind(const ir::Model& model) {
  if (model.bodies.empty() && model.beams.empty())
    throw InvalidInput("model '" + model.name + "' has neither bodies nor beams");
  if (model.beams.empty()) return ModelKind::kRigid;
  if (model.bodies.empty()) return ModelKind::kBeams;
  return ModelKind::kCoupled;
}

namespace {

// omega_limit of an auto beam while its limit is being chosen: no mode is changed.
constexpr double kAboveEveryMode = std::numeric_limits<double>::max();

/// Whether the linearised run may choose omega_limit: auto (as far as the
/// file tells before the beams are analysed: linearised_run_unavailable
/// decides after).
bool linearised_run_possible(const ir::Model& model, const BeamAnalysisOptions& options) {
  if (model.bodies.empty() || model.beams.empty() || !model.constraints.empty() || model.dimension != 2) return false;
  bool springs = false;
  for (const ir::Contact& c : model.contacts) {
    if (c.is_constraint()) return false;
    springs = true;
  }
  for (const ir::Beam& b : model.beams)
    if ((b.adjustment.active() && b.adjustment.scope == ir::AdjustmentScope::kJoined) ||
        2 * (b.elements + 1) > options.dense_limit)
      return false;
  return springs;
}

}  // namespace

AssembledModel::AssembledModel(ir::Model model, const mbfe_model_v1* kernels, const BeamAnalysisOptions& beams)
    : model_(std::move(model)), kind_(model_kind(model_)) {
  if (!model_.bodies.empty()) {
    if (!kernels)
      throw InvalidInput("model '" + model_.name + "' has bodies: it needs its generated solver");
    coordinates_ = rigid_coordinates(model_);
    if (kernels->model_name != model_.name || kernels->num_coordinates != coordinates_.nq)
      throw InvalidInput("the solver '" + std::string(kernels->model_name) + "' (" +
                         std::to_string(kernels->num_coordinates) + " coordinates) is not the solver of model '" +
                         model_.name + "' (" + std::to_string(coordinates_.nq) + " position coordinates)");
    kernels_ = kernels;
    bodies_ = body_inertias(model_);
  }
  // A coupled model integrates its beams in nodal coordinates (sparse M, C,
  // K): a beam beyond the dense modal path needs only its lowest modes (for
  // the report), or with a per-beam cap every mode the cap keeps; whether its
  // adjustment can be built from them is checked below.
  BeamAnalysisOptions options = beams;
  if (kind_ == ModelKind::kCoupled && options.sparse_modes == 0) options.sparse_modes = kLargeBeamModes;
  if (kind_ == ModelKind::kCoupled && !options.original_only) options.modes_kept_by_cap = true;
  // omega_limit: auto, chosen for its tolerance before the beams are
  // adjusted: by the linearised run where it applies (after the original
  // model is built, below), else by the point figure of each beam.
  const bool linearised = linearised_run_possible(model_, options);
  std::vector<std::size_t> chosen_by_run;
  for (std::size_t i = 0; i < model_.beams.size(); ++i) {
    ir::Adjustment& a = model_.beams[i].adjustment;
    if (!a.present || !a.omega_limit_auto) continue;
    if (a.policy != ir::AdjustmentPolicy::kNone && linearised) {
      chosen_by_run.push_back(i);
      a.omega_limit = kAboveEveryMode;  // for now nothing is changed
    } else if (a.policy != ir::AdjustmentPolicy::kNone) {
      try {
        a.omega_limit = choose_omega_limit(model_, i, options);
      } catch (const InvalidInput&) {
        throw;
      } catch (const std::invalid_argument& e) {
        throw InvalidInput(model_.source_path + ": " + e.what());
      }
    } else {
      a.omega_limit = 1.0;  // policy none changes nothing
    }
    // omega_limit_auto stays set: the limit was chosen (the run's record says so).
  }
  try {
    beams_ = analyse_beams(model_, options);
  } catch (const std::invalid_argument& e) {
    throw InvalidInput(model_.source_path + ": " + e.what());
  }
  // Beams joined by links and adjusted together (scope 'joined'): a coupled
  // model's structures, built when every mode of each is within reach.
  bool any_joined = false;
  for (const ir::Beam& b : model_.beams)
    any_joined = any_joined || (b.adjustment.active() && b.adjustment.scope == ir::AdjustmentScope::kJoined);
  if (any_joined && kind_ == ModelKind::kCoupled) {
    try {
      joined_ = joined_structures(model_, beams_, options.dense_limit);
    } catch (const JoinedStructureError& e) {
      adjustment_unavailable_ = e.what();
      adjustment_unavailable_at_ = model_.beams[e.beam].adjustment.loc;
    }
  }
  if (options.original_only && beams_.any_adjustment) {
    adjustment_unavailable_ = "model '" + model_.name + "' was assembled for runs of the original model only";
    for (const ir::Beam& b : model_.beams)
      if (b.adjustment.active()) adjustment_unavailable_at_ = b.adjustment.loc;
  }
  for (const BeamPart& part : beams_.beams) {
    // The low-rank adjusted operators keep the computed modes and cap the
    // rest uniformly: right only if every mode left out is one the cap changes.
    // (A joined structure's members are adjusted as the structure, above.)
    const ir::Beam& b = model_.beams[&part - beams_.beams.data()];
    if (b.adjustment.scope == ir::AdjustmentScope::kJoined) continue;
    if (adjustment_unavailable_.empty() && part.has_adjustment && !part.basis.complete &&
        !(part.adjusted.adjusted > 0 && part.adjusted.change.back() == ModeChange::kAdjusted &&
          (part.adjusted.uniform || part.adjusted.policy == ir::AdjustmentPolicy::kMass))) {
      adjustment_unavailable_at_ = b.adjustment.loc;
      std::string why;
      if (!part.kept_modes_unavailable.empty())
        why = "the modes its cap keeps could not be found (" + part.kept_modes_unavailable + ")";
      else if (b.adjustment.policy != ir::AdjustmentPolicy::kCap && b.adjustment.policy != ir::AdjustmentPolicy::kMass)
        why = "its policy needs every mode; beyond that limit only the policies cap and mass are built, from the "
              "modes they keep";
      else
        why = "its " + std::to_string(part.basis.omega.size()) + " lowest modes do not reach its adjustment's limit";
      adjustment_unavailable_ = "beam '" + part.system.name + "' has " + std::to_string(part.system.M.rows()) +
                                " DOFs, beyond the dense modal analysis (" + std::to_string(options.dense_limit) +
                                "), and " + why + "; run the original model (adjust off), e.g. with generalized_alpha";
    }
  }
  // Policy mass in a coupled model is built on the beam's stiffness
  // (M_adj = K / k* + ..., structure/adjusted_parts.cpp): a beam its own
  // supports do not hold against rigid motion has a singular K, and its
  // rigid mode would get no mass at all.
  for (const ir::Beam& b : model_.beams) {
    if (!adjustment_unavailable_.empty() || kind_ != ModelKind::kCoupled || !b.adjustment.active() ||
        b.adjustment.policy != ir::AdjustmentPolicy::kMass || b.adjustment.scope == ir::AdjustmentScope::kJoined ||
        held_against_rigid_motion(b))
      continue;
    adjustment_unavailable_at_ = b.adjustment.loc;
    adjustment_unavailable_ = "beam '" + b.name +
                              "': policy mass keeps every mode's stiffness and builds the adjusted "
                              "mass from the beam's stiffness K, which its supports leave singular (" +
                              supports_in_words(b) +
                              ": it can move as a rigid body), so it cannot keep its static "
                              "compliance; give it supports that hold it (two pinned, or one clamped), or use "
                              "policy: cap";
  }
  if (!model_.links.empty()) {
    if (kind_ != ModelKind::kCoupled)
      throw InvalidInput(model_.source_path + ": links join beams in coupled models (with bodies); model '" +
                         model_.name + "' has no bodies");
    links_ = find_link_rest_offsets(model_, beams_);
  }
  if (kind_ == ModelKind::kCoupled) {
    try {
      original_coupled_ = std::make_shared<const CoupledModel>(*kernels_, coupled_beams(beams_, false), bodies_,
                                                              model_.links, links_.rest, model_.contacts);
    } catch (const std::invalid_argument& e) {
      throw InvalidInput(model_.source_path + ": " + e.what());
    }
    if (!chosen_by_run.empty()) choose_limits_by_linearised_run(chosen_by_run, options);
    try {
      if (beams_.any_adjustment && adjustment_unavailable_.empty())
        adjusted_coupled_ = std::make_shared<const CoupledModel>(*kernels_, coupled_beams(beams_, true, joined_),
                                                                bodies_, model_.links, links_.rest, model_.contacts);
    } catch (const std::invalid_argument& e) {
      throw InvalidInput(model_.source_path + ": " + e.what());
    }
  }
}

void AssembledModel::choose_limits_by_linearised_run(const std::vector<std::size_t>& beams,
                                                     const BeamAnalysisOptions& options) {
  std::vector<double> limits;
  if (linearised_run_unavailable(*this).empty()) {
    try {
      limits.assign(beams.size(), choose_common_omega_limit(*this, beams, model_start(*this)));
    } catch (const std::runtime_error&) {
      // A singular linearised run (a body held by nothing at the start):
      // the point figures below.
    }
  }
  if (limits.empty())
    for (const std::size_t i : beams) limits.push_back(choose_omega_limit(model_, i, options));
  for (std::size_t k = 0; k < beams.size(); ++k) model_.beams[beams[k]].adjustment.omega_limit = limits[k];
  try {
    readjust_beams(beams_, model_, beams);
  } catch (const std::invalid_argument& e) {
    throw InvalidInput(model_.source_path + ": " + e.what());
  }
}

bool AssembledModel::resolve_adjusted(std::optional<bool> asked) const {
  const bool adjusted = asked.value_or(beams_.any_adjustment);
  if (adjusted && !adjustment_unavailable_.empty())
    throw InvalidInput(model_.source_path + ":" + std::to_string(adjustment_unavailable_at_.line) + ":" +
                       std::to_string(adjustment_unavailable_at_.column) + ": " + adjustment_unavailable_);
  if (adjusted && !beams_.any_adjustment)
    throw InvalidInput("adjust on: no beam of '" + model_.name +
                       "' has an `adjustment:` block (e.g. adjustment: {omega_limit: 1.0e5, margin: 0.1})");
  return adjusted;
}

void AssembledModel::refuse_truncation(bool adjusted, const std::string& what) const {
  if (!adjusted) return;
  for (const ir::Beam& b : model_.beams) {
    const ir::Adjustment& a = b.adjustment;
    if (!a.active() || a.policy != ir::AdjustmentPolicy::kTruncate) continue;
    throw InvalidInput(model_.source_path + ":" + std::to_string(a.loc.line) + ":" + std::to_string(a.loc.column) +
                       ": beam '" + b.name + "' has policy truncate, which only an explicit integrator runs, in a "
                       "coupled model's split coordinates (no pin or slider_pin contacts, no joined structures); " +
                       what + " (adjust off runs the original model)");
  }
}

std::shared_ptr<const CoupledModel> AssembledModel::coupled_model(bool adjusted) const {
  if (kind_ != ModelKind::kCoupled)
    throw InvalidInput("model '" + model_.name + "' is not a coupled model (bodies and beams)");
  resolve_adjusted(adjusted);  // no adjusted beams without an adjustment block
  return adjusted ? adjusted_coupled_ : original_coupled_;
}

std::shared_ptr<CoupledDynamics> AssembledModel::make_dynamics(bool adjusted) const {
  return std::make_shared<CoupledDynamics>(coupled_model(adjusted));
}

void AssembledModel::initial_coordinates(Eigen::VectorXd& q, Eigen::VectorXd& qd) const {
  const int nq = coordinates_.nq, nv = coordinates_.nv;
  q = Eigen::VectorXd::Zero(nq + beams_.dof);
  qd = Eigen::VectorXd::Zero(nv + beams_.dof);
  for (int i = 0; i < nq; ++i) q[i] = model_.initial.q[i];
  for (int i = 0; i < nv; ++i) qd[i] = model_.initial.qd[i];
}

}  // namespace mbfe::runtime
