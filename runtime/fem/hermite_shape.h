// Hermite cubic shape functions of a planar Euler-Bernoulli beam element.
//
// On an element of length le, with local coordinate xi = (s - s_e) / le in
// [0, 1] (s_e = where the element starts along the beam), the transverse
// displacement is
//   w(s) = N(xi, le) q_e,   q_e = [w_1, w'_1, w_2, w'_2]
// (w in m, w' = dw/ds dimensionless). Reused by contacts and probes: evaluate
// w(s) = N q_e on the element that contains s (see locate_on_beam in
// beam_system.h).
#pragma once

#include <Eigen/Core>

namespace mbfe::runtime::hermite {

using Row4 = Eigen::Matrix<double, 1, 4>;

/// N(xi): w = N q_e. @param xi in [0, 1] @param le element length in m (> 0).
inline Row4 N(double xi, double le) {
  const double x2 = xi * xi;
  const double x3 = x2 * xi;
  Row4 n;
  n << 1.0 - 3.0 * x2 + 2.0 * x3, le * (xi - 2.0 * x2 + x3), 3.0 * x2 - 2.0 * x3, le * (x3 - x2);
  return n;
}

/// dN/ds (1/m): w' = dN_ds q_e.
inline Row4 dN_ds(double xi, double le) {
  const double x2 = xi * xi;
  Row4 n;
  n << (6.0 * x2 - 6.0 * xi) / le, 1.0 - 4.0 * xi + 3.0 * x2, (6.0 * xi - 6.0 * x2) / le,
      3.0 * x2 - 2.0 * xi;
  return n;
}

/// d2N/ds2 (1/m^2): curvature w'' = d2N_ds2 q_e.
inline Row4 d2N_ds2(double xi, double le) {
  Row4 n;
  n << (12.0 * xi - 6.0) / (le * le), (6.0 * xi - 4.0) / le, (6.0 - 12.0 * xi) / (le * le),
      (6.0 * xi - 2.0) / le;
  return n;
}

}  // namespace mbfe::runtime::hermite
