#include "runtime/coupled/partition_choice.h"

#include <Eigen/QR>
#include <Eigen/SVD>
#include <cmath>
#include <sstream>

#include "runtime/errors/multibody_errors.h"

namespace mbfe::runtime {

void throw_singular_constraints(const ContactConstraints& cc,
                                             const Eigen::MatrixXd& jb, double t, double rcond,
                                             const std::string& what) {
  // The constraint row that carries most of the lost rank.
  int row = 0;
  if (jb.rows() > 0) {
    Eigen::JacobiSVD<Eigen::MatrixXd> svd(jb, Eigen::ComputeFullU);
    svd.matrixU().col(jb.rows() - 1).cwiseAbs().maxCoeff(&row);
  }
  const int c = cc.num_rows() > 0 ? cc.contact_of_row(row) : 0;
  const std::string name = cc.num_contacts() > 0 ? cc.contact_name(c) : "?";
  std::ostringstream os;
  os << "contact '" << name << "': singular constraint Jacobian at t = " << t << " s ("
     << what << ", reciprocal condition " << rcond
     << "): the rigid coordinates cannot move the contact point in the direction of row "
     << row - (cc.num_rows() > 0 ? cc.first_row(c) : 0)
     << " of this contact (a linkage at a dead point, or redundant contacts)";
  throw SingularConstraintError(os.str(), name, t, rcond);
}

double constraint_scale(const ConstraintValues& cv) {
  double scale = 0.0;
  if (cv.jb.size() > 0) {
    Eigen::JacobiSVD<Eigen::MatrixXd> svd(cv.jb);
    scale = svd.singularValues()(0);
  }
  if (cv.je.size() > 0) scale = std::max(scale, cv.je.cwiseAbs().maxCoeff());
  return std::max(scale, 1e-300);
}

bool clearly_regular(SmallLu& jv_lu, const ConstraintValues& cv) {
  if (jv_lu.size() == 0) return true;  // no dependent coordinates: nothing to invert
  // constraint_scale(cv) = max(sigma_max(J_b), max |J_e|) <= this, since
  // sigma_max <= the Frobenius norm.
  double scale_upper = cv.jb.size() > 0 ? cv.jb.norm() : 0.0;
  if (cv.je.size() > 0) scale_upper = std::max(scale_upper, cv.je.cwiseAbs().maxCoeff());
  const double needed = kSingularConstraint * std::max(scale_upper, 1e-300);
  return jv_lu.sigma_min_lower_cheap() >= needed || jv_lu.sigma_min_lower() >= needed;
}

double sigma_min(const Eigen::MatrixXd& a) {
  if (a.size() == 0) return 1.0;
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(a);
  return svd.singularValues()(svd.singularValues().size() - 1);
}

Partition choose_partition(const ContactConstraints& cc, const ConstraintValues& cv, double t,
                           double* sigma_min_out) {
  const Eigen::MatrixXd& jb = cv.jb;
  const int m = static_cast<int>(jb.rows());
  const int nb = static_cast<int>(jb.cols());
  if (m > nb) {
    std::ostringstream os;
    os << "the contacts impose " << m << " constraint rows on " << nb
       << " rigid coordinates; the dependent coordinates are taken among the rigid ones, "
          "so at most "
       << nb << " rows are possible";
    throw SingularConstraintError(os.str(), cc.num_contacts() ? cc.contact_name(0) : "?", t,
                                  0.0);
  }
  Partition p;
  if (m == 0) {
    for (int j = 0; j < nb; ++j) p.independent.push_back(j);
    if (sigma_min_out) *sigma_min_out = 1.0;
    return p;
  }
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(jb);
  std::vector<bool> dep(nb, false);
  for (int i = 0; i < m; ++i) dep[qr.colsPermutation().indices()(i)] = true;
  for (int j = 0; j < nb; ++j) (dep[j] ? p.dependent : p.independent).push_back(j);
  Eigen::MatrixXd jv(m, m);
  for (int i = 0; i < m; ++i) jv.col(i) = jb.col(p.dependent[i]);
  const double smin = sigma_min(jv);
  const double rel = smin / constraint_scale(cv);
  if (!(rel >= kSingularConstraint)) throw_singular_constraints(cc, jb, t, rel, "J_b has rank < rows");
  if (sigma_min_out) *sigma_min_out = smin;
  return p;
}

}  // namespace mbfe::runtime
