// The kinematic tree of a spatial model in MuJoCo (Debian's libmujoco-dev):
// written as MJCF (mjcf_text), compiled by MuJoCo, M by its composite-rigid-
// body pass (mj_crb) and the bias by its recursive Newton-Euler pass (mj_rne).
// Only the tree and gravity are carried over; the model's other loads are not
// (bias holds the weights and the velocity terms only, spatial_baseline.h).
#pragma once

#include <Eigen/Dense>

#include <string>
#include <vector>

#include "ir/coordinate_layout.h"
#include "tests/reference/spatial_baseline.h"

struct mjModel_;
struct mjData_;

namespace mbfe::reference {

/// The MJCF of a spatial model's tree. Every body becomes a MuJoCo body at
/// `at`, turned by `rotation` (as a quaternion), with one joint at its origin
/// named after it: a hinge about `axis`, a slide along `rotation`^T `axis`
/// (MuJoCo reads it in the body frame), a ball or a free joint; its inertia
/// is given diagonalised (principal moments and the frame that holds them),
/// so that MuJoCo's compiler does not diagonalise it again with its own
/// iterative tolerance. Numbers are written with 17 digits.
/// @throws std::invalid_argument for a planar model, or a free joint below
///         another body (MuJoCo allows free joints only at the top level).
std::string mjcf_text(const ir::Model& model);

class MujocoTree final : public SpatialBaseline {
 public:
  /// Compiles mjcf_text(model).
  /// @throws std::runtime_error with MuJoCo's message when it refuses the
  ///         model (a body without mass, for one).
  explicit MujocoTree(const ir::Model& model);
  ~MujocoTree() override;
  MujocoTree(const MujocoTree&) = delete;
  MujocoTree& operator=(const MujocoTree&) = delete;

  std::string name() const override;
  int native_positions() const override;
  int native_velocities() const override;
  void to_native(const double* q, const double* v, double* native_q, double* native_v) const override;
  /// mj_kinematics, mj_comPos, mj_crb, mj_comVel, mj_rne: M in MuJoCo's
  /// sparse form (qM) and qfrc_bias. Nothing else of mj_forward.
  void evaluate(const double* native_q, const double* native_v) override;
  /// M through mj_fullM, then into mbfe's coordinates.
  void result(double* M, double* bias) const override;
  void set_gravity(bool on) override;

 private:
  ir::Model model_;
  ir::CoordinateLayout layout_;
  mjModel_* m_ = nullptr;
  mjData_* d_ = nullptr;
  std::vector<int> qpos_of_;  // per body: its joint's first entry of MuJoCo's qpos
  Eigen::MatrixXd velocity_map_;  // T: MuJoCo's qvel = T v
};

}  // namespace mbfe::reference
