#include "runtime/coupled/slider_spring_force.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "runtime/fem/hermite_shape.h"
#include "runtime/fem/running_surface.h"

namespace mbfe::runtime {

namespace {

/// The element holding s on a beam (s in [0, L]).
int element_at(const BeamMesh& beam, double s) {
  return std::clamp(static_cast<int>(std::floor(s / beam.element_length)), 0, beam.num_elements - 1);
}

}  // namespace

SliderSpringForce::SliderSpringForce(const mbfe_model_v1& model, int index, BeamMesh mesh, int offset, SpringLaw law)
    : kernels_(model.contacts[index]), index_(index), nb_(model.num_coordinates), offset_(offset),
      mesh_(std::move(mesh)), law_(law) {
  if (kernels_.type != 2)
    throw std::invalid_argument("contact " + std::to_string(index) + " is not a slider_spring");
  name_ = kernels_.name ? kernels_.name : "contact " + std::to_string(index);
  if (law_.hertz && !(law_.coefficient > 0.0 && std::isfinite(law_.coefficient)))
    throw std::invalid_argument("contact '" + name_ + "': a Hertzian coefficient must be positive");
}

double SliderSpringForce::law_force(double delta, double rate) const {
  if (!law_.hertz) return kernels_.stiffness * delta + kernels_.damping * rate;
  if (!(delta > 0.0)) return 0.0;
  return law_.coefficient * delta * std::sqrt(delta) + kernels_.damping * rate;
}

double SliderSpringForce::law_stiffness(double delta) const {
  if (!law_.hertz) return kernels_.stiffness;
  return delta > 0.0 ? 1.5 * law_.coefficient * std::sqrt(delta) : 0.0;
}

double SliderSpringForce::surface_offset(double s) const { return mesh_.surface ? mesh_.surface->offset(s) : 0.0; }

std::unique_ptr<ForceState> SliderSpringForce::make_state() const {
  auto state = std::make_unique<State>();
  state->gradient.jb.resize(static_cast<std::size_t>(std::max(1, nb_)));
  return state;
}

void SliderSpringForce::beam_dofs_read(const double* qb, std::vector<int>& out) const {
  const double s = kernels_.position(qb);
  if (!(s >= 0.0 && s <= mesh_.length())) return;
  const int element = element_at(mesh_, s);
  for (int j = 0; j < 4; ++j) {
    const int f = mesh_.full_to_free[2 * element + j];
    if (f >= 0) out.push_back(offset_ + f);
  }
}

void SliderSpringForce::add_force(const ForceArgs& x, ForceState& state, ForceSink& out) const {
  State& self = static_cast<State&>(state);
  SpringContactState& st = self.contact;
  SpringGradient& g = self.gradient;
  st = SpringContactState{};
  g.pressing = false;
  st.s = kernels_.position(x.qb);
  st.on_beam = st.s >= 0.0 && st.s <= mesh_.length();
  if (!st.on_beam) return;
  const int element = element_at(mesh_, st.s);
  const double s0 = element * mesh_.element_length;
  double qe[4], qed[4];
  for (int j = 0; j < 4; ++j) {
    const int f = mesh_.full_to_free[2 * element + j];
    g.cols[j] = f >= 0 ? offset_ + f : -1;
    qe[j] = f >= 0 ? x.qc[g.cols[j]] : 0.0;
    qed[j] = f >= 0 ? x.vc[g.cols[j]] : 0.0;
  }
  st.w = hermite::N((st.s - s0) / mesh_.element_length, mesh_.element_length) *
         Eigen::Map<const Eigen::Vector4d>(qe);
  // The point rides on the running surface, w + profile - camber.
  if (mesh_.surface) mesh_.surface->add_to_element(element, st.s, s0, mesh_.element_length, qe);
  kernels_.phi(x.qb, qe, s0, mesh_.element_length, &st.delta);
  // Pressed from the +w side: the penetration and its gradient change sign.
  const double side = kernels_.from_below ? -1.0 : 1.0;
  st.delta *= side;
  std::vector<double>& jb = g.jb;
  kernels_.jacobians(x.qb, qe, s0, mesh_.element_length, jb.data(), g.je);
  if (side < 0.0) {
    for (int j = 0; j < nb_; ++j) jb[j] = -jb[j];
    for (double& v : g.je) v = -v;
  }
  for (int j = 0; j < nb_; ++j) st.rate += jb[j] * x.vb[j];
  for (int j = 0; j < 4; ++j)
    if (g.cols[j] >= 0) st.rate += g.je[j] * qed[j];
  double force = law_force(st.delta, st.rate);
  if (kernels_.unilateral && (st.delta <= 0.0 || force < 0.0)) force = 0.0;
  st.force = force;
  // Apart, a Hertzian contact is no spring at all (bilateral or not).
  g.pressing = law_.hertz ? st.delta > 0.0 && (!kernels_.unilateral || force > 0.0)
                          : !kernels_.unilateral || force > 0.0;
  if (force == 0.0) return;
  for (int j = 0; j < nb_; ++j) out.fb[j] -= jb[j] * force;
  for (int j = 0; j < 4; ++j)
    if (g.cols[j] >= 0) out.fc[g.cols[j]] -= g.je[j] * force;
}

void SliderSpringForce::add_tangent(const ForceArgs&, const ForceState& state, double c_q, double c_v,
                                    TangentSink& out) const {
  const State& self = static_cast<const State&>(state);
  const SpringGradient& g = self.gradient;
  if (!g.pressing) return;
  const double w = c_q * law_stiffness(self.contact.delta) + c_v * kernels_.damping;
  // g over the rigid coordinates, then the 4 beam DOFs (at nb + column).
  std::vector<std::pair<int, double>>& entries = self.entries;
  entries.clear();
  for (int j = 0; j < nb_; ++j)
    if (g.jb[j] != 0.0) entries.emplace_back(j, g.jb[j]);
  for (int j = 0; j < 4; ++j)
    if (g.cols[j] >= 0 && g.je[j] != 0.0) entries.emplace_back(nb_ + g.cols[j], g.je[j]);
  for (const auto& [i, gi] : entries)
    for (const auto& [j, gj] : entries) out.add(i, j, w * gi * gj);
}

}  // namespace mbfe::runtime
