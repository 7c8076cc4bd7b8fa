#include "runtime/multibody/loop_systems.h"

#include <Eigen/LU>
#include <Eigen/SVD>
#include <sstream>
#include <stdexcept>

#include "runtime/errors/multibody_errors.h"

namespace mbfe::runtime {

namespace {

double smallest_singular_value(const Eigen::MatrixXd& a) {
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(a);
  return svd.singularValues()(svd.singularValues().size() - 1);
}

// The reciprocal condition below which the saddle-point matrix of the
// augmented formulation is singular (a redundant loop, a dead point).
constexpr double kSaddleRcondFloor = 1e-13;

}  // namespace

LoopSystem::LoopSystem(const mbfe_model_v1& model, std::vector<BodyInertia> bodies, RigidCoordinates coordinates,
                       const double* rows_at)
    : model_(model),
      bodies_(std::move(bodies)),
      closure_(model, std::move(coordinates), rows_at),
      nq_(closure_.coordinates().nq),
      nv_(closure_.coordinates().nv),
      nc_(closure_.rows()) {
  if (model.abi_version != MBFE_MODEL_ABI_VERSION || model.num_coordinates != nq_)
    throw std::invalid_argument(std::string("LoopSystem: the solver of '") + model.model_name +
                                "' does not match its coordinate layout or this runtime's ABI");
  m_row_.resize(nv_, nv_);
  m_.resize(nv_, nv_);
  f_.resize(nv_);
  q_force_.resize(nv_);
}

void LoopSystem::dynamics(const double* q, const double* v, double t) {
  evaluate_dynamics(model_, q, v, t, m_row_.data(), f_.data(), q_force_.data());
  m_ = m_row_;
}

void LoopSystem::position_rates(const double* q, const double* v, double* qdot) const {
  if (model_.position_derivative != nullptr) model_.position_derivative(q, v, qdot);
  else Eigen::Map<Eigen::VectorXd>(qdot, nq_) = Eigen::Map<const Eigen::VectorXd>(v, nv_);
}

void LoopSystem::make_consistent(double t, Eigen::VectorXd& q, Eigen::VectorXd& v) const {
  normalize_quaternions(closure_.coordinates(), q.data());
  closure_.impose_motion(t, q.data(), v.data());
  // The coordinates given a velocity stay independent where the loops allow,
  // so that what the user set moves as set (a crank's angle and rate). A
  // driven coordinate is dependent whatever its rate: its row says so.
  std::vector<bool> keep(nv_);
  for (int i = 0; i < nv_; ++i) keep[i] = v[i] != 0.0;
  for (int d : closure_.driven_velocities()) keep[d] = false;
  const LoopPartition part = closure_.choose_partition(q.data(), t, nullptr, &keep);
  closure_.close(q.data(), part.dependent, t);
  // The partition at the closed q (it may differ from the one at the given q).
  const LoopPartition closed = closure_.choose_partition(q.data(), t, nullptr, &keep);
  Eigen::MatrixXd J;
  closure_.jacobian(q.data(), J);
  Eigen::MatrixXd jd(nc_, nc_);
  Eigen::VectorXd b;
  closure_.velocity_target(t, b);
  for (int k = 0; k < nc_; ++k) jd.col(k) = J.col(closed.dependent[k]);
  for (int i : closed.independent) b -= J.col(i) * v[i];
  const Eigen::VectorXd vd = jd.partialPivLu().solve(b);
  for (int k = 0; k < nc_; ++k) v[closed.dependent[k]] = vd[k];
}

// ---- Partitioned ----

LoopPartitionedSystem::LoopPartitionedSystem(const mbfe_model_v1& model, std::vector<BodyInertia> bodies,
                                             RigidCoordinates coordinates, const double* rows_at)
    : LoopSystem(model, std::move(bodies), std::move(coordinates), rows_at) {
  // Until state_of() chooses at the initial state: the last nc coordinates.
  for (int i = 0; i < nv_; ++i) (i < nv_ - nc_ ? part_.independent : part_.dependent).push_back(i);
  llt_.compute(Eigen::MatrixXd::Identity(nv_ - nc_, nv_ - nc_));
}

void LoopPartitionedSystem::close(double t, const Eigen::VectorXd& y) {
  const int nu = nv_ - nc_;
  q_ = y.head(nq_);
  normalize_quaternions(closure_.coordinates(), q_.data());
  closure_.close(q_.data(), part_.dependent, t);
  closure_.jacobian(q_.data(), j_);
  jd_.resize(nc_, nc_);
  ju_.resize(nc_, nu);
  for (int k = 0; k < nc_; ++k) jd_.col(k) = j_.col(part_.dependent[k]);
  for (int k = 0; k < nu; ++k) ju_.col(k) = j_.col(part_.independent[k]);
  lu_.compute(jd_);
  // v = B v_u + w: B's independent rows the identity, its dependent rows
  // -J_d^-1 J_u; w the drives' share, J_d w_d = nu(t), zero without drives.
  b_.setZero(nv_, nu);
  if (nu > 0) {  // a solve with no right-hand side reads a null pointer in Eigen
    const Eigen::MatrixXd dependent_rows = -lu_.solve(ju_);
    for (int k = 0; k < nu; ++k) b_(part_.independent[k], k) = 1.0;
    for (int k = 0; k < nc_; ++k) b_.row(part_.dependent[k]) = dependent_rows.row(k);
  }
  v_ = b_ * y.tail(nu);
  if (closure_.driven_rows() > 0) {
    closure_.velocity_target(t, nu_);
    const Eigen::VectorXd wd = lu_.solve(nu_);
    for (int k = 0; k < nc_; ++k) v_[part_.dependent[k]] += wd[k];
  }
  closure_.gamma(q_.data(), v_.data(), t, gamma_);
  const Eigen::VectorXd cd = lu_.solve(gamma_);
  c_.setZero(nv_);
  for (int k = 0; k < nc_; ++k) c_[part_.dependent[k]] = cd[k];
}

void LoopPartitionedSystem::rhs(double t, const Eigen::VectorXd& y, Eigen::VectorXd& ydot) {
  if (y.size() != size()) {
    std::ostringstream os;
    os << "LoopPartitionedSystem: y has " << y.size() << " entries, expected " << size() << " ([q; v_u])";
    throw std::invalid_argument(os.str());
  }
  close(t, y);
  dynamics(q_.data(), v_.data(), t);
  if (nv_ > nc_) {
    reduced_.noalias() = b_.transpose() * m_ * b_;
    rhs_.noalias() = b_.transpose() * (q_force_ - f_ - m_ * c_);
    llt_.compute(reduced_);
    if (llt_.info() != Eigen::Success || !(llt_.rcond() >= RigidSystem::kMassRcondFloor))
      throw_singular_mass_matrix(model_, bodies_, m_, t);
    a_u_ = llt_.solve(rhs_);
  } else {
    a_u_.resize(0);  // the loops and drives fix every coordinate: kinematics only
  }
  ydot.resize(size());
  position_rates(q_.data(), v_.data(), ydot.data());
  ydot.tail(nv_ - nc_) = a_u_;
}

void LoopPartitionedSystem::drive_reactions(double t, const Eigen::VectorXd& y, Eigen::VectorXd& out) {
  const int nd = closure_.driven_rows();
  out.resize(nd);
  if (nd == 0) return;
  Eigen::VectorXd ydot;
  rhs(t, y, ydot);
  // M v' + J^T mu = Q - F with v' = B v_u' + c; the dependent columns give
  // J_d^T mu = (Q - F - M v')_d, and a drive exerts -mu of its row.
  const Eigen::VectorXd residual = q_force_ - f_ - m_ * (b_ * a_u_ + c_);
  Eigen::VectorXd rd(nc_);
  for (int k = 0; k < nc_; ++k) rd[k] = residual[part_.dependent[k]];
  const Eigen::VectorXd mu = lu_.transpose().solve(rd);
  out = -mu.tail(nd);
}

void LoopPartitionedSystem::after_step(double t, Eigen::VectorXd& y) {
  close(t, y);
  y.head(nq_) = q_;
  double best = 0.0;
  const LoopPartition candidate = closure_.choose_partition(q_.data(), t, &best);
  if (candidate.dependent == part_.dependent) return;
  if (smallest_singular_value(jd_) >= kRepartitionRatio * best) return;
  // J_d has become ill-conditioned: the same state in the new independent velocities.
  part_ = candidate;
  ++repartitions_;
  for (int k = 0; k < nv_ - nc_; ++k) y[nq_ + k] = v_[part_.independent[k]];
}

std::string LoopPartitionedSystem::name(int i) const {
  if (i < nq_) return closure_.coordinates().position_columns[i];
  return closure_.coordinates().velocity_columns[part_.independent[i - nq_]];
}

Eigen::VectorXd LoopPartitionedSystem::state_of(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& v) {
  part_ = closure_.choose_partition(q.data(), t);
  Eigen::VectorXd y(size());
  y.head(nq_) = q;
  for (int k = 0; k < nv_ - nc_; ++k) y[nq_ + k] = v[part_.independent[k]];
  return y;
}

void LoopPartitionedSystem::full_state(double t, const Eigen::VectorXd& y, Eigen::VectorXd& q, Eigen::VectorXd& v) {
  close(t, y);
  q = q_;
  v = v_;
}

// ---- Augmented ----

LoopAugmentedSystem::LoopAugmentedSystem(const mbfe_model_v1& model, std::vector<BodyInertia> bodies,
                                         RigidCoordinates coordinates, const double* rows_at)
    : LoopSystem(model, std::move(bodies), std::move(coordinates), rows_at) {
  saddle_.resize(nv_ + nc_, nv_ + nc_);
  rhs_.resize(nv_ + nc_);
}

void LoopAugmentedSystem::rhs(double t, const Eigen::VectorXd& y, Eigen::VectorXd& ydot) {
  if (y.size() != size()) {
    std::ostringstream os;
    os << "LoopAugmentedSystem: y has " << y.size() << " entries, expected " << size() << " ([q; v])";
    throw std::invalid_argument(os.str());
  }
  q_ = y.head(nq_);
  normalize_quaternions(closure_.coordinates(), q_.data());
  const Eigen::VectorXd v = y.tail(nv_);
  dynamics(q_.data(), v.data(), t);
  closure_.jacobian(q_.data(), j_);
  closure_.gamma(q_.data(), v.data(), t, gamma_);
  saddle_.setZero();
  saddle_.topLeftCorner(nv_, nv_) = m_;
  saddle_.topRightCorner(nv_, nc_) = j_.transpose();
  saddle_.bottomLeftCorner(nc_, nv_) = j_;
  rhs_.head(nv_) = q_force_ - f_;
  rhs_.tail(nc_) = gamma_;
  const Eigen::FullPivLU<Eigen::MatrixXd> lu(saddle_);
  if (!(lu.rcond() >= kSaddleRcondFloor)) {
    std::ostringstream os;
    os << "model '" << model_.model_name << "': the augmented matrix [[M, J^T], [J, 0]] is singular at t = " << t
       << " s (rcond " << lu.rcond() << "): a redundant loop, a dead point or a body without mass";
    throw SingularConstraintError(os.str(), "", t, lu.rcond());
  }
  x_ = lu.solve(rhs_);
  ydot.resize(size());
  position_rates(q_.data(), v.data(), ydot.data());
  ydot.tail(nv_) = x_.head(nv_);
}

void LoopAugmentedSystem::after_step(double t, Eigen::VectorXd& y) {
  normalize_quaternions(closure_.coordinates(), y.data());
  closure_.project(y.data(), t);
  closure_.project_velocity(y.data(), t, y.data() + nq_);
}

void LoopAugmentedSystem::drive_reactions(double t, const Eigen::VectorXd& y, Eigen::VectorXd& out) {
  const int nd = closure_.driven_rows();
  out.resize(nd);
  if (nd == 0) return;
  Eigen::VectorXd ydot;
  rhs(t, y, ydot);
  out = -x_.tail(nd);  // [v'; mu] solves M v' + J^T mu = Q - F; a drive exerts -mu
}

std::string LoopAugmentedSystem::name(int i) const {
  if (i < nq_) return closure_.coordinates().position_columns[i];
  return closure_.coordinates().velocity_columns[i - nq_];
}

Eigen::VectorXd LoopAugmentedSystem::state_of(double, const Eigen::VectorXd& q, const Eigen::VectorXd& v) {
  Eigen::VectorXd y(size());
  y << q, v;
  return y;
}

void LoopAugmentedSystem::full_state(double, const Eigen::VectorXd& y, Eigen::VectorXd& q, Eigen::VectorXd& v) {
  q = y.head(nq_);
  v = y.tail(nv_);
}

}  // namespace mbfe::runtime
