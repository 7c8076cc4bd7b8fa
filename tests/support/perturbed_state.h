// A coupled model's state away from rest, for tests that compare two paths
// at one state: the rigid coordinates as the model starts, every beam DOF
// perturbed (2 mm, 2 cm/s at most), drawn from `seed`.
#pragma once

#include <Eigen/Core>
#include <random>

#include "api/mbfe.h"

namespace mbfe::test {

inline void perturbed_state(const Model& model, int nb, unsigned seed, Eigen::VectorXd& q, Eigen::VectorXd& qd) {
  model.assembled().initial_coordinates(q, qd);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int i = nb; i < q.size(); ++i) {
    q[i] = 2e-3 * u(rng);
    qd[i] = 2e-2 * u(rng);
  }
}

}  // namespace mbfe::test
