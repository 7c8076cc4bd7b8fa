// The exact response of decoupled modes to a load stepped on at t = 0, from
// rest: each mode m_j eta_j'' + c_j eta_j' + k_j eta_j = p_j has a closed form
// (under-, critically or over-damped), and a point of the structure is a fixed
// combination w = g . eta of them. The oracle the accuracy studies measure
// integrators and the adjustment against (docs/accuracy-vs-cost.md).
#pragma once

#include <Eigen/Core>
#include <vector>

#include "runtime/modal/state_spectrum.h"

namespace mbfe::runtime {

struct ModalStepResponse {
  std::vector<ModalDynamics> modes;  // c_j (1/s), k_j (1/s^2 > 0), m_j (> 0)
  Eigen::VectorXd p;                 // modal loads (one per mode)
  Eigen::VectorXd g;                 // weights of the modes in the output, w = g . eta

  /// eta_j(t), t >= 0 (s).
  double eta(int j, double t) const;
  /// w(t) = sum_j g_j eta_j(t).
  double w(double t) const;
  /// The static value sum_j g_j p_j / k_j that w(t) settles on.
  double w_static() const;
};

}  // namespace mbfe::runtime
