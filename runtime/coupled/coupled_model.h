// A coupled model (Section 4 of the paper, eqs (14)-(17)) as the numerics
// hold it, constant once built:
//
//   M_b(q_b) q_b'' + F_b + J_b^T lambda = Q_b + f_b                (15a)
//   M_c q_c'' + C_c q_c' + K_c q_c + J_c^T lambda = P_c + f_c      (15b)
//   Phi(q_b, q_c) = 0                                              (15c)
//
// the generated kernels (M_b, F_b, Q_b, the contact kernels), the beams and
// the adjusted structures over them (M_c, C_c, K_c: runtime/structure/), the
// constraint contacts (Phi), the force elements (f_b, f_c: slider springs,
// links, time loads) and the driven coordinates. Everything a run writes into
// lives in a CoupledData (coupled_dynamics.h), one per run or thread; the
// algorithms (coupled_dynamics.h, the formulations, the implicit system) read
// the model and write the data.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCholesky>
#include <memory>
#include <string>
#include <vector>

#include "ir/model.h"
#include "runtime/abi/mbfe_model_abi.h"
#include "runtime/coupled/contact_constraints.h"
#include "runtime/coupled/force_element.h"
#include "runtime/coupled/link_force.h"
#include "runtime/coupled/slider_spring_force.h"
#include "runtime/multibody/driven_coordinates.h"
#include "runtime/multibody/rigid_system.h"
#include "runtime/structure/coupled_beam.h"
#include "runtime/structure/low_rank_structure.h"

namespace mbfe::runtime {

class CoupledModel {
 public:
  using Factor = Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>;

  /// `kernels` (which must outlive the model), the beams and their adjusted
  /// structures, body inertias (for messages), the links with their rest
  /// offsets (`link_rests`, one per link: the IR's, or form finding's), the
  /// contacts of the IR (`contacts`, model order; empty: every slider_spring
  /// takes the linear law of its kernels).
  /// @throws std::invalid_argument for beams, structures or contacts that do
  ///         not fit, driven joints with constraint contacts;
  ///         std::runtime_error if a beam's mass matrix is not positive definite.
  CoupledModel(const mbfe_model_v1& kernels, CoupledBeams beams, std::vector<BodyInertia> bodies = {},
               const std::vector<ir::Link>& links = {}, const std::vector<double>& link_rests = {},
               const std::vector<ir::Contact>& contacts = {});

  const mbfe_model_v1& kernels() const { return kernels_; }
  int nb() const { return nb_; }                 // rigid coordinates
  int nc() const { return nc_; }                 // beam coordinates (free DOFs of every beam)
  int n() const { return nb_ + nc_; }
  int m() const { return constraints_.num_rows(); }  // constraint rows

  const std::vector<CoupledBeam>& beams() const { return beams_; }
  const std::vector<std::shared_ptr<const LowRankStructure>>& structures() const { return structures_; }
  const ContactConstraints& constraints() const { return constraints_; }
  const DrivenCoordinates& driven() const { return driven_; }
  const std::vector<BodyInertia>& bodies() const { return bodies_; }

  /// Every force element, in the order their forces are summed.
  const std::vector<std::unique_ptr<const ForceElement>>& forces() const { return forces_; }
  /// The slider_spring contacts and the links among them (model order), and
  /// where each is in forces().
  const std::vector<const SliderSpringForce*>& slider_springs() const { return springs_; }
  const std::vector<int>& slider_spring_elements() const { return spring_elements_; }
  const std::vector<const LinkForce*>& links() const { return links_; }
  const std::vector<int>& link_elements() const { return link_elements_; }

  /// The constant loads P of every beam, over q_c (N).
  const Eigen::VectorXd& loads() const { return loads_; }
  /// The factorisation of beam b's M (a beam outside any structure solves
  /// with it; a constraint's columns W = M^-1 J_c^T use it); the adjusted
  /// structure's own when the beam is one on its M, not a second one.
  const Factor& mass_factor(int beam) const { return *mass_factors_[static_cast<std::size_t>(beam)]; }

  /// Split coordinates (docs/damping-adjustment.md, "Split coordinates") can
  /// be had: no constraint contacts, no joined structure, and some adjusted
  /// beam in the low-rank form (the ones that split; the rest stay nodal).
  bool splittable() const { return splittable_; }

  /// Names of the full coordinates [q_b; q_c]: rigid coordinate names, then
  /// "<beam>_w<node>" / "<beam>_dw<node>" for the free beam DOFs.
  std::vector<std::string> coordinate_names() const;

 private:
  const mbfe_model_v1& kernels_;
  std::vector<CoupledBeam> beams_;
  std::vector<std::shared_ptr<const LowRankStructure>> structures_;
  std::vector<BodyInertia> bodies_;
  ContactConstraints constraints_;
  DrivenCoordinates driven_;
  int nb_, nc_;
  std::vector<std::unique_ptr<const ForceElement>> forces_;
  std::vector<const SliderSpringForce*> springs_;
  std::vector<int> spring_elements_;
  std::vector<const LinkForce*> links_;
  std::vector<int> link_elements_;
  Eigen::VectorXd loads_;
  std::vector<std::shared_ptr<const Factor>> mass_factors_;
  bool splittable_ = false;
};

}  // namespace mbfe::runtime
