// Driven joints (`joint.motion`, docs/model-format.md): rigid coordinates
// whose q, q' and q'' are their motion's at t, not unknowns. Every system
// that steps a model with bodies treats them here: the state's entries are
// overwritten with the motion, their equations of motion are replaced by
// q''_d = motion''(t) (explicitly: eliminated from M q'' = rhs; implicitly:
// a residual a_d - motion''(t) and a unit row), and the generalized force
// each one exerts to follow its motion is reported.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "runtime/abi/mbfe_model_abi.h"

namespace mbfe::runtime {

/// In M q'' = rhs, the entries `driven` of q'' are `qdd_driven` (in that
/// order): their columns of M move to the right-hand side and their rows
/// become q''_d = qdd_driven, so that M stays symmetric positive definite and
/// the free coordinates follow M_ff q''_f = rhs_f - M_fd q''_d.
inline void eliminate_driven(Eigen::MatrixXd& M, Eigen::VectorXd& rhs, const std::vector<int>& driven,
                             const Eigen::VectorXd& qdd_driven) {
  for (std::size_t k = 0; k < driven.size(); ++k) rhs -= M.col(driven[k]) * qdd_driven[static_cast<Eigen::Index>(k)];
  for (std::size_t k = 0; k < driven.size(); ++k) {
    const int d = driven[k];
    M.row(d).setZero();
    M.col(d).setZero();
    M(d, d) = 1.0;
    rhs[d] = qdd_driven[static_cast<Eigen::Index>(k)];
  }
}

class DrivenCoordinates {
 public:
  /// The motion of every driven coordinate at one time (one entry each, in
  /// the order of indices()): m or rad, per s, per s^2.
  struct Motion {
    Eigen::VectorXd q, qd, qdd;
  };

  /// The driven coordinates of `model` (its kernels must outlive this object).
  explicit DrivenCoordinates(const mbfe_model_v1& model);

  bool empty() const { return indices_.empty(); }
  int count() const { return static_cast<int>(indices_.size()); }
  /// Rigid coordinate indices, model order.
  const std::vector<int>& indices() const { return indices_; }
  /// One flag per rigid coordinate.
  const std::vector<bool>& mask() const { return mask_; }
  bool is_driven(int i) const { return mask_[static_cast<std::size_t>(i)]; }

  /// A Motion sized for these coordinates.
  Motion make_motion() const;
  /// The motion at t.
  void motion(double t, Motion& out) const;
  /// Overwrites the driven entries of q and qd (rigid coordinates first in
  /// both) with the motion at t, left in `scratch`.
  void impose(double t, double* q, double* qd, Motion& scratch) const;

 private:
  const mbfe_model_v1& model_;
  std::vector<int> indices_;
  std::vector<bool> mask_;
};

}  // namespace mbfe::runtime
