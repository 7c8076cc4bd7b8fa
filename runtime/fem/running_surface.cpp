#include "runtime/fem/running_surface.h"

#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "runtime/fem/beam_system.h"

namespace mbfe::runtime {

namespace {

// Grid points per shortest wavelength of a tabulated spectrum profile: the
// cubic Hermite interpolant of r and r' errs by at most (h omega)^4 / 384
// relative, 3.9e-6 at h = lambda_min / 32.
constexpr int kGridPerWavelength = 32;

}  // namespace

RunningSurface::RunningSurface(const ir::BeamProfile& profile, double length, int elements,
                               Eigen::VectorXd camber_full)
    : kind_(profile.kind), camber_(std::move(camber_full)), element_length_(length / elements),
      elements_(elements) {
  if (camber_.size() != 0 && camber_.size() != 2 * (elements + 1))
    throw std::invalid_argument("running surface: " + std::to_string(camber_.size()) +
                                " camber DOFs; expected " + std::to_string(2 * (elements + 1)));
  switch (kind_) {
    case ir::ProfileKind::kNone: break;
    case ir::ProfileKind::kExpression: expression_ = profile.expression; break;
    case ir::ProfileKind::kTable: {
      table_s_ = profile.table_s;
      table_r_ = profile.table_offset;
      if (table_s_.size() < 2 || table_s_.size() != table_r_.size())
        throw std::invalid_argument("running surface: a profile table needs at least 2 rows of (s, offset)");
      for (std::size_t i = 1; i < table_s_.size(); ++i)
        if (!(table_s_[i] > table_s_[i - 1]))
          throw std::invalid_argument("running surface: the profile table's s is not strictly increasing");
      break;
    }
    case ir::ProfileKind::kSpectrum: {
      const HarmonicProfile harmonics =
          spectrum_profile(profile.spectrum, profile.spectrum_class, profile.wavelength_min, profile.wavelength_max,
                           length, profile.seed);
      grid_step_ = profile.wavelength_min / kGridPerWavelength;
      const int n = static_cast<int>(std::ceil(length / grid_step_)) + 1;
      grid_r_.resize(n + 1);
      grid_dr_.resize(n + 1);
      for (int k = 0; k <= n; ++k) {
        double ddr = 0.0;
        harmonics.evaluate(k * grid_step_, grid_r_[k], grid_dr_[k], ddr);
      }
      break;
    }
  }
}

Jet RunningSurface::profile(double s) const {
  switch (kind_) {
    case ir::ProfileKind::kNone: return {};
    case ir::ProfileKind::kExpression: return evaluate_jet(expression_, s);
    case ir::ProfileKind::kTable: {
      // The segment holding s; beyond the ends the end segments go on.
      const auto it = std::upper_bound(table_s_.begin(), table_s_.end(), s);
      const std::size_t hi =
          std::clamp<std::size_t>(static_cast<std::size_t>(it - table_s_.begin()), 1, table_s_.size() - 1);
      const double slope = (table_r_[hi] - table_r_[hi - 1]) / (table_s_[hi] - table_s_[hi - 1]);
      return {table_r_[hi - 1] + slope * (s - table_s_[hi - 1]), slope, 0.0};
    }
    case ir::ProfileKind::kSpectrum: {
      const int last = static_cast<int>(grid_r_.size()) - 2;
      const int k = std::clamp(static_cast<int>(std::floor(s / grid_step_)), 0, last);
      const double h = grid_step_;
      const double x = (s - k * h) / h;
      const double r0 = grid_r_[k], r1 = grid_r_[k + 1], m0 = grid_dr_[k] * h, m1 = grid_dr_[k + 1] * h;
      // Cubic Hermite on [k h, (k + 1) h] in x in [0, 1].
      const double x2 = x * x, x3 = x2 * x;
      const double value = (2 * x3 - 3 * x2 + 1) * r0 + (x3 - 2 * x2 + x) * m0 + (-2 * x3 + 3 * x2) * r1 +
                           (x3 - x2) * m1;
      const double d1 = ((6 * x2 - 6 * x) * r0 + (3 * x2 - 4 * x + 1) * m0 + (-6 * x2 + 6 * x) * r1 +
                         (3 * x2 - 2 * x) * m1) / h;
      const double d2 = ((12 * x - 6) * r0 + (6 * x - 4) * m0 + (-12 * x + 6) * r1 + (6 * x - 2) * m1) / (h * h);
      return {value, d1, d2};
    }
  }
  return {};
}

double RunningSurface::offset(double s) const {
  double out = profile(s).value;
  if (camber_.size() > 0) {
    const int e = std::clamp(static_cast<int>(std::floor(s / element_length_)), 0, elements_ - 1);
    const double le = element_length_;
    const double xi = (s - e * le) / le;
    const double xi2 = xi * xi, xi3 = xi2 * xi;
    out -= (1 - 3 * xi2 + 2 * xi3) * camber_[2 * e] + le * (xi - 2 * xi2 + xi3) * camber_[2 * e + 1] +
           (3 * xi2 - 2 * xi3) * camber_[2 * e + 2] + le * (xi3 - xi2) * camber_[2 * e + 3];
  }
  return out;
}

void RunningSurface::add_to_element(int element, double s, double s0, double le, double* qe) const {
  if (kind_ != ir::ProfileKind::kNone) {
    const Jet r = profile(s);
    // p(x) = r + r' (x - s) + r'' (x - s)^2 / 2 at the element's two nodes.
    for (int end = 0; end < 2; ++end) {
      const double d = s0 + end * le - s;
      qe[2 * end] += r.value + r.d1 * d + 0.5 * r.d2 * d * d;
      qe[2 * end + 1] += r.d1 + r.d2 * d;
    }
  }
  if (camber_.size() > 0)
    for (int j = 0; j < 4; ++j) qe[j] -= camber_[2 * element + j];
}

std::optional<RunningSurface> running_surface(const ir::Beam& beam, const ir::Vec2& gravity) {
  if (!beam.profile.active()) return std::nullopt;
  Eigen::VectorXd camber;
  if (beam.profile.camber_static) {
    ir::Beam dead = beam;
    dead.profile = {};
    dead.loads.clear();
    dead.moving_loads.clear();
    const BeamSystem sys = assemble_beam(dead, gravity);
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(sys.K);
    const double scale = sys.K.size() > 0 ? Eigen::VectorXd(sys.K.diagonal()).cwiseAbs().maxCoeff() : 1.0;
    const bool held = ldlt.info() == Eigen::Success && sys.K.rows() > 0 &&
                      ldlt.vectorD().minCoeff() > 1e-12 * scale;
    if (!held)
      throw std::invalid_argument("beam '" + beam.name +
                                  "': camber: static needs a beam its own supports hold (its stiffness is "
                                  "singular without them: a wire hung from droppers has no own-weight sag to "
                                  "take out); give the beam supports or drop camber");
    const Eigen::VectorXd w = ldlt.solve(sys.P);
    camber = Eigen::VectorXd::Zero(2 * sys.num_nodes);
    for (std::size_t f = 0; f < sys.free_dof.size(); ++f) camber[sys.free_dof[f]] = w[static_cast<Eigen::Index>(f)];
  }
  return RunningSurface(beam.profile, beam.length, beam.elements, std::move(camber));
}

}  // namespace mbfe::runtime
