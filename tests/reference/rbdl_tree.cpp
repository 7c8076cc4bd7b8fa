#include "tests/reference/rbdl_tree.h"

#include <rbdl/rbdl.h>

#include <algorithm>
#include <cmath>

namespace mbfe::reference {

namespace rbdl = RigidBodyDynamics;
using rbdl::Math::Matrix3d;
using rbdl::Math::MatrixNd;
using rbdl::Math::SpatialTransform;
using rbdl::Math::Vector3d;
using rbdl::Math::VectorNd;
using ir::JointType;

struct RbdlTree::Impl {
  rbdl::Model model;
  VectorNd q, v, bias;
  MatrixNd M;
  Vector3d gravity;
  std::vector<unsigned> body_id;  // per body: RBDL's id of the body that carries its mass
  std::vector<unsigned> w_index;  // per body with a quaternion: where RBDL keeps its w
};

namespace {

Vector3d to_rbdl(const Eigen::Vector3d& v) { return Vector3d(v.x(), v.y(), v.z()); }

Matrix3d to_rbdl(const Eigen::Matrix3d& m) {
  Matrix3d r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) r(i, j) = m(i, j);
  return r;
}

/// RBDL's specialised joint for a revolute joint about +x, +y or +z, else the general one.
rbdl::Joint revolute(const ir::Vec3& axis) {
  if (axis[1] == 0.0 && axis[2] == 0.0 && axis[0] == 1.0) return rbdl::Joint(rbdl::JointTypeRevoluteX);
  if (axis[0] == 0.0 && axis[2] == 0.0 && axis[1] == 1.0) return rbdl::Joint(rbdl::JointTypeRevoluteY);
  if (axis[0] == 0.0 && axis[1] == 0.0 && axis[2] == 1.0) return rbdl::Joint(rbdl::JointTypeRevoluteZ);
  return rbdl::Joint(rbdl::JointTypeRevolute, to_rbdl(vector3(axis)));
}

}  // namespace

RbdlTree::RbdlTree(const ir::Model& model)
    : impl_(std::make_unique<Impl>()), model_(model), layout_(ir::coordinate_layout(model)) {
  Impl& r = *impl_;
  r.gravity = to_rbdl(vector3(model.gravity3));
  r.model.gravity = r.gravity;
  for (const ir::Body& body : model.bodies) {
    const ir::Joint& joint = body.joint;
    const Eigen::Matrix3d fixed = rpy_rotation(joint.rotation);
    // RBDL's E turns parent coordinates into joint-frame coordinates: C^T.
    const SpatialTransform frame(to_rbdl(Eigen::Matrix3d(fixed.transpose())), to_rbdl(vector3(joint.at3)));
    const rbdl::Body mass(body.mass, to_rbdl(vector3(body.com3)), to_rbdl(inertia_matrix(body.inertia3)));
    const unsigned parent = body.parent < 0 ? 0 : r.body_id[body.parent];
    unsigned id = 0;
    switch (joint.type) {
      case JointType::kRevolute:
        id = r.model.AddBody(parent, frame, revolute(joint.axis3), mass, body.name);
        break;
      case JointType::kPrismatic:
        id = r.model.AddBody(parent, frame,
                             rbdl::Joint(rbdl::JointTypePrismatic, to_rbdl(Eigen::Vector3d(fixed.transpose() * vector3(joint.axis3)))),
                             mass, body.name);
        break;
      case JointType::kSpherical:
        id = r.model.AddBody(parent, frame, rbdl::Joint(rbdl::JointTypeSpherical), mass, body.name);
        break;
      case JointType::kFree: {
        rbdl::Body none(0.0, Vector3d(0.0, 0.0, 0.0), Vector3d(0.0, 0.0, 0.0));
        none.mIsVirtual = true;
        const unsigned translation =
            r.model.AddBody(parent, frame, rbdl::Joint(rbdl::JointTypeTranslationXYZ), none);
        id = r.model.AddBody(translation, SpatialTransform(), rbdl::Joint(rbdl::JointTypeSpherical), mass, body.name);
        break;
      }
    }
    r.body_id.push_back(id);
  }
  // RBDL moves the w entries as bodies are added: read them at the end.
  for (unsigned id : r.body_id)
    r.w_index.push_back(r.model.mJoints[id].mJointType == rbdl::JointTypeSpherical ? r.model.multdof3_w_index[id] : 0);
  r.q = VectorNd::Zero(r.model.q_size);
  r.v = VectorNd::Zero(r.model.qdot_size);
  r.bias = VectorNd::Zero(r.model.qdot_size);
  r.M = MatrixNd::Zero(r.model.qdot_size, r.model.qdot_size);  // CRBA writes only the non-zero entries
}

RbdlTree::~RbdlTree() = default;

std::string RbdlTree::name() const {
  const int version = RBDL_API_VERSION;
  return "RBDL " + std::to_string(version >> 16) + "." + std::to_string((version >> 8) & 0xff) + "." +
         std::to_string(version & 0xff);
}
int RbdlTree::native_positions() const { return static_cast<int>(impl_->model.q_size); }
int RbdlTree::native_velocities() const { return static_cast<int>(impl_->model.qdot_size); }

void RbdlTree::to_native(const double* q, const double* v, double* native_q, double* native_v) const {
  const Impl& r = *impl_;
  for (std::size_t b = 0; b < model_.bodies.size(); ++b) {
    const JointType type = model_.bodies[b].joint.type;
    const double* from = q + layout_.first_position[b];
    const unsigned id = r.body_id[b];
    const unsigned first = r.model.mJoints[id].q_index;
    switch (type) {
      case JointType::kRevolute:
      case JointType::kPrismatic:
        native_q[first] = from[0];
        break;
      case JointType::kFree:  // x, y, z of the translation joint, just before the spherical one
        std::copy(from, from + 3, native_q + first - 3);
        from += 3;
        [[fallthrough]];
      case JointType::kSpherical:  // (w, x, y, z) -> x, y, z in place, w at the end
        std::copy(from + 1, from + 4, native_q + first);
        native_q[r.w_index[b]] = from[0];
        break;
    }
  }
  std::copy(v, v + layout_.num_velocities, native_v);  // same order, same meaning
}

void RbdlTree::evaluate(const double* native_q, const double* native_v) {
  Impl& r = *impl_;
  std::copy(native_q, native_q + r.q.size(), r.q.data());
  std::copy(native_v, native_v + r.v.size(), r.v.data());
  rbdl::NonlinearEffects(r.model, r.q, r.v, r.bias);
  rbdl::CompositeRigidBodyAlgorithm(r.model, r.q, r.M, /*update_kinematics=*/false);
}

void RbdlTree::result(double* M, double* bias) const {
  const Impl& r = *impl_;
  const int n = layout_.num_velocities;
  for (int i = 0; i < n; ++i) {
    bias[i] = r.bias[i];
    for (int j = 0; j < n; ++j) M[i * n + j] = r.M(i, j);
  }
}

void RbdlTree::set_gravity(bool on) { impl_->model.gravity = on ? impl_->gravity : Vector3d(0.0, 0.0, 0.0); }

}  // namespace mbfe::reference
