// Which rigid coordinates the partitioned formulation closes by the
// constraints (the dependent v) and which it integrates (the independent u):
// the largest pivots of J_b, and the tests that tell a healthy J_v from a
// singular one (docs/partitioning.md).
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "runtime/coupled/contact_constraints.h"
#include "runtime/linalg/small_lu.h"

namespace mbfe::runtime {

/// Which rigid coordinates are dependent (v, m of them) and independent (u).
struct Partition {
  std::vector<int> dependent;    // ascending rigid indices
  std::vector<int> independent;  // ascending rigid indices
};

/// The best partition for the rigid Jacobian cv.jb (m x nb): the columns of
/// the first m pivots of a column-pivoted QR (largest pivots). `sigma_min`
/// receives the smallest singular value of the chosen J_v (the quality measure
/// that PartitionedSystem compares between partitions).
/// @throws SingularConstraintError (naming the contact most involved in the
///         rank loss, t and sigma_min / scale) if sigma_min(J_v) is below 1e-13
///         times constraint_scale(cv): J_b has rank < m.
Partition choose_partition(const ContactConstraints& cc, const ConstraintValues& cv, double t,
                           double* sigma_min = nullptr);

/// Scale of the constraint Jacobian, max(sigma_max(J_b), max |J_e|), against
/// which a singular J_v is judged (so that a J_b that vanishes as a whole, a
/// linkage at a dead point, is caught).
double constraint_scale(const ConstraintValues& cv);

/// Smallest singular value of a matrix (1 for an empty one).
double sigma_min(const Eigen::MatrixXd& a);

/// J_v is declared singular when sigma_min(J_v) < kSingularConstraint x
/// constraint_scale(cv) (double precision with a margin of ~1e3 ulps).
constexpr double kSingularConstraint = 1e-13;

/// A cheap sufficient test (rigorous up to the rounding of the LU) that J_v,
/// factored as `jv_lu`, passes the singularity test: a lower bound of
/// sigma_min(J_v) (the pivot bound of SmallLu, then 1 / ||J_v^-1||_F) against an upper bound of
/// constraint_scale(cv) (||J_b||_F, max |J_e|). When it returns false the
/// caller runs the exact (SVD) test; it only saves the SVDs on the common,
/// healthy path.
bool clearly_regular(SmallLu& jv_lu, const ConstraintValues& cv);

/// Throws SingularConstraintError naming the contact whose row carries most of
/// the rank J_b has lost, with t (s), the reciprocal condition `rcond` and
/// `what` (which matrix was found singular).
[[noreturn]] void throw_singular_constraints(const ContactConstraints& cc, const Eigen::MatrixXd& jb, double t,
                                             double rcond, const std::string& what);

}  // namespace mbfe::runtime
