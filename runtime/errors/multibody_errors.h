// Numerical faults of the multibody and coupled (multibody + beam) systems that
// a user must hear about. Each is a std::runtime_error whose what() is the full,
// actionable message; the fields repeat its parts for callers that format their
// own report (the CLI keeps the output written so far and exits with status 3).
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

namespace mbfe::runtime {

/// M(q) of the rigid part is singular or not positive definite: some
/// coordinate moves no mass. what() names the coordinates in the null space and
/// the bodies that carry no inertia (mass == 0 and inertia == 0).
class SingularMassMatrixError : public std::runtime_error {
 public:
  SingularMassMatrixError(const std::string& message, double t,
                          std::vector<std::string> coordinates,
                          std::vector<std::string> massless_bodies)
      : std::runtime_error(message),
        t_(t),
        coordinates_(std::move(coordinates)),
        massless_bodies_(std::move(massless_bodies)) {}
  double t() const { return t_; }
  /// Coordinates with a significant share in the null space of M.
  const std::vector<std::string>& coordinates() const { return coordinates_; }
  /// Bodies with mass == 0 and inertia == 0 (empty if unknown).
  const std::vector<std::string>& massless_bodies() const { return massless_bodies_; }

 private:
  double t_;
  std::vector<std::string> coordinates_;
  std::vector<std::string> massless_bodies_;
};

/// A fault tied to one contact: the contact's name, the time and the offending
/// value are part of what() and available separately.
class ContactError : public std::runtime_error {
 public:
  ContactError(const std::string& message, std::string contact, double t, double value)
      : std::runtime_error(message), contact_(std::move(contact)), t_(t), value_(value) {}
  const std::string& contact() const { return contact_; }
  double t() const { return t_; }
  double value() const { return value_; }

 private:
  std::string contact_;
  double t_;
  double value_;
};

/// A slider_pin contact point left its beam: s < 0 or s > L. value() = s (m).
class SliderOffBeamError : public ContactError {
 public:
  using ContactError::ContactError;
};

/// The constraint Jacobian (J_b for the partitioned formulation, the whole
/// saddle-point matrix for the augmented one) is singular: the rigid part cannot
/// follow the contact. value() = reciprocal condition estimate of the matrix.
class SingularConstraintError : public ContactError {
 public:
  using ContactError::ContactError;
};

/// Newton closure of the dependent coordinates failed to bring |Phi| below its
/// tolerance. value() = the |Phi| reached (m).
class NewtonClosureError : public ContactError {
 public:
  using ContactError::ContactError;
};

}  // namespace mbfe::runtime
