#include "runtime/coupled/contact_springs.h"

#include <algorithm>
#include <cmath>

#include "runtime/fem/hermite_shape.h"

namespace mbfe::runtime {

namespace {

/// The element holding s on a beam (s in [0, L]).
int element_at(const BeamMesh& beam, double s) {
  return std::clamp(static_cast<int>(std::floor(s / beam.element_length)), 0, beam.num_elements - 1);
}

}  // namespace

ContactSprings::ContactSprings(const mbfe_model_v1& model, const ContactConstraints& constraints)
    : model_(model), cc_(constraints) {
  for (int c = 0; c < model.num_contacts; ++c)
    if (model.contacts[c].type == 2) contacts_.push_back(c);
  states_.resize(contacts_.size());
  gradients_.resize(contacts_.size());
  for (SpringGradient& g : gradients_) g.jb.resize(static_cast<std::size_t>(std::max(1, model.num_coordinates)));
}

std::string ContactSprings::name(int k) const { return cc_.contact_name(contacts_[k]); }

void ContactSprings::columns_read(const double* qb, std::vector<int>& out) const {
  for (int c : contacts_) {
    const mbfe_contact_kernels_v1& kern = model_.contacts[c];
    const BeamMesh& beam = cc_.beams()[kern.beam];
    const double s = kern.position(qb);
    if (!(s >= 0.0 && s <= beam.length())) continue;
    const int element = element_at(beam, s);
    for (int j = 0; j < 4; ++j) {
      const int f = beam.full_to_free[2 * element + j];
      if (f >= 0) out.push_back(cc_.beam_offset(kern.beam) + f);
    }
  }
}

void ContactSprings::apply(const double* qb, const double* qc, const double* qbd, const double* qcd,
                           Eigen::Ref<Eigen::VectorXd> q_force, Eigen::Ref<Eigen::VectorXd> beam_force) {
  const int nb = model_.num_coordinates;
  for (std::size_t k = 0; k < contacts_.size(); ++k) {
    const mbfe_contact_kernels_v1& kern = model_.contacts[contacts_[k]];
    const BeamMesh& beam = cc_.beams()[kern.beam];
    SpringContactState& st = states_[k];
    st = SpringContactState{};
    SpringGradient& g = gradients_[k];
    g.pressing = false;
    st.s = kern.position(qb);
    st.on_beam = st.s >= 0.0 && st.s <= beam.length();
    if (!st.on_beam) continue;
    const int element = element_at(beam, st.s);
    const double s0 = element * beam.element_length;
    const int offset = cc_.beam_offset(kern.beam);
    double qe[4], qed[4];
    int* cols = g.cols;
    for (int j = 0; j < 4; ++j) {
      const int f = beam.full_to_free[2 * element + j];
      cols[j] = f >= 0 ? offset + f : -1;
      qe[j] = f >= 0 ? qc[cols[j]] : 0.0;
      qed[j] = f >= 0 ? qcd[cols[j]] : 0.0;
    }
    kern.phi(qb, qe, s0, beam.element_length, &st.delta);
    // Pressed from the +w side: the penetration and its gradient change sign.
    const double side = kern.from_below ? -1.0 : 1.0;
    st.delta *= side;
    st.w = hermite::N((st.s - s0) / beam.element_length, beam.element_length) *
           Eigen::Map<const Eigen::Vector4d>(qe);
    double* je = g.je;
    std::vector<double>& jb = g.jb;
    kern.jacobians(qb, qe, s0, beam.element_length, jb.data(), je);
    if (side < 0.0) {
      for (int j = 0; j < nb; ++j) jb[j] = -jb[j];
      for (int j = 0; j < 4; ++j) je[j] = -je[j];
    }
    for (int j = 0; j < nb; ++j) st.rate += jb[j] * qbd[j];
    for (int j = 0; j < 4; ++j)
      if (cols[j] >= 0) st.rate += je[j] * qed[j];
    double force = kern.stiffness * st.delta + kern.damping * st.rate;
    if (kern.unilateral && (st.delta <= 0.0 || force < 0.0)) force = 0.0;
    st.force = force;
    g.pressing = !kern.unilateral || force > 0.0;
    if (force == 0.0) continue;
    for (int j = 0; j < nb; ++j) q_force[j] -= jb[j] * force;
    for (int j = 0; j < 4; ++j)
      if (cols[j] >= 0) beam_force[cols[j]] -= je[j] * force;
  }
}

}  // namespace mbfe::runtime
