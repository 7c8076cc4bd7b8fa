#include "tests/reference/mujoco_tree.h"

#include <mujoco/mujoco.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <initializer_list>
#include <memory>
#include <sstream>
#include <stdexcept>

namespace mbfe::reference {

namespace {

using ir::JointType;

std::string numbers(std::initializer_list<double> values) {
  std::string out;
  char buffer[32];
  for (double v : values) {
    std::snprintf(buffer, sizeof buffer, "%.17g", v);
    out += (out.empty() ? "" : " ") + std::string(buffer);
  }
  return out;
}

std::string quaternion_text(const Eigen::Matrix3d& rotation) {
  const Eigen::Quaterniond q(rotation);
  return numbers({q.w(), q.x(), q.y(), q.z()});
}

void write_body(const ir::Model& model, int b, const std::vector<std::vector<int>>& children, int depth,
                std::ostringstream& out) {
  const ir::Body& body = model.bodies[b];
  const ir::Joint& joint = body.joint;
  const std::string indent(2 * depth, ' ');
  const Eigen::Matrix3d fixed = rpy_rotation(joint.rotation);
  out << indent << "<body name=\"" << body.name << "\" pos=\"" << numbers({joint.at3[0], joint.at3[1], joint.at3[2]})
      << "\" quat=\"" << quaternion_text(fixed) << "\">\n";
  switch (joint.type) {
    case JointType::kRevolute:
      out << indent << "  <joint name=\"" << body.name << "\" type=\"hinge\" axis=\""
          << numbers({joint.axis3[0], joint.axis3[1], joint.axis3[2]}) << "\"/>\n";
      break;
    case JointType::kPrismatic: {
      // mbfe's axis is in the parent frame, MuJoCo's in the body frame.
      const Eigen::Vector3d axis = fixed.transpose() * vector3(joint.axis3);
      out << indent << "  <joint name=\"" << body.name << "\" type=\"slide\" axis=\""
          << numbers({axis.x(), axis.y(), axis.z()}) << "\"/>\n";
      break;
    }
    case JointType::kSpherical:
      out << indent << "  <joint name=\"" << body.name << "\" type=\"ball\"/>\n";
      break;
    case JointType::kFree:
      if (body.parent >= 0)
        throw std::invalid_argument("MuJoCo allows a free joint only on a body of the ground; '" + body.name +
                                    "' hangs from '" + model.bodies[body.parent].name + "'");
      out << indent << "  <joint name=\"" << body.name << "\" type=\"free\"/>\n";
      break;
  }
  // The principal moments and the frame that holds them (a proper rotation).
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(inertia_matrix(body.inertia3));
  Eigen::Matrix3d axes = eigen.eigenvectors();
  if (axes.determinant() < 0) axes.col(2) = -axes.col(2);
  const Eigen::Vector3d moments = eigen.eigenvalues();
  out << indent << "  <inertial pos=\"" << numbers({body.com3[0], body.com3[1], body.com3[2]}) << "\" quat=\""
      << quaternion_text(axes) << "\" mass=\"" << numbers({body.mass}) << "\" diaginertia=\""
      << numbers({moments[0], moments[1], moments[2]}) << "\"/>\n";
  for (int child : children[b]) write_body(model, child, children, depth + 1, out);
  out << indent << "</body>\n";
}

}  // namespace

std::string mjcf_text(const ir::Model& model) {
  if (model.dimension != 3) throw std::invalid_argument("mjcf_text: '" + model.name + "' is not a spatial model");
  std::vector<std::vector<int>> children(model.bodies.size());
  std::vector<int> roots;
  for (std::size_t b = 0; b < model.bodies.size(); ++b)
    (model.bodies[b].parent < 0 ? roots : children[model.bodies[b].parent]).push_back(static_cast<int>(b));
  std::ostringstream out;
  out << "<mujoco model=\"" << model.name << "\">\n"
      << "  <compiler angle=\"radian\" inertiafromgeom=\"false\" boundmass=\"0\" boundinertia=\"0\""
         " balanceinertia=\"false\"/>\n"
      << "  <option gravity=\"" << numbers({model.gravity3[0], model.gravity3[1], model.gravity3[2]}) << "\"/>\n"
      << "  <worldbody>\n";
  for (int root : roots) write_body(model, root, children, 2, out);
  out << "  </worldbody>\n</mujoco>\n";
  return out.str();
}

MujocoTree::MujocoTree(const ir::Model& model) : model_(model), layout_(ir::coordinate_layout(model)) {
  const std::string text = mjcf_text(model);
  auto vfs = std::make_unique<mjVFS>();
  mj_defaultVFS(vfs.get());
  const char* file = "model.xml";
  if (mj_makeEmptyFileVFS(vfs.get(), file, static_cast<int>(text.size())) != 0)
    throw std::runtime_error("MuJoCo: no room for the model in its virtual file system");
  std::memcpy(vfs->filedata[vfs->nfile - 1], text.data(), text.size());
  char error[1000] = "";
  m_ = mj_loadXML(file, vfs.get(), error, sizeof error);
  mj_deleteVFS(vfs.get());
  if (!m_) throw std::runtime_error("MuJoCo refused the MJCF of '" + model.name + "': " + error);
  d_ = mj_makeData(m_);

  qpos_of_.resize(model.bodies.size());
  velocity_map_ = Eigen::MatrixXd::Zero(m_->nv, layout_.num_velocities);
  for (std::size_t b = 0; b < model.bodies.size(); ++b) {
    const int joint = mj_name2id(m_, mjOBJ_JOINT, model.bodies[b].name.c_str());
    qpos_of_[b] = m_->jnt_qposadr[joint];
    const int dof = m_->jnt_dofadr[joint], first = layout_.first_velocity[b];
    const int count = ir::velocity_count(model.bodies[b].joint.type);
    for (int c = 0; c < count; ++c) velocity_map_(dof + c, first + c) = 1.0;
    if (model.bodies[b].joint.type == JointType::kFree)  // MuJoCo's linear velocity is in the ground frame
      velocity_map_.block<3, 3>(dof, first) = rpy_rotation(model.bodies[b].joint.rotation);
  }
}

MujocoTree::~MujocoTree() {
  if (d_) mj_deleteData(d_);
  if (m_) mj_deleteModel(m_);
}

std::string MujocoTree::name() const { return std::string("MuJoCo ") + mj_versionString(); }
int MujocoTree::native_positions() const { return m_->nq; }
int MujocoTree::native_velocities() const { return m_->nv; }

void MujocoTree::to_native(const double* q, const double* v, double* native_q, double* native_v) const {
  for (std::size_t b = 0; b < model_.bodies.size(); ++b) {
    const ir::Joint& joint = model_.bodies[b].joint;
    const double* from = q + layout_.first_position[b];
    double* to = native_q + qpos_of_[b];
    if (joint.type != JointType::kFree) {
      std::copy(from, from + ir::position_count(joint.type), to);
      continue;
    }
    // MuJoCo's free joint holds the body's ground-frame position and orientation.
    const Eigen::Matrix3d fixed = rpy_rotation(joint.rotation);
    const Eigen::Vector3d position = vector3(joint.at3) + fixed * Eigen::Vector3d(from[0], from[1], from[2]);
    const Eigen::Quaterniond turn =
        Eigen::Quaterniond(fixed) * Eigen::Quaterniond(from[3], from[4], from[5], from[6]);
    const double values[7] = {position.x(), position.y(), position.z(), turn.w(), turn.x(), turn.y(), turn.z()};
    std::copy(values, values + 7, to);
  }
  Eigen::Map<Eigen::VectorXd>(native_v, m_->nv) =
      velocity_map_ * Eigen::Map<const Eigen::VectorXd>(v, layout_.num_velocities);
}

void MujocoTree::evaluate(const double* native_q, const double* native_v) {
  mju_copy(d_->qpos, native_q, m_->nq);
  mju_copy(d_->qvel, native_v, m_->nv);
  mj_kinematics(m_, d_);
  mj_comPos(m_, d_);
  mj_crb(m_, d_);
  mj_comVel(m_, d_);
  mj_rne(m_, d_, 0, d_->qfrc_bias);
}

void MujocoTree::result(double* M, double* bias) const {
  const int n = m_->nv, nv = layout_.num_velocities;
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> full(n, n);
  mj_fullM(m_, full.data(), d_->qM);
  const Eigen::MatrixXd& t = velocity_map_;
  Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(M, nv, nv) =
      t.transpose() * full * t;
  Eigen::Map<Eigen::VectorXd>(bias, nv) = t.transpose() * Eigen::Map<const Eigen::VectorXd>(d_->qfrc_bias, n);
}

void MujocoTree::set_gravity(bool on) {
  if (on)
    m_->opt.disableflags &= ~mjDSBL_GRAVITY;
  else
    m_->opt.disableflags |= mjDSBL_GRAVITY;
}

}  // namespace mbfe::reference
