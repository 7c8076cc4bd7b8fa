// models/four_bar.yaml written by hand for tests: the position analysis of
// the planar four-bar in closed form (where the circles about the coupler's
// and the rocker's pivots meet), its potential energy and the effective mass
// of its one degree of freedom, for oracles of its equilibria and their
// small oscillations.
#pragma once

#include <Eigen/Dense>
#include <cmath>

namespace mbfe::test {

// models/four_bar.yaml by hand: ground pivots O = (0, 0) and D = (0.6, 0),
// crank OB (0.2 m), coupler BC (0.7 m), rocker DC (0.5 m), gravity -y.
// The bodies and the loop of models/four_bar.yaml, with FourBar's
// dimensions and inertias, as a model file's `bodies:` and `constraints:`.
inline constexpr const char* kFourBarBodies =
    "bodies:\n"
    "  - {name: crank, parent: ground, joint: {type: revolute}, mass: 0.4, inertia: 0.0015, com: [0.1, 0],"
    " points: {end: [0.2, 0]}}\n"
    "  - {name: coupler, parent: crank, joint: {type: revolute, at: [0.2, 0]}, mass: 1.2, inertia: 0.05,"
    " com: [0.35, 0], points: {end: [0.7, 0]}}\n"
    "  - {name: rocker, parent: ground, joint: {type: revolute, at: [0.6, 0]}, mass: 0.9, inertia: 0.019,"
    " com: [0.25, 0], points: {end: [0.5, 0]}}\n"
    "constraints:\n"
    "  - {name: coupler_rocker, type: revolute, a: {body: coupler, point: end}, b: {body: rocker, point: end}}\n";

struct FourBar {
  static constexpr double kGravity = 9.81;
  static constexpr double kPi = 3.14159265358979323846;
  double a = 0.2, b = 0.7, c = 0.5, d = 0.6;
  double m_crank = 0.4, m_coupler = 1.2, m_rocker = 0.9;
  double i_crank = 0.0015, i_coupler = 0.05, i_rocker = 0.019;  // about the centres of mass

  // Absolute angles of the coupler and the rocker at crank angle theta: C is
  // where the circles about B (radius b) and D (radius c) meet, on the side
  // of BD the shipped initial state is on (C above BD for theta = 1).
  void angles(double theta, double& phi, double& psi) const {
    const Eigen::Vector2d B(a * std::cos(theta), a * std::sin(theta)), D(d, 0.0);
    const Eigen::Vector2d e = D - B;
    const double l = e.norm();
    const double x = (b * b - c * c + l * l) / (2.0 * l), h = std::sqrt(b * b - x * x);
    const Eigen::Vector2d u = e / l, n(-u.y(), u.x());
    const Eigen::Vector2d C = B + x * u + h * n;
    phi = std::atan2(C.y() - B.y(), C.x() - B.x());
    psi = std::atan2(C.y(), C.x() - d);
  }
  // Centres of mass (x, y) of crank, coupler and rocker: 6 numbers.
  Eigen::Matrix<double, 6, 1> centres(double theta) const {
    double phi, psi;
    angles(theta, phi, psi);
    Eigen::Matrix<double, 6, 1> r;
    r << 0.1 * std::cos(theta), 0.1 * std::sin(theta), a * std::cos(theta) + 0.35 * std::cos(phi),
        a * std::sin(theta) + 0.35 * std::sin(phi), d + 0.25 * std::cos(psi), 0.25 * std::sin(psi);
    return r;
  }
  double potential(double theta) const {
    const auto r = centres(theta);
    return kGravity * (m_crank * r[1] + m_coupler * r[3] + m_rocker * r[5]);
  }
  // T = 1/2 m_eff(theta) theta'^2.
  double effective_mass(double theta) const {
    constexpr double h = 1e-5;
    const Eigen::Matrix<double, 6, 1> dr = (centres(theta + h) - centres(theta - h)) / (2 * h);
    double phi_p, psi_p, phi_m, psi_m;
    angles(theta + h, phi_p, psi_p);
    angles(theta - h, phi_m, psi_m);
    const double dphi = (phi_p - phi_m) / (2 * h), dpsi = (psi_p - psi_m) / (2 * h);
    return m_crank * dr.segment<2>(0).squaredNorm() + m_coupler * dr.segment<2>(2).squaredNorm() +
           m_rocker * dr.segment<2>(4).squaredNorm() + i_crank + i_coupler * dphi * dphi + i_rocker * dpsi * dpsi;
  }
  double slope(double theta) const {
    constexpr double h = 1e-5;
    return (potential(theta + h) - potential(theta - h)) / (2 * h);
  }
  double curvature(double theta) const {
    constexpr double h = 1e-4;
    return (potential(theta + h) - 2 * potential(theta) + potential(theta - h)) / (h * h);
  }
  // The lowest point of V over a turn of the crank (a Grashof crank-rocker:
  // the crank turns fully), by a scan and Newton on dV/dtheta.
  double hanging_angle() const {
    double best = 0.0;
    for (int k = 0; k < 360; ++k) {
      const double theta = 2 * kPi * k / 360;
      if (potential(theta) < potential(best)) best = theta;
    }
    for (int it = 0; it < 20; ++it) best -= slope(best) / curvature(best);
    return best;
  }
};

}  // namespace mbfe::test
