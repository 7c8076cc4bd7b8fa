#include "runtime/fem/hermite_beam_element.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace mbfe::runtime {

HermiteBeamElement::HermiteBeamElement(double le, double EI, double rhoA,
                                       ir::MassLumping lumping)
    : le_(le), EI_(EI), rhoA_(rhoA), lumping_(lumping) {}

Eigen::MatrixXd HermiteBeamElement::stiffness() const {
  const double l = le_;
  const double l2 = l * l;
  Eigen::MatrixXd k(4, 4);
  k << 12.0, 6.0 * l, -12.0, 6.0 * l,    //
      6.0 * l, 4.0 * l2, -6.0 * l, 2.0 * l2,  //
      -12.0, -6.0 * l, 12.0, -6.0 * l,   //
      6.0 * l, 2.0 * l2, -6.0 * l, 4.0 * l2;
  return (EI_ / (l2 * l)) * k;
}

Eigen::MatrixXd HermiteBeamElement::mass() const {
  const double l = le_;
  const double l2 = l * l;
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(4, 4);
  if (lumping_ == ir::MassLumping::kLumped) {
    // HRZ lumping: the consistent diagonal scaled so the translational terms
    // add up to the element mass; keeps a positive rotary inertia (M stays
    // positive definite, so every mode has a finite frequency).
    const double m_e = rhoA_ * l;
    m(0, 0) = m(2, 2) = 0.5 * m_e;
    m(1, 1) = m(3, 3) = m_e * l2 / 78.0;
    return m;
  }
  m << 156.0, 22.0 * l, 54.0, -13.0 * l,      //
      22.0 * l, 4.0 * l2, 13.0 * l, -3.0 * l2,  //
      54.0, 13.0 * l, 156.0, -22.0 * l,       //
      -13.0 * l, -3.0 * l2, -22.0 * l, 4.0 * l2;
  return (rhoA_ * l / 420.0) * m;
}

Eigen::VectorXd HermiteBeamElement::uniform_load(double q) const {
  Eigen::VectorXd p(4);
  p << 0.5 * q * le_, q * le_ * le_ / 12.0, 0.5 * q * le_, -q * le_ * le_ / 12.0;
  return p;
}

Eigen::MatrixXd HermiteBeamElement::stiffness_factor() const {
  const double l = le_;
  const double root = std::sqrt(EI_ * l);
  const double r12 = std::sqrt(12.0);
  Eigen::MatrixXd f(2, 4);
  f << 0.0, -root / l, 0.0, root / l,  // mean curvature (theta2 - theta1) / le
      root * 12.0 / (r12 * l * l), root * 6.0 / (r12 * l), -root * 12.0 / (r12 * l * l),
      root * 6.0 / (r12 * l);  // curvature change k1 - k0, over sqrt(12)
  return f;
}

std::unique_ptr<BeamElement> make_beam_element(const ir::Beam& beam) {
  const auto require_positive = [&](double v, const char* what) {
    if (!(v > 0.0) || !std::isfinite(v)) {
      throw std::invalid_argument("beam '" + beam.name + "': " + what + " must be > 0 (got " +
                                  std::to_string(v) + ")");
    }
  };
  require_positive(beam.length, "length");
  require_positive(static_cast<double>(beam.elements), "elements");
  require_positive(beam.area, "section area");
  require_positive(beam.second_moment, "second moment of area");
  require_positive(beam.youngs_modulus, "youngs_modulus");
  require_positive(beam.density, "density");
  const double le = beam.length / beam.elements;
  return std::make_unique<HermiteBeamElement>(le, beam.youngs_modulus * beam.second_moment,
                                              beam.density * beam.area, beam.mass);
}

}  // namespace mbfe::runtime
