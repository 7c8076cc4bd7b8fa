// Steps the generated double pendulum with the mbfe runtime for 1 s and checks
// that its energy stays put (no damping, RK4 at 1e-3 s): exit 0 when it does.
#include <cmath>
#include <cstdio>

#include "runtime/integrators/integrator.h"
#include "runtime/multibody/rigid_system.h"

extern "C" const mbfe_model_v1* mbfe_model_double_pendulum(void);

int main() {
  const mbfe_model_v1& model = *mbfe_model_double_pendulum();
  mbfe::runtime::RigidSystem system(model);
  auto stepper = mbfe::runtime::make_stepper(mbfe::runtime::parse_integrator("rk4"), system);
  Eigen::VectorXd y = Eigen::VectorXd::Zero(4);
  y[0] = 0.3;
  // Kinetic energy plus gravity's potential (uniform 1 kg links: each centre of
  // mass halfway along its link, so heights from the two tip positions).
  auto energy = [&](const Eigen::VectorXd& s) {
    double tip1[2], tip2[2];
    const double q[2] = {s[0], s[1]};
    model.point_position(q, 0, 0, tip1);
    model.point_position(q, 1, 0, tip2);
    const double potential = 9.81 * (0.5 * tip1[1] + 0.5 * (tip1[1] + tip2[1]));
    return system.kinetic_energy(s) + potential;
  };
  const double e0 = energy(y);
  stepper->reset(0.0, y);
  constexpr double h = 1e-3;
  for (int i = 0; i < 1000; ++i) stepper->step(i * h, h, y);
  const double drift = std::abs(energy(y) - e0) / std::abs(e0);
  std::printf("downstream: double pendulum, 1 s of RK4, relative energy drift %.3g\n", drift);
  return drift < 1e-6 ? 0 : 1;
}
