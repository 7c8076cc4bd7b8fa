// PartitionedSystem: the coordinate-partitioning formulation of eqs (16)-(17).
// The scheme (docs/partitioning.md):
//   y = [u; q_c; u'; q_c'];  at every evaluation f(t, y):
//   1. closure: Newton on Phi(u, v, q_c) = 0 for v, started from the v of the
//      last accepted step extrapolated with its v' (v + (t - t_last) v'),
//      v <- v - J_v^-1 Phi, until the update stalls at
//      round-off (|dv| <= 1e-14 (1 + |v|)) or |Phi| <= 1e-15 m; failure if
//      max |Phi| > closure_tol (1e-10 m) after max_newton iterations;
//   2. velocities: v' = -J_v^-1 (J_u u' + J_c q_c');
//   3. accelerations: CoupledDynamics::solve_partitioned;
//   f = [u'; q_c'; u''; q_c''].
// after_step: closure at the accepted y (the next Newton start), and a new
// partition when sigma_min(J_v) has fallen below repartition_ratio times that
// of the best partition (the first m column pivots of J_b).
#include <Eigen/SVD>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "runtime/coupled/coordinate_partitioning.h"
#include "runtime/errors/multibody_errors.h"

namespace mbfe::runtime {

namespace {

// Newton stops once the update is at round-off of the coordinates, or Phi is.
constexpr double kStepRoundoff = 1e-14;
// The Newton start is extrapolated with v' over at most this many accepted steps.
constexpr double kMaxExtrapolatedSteps = 4.0;
constexpr double kPhiRoundoff = 1e-15;  // m

}  // namespace

PartitionedSystem::PartitionedSystem(std::shared_ptr<CoupledDynamics> dyn, PartitionOptions opt)
    : CoupledSystem(std::move(dyn)), opt_(opt) {
  const int nb = dyn_->nb(), m = dyn_->m();
  if (m > nb) {
    std::ostringstream os;
    os << "model '" << dyn_->kernels().model_name << "': " << m
       << " constraint rows but only " << nb
       << " rigid coordinates to take the dependent ones from";
    throw std::invalid_argument(os.str());
  }
  Partition p;
  for (int i = 0; i < nb; ++i) (i < nb - m ? p.independent : p.dependent).push_back(i);
  set_partition(p);
  q_.setZero(dyn_->n());
  qd_.setZero(dyn_->n());
  guess_.v.setZero(m);
  guess_.vd.setZero(m);
}

void PartitionedSystem::set_partition(const Partition& p) {
  closed_valid_ = false;
  part_ = p;
  nu_ = static_cast<int>(p.independent.size());
  nz_ = nu_ + dyn_->nc();
}

void PartitionedSystem::close(double t, const Eigen::VectorXd& y) {
  if (y.size() != 2 * nz_) {
    throw std::invalid_argument("PartitionedSystem: y has " + std::to_string(y.size()) +
                                " entries, expected " + std::to_string(2 * nz_) +
                                " ([u; q_c; u'; q_c'])");
  }
  if (closed_valid_ && closed_y_.size() == y.size() && closed_y_ == y) {
    last_iters_ = 0;  // q_, qd_, jv_ and its LU are those of this y already
    return;
  }
  closed_valid_ = false;
  const int nb = dyn_->nb(), nc = dyn_->nc(), m = dyn_->m();
  const ContactConstraints& cc = dyn_->constraints();
  for (int i = 0; i < nu_; ++i) q_(part_.independent[i]) = y(i);
  // Extrapolate over at most a few accepted steps: an RK stage or the next
  // step, not a call at some distant t that could land on another branch of
  // the linkage.
  const bool extrapolate = guess_.valid && guess_.h > 0.0 &&
                           std::abs(t - guess_.t) <= kMaxExtrapolatedSteps * guess_.h;
  for (int i = 0; i < m; ++i) {
    const double v = guess_.v(i);
    const double predicted = extrapolate ? v + (t - guess_.t) * guess_.vd(i) : v;
    q_(part_.dependent[i]) = std::isfinite(predicted) ? predicted : v;
  }
  q_.tail(nc) = y.segment(nu_, nc);
  dyn_->impose_motion(t, q_, qd_);  // driven coordinates follow their motion, not y
  ConstraintValues& cv = cv_close_;
  jv_.resize(m, m);
  bool stalled = false, diverged = false;
  int it = 0;
  for (;; ++it) {
    cc.evaluate(t, q_.data(), q_.data() + nb, nullptr, nullptr, cv);
    for (int i = 0; i < m; ++i) jv_.col(i) = cv.jb.col(part_.dependent[i]);
    const double phi = dyn_->phi_max(cv);
    if (phi <= kPhiRoundoff || stalled || it >= opt_.max_newton) break;
    jv_lu_.compute(jv_);
    const double rel =
        clearly_regular(jv_lu_, cv) ? 1.0 : sigma_min(jv_) / constraint_scale(cv);
    if (!(rel >= kSingularConstraint)) {
      // choose_partition names the contact when J_b itself is singular.
      choose_partition(cc, cv, t);
      std::ostringstream os;
      os << "contact '" << cc.contact_name(0) << "': J_v of the dependent coordinates is "
         << "singular during closure at t = " << t << " s (sigma_min / scale = " << rel
         << "); the partition is chosen again only between steps: reduce the step";
      throw SingularConstraintError(os.str(), cc.contact_name(0), t, rel);
    }
    jv_lu_.solve(cv.phi, dv_);
    const Eigen::VectorXd& dv = dv_;
    double vmax = 0.0;
    for (int i = 0; i < m; ++i) {
      q_(part_.dependent[i]) -= dv(i);
      vmax = std::max(vmax, std::abs(q_(part_.dependent[i])));
    }
    if (!dv.allFinite()) {  // q_ is lost and cv no longer describes it: a failure
      diverged = true;
      break;
    }
    stalled = dv.cwiseAbs().maxCoeff() <= kStepRoundoff * (1.0 + vmax);
  }
  last_iters_ = it;
  int row = 0;
  const double phi = diverged ? NAN : dyn_->phi_max(cv, &row);
  if (!(phi <= opt_.closure_tol)) {
    const int c = cc.contact_of_row(row);
    std::ostringstream os;
    os << "contact '" << cc.contact_name(c) << "': Newton closure of the dependent coordinates "
       << "failed at t = " << t << " s: |Phi| = " << phi << " m after " << it
       << " iterations (tolerance " << opt_.closure_tol
       << " m); the step is too large for the motion, or the linkage cannot reach the beam";
    throw NewtonClosureError(os.str(), cc.contact_name(c), t, phi);
  }
  // Velocities: J_v v' = -(J_u u' + J_c q_c').
  for (int i = 0; i < nu_; ++i) qd_(part_.independent[i]) = y(nz_ + i);
  qd_.tail(nc) = y.segment(nz_ + nu_, nc);
  dyn_->impose_motion(t, q_, qd_);
  if (m > 0) {
    jv_lu_.compute(jv_);
    cv.jc_times(qd_.tail(nc), r_);
    for (int i = 0; i < nu_; ++i) r_ += cv.jb.col(part_.independent[i]) * y(nz_ + i);
    r_ = -r_;
    jv_lu_.solve(r_, vd_);
    for (int i = 0; i < m; ++i) qd_(part_.dependent[i]) = vd_(i);
  }
  closed_y_ = y;
  closed_valid_ = true;
}

void PartitionedSystem::rhs(double t, const Eigen::VectorXd& y, Eigen::VectorXd& ydot) {
  close(t, y);
  dyn_->evaluate(t, q_, qd_, &cv_close_);  // close() evaluated the constraints at q_
  dyn_->solve_partitioned(t, part_, qdd_, lambda_);
  const int nb = dyn_->nb(), nc = dyn_->nc();
  ydot.resize(2 * nz_);
  ydot.head(nz_) = y.tail(nz_);
  for (int i = 0; i < nu_; ++i) ydot(nz_ + i) = qdd_(part_.independent[i]);
  ydot.tail(nc) = qdd_.segment(nb, nc);
}

void PartitionedSystem::remember_start(double t) {
  const int m = dyn_->m();
  guess_.h = guess_.valid ? t - guess_.t : 0.0;
  guess_.t = t;
  guess_.valid = true;
  guess_.v.resize(m);
  guess_.vd.resize(m);
  for (int i = 0; i < m; ++i) {
    guess_.v(i) = q_(part_.dependent[i]);
    guess_.vd(i) = qd_(part_.dependent[i]);
  }
}

void PartitionedSystem::after_step(double t, Eigen::VectorXd& y) {
  close(t, y);
  remember_start(t);
  if (dyn_->m() == 0) return;
  // close() ended with an evaluation at the closed q_: its values are those of this state.
  const ConstraintValues& cv = cv_close_;
  // No partition can do 1 / repartition_ratio times better than this one when
  // sigma_min(J_v) already reaches that fraction of ||J_b||_F >= sigma_max(J_b)
  // >= the best partition's sigma_min: skip the search. SmallLu's lower bounds
  // of sigma_min(J_v) cost no SVD.
  const double bound = opt_.repartition_ratio * cv.jb.norm();
  if (jv_.size() > 0 &&
      (jv_lu_.sigma_min_lower_cheap() >= bound || jv_lu_.sigma_min_lower() >= bound)) {
    return;
  }
  const double current = sigma_min(jv_);
  if (current >= bound) return;
  double best = 0.0;
  const Partition p = choose_partition(dyn_->constraints(), cv, t, &best);
  if (current < opt_.repartition_ratio * best && p.dependent != part_.dependent) {
    set_partition(p);
    ++repartitions_;
    const int nc = dyn_->nc();
    for (int i = 0; i < nu_; ++i) {
      y(i) = q_(part_.independent[i]);
      y(nz_ + i) = qd_(part_.independent[i]);
    }
    y.segment(nu_, nc) = q_.tail(nc);
    y.segment(nz_ + nu_, nc) = qd_.tail(nc);
    for (int i = 0; i < dyn_->m(); ++i) {  // the same start, in the new dependent coordinates
      guess_.v(i) = q_(part_.dependent[i]);
      guess_.vd(i) = qd_(part_.dependent[i]);
    }
  }
}

std::string PartitionedSystem::name(int i) const {
  const std::vector<std::string> names = dyn_->model().coordinate_names();
  const int k = i % nz_;
  const std::string base = k < nu_ ? names[part_.independent[k]] : names[dyn_->nb() + k - nu_];
  return i < nz_ ? base : base + "_dot";
}

Eigen::VectorXd PartitionedSystem::initial_state(double t, const Eigen::VectorXd& q,
                                                 const Eigen::VectorXd& qd) {
  const int n = dyn_->n(), nb = dyn_->nb(), nc = dyn_->nc();
  if (q.size() != n || qd.size() != n) {
    throw std::invalid_argument("initial state has " + std::to_string(q.size()) + " / " +
                                std::to_string(qd.size()) + " entries, expected " +
                                std::to_string(n) + " ([q_b; q_c])");
  }
  ConstraintValues cv;
  dyn_->constraints().evaluate(t, q.data(), q.data() + nb, nullptr, nullptr, cv);
  Partition p = choose_partition(dyn_->constraints(), cv, t);
  if (!opt_.initial_dependent.empty()) {
    std::vector<bool> dep(nb, false);
    for (int j : opt_.initial_dependent) {
      if (j < 0 || j >= nb || dep[j]) {
        throw std::invalid_argument("initial_dependent: index " + std::to_string(j) +
                                    " is out of range or repeated");
      }
      dep[j] = true;
    }
    if (static_cast<int>(opt_.initial_dependent.size()) != dyn_->m()) {
      throw std::invalid_argument("initial_dependent has " +
                                  std::to_string(opt_.initial_dependent.size()) +
                                  " entries, expected " + std::to_string(dyn_->m()) +
                                  " (one per constraint row)");
    }
    p = Partition{};
    for (int j = 0; j < nb; ++j) (dep[j] ? p.dependent : p.independent).push_back(j);
  }
  set_partition(p);
  for (int i = 0; i < dyn_->m(); ++i) guess_.v(i) = q(part_.dependent[i]);
  guess_.valid = false;
  Eigen::VectorXd y(2 * nz_);
  for (int i = 0; i < nu_; ++i) {
    y(i) = q(part_.independent[i]);
    y(nz_ + i) = qd(part_.independent[i]);
  }
  y.segment(nu_, nc) = q.tail(nc);
  y.segment(nz_ + nu_, nc) = qd.tail(nc);
  close(t, y);
  remember_start(t);
  return y;
}

void PartitionedSystem::full_state(double t, const Eigen::VectorXd& y, Eigen::VectorXd& q,
                                   Eigen::VectorXd& qd) {
  close(t, y);
  q = q_;
  qd = qd_;
}

const ContactReport& PartitionedSystem::report(double t, const Eigen::VectorXd& y) {
  rhs(t, y, report_ydot_);
  ContactReport& r = report_;
  r.lambda = lambda_;
  r.qdd = qdd_;
  ConstraintValues& cv = report_cv_;
  dyn_->constraints().evaluate(t, q_.data(), q_.data() + dyn_->nb(), nullptr, nullptr, cv);
  r.phi = cv.phi;
  r.phi_max = dyn_->phi_max(cv);
  r.s = cv.s;
  return r;
}

}  // namespace mbfe::runtime
