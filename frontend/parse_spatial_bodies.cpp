// ModelParser: the bodies, joints and loads of a spatial model (dimension: 3).
#include <Eigen/Dense>

#include <algorithm>
#include <cmath>

#include "frontend/model_parser.h"
#include "ir/coordinate_layout.h"

namespace mbfe::frontend {

namespace {

// A principal moment may fall short of 0, or of the triangle inequality, by
// this fraction of the largest one: the round-off of an exact flat body
// (a disc: A + B = C) computed in decimals, not a physical violation.
constexpr double kInertiaTolerance = 1e-9;

const char* joint_type_name(JointType type) {
  switch (type) {
    case JointType::kRevolute: return "revolute";
    case JointType::kPrismatic: return "prismatic";
    case JointType::kSpherical: return "spherical";
    case JointType::kFree: return "free";
  }
  return "?";
}

}  // namespace

void ModelParser::parse_spatial_body(const MapView& view, Body& body) {
  body.joint = parse_spatial_joint(view.sub(view.require("joint")));
  body.mass = view.number_at_least(view.require("mass"), 0.0);
  body.inertia3 = parse_inertia_tensor(view, view.require("inertia"));
  body.com3 = view.vec3_or("com", {0.0, 0.0, 0.0});
  if (const Field* points = view.find("points")) body.points = parse_points(view, *points);
}

Joint ModelParser::parse_spatial_joint(const MapView& view) {
  view.allow({"type", "at", "axis", "rotation", "motion"});
  Joint joint;
  joint.loc = view.loc();
  const Field& type = view.require("type");
  joint.type = static_cast<JointType>(view.choice(type, {"revolute", "prismatic", "spherical", "free"}));
  joint.at3 = view.vec3_or("at", {0.0, 0.0, 0.0});
  if (const Field* rotation = view.find("rotation")) {  // URDF's rpy, rad
    const std::vector<double> rpy = view.numbers(*rotation, 3, "[roll, pitch, yaw]");
    joint.rotation = {rpy[0], rpy[1], rpy[2]};
  }
  const bool one_axis = joint.type == JointType::kRevolute || joint.type == JointType::kPrismatic;
  const Field* axis = view.find("axis");
  if (one_axis) {
    joint.axis3 = unit_direction(view, view.require("axis"));
  } else if (axis) {
    view.fail(axis->key_loc, view.prefixed(std::string("joint.axis applies to revolute and prismatic joints; a ") +
                                           joint_type_name(joint.type) + " joint turns about every axis"));
  }
  if (const Field* motion = view.find("motion")) {
    if (!one_axis) {
      view.fail(motion->key_loc, view.prefixed(std::string("joint.motion drives one coordinate: a revolute or "
                                                           "prismatic joint, not a ") +
                                               joint_type_name(joint.type) + " one"));
    }
    joint.motion = view.expression(*motion);
    joint.motion_loc = motion->value_loc;
  }
  return joint;
}

InertiaTensor ModelParser::parse_inertia_tensor(const MapView& view, const Field& field) const {
  const std::vector<double> v = view.numbers(field, 6, "[Ixx, Iyy, Izz, Ixy, Ixz, Iyz]");
  const InertiaTensor tensor{v[0], v[1], v[2], v[3], v[4], v[5]};
  Eigen::Matrix3d matrix;
  matrix << v[0], v[3], v[4], v[3], v[1], v[5], v[4], v[5], v[2];
  const Eigen::Vector3d moments = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(matrix).eigenvalues();  // ascending
  const double slack = kInertiaTolerance * std::max(std::fabs(moments[0]), std::fabs(moments[2]));
  const std::string principal = "principal moments " + format_number(moments[0]) + ", " +
                                format_number(moments[1]) + ", " + format_number(moments[2]);
  if (moments[0] < -slack) {
    view.fail(field.value_loc,
              view.prefixed(view.what(field) + " is not an inertia tensor: its " + principal +
                            " include a negative one (expected a positive semidefinite matrix "
                            "[[Ixx, Ixy, Ixz], [Ixy, Iyy, Iyz], [Ixz, Iyz, Izz]])"));
  }
  if (moments[0] + moments[1] < moments[2] - slack) {
    view.fail(field.value_loc,
              view.prefixed(view.what(field) + " is not the inertia of a rigid body: its " + principal +
                            " violate the triangle inequality (" + format_number(moments[0]) + " + " +
                            format_number(moments[1]) + " < " + format_number(moments[2]) +
                            "; any body's principal moments satisfy A + B >= C, a flat one with equality)"));
  }
  return tensor;
}

void ModelParser::claim_joint_coordinate_names(const MapView& view, const Field& name, const Body& body) {
  const JointType type = body.joint.type;
  if (type != JointType::kSpherical && type != JointType::kFree) return;
  std::vector<std::string> names = position_names(type, body.name);
  for (std::string& n : velocity_names(type, body.name)) names.push_back(std::move(n));
  for (const std::string& n : names) {
    const auto [it, inserted] = coordinate_names_.emplace(n, name.value_loc);
    if (inserted) continue;
    view.fail(name.value_loc,
              view.prefixed(std::string("its ") + joint_type_name(type) + " joint names its coordinates " +
                            body.name + "_..., and " + quoted(n) + " is already the name at line " +
                            std::to_string(it->second.line)));
  }
}

void ModelParser::parse_spatial_load_value(const MapView& view, Load& load) {
  const std::array<Expression, 3> value = view.expression_triple(view.require("value"));
  if (load.type == LoadType::kForce) load.force3 = value;
  else load.torque3 = value;
}

void ModelParser::refuse_planar_only_sections(const MapView& top) const {
  if (const Field* beams = top.find("beams")) {
    top.fail(beams->key_loc, "beams: a spatial model (dimension: 3) cannot have beams: 3D beams do not exist yet");
  }
  for (const char* key : {"contacts", "links"}) {
    if (const Field* field = top.find(key)) {
      top.fail(field->key_loc, std::string(key) + ": a spatial model (dimension: 3) cannot have " + key + ": they " +
                                   "act on beams, and 3D beams do not exist yet");
    }
  }
}

Vec3 ModelParser::unit_direction(const MapView& view, const Field& field) const {
  Vec3 direction{0.0, 0.0, 0.0};
  if (model_.dimension == 3) {
    direction = view.vec3(field);
  } else {
    const Vec2 planar = view.vec2(field);
    direction = {planar[0], planar[1], 0.0};
  }
  const double norm = std::hypot(direction[0], direction[1], direction[2]);
  if (!(norm > 0.0) || !std::isfinite(norm)) {
    view.fail(field.value_loc, view.prefixed(view.what(field) + " must be a non-zero, finite direction"));
  }
  for (double& c : direction) c /= norm;
  return direction;
}

}  // namespace mbfe::frontend
