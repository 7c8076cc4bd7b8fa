#include "runtime/multibody/tangent_linearization.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace mbfe::runtime {

Eigen::VectorXd velocity_increment(const RigidCoordinates& c, const double* q0, const Eigen::VectorXd& dq) {
  Eigen::VectorXd dv(c.nv);
  for (int i = 0; i < c.nv; ++i) {
    if (c.rate_of[i] >= 0) {
      dv[i] = dq[c.rate_of[i]];
      continue;
    }
    // The body-frame rotation of dq = q0 (0, r / 2): r = 2 vec(conj(q0) dq).
    const int w = c.rotation_of[i];
    const double a0 = q0[w], a1 = -q0[w + 1], a2 = -q0[w + 2], a3 = -q0[w + 3];
    const double b0 = dq[w], b1 = dq[w + 1], b2 = dq[w + 2], b3 = dq[w + 3];
    const double product[3] = {a0 * b1 + a1 * b0 + a2 * b3 - a3 * b2, a0 * b2 - a1 * b3 + a2 * b0 + a3 * b1,
                               a0 * b3 + a1 * b2 - a2 * b1 + a3 * b0};
    dv[i] = 2.0 * product[c.rotation_axis[i]];
  }
  return dv;
}

Eigen::MatrixXd tangent_jacobian(OdeSystem& system, const RigidCoordinates& c, const std::vector<int>& moved,
                                 double t, const Eigen::VectorXd& y, double rel_step) {
  const int n = static_cast<int>(moved.size());
  if (y.size() != c.nq + n || system.size() != c.nq + n) {
    std::ostringstream os;
    os << "tangent_jacobian: y has " << y.size() << " entries and the system " << system.size() << ", expected "
       << c.nq + n << " (nq + the moved directions)";
    throw std::invalid_argument(os.str());
  }
  Eigen::MatrixXd a(2 * n, 2 * n);
  Eigen::VectorXd yp = y, fp, fm, dv = Eigen::VectorXd::Zero(c.nv);
  // One column of A from f at y +- the perturbation (h the step in z).
  auto column = [&](int j, double h) {
    const Eigen::VectorXd dq = velocity_increment(c, y.data(), (fp.head(c.nq) - fm.head(c.nq)) / (2.0 * h));
    for (int k = 0; k < n; ++k) a(k, j) = dq[moved[k]];
    a.col(j).tail(n) = (fp.tail(n) - fm.tail(n)) / (2.0 * h);
  };
  for (int j = 0; j < n; ++j) {
    const int i = moved[j];
    const double h = rel_step * (c.rate_of[i] >= 0 ? std::max(1.0, std::abs(y[c.rate_of[i]])) : 1.0);
    for (const double sign : {1.0, -1.0}) {
      yp.head(c.nq) = y.head(c.nq);
      dv[i] = sign * h;
      displace(c, yp.data(), dv);
      system.rhs(t, yp, sign > 0.0 ? fp : fm);
    }
    dv[i] = 0.0;
    yp.head(c.nq) = y.head(c.nq);
    column(j, h);
  }
  for (int j = 0; j < n; ++j) {
    const double h = rel_step * std::max(1.0, std::abs(y[c.nq + j]));
    yp[c.nq + j] = y[c.nq + j] + h;
    system.rhs(t, yp, fp);
    yp[c.nq + j] = y[c.nq + j] - h;
    system.rhs(t, yp, fm);
    yp[c.nq + j] = y[c.nq + j];
    column(n + j, h);
  }
  system.rhs(t, y, fp);  // leave the system's state at y
  return a;
}

}  // namespace mbfe::runtime
