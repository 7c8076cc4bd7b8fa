#include "runtime/multibody/loop_closure.h"

#include <Eigen/LU>
#include <Eigen/QR>
#include <Eigen/SVD>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "runtime/errors/multibody_errors.h"

namespace mbfe::runtime {

namespace {

double smallest_singular_value(const Eigen::MatrixXd& a) {
  if (a.size() == 0) return 1.0;
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(a);
  return svd.singularValues()(svd.singularValues().size() - 1);
}

}  // namespace

LoopClosure::LoopClosure(const mbfe_model_v1& model, RigidCoordinates coordinates)
    : model_(model),
      coordinates_(std::move(coordinates)),
      nl_(model.num_loop_rows),
      nc_(model.num_loop_rows + model.num_driven),
      nv_(coordinates_.nv) {
  if (nl_ <= 0 || !model.loop_constraints || !model.loop_jacobian || !model.loop_gamma)
    throw std::invalid_argument(std::string("model '") + model.model_name + "' has no loop kernels");
  if (nc_ > nv_) {
    std::ostringstream os;
    os << "model '" << model.model_name << "': its loops have " << nl_ << " constraint rows";
    if (model.num_driven > 0) os << " and its driven joints " << model.num_driven;
    os << " but the tree only " << nv_
       << " velocity coordinates; some loops are redundant (remove them or use a point loop where a revolute one "
          "repeats a condition)";
    if (model.num_driven > 0) os << " or the drives fix what the loops already fix";
    throw std::invalid_argument(os.str());
  }
  if (model.num_driven > 0 && model.motion == nullptr)
    throw std::invalid_argument(std::string("model '") + model.model_name + "' has driven joints but no motion kernel");
  row_loop_.assign(nc_, "?");
  row_what_.assign(nc_, "loop '?'");
  for (int k = 0; k < model.num_loops; ++k) {
    const mbfe_loop_constraint_v1& loop = model.loops[k];
    for (int r = loop.first_row; r < loop.first_row + loop.rows && r < nl_; ++r) {
      row_loop_[r] = loop.name;
      row_what_[r] = std::string("loop '") + loop.name + "'";
    }
  }
  for (int k = 0; k < model.num_driven; ++k) {
    const int v = model.driven_coordinates[k];
    drive_v_.push_back(v);
    drive_q_.push_back(model.driven_positions ? model.driven_positions[k] : v);
    const std::string& name = coordinates_.position_columns[drive_q_.back()];
    row_loop_[nl_ + k] = name;
    row_what_[nl_ + k] = "the motion of '" + name + "'";
  }
  motion_q_.resize(model.num_driven);
  motion_qd_.resize(model.num_driven);
  motion_qdd_.resize(model.num_driven);
}

void LoopClosure::motion(double t) const {
  if (nc_ > nl_) model_.motion(t, motion_q_.data(), motion_qd_.data(), motion_qdd_.data());
}

void LoopClosure::phi(const double* q, double t, Eigen::VectorXd& out) const {
  out.resize(nc_);
  model_.loop_constraints(q, out.data());
  if (nc_ == nl_) return;
  motion(t);
  for (int k = 0; k < nc_ - nl_; ++k) out[nl_ + k] = q[drive_q_[k]] - motion_q_[k];
}

void LoopClosure::jacobian(const double* q, Eigen::MatrixXd& out) const {
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> row_major(nl_, nv_);
  model_.loop_jacobian(q, row_major.data());
  out.setZero(nc_, nv_);
  out.topRows(nl_) = row_major;
  for (int k = 0; k < nc_ - nl_; ++k) out(nl_ + k, drive_v_[k]) = 1.0;
}

void LoopClosure::gamma(const double* q, const double* v, double t, Eigen::VectorXd& out) const {
  out.resize(nc_);
  model_.loop_gamma(q, v, out.data());
  if (nc_ == nl_) return;
  motion(t);
  out.tail(nc_ - nl_) = motion_qdd_;
}

void LoopClosure::velocity_target(double t, Eigen::VectorXd& out) const {
  out.setZero(nc_);
  if (nc_ == nl_) return;
  motion(t);
  out.tail(nc_ - nl_) = motion_qd_;
}

void LoopClosure::impose_motion(double t, double* q, double* v) const {
  if (nc_ == nl_) return;
  motion(t);
  for (int k = 0; k < nc_ - nl_; ++k) {
    q[drive_q_[k]] = motion_q_[k];
    v[drive_v_[k]] = motion_qd_[k];
  }
}

double LoopClosure::residual(const double* q) const {
  Eigen::VectorXd p(nl_);
  model_.loop_constraints(q, p.data());
  return p.cwiseAbs().maxCoeff();
}

LoopPartition LoopClosure::choose_partition(const double* q, double t, double* sigma_min,
                                            const std::vector<bool>* keep) const {
  // A kept column scaled down this much pivots after every other column that
  // can still give J_d full rank.
  constexpr double kKeptColumnScale = 1e-3;
  Eigen::MatrixXd J;
  jacobian(q, J);
  Eigen::MatrixXd scaled = J;
  if (keep)
    for (int i = 0; i < nv_; ++i)
      if ((*keep)[i]) scaled.col(i) *= kKeptColumnScale;
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(scaled);
  std::vector<bool> is_dependent(nv_, false);
  for (int k = 0; k < nc_; ++k) is_dependent[qr.colsPermutation().indices()[k]] = true;
  LoopPartition p;
  for (int i = 0; i < nv_; ++i) (is_dependent[i] ? p.dependent : p.independent).push_back(i);
  Eigen::MatrixXd jd(nc_, nc_);
  for (int k = 0; k < nc_; ++k) jd.col(k) = J.col(p.dependent[k]);
  const double sigma = smallest_singular_value(jd);
  const double scale = std::max(J.norm(), 1e-300);
  if (!(sigma >= kSingularLoops * scale)) {
    // The loop whose row is best explained by the others has lost its rank.
    Eigen::JacobiSVD<Eigen::MatrixXd> svd(J, Eigen::ComputeFullU);
    Eigen::Index worst = 0;
    svd.matrixU().col(nc_ - 1).cwiseAbs().maxCoeff(&worst);
    std::ostringstream os;
    os << "model '" << model_.model_name << "': the loop Jacobian has lost rank at t = " << t
       << " s (sigma_min / scale = " << sigma / scale << "); " << row_what_[worst]
       << " repeats a condition of the others or the linkage is at a dead point";
    throw SingularConstraintError(os.str(), row_loop_[worst], t, sigma / scale);
  }
  if (sigma_min) *sigma_min = sigma;
  return p;
}

void LoopClosure::fail(const Eigen::VectorXd& p, double t, int iterations) const {
  Eigen::Index worst = 0;
  const double r = p.allFinite() ? p.cwiseAbs().maxCoeff(&worst) : NAN;
  std::ostringstream os;
  os << "model '" << model_.model_name << "': Newton's closure of the loops did not converge at t = " << t << " s ("
     << iterations << " iterations, max |Phi| = " << r << " in " << row_what_[worst]
     << "): the state is far from the loops, or the step is too long";
  throw NewtonClosureError(os.str(), row_loop_[worst], t, r);
}

int LoopClosure::close(double* q, const std::vector<int>& dependent, double t) const {
  Eigen::VectorXd p, dv = Eigen::VectorXd::Zero(nv_), step;
  double last = INFINITY;
  Eigen::MatrixXd J, jd(nc_, nc_);
  for (int it = 0; it <= kMaxNewton; ++it) {
    phi(q, t, p);
    if (!p.allFinite()) fail(p, t, it);
    const double r = p.cwiseAbs().maxCoeff();
    if (r <= kClosureTol || (r <= kStagnationTol && r > 0.5 * last)) {
      // A drive's row is linear in its coordinate: its exact root costs the
      // loops' rows round-off only, and the output shows the motion's value.
      for (int k = 0; k < nc_ - nl_; ++k) q[drive_q_[k]] = motion_q_[k];
      return it;
    }
    last = r;
    if (it == kMaxNewton) break;
    jacobian(q, J);
    for (int k = 0; k < nc_; ++k) jd.col(k) = J.col(dependent[k]);
    step = jd.partialPivLu().solve(-p);
    dv.setZero();
    for (int k = 0; k < nc_; ++k) dv[dependent[k]] = step[k];
    displace(coordinates_, q, dv);
  }
  fail(p, t, kMaxNewton);
}

int LoopClosure::project(double* q, double t) const {
  Eigen::VectorXd p, dv;
  Eigen::MatrixXd J;
  double last = INFINITY;
  for (int it = 0; it <= kMaxNewton; ++it) {
    phi(q, t, p);
    if (!p.allFinite()) fail(p, t, it);
    const double r = p.cwiseAbs().maxCoeff();
    if (r <= kClosureTol || (r <= kStagnationTol && r > 0.5 * last)) {
      // A drive's row is linear in its coordinate: its exact root costs the
      // loops' rows round-off only, and the output shows the motion's value.
      for (int k = 0; k < nc_ - nl_; ++k) q[drive_q_[k]] = motion_q_[k];
      return it;
    }
    last = r;
    if (it == kMaxNewton) break;
    jacobian(q, J);
    dv = -J.transpose() * (J * J.transpose()).ldlt().solve(p);
    displace(coordinates_, q, dv);
  }
  fail(p, t, kMaxNewton);
}

void LoopClosure::project_velocity(const double* q, double t, double* v) const {
  Eigen::MatrixXd J;
  jacobian(q, J);
  Eigen::Map<Eigen::VectorXd> vel(v, nv_);
  Eigen::VectorXd drift;
  velocity_target(t, drift);
  drift = J * vel - drift;
  vel -= J.transpose() * (J * J.transpose()).ldlt().solve(drift);
}

}  // namespace mbfe::runtime
