#include "runtime/coupled/contact_constraints.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "runtime/errors/multibody_errors.h"
#include "runtime/fem/running_surface.h"

namespace mbfe::runtime {

namespace {
constexpr double kEndSlack = 1e-3;  // of an element length
}  // namespace

void ConstraintValues::jc_times(const Eigen::Ref<const Eigen::VectorXd>& x, Eigen::VectorXd& out) const {
  out.setZero(je.rows());
  for (int r = 0; r < je.rows(); ++r) {
    for (int k = 0; k < 4; ++k) {
      if (jcol(r, k) >= 0) out(r) += je(r, k) * x(jcol(r, k));
    }
  }
}

Eigen::MatrixXd ConstraintValues::jc_dense(int nc) const {
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(je.rows(), nc);
  for (int r = 0; r < je.rows(); ++r) {
    for (int k = 0; k < 4; ++k) {
      if (jcol(r, k) >= 0) out(r, jcol(r, k)) += je(r, k);
    }
  }
  return out;
}

ContactConstraints::ContactConstraints(const mbfe_model_v1& model, std::vector<BeamMesh> beams)
    : model_(model), beams_(std::move(beams)), nb_(model.num_coordinates) {
  for (const BeamMesh& b : beams_) {
    if (b.num_elements <= 0 || !(b.element_length > 0.0) ||
        static_cast<int>(b.full_to_free.size()) != 2 * (b.num_elements + 1)) {
      throw std::invalid_argument("beam '" + b.name +
                                  "': mesh needs elements > 0, element length > 0 and "
                                  "2 (elements + 1) entries in full_to_free");
    }
    beam_offset_.push_back(nc_);
    nc_ += b.num_free;
  }
  for (int c = 0; c < model.num_contacts; ++c) {
    const mbfe_contact_kernels_v1& k = model.contacts[c];
    const std::string name = k.name ? k.name : "contact " + std::to_string(c);
    if (k.beam < 0 || k.beam >= static_cast<int>(beams_.size())) {
      std::ostringstream os;
      os << "contact '" << name << "': beam index " << k.beam << " outside the "
         << beams_.size() << " beams given";
      throw std::invalid_argument(os.str());
    }
    const int want_rows = k.type == 0 ? 2 : 1;
    if (k.type < 0 || k.type > 2 || k.rows != want_rows) {
      std::ostringstream os;
      os << "contact '" << name << "': type " << k.type << " with " << k.rows
         << " rows, expected type 0 (pin, 2 rows), 1 (slider_pin, 1 row) or 2 (slider_spring, 1 row)";
      throw std::invalid_argument(os.str());
    }
    if (!k.position || !k.phi || !k.jacobians || !k.gamma) {
      throw std::invalid_argument("contact '" + name + "': a kernel pointer is null");
    }
    if (k.type == 0 && (k.at < 0.0 || k.at > beams_[k.beam].length())) {
      std::ostringstream os;
      os << "contact '" << name << "': pin at s = " << k.at << " m is outside beam '"
         << beams_[k.beam].name << "' [0, " << beams_[k.beam].length() << "] m";
      throw std::invalid_argument(os.str());
    }
    row0_.push_back(rows_);
    if (k.type == 2) continue;  // a penalty force (contact_springs.h), no constraint row
    for (int r = 0; r < k.rows; ++r) contact_of_row_.push_back(c);
    rows_ += k.rows;
  }
}

std::string ContactConstraints::contact_name(int c) const {
  const char* n = model_.contacts[c].name;
  return n ? n : "contact " + std::to_string(c);
}

void ContactConstraints::evaluate(double t, const double* qb, const double* qc,
                                  const double* qbd, const double* qcd,
                                  ConstraintValues& out) const {
  const bool want_gamma = qbd != nullptr && qcd != nullptr;
  out.phi.resize(rows_);
  out.jb.resize(rows_, nb_);
  out.je.resize(rows_, 4);
  out.jcol.resize(rows_, 4);
  if (want_gamma) out.gamma.resize(rows_);
  out.s.resize(row0_.size());
  out.element.resize(row0_.size());
  double jb_buf[2 * 64];
  std::vector<double> jb_heap;
  for (int c = 0; c < num_contacts(); ++c) {
    const mbfe_contact_kernels_v1& k = model_.contacts[c];
    const BeamMesh& beam = beams_[k.beam];
    if (k.type == 2) {  // not a constraint
      out.s[c] = k.position(qb);
      out.element[c] = -1;
      continue;
    }
    const double s = k.type == 0 ? k.at : k.position(qb);
    const double L = beam.length();
    // A slider exactly at an end is on the beam, and so is one that a finite
    // difference (linearization.h) nudges past it: within a thousandth of an
    // element the end element's cubic is extended, which is exact to O(slack^2).
    const double slack = kEndSlack * beam.element_length;
    if (!(s >= -slack && s <= L + slack)) {
      std::ostringstream os;
      os.precision(10);
      os << "contact '" << contact_name(c) << "' left beam '" << beam.name << "' at t = " << t
         << " s: s = " << s << " m is outside the beam's [0, " << L << "] m";
      throw SliderOffBeamError(os.str(), contact_name(c), t, s);
    }
    const int idx =
        std::clamp(static_cast<int>(std::floor(s / beam.element_length)), 0, beam.num_elements - 1);
    const double s0 = idx * beam.element_length;
    out.s[c] = s;
    out.element[c] = idx;
    double qe[4], qed[4];
    int cols[4];
    for (int j = 0; j < 4; ++j) {
      const int f = beam.full_to_free[2 * idx + j];
      cols[j] = f >= 0 ? beam_offset_[k.beam] + f : -1;
      qe[j] = f >= 0 ? qc[cols[j]] : 0.0;
      qed[j] = (f >= 0 && want_gamma) ? qcd[cols[j]] : 0.0;
    }
    // A slider rides on the running surface, w + profile - camber; a pin holds the axis.
    if (k.type == 1 && beam.surface) beam.surface->add_to_element(idx, s, s0, beam.element_length, qe);
    const int r0 = row0_[c];
    k.phi(qb, qe, s0, beam.element_length, out.phi.data() + r0);
    double* jb = jb_buf;
    if (k.rows * nb_ > 2 * 64) {
      jb_heap.resize(k.rows * nb_);
      jb = jb_heap.data();
    }
    double je[8];
    k.jacobians(qb, qe, s0, beam.element_length, jb, je);
    for (int r = 0; r < k.rows; ++r) {
      for (int j = 0; j < nb_; ++j) out.jb(r0 + r, j) = jb[r * nb_ + j];
      for (int j = 0; j < 4; ++j) {
        out.je(r0 + r, j) = cols[j] >= 0 ? je[r * 4 + j] : 0.0;
        out.jcol(r0 + r, j) = cols[j];
      }
    }
    if (want_gamma) {
      k.gamma(qb, qbd, qe, qed, s0, beam.element_length, out.gamma.data() + r0);
    }
  }
}

void ContactConstraints::evaluate_gamma(const double* qb, const double* qc, const double* qbd,
                                        const double* qcd, ConstraintValues& out) const {
  out.gamma.resize(rows_);
  for (int c = 0; c < num_contacts(); ++c) {
    const mbfe_contact_kernels_v1& k = model_.contacts[c];
    if (k.type == 2) continue;
    const BeamMesh& beam = beams_[k.beam];
    const int idx = out.element[c];
    double qe[4], qed[4];
    for (int j = 0; j < 4; ++j) {
      const int col = out.jcol(row0_[c], j);
      qe[j] = col >= 0 ? qc[col] : 0.0;
      qed[j] = col >= 0 ? qcd[col] : 0.0;
    }
    if (k.type == 1 && beam.surface)
      beam.surface->add_to_element(idx, out.s[c], idx * beam.element_length, beam.element_length, qe);
    k.gamma(qb, qbd, qe, qed, idx * beam.element_length, beam.element_length,
            out.gamma.data() + row0_[c]);
  }
}

}  // namespace mbfe::runtime
