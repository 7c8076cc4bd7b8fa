#include "runtime/fem/hermite_beam_element.h"

#include "runtime/fem/hermite_shape.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace mbfe::runtime {

HermiteBeamElement::HermiteBeamElement(double le, double EI, double rhoA,
                                       ir::MassLumping lumping, double tension)
    : le_(le), EI_(EI), rhoA_(rhoA), lumping_(lumping), tension_(tension) {}



Eigen::MatrixXd HermiteBeamElement::stiffness() const {
  const double l = le_;
  const double l2 = l * l;
  Eigen::MatrixXd k(4, 4);
  k << 12.0, 6.0 * l, -12.0, 6.0 * l,    //
      6.0 * l, 4.0 * l2, -6.0 * l, 2.0 * l2,  //
      -12.0, -6.0 * l, 12.0, -6.0 * l,   //
      6.0 * l, 2.0 * l2, -6.0 * l, 4.0 * l2;
  Eigen::MatrixXd out = (EI_ / (l2 * l)) * k;
  if (tension_ > 0.0) {
    Eigen::MatrixXd g(4, 4);
    g << 36.0, 3.0 * l, -36.0, 3.0 * l,   //
        3.0 * l, 4.0 * l2, -3.0 * l, -l2,  //
        -36.0, -3.0 * l, 36.0, -3.0 * l,  //
        3.0 * l, -l2, -3.0 * l, 4.0 * l2;
    out += (tension_ / (30.0 * l)) * g;
  }
  return out;
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
  if (!(tension_ > 0.0)) return f;
  // T int_0^l N'^T N' ds by 3-point Gauss on [0, 1]: rows sqrt(T l w_g) N'(xi_g).
  const double a = std::sqrt(0.6);
  const double xi[3] = {0.5 * (1.0 - a), 0.5, 0.5 * (1.0 + a)};
  const double w[3] = {5.0 / 18.0, 8.0 / 18.0, 5.0 / 18.0};
  Eigen::MatrixXd out(5, 4);
  out.topRows(2) = f;
  for (int g = 0; g < 3; ++g) out.row(2 + g) = std::sqrt(tension_ * l * w[g]) * hermite::dN_ds(xi[g], l);
  return out;
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
  if (!(beam.tension >= 0.0) || !std::isfinite(beam.tension))
    throw std::invalid_argument("beam '" + beam.name + "': tension must be >= 0");
  return std::make_unique<HermiteBeamElement>(le, beam.youngs_modulus * beam.second_moment,
                                              beam.density * beam.area, beam.mass, beam.tension);
}

}  // namespace mbfe::runtime
