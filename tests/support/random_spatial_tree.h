// Random spatial trees for the oracle tests of the spatial generator: random
// joints about random axes with random fixed rotations, physical inertia
// tensors with products of inertia, every kind of load, and random states
// with unit quaternions. Seeded by the caller.
#pragma once

#include <Eigen/Dense>
#include <Eigen/Geometry>

#include <initializer_list>
#include <random>
#include <sstream>
#include <string>

#include "ir/coordinate_layout.h"
#include "ir/model.h"

namespace mbfe::test {

inline std::string numbers(std::initializer_list<double> values) {
  std::ostringstream out;
  out.precision(17);
  out << "[";
  bool first = true;
  for (double v : values) {
    out << (first ? "" : ", ") << v;
    first = false;
  }
  return out.str() + "]";
}

/// A random rotation (a normalised random quaternion).
inline Eigen::Matrix3d random_rotation(std::mt19937& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  return Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized().toRotationMatrix();
}

/// The inertia of a random box of mass m, turned by a random rotation: a
/// physical tensor with products of inertia.
inline std::string random_inertia(std::mt19937& rng, double mass) {
  std::uniform_real_distribution<double> side(0.05, 0.6);
  const double a = side(rng), b = side(rng), c = side(rng);
  const Eigen::Vector3d principal(mass * (b * b + c * c) / 12, mass * (a * a + c * c) / 12, mass * (a * a + b * b) / 12);
  const Eigen::Matrix3d r = random_rotation(rng);
  const Eigen::Matrix3d i = r * principal.asDiagonal() * r.transpose();
  return numbers({i(0, 0), i(1, 1), i(2, 2), i(0, 1), i(0, 2), i(1, 2)});
}

/// A random tree of `bodies` bodies; `quaternions`: a free root and a
/// spherical joint among them.
inline std::string random_spatial_tree_yaml(std::mt19937& rng, int bodies, bool quaternions) {
  std::uniform_real_distribution<double> u(-1.0, 1.0), pos(0.2, 2.0);
  std::ostringstream y;
  y.precision(17);
  y << "model: random_spatial_tree\ndimension: 3\ngravity: " << numbers({u(rng), u(rng), -9.81}) << "\nbodies:\n";
  for (int i = 0; i < bodies; ++i) {
    const int parent = i == 0 ? -1 : static_cast<int>(rng() % i);
    y << "  - name: b" << i << "\n    parent: " << (parent < 0 ? "ground" : "b" + std::to_string(parent)) << "\n";
    const std::string at = numbers({u(rng), u(rng), u(rng)}), rpy = numbers({u(rng), u(rng), u(rng)});
    const std::string axis = numbers({u(rng), u(rng), u(rng)});
    if (quaternions && i == 0)
      y << "    joint: {type: free, at: " << at << ", rotation: " << rpy << "}\n";
    else if (quaternions && i == 2)
      y << "    joint: {type: spherical, at: " << at << ", rotation: " << rpy << "}\n";
    else if (rng() % 3 == 0)
      y << "    joint: {type: prismatic, axis: " << axis << ", at: " << at << ", rotation: " << rpy << "}\n";
    else
      y << "    joint: {type: revolute, axis: " << axis << ", at: " << at << ", rotation: " << rpy << "}\n";
    const double mass = pos(rng);
    y << "    mass: " << mass << "\n    inertia: " << random_inertia(rng, mass) << "\n    com: "
      << numbers({u(rng), u(rng), u(rng)}) << "\n    points: {p: " << numbers({u(rng), u(rng), u(rng)}) << "}\n";
  }
  y << "loads:\n";
  // Loads that vary with time, one switched on at 0.5 s and one off at 0.6 s.
  y << "  - {type: force, body: b0, point: p, value: [\"0.5*sin(3*t)\", 0, \"t^2\"], start: 0.5}\n";
  y << "  - {type: torque, body: b" << bodies - 1 << ", value: [1, \"cos(t)\", 0], stop: 0.6}\n";
  for (int i = 0; i < bodies; ++i) {
    y << "  - {type: force, body: b" << i << ", point: p, value: " << numbers({u(rng), u(rng), u(rng)}) << "}\n";
    y << "  - {type: torque, body: b" << i << ", value: " << numbers({u(rng), u(rng), u(rng)}) << "}\n";
    if (!(quaternions && (i == 0 || i == 2)))
      y << "  - {type: spring_damper, joint: b" << i << ", stiffness: " << pos(rng) << ", damping: " << pos(rng)
        << ", rest: " << u(rng) << "}\n";
  }
  return y.str();
}

/// A random state: angles and lengths in [-3, 3], unit quaternions, rates in [-2, 2].
inline void random_state(std::mt19937& rng, const ir::Model& m, const ir::CoordinateLayout& layout, Eigen::VectorXd& q,
                  Eigen::VectorXd& v) {
  std::uniform_real_distribution<double> angle(-3.0, 3.0), rate(-2.0, 2.0);
  q.resize(layout.num_positions);
  v.resize(layout.num_velocities);
  for (int i = 0; i < q.size(); ++i) q[i] = angle(rng);
  for (int i = 0; i < v.size(); ++i) v[i] = rate(rng);
  for (std::size_t b = 0; b < m.bodies.size(); ++b) {
    const ir::JointType type = m.bodies[b].joint.type;
    if (type != ir::JointType::kSpherical && type != ir::JointType::kFree) continue;
    const int k = layout.first_position[b] + (type == ir::JointType::kFree ? 3 : 0);
    q.segment(k, 4).normalize();
  }
}

}  // namespace mbfe::test
