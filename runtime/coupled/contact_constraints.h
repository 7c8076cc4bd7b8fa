// The contact constraints of a coupled model (Section 4, eqs (12)-(13)),
// stacked over the contacts in model (file) order: 2 rows per pin, 1 per
// slider_pin. Evaluates the generated per-contact kernels on the beam element
// that holds the contact point and scatters the element-local Jacobian J_e
// (columns w1, w1', w2, w2') onto the global beam coordinates q_c.
//
// Coordinates: q = [q_b; q_c], q_b the rigid coordinates (model order), q_c the
// free DOFs of every beam, beams in model order, each in the beam contract order
// (nodes from s = 0 to L, [w, w'] per node, DOFs fixed by supports removed).
#pragma once

#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

#include "runtime/abi/mbfe_model_abi.h"
#include "runtime/structure/beam_mesh.h"

namespace mbfe::runtime {

/// Phi, J_b, J_c and gamma of all contacts at one state.
/// J_c is stored element-locally: row r has 4 entries je(r, k) at the global
/// q_c columns jcol(r, k) (-1: a DOF fixed by a support, dropped).
struct ConstraintValues {
  Eigen::VectorXd phi;    // m rows (m)
  Eigen::MatrixXd jb;     // m x nb (m/rad or 1)
  Eigen::Matrix<double, Eigen::Dynamic, 4, Eigen::RowMajor> je;  // m x 4
  Eigen::Matrix<int, Eigen::Dynamic, 4, Eigen::RowMajor> jcol;   // m x 4
  Eigen::VectorXd gamma;  // m rows (m/s^2), only if asked for
  std::vector<double> s;        // per contact: position along its beam (m)
  std::vector<int> element;     // per contact: element holding s

  /// out = J_c x (x: nc entries).
  void jc_times(const Eigen::Ref<const Eigen::VectorXd>& x, Eigen::VectorXd& out) const;
  /// J_c as a dense m x nc matrix.
  Eigen::MatrixXd jc_dense(int nc) const;
};

class ContactConstraints {
 public:
  /// @throws std::invalid_argument if a contact names a beam index outside
  ///         `beams`, has rows other than 2 (pin) / 1 (slider_pin), a null
  ///         kernel, or a pin position outside [0, L].
  ContactConstraints(const mbfe_model_v1& model, std::vector<BeamMesh> beams);

  int num_rows() const { return rows_; }
  int num_rigid() const { return nb_; }
  int num_beam_dofs() const { return nc_; }
  int num_contacts() const { return static_cast<int>(row0_.size()); }
  const std::vector<BeamMesh>& beams() const { return beams_; }
  /// First q_c index of beam k.
  int beam_offset(int k) const { return beam_offset_[k]; }
  const std::vector<int>& beam_offsets() const { return beam_offset_; }
  /// Contact of constraint row r, and its name.
  int contact_of_row(int r) const { return contact_of_row_[r]; }
  std::string contact_name(int c) const;
  int first_row(int c) const { return row0_[c]; }

  /// Evaluates phi, jb, je, jcol, s, element at (qb, qc); gamma too when
  /// qbd and qcd are not null. `t` (s) only for messages.
  /// @throws SliderOffBeamError if a slider's s(q) is outside [0, L].
  void evaluate(double t, const double* qb, const double* qc, const double* qbd,
                const double* qcd, ConstraintValues& out) const;

  /// gamma alone, into `out` that holds an evaluate() at this very (qb, qc)
  /// (its elements and columns are reused): what an evaluation with rates
  /// costs beyond one without.
  void evaluate_gamma(const double* qb, const double* qc, const double* qbd, const double* qcd,
                      ConstraintValues& out) const;

 private:
  const mbfe_model_v1& model_;
  std::vector<BeamMesh> beams_;
  std::vector<int> beam_offset_;
  std::vector<int> row0_;
  std::vector<int> contact_of_row_;
  int nb_ = 0, nc_ = 0, rows_ = 0;
};

}  // namespace mbfe::runtime
