#include "runtime/simulation/running_surface_seat.h"

#include <Eigen/QR>
#include <algorithm>
#include <cmath>

#include "runtime/coupled/slider_spring_force.h"

namespace mbfe::runtime {

namespace {

/// How deep a contact seated on its running surface starts pressed (m): a
/// first guess, not a result (the equilibrium does not depend on it), deeper
/// than the static start's difference step (6e-6 m near 0) so that
/// both sides of it press, and far below any static compression of a
/// wheel or pan head (a tyre's mm, Hertz's 0.1 mm).
constexpr double kSeatDepth = 1e-5;
/// Passes of the seating Newton (the contact's penetration is nonlinear in
/// rotations; a translation seats in one).
constexpr int kSeatPasses = 4;

}  // namespace

void seat_on_running_surfaces(const ir::Model& model, CoupledDynamics& dyn, const std::vector<int>& unknown,
                              double relative_step, Eigen::VectorXd& q, const Eigen::VectorXd& qd) {
  const std::vector<const SliderSpringForce*>& springs = dyn.model().slider_springs();
  std::vector<int> compression_only;
  for (std::size_t k = 0; k < springs.size(); ++k) {
    const ir::Contact& c = model.contacts[static_cast<std::size_t>(springs[k]->contact())];
    if (c.unilateral || c.law == ir::ContactLaw::kHertz) compression_only.push_back(static_cast<int>(k));
  }
  if (compression_only.empty()) return;
  std::vector<int> rigid;  // the rigid unknowns
  for (int i : unknown)
    if (i < dyn.nb()) rigid.push_back(i);
  if (rigid.empty()) return;
  const auto penetrations = [&](const Eigen::VectorXd& at, Eigen::VectorXd& delta, std::vector<bool>* on_beam) {
    dyn.evaluate(0.0, at, qd);
    delta.resize(static_cast<Eigen::Index>(compression_only.size()));
    for (std::size_t r = 0; r < compression_only.size(); ++r) {
      const SpringContactState& st = dyn.spring_state(compression_only[r]);
      delta[static_cast<Eigen::Index>(r)] = st.delta;
      if (on_beam) (*on_beam)[r] = st.on_beam;
    }
  };
  std::vector<bool> on_beam(compression_only.size()), seat(compression_only.size(), false);
  Eigen::VectorXd delta, dp, dm;
  penetrations(q, delta, &on_beam);
  bool any = false;
  for (std::size_t r = 0; r < compression_only.size(); ++r) {
    const SliderSpringForce& spring = *springs[static_cast<std::size_t>(compression_only[r])];
    const SpringContactState& st = dyn.spring_state(compression_only[r]);
    const double smooth = st.delta - spring.side() * spring.surface_offset(st.s);
    seat[r] = on_beam[r] && st.delta < 0.0 && smooth >= 0.0;
    any = any || seat[r];
  }
  if (!any) return;
  const Eigen::VectorXd start = q;
  const Eigen::VectorXd target = delta;  // kept, but for the contacts seated
  Eigen::MatrixXd J(delta.size(), static_cast<Eigen::Index>(rigid.size()));
  for (int pass = 0; pass < kSeatPasses; ++pass) {
    Eigen::VectorXd change(delta.size());
    bool seated = true;
    for (Eigen::Index r = 0; r < delta.size(); ++r) {
      const bool row = on_beam[static_cast<std::size_t>(r)];
      change[r] = !row ? 0.0 : seat[static_cast<std::size_t>(r)] ? kSeatDepth - delta[r] : target[r] - delta[r];
      if (seat[static_cast<std::size_t>(r)] && delta[r] < 0.5 * kSeatDepth) seated = false;
    }
    if (seated) return;
    for (std::size_t j = 0; j < rigid.size(); ++j) {
      const int i = rigid[j];
      const double h = relative_step * std::max(1.0, std::abs(q[i]));
      Eigen::VectorXd x = q;
      x[i] += h;
      penetrations(x, dp, nullptr);
      x[i] = q[i] - h;
      penetrations(x, dm, nullptr);
      J.col(static_cast<Eigen::Index>(j)) = (dp - dm) / (2.0 * h);
    }
    for (std::size_t r = 0; r < on_beam.size(); ++r)
      if (!on_beam[r]) J.row(static_cast<Eigen::Index>(r)).setZero();
    const Eigen::VectorXd step = J.completeOrthogonalDecomposition().solve(change);
    if (!step.allFinite()) break;
    for (std::size_t j = 0; j < rigid.size(); ++j) q[rigid[j]] += step[static_cast<Eigen::Index>(j)];
    penetrations(q, delta, &on_beam);
  }
  // Not seated (a contact whose penetration no unknown changes): Newton
  // from the guess as given says why.
  for (std::size_t r = 0; r < seat.size(); ++r)
    if (seat[r] && !(on_beam[r] && delta[static_cast<Eigen::Index>(r)] > 0.0)) {
      q = start;
      return;
    }
}

}  // namespace mbfe::runtime
