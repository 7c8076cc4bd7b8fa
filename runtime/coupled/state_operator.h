// What the spectrum of a linearised model (tangent_spectrum.h) needs of it:
// the state matrix A = [[0, I], [-M^-1 K_t, -M^-1 C_t]] over n free
// coordinates, applied, shifted and solved, or formed for small models. The
// coupled model's own tangents (coupled_tangents.h) and their projection on a
// truncated structure's kept modes (truncated_tangents.h) provide it.
#pragma once

#include <Eigen/Core>

namespace mbfe::runtime {

class StateOperator {
 public:
  virtual ~StateOperator() = default;
  /// Free coordinates n (A is 2n square).
  virtual int size() const = 0;
  /// Driven coordinates left out: each is a zero pair of the full A.
  virtual int num_driven() const = 0;
  /// out = A in (2n entries each, [z; z']).
  virtual void apply_state_matrix(const double* in, double* out) const = 0;
  /// Factors S = sigma^2 M + sigma C_t + K_t for solve_shifted (sigma in 1/s).
  /// @throws std::runtime_error when S is singular.
  virtual void factorize_shifted(double sigma) = 0;
  virtual double shift() const = 0;
  /// out = (A - sigma I)^-1 in, sigma of the last factorize_shifted.
  virtual void solve_shifted(const double* in, double* out) const = 0;
  /// A as a dense matrix (small models and tests).
  virtual Eigen::MatrixXd dense_state_matrix() const = 0;
};

}  // namespace mbfe::runtime
