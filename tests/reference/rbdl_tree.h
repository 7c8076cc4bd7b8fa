// The kinematic tree of a spatial model in RBDL (installed separately, found
// by CMake's MBFE_RBDL_DIR; docs/performance.md): one RBDL body per body,
// added in file order, M by RBDL's CompositeRigidBodyAlgorithm and the bias
// by NonlinearEffects. Only the tree and gravity are carried over; the
// model's other loads are not (spatial_baseline.h).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "ir/coordinate_layout.h"
#include "tests/reference/spatial_baseline.h"

namespace mbfe::reference {

class RbdlTree final : public SpatialBaseline {
 public:
  /// Joint frames as SpatialTransforms (RBDL's E = rotation^T, r = at); a
  /// revolute joint about a coordinate axis becomes RBDL's specialised
  /// RevoluteX, Y or Z, any other axis its general Revolute; a prismatic
  /// joint slides along rotation^T axis (RBDL reads it in the joint frame); a
  /// spherical joint is RBDL's Spherical, a free joint a TranslationXYZ
  /// followed by a Spherical (what RBDL's FloatingBase adds). RBDL's
  /// coordinates are then mbfe's, except that each quaternion keeps its
  /// x, y, z in place and its w at the end of q.
  explicit RbdlTree(const ir::Model& model);
  ~RbdlTree() override;

  std::string name() const override;
  int native_positions() const override;
  int native_velocities() const override;
  void to_native(const double* q, const double* v, double* native_q, double* native_v) const override;
  /// NonlinearEffects, then CompositeRigidBodyAlgorithm on the joint
  /// transforms it has just computed (update_kinematics = false): one
  /// kinematic pass for both.
  void evaluate(const double* native_q, const double* native_v) override;
  void result(double* M, double* bias) const override;
  void set_gravity(bool on) override;

 private:
  struct Impl;  // RBDL's types stay out of this header
  std::unique_ptr<Impl> impl_;
  ir::Model model_;
  ir::CoordinateLayout layout_;
};

}  // namespace mbfe::reference
