// A model put together for the numerics: its IR, its generated kernels, its
// beams assembled and analysed (original and adjusted), and, for a coupled
// model, the beams as the coupled dynamics sees them. simulate() and
// model_spectrum() work on it. Built once and constant afterwards; everything
// a run writes into (CoupledDynamics, the systems) is made fresh per run, so
// one AssembledModel can serve several runs, also from several threads.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "ir/model.h"
#include "runtime/simulation/model_kind.h"
#include "runtime/abi/mbfe_model_abi.h"
#include "runtime/damping/beam_model.h"
#include "runtime/coupled/coupled_dynamics.h"
#include "runtime/coupled/coupled_model.h"
#include "runtime/multibody/rigid_system.h"
#include "runtime/structure/joined_structures.h"
#include "runtime/structure/link_form_finding.h"

namespace mbfe::runtime {

class AssembledModel {
 public:
  /// @param kernels the generated solver of `model`: required when the model
  ///        has bodies (it must outlive this object), ignored otherwise.
  /// @throws InvalidInput if kernels are missing or belong to another model
  ///         (other name or coordinate count), or for a beam the assembly or
  ///         the modal analysis rejects (the message names the beam).
  AssembledModel(ir::Model model, const mbfe_model_v1* kernels, const BeamAnalysisOptions& beams = {});

  ModelKind kind() const { return kind_; }
  const ir::Model& ir() const { return model_; }
  /// Null for a beam-only model.
  const mbfe_model_v1* kernels() const { return kernels_; }
  const BeamModel& beams() const { return beams_; }
  /// Some beam has an active `adjustment:` block.
  bool has_adjustment() const { return beams_.any_adjustment; }

  /// Whether a run uses the adjusted beams: `asked`, or, when absent, whether
  /// some beam has an active adjustment block.
  /// @throws InvalidInput when adjusted beams are asked for and no beam has an
  ///         active adjustment block.
  bool resolve_adjusted(std::optional<bool> asked) const;

  /// Policy truncate (a modal truncation) is integrated only in split
  /// coordinates by an explicit integrator (docs/damping-adjustment.md,
  /// "Policy truncate"). With `adjusted` true and some beam truncated, throws
  /// InvalidInput at that beam's adjustment block: `what` says which path
  /// cannot take it. Does nothing otherwise.
  void refuse_truncation(bool adjusted, const std::string& what) const;

  /// Mass properties per body, for the message of a singular mass matrix.
  const std::vector<BodyInertia>& bodies() const { return bodies_; }
  /// Where the bodies' position and velocity coordinates sit (nq, nv,
  /// quaternions); empty (nq = 0) for a beam-only model.
  const RigidCoordinates& coordinates() const { return coordinates_; }

  /// The coupled model with the original or the adjusted beams, built once
  /// and shared by every run. Coupled models only.
  /// @throws InvalidInput as resolve_adjusted, or for a model that is not coupled.
  std::shared_ptr<const CoupledModel> coupled_model(bool adjusted) const;
  /// A fresh coupled dynamics over coupled_model(adjusted): the workspace of
  /// one run (or thread).
  std::shared_ptr<CoupledDynamics> make_dynamics(bool adjusted) const;

  /// The initial coordinates of the model's `initial:` block, [q_b; q_c]:
  /// the rigid coordinates in model order, then every beam's free DOFs at rest
  /// and undeformed (zero). q and qd are resized (nq + nc and nv + nc
  /// entries; nq = nv = one per body in a planar model).
  void initial_coordinates(Eigen::VectorXd& q, Eigen::VectorXd& qd) const;

  /// The links' rest offsets (their `rest`, or found for `hold`) and the
  /// static equilibrium of the beams and links alone (docs/catenary.md).
  const LinkFormFinding& links() const { return links_; }

  /// The joined structures of a coupled model (beams adjusted together,
  /// runtime/structure/joined_structures.h); empty without scope 'joined'.
  const std::vector<JoinedStructure>& joined() const { return joined_; }

 private:
  ir::Model model_;
  const mbfe_model_v1* kernels_ = nullptr;
  ModelKind kind_;
  BeamModel beams_;
  std::vector<BodyInertia> bodies_;
  RigidCoordinates coordinates_;
  // The coupled model, original and adjusted (null when there is none).
  std::shared_ptr<const CoupledModel> original_coupled_, adjusted_coupled_;
  LinkFormFinding links_;
  std::vector<JoinedStructure> joined_;
  // Why the adjusted beams cannot be built (a large beam whose lowest modes
  // do not reach its cap); empty when they can.
  std::string adjustment_unavailable_;
  ir::SourceLoc adjustment_unavailable_at_;  // the adjustment block it concerns
  // omega_limit: auto of `beams` by the linearised run (linearised_estimate.h),
  // their adjusted modes redone; the point figure's choice where that run
  // cannot stand for the model.
  void choose_limits_by_linearised_run(const std::vector<std::size_t>& beams, const BeamAnalysisOptions& options);
  // Modes computed of a coupled model's beam beyond the dense modal path.
  static constexpr int kLargeBeamModes = 40;
};

}  // namespace mbfe::runtime
