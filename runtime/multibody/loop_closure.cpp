#include "runtime/multibody/loop_closure.h"

#include <Eigen/LU>
#include <Eigen/QR>
#include <Eigen/SVD>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <utility>
#include <vector>

#include "runtime/errors/multibody_errors.h"

namespace mbfe::runtime {

namespace {

double smallest_singular_value(const Eigen::MatrixXd& a) {
  if (a.size() == 0) return 1.0;
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(a);
  return svd.singularValues()(svd.singularValues().size() - 1);
}

}  // namespace

LoopClosure::LoopClosure(const mbfe_model_v1& model, RigidCoordinates coordinates, const double* rows_at)
    : model_(model), coordinates_(std::move(coordinates)), nl_(model.num_loop_rows), nv_(coordinates_.nv) {
  if (nl_ <= 0 || !model.loop_constraints || !model.loop_jacobian || !model.loop_gamma)
    throw std::invalid_argument(std::string("model '") + model.model_name + "' has no loop kernels");
  if (model.num_driven > 0 && model.motion == nullptr)
    throw std::invalid_argument(std::string("model '") + model.model_name + "' has driven joints but no motion kernel");
  for (int k = 0; k < model.num_driven; ++k) {
    drive_v_.push_back(model.driven_coordinates[k]);
    drive_q_.push_back(model.driven_positions ? model.driven_positions[k] : drive_v_.back());
  }
  for (int r = 0; r < nl_; ++r) rows_.push_back(r);
  if (rows_at) select_rows(rows_at);
  na_ = static_cast<int>(rows_.size());
  nc_ = na_ + model.num_driven;
  if (nc_ > nv_) {
    std::ostringstream os;
    os << "model '" << model.model_name << "': its loops have " << na_ << " constraint rows";
    if (!redundant_.empty()) os << " (and " << redundant_.size() << " that repeat them)";
    if (model.num_driven > 0) os << " and its driven joints " << model.num_driven;
    os << " but the tree only " << nv_
       << " velocity coordinates; some loops are redundant (remove them or use a point loop where a revolute one "
          "repeats a condition)";
    if (model.num_driven > 0) os << " or the drives fix what the loops already fix";
    throw std::invalid_argument(os.str());
  }
  const auto loop_of_row = [&](int r) -> std::string {
    for (int k = 0; k < model.num_loops; ++k)
      if (r >= model.loops[k].first_row && r < model.loops[k].first_row + model.loops[k].rows) return model.loops[k].name;
    return "?";
  };
  for (int r : rows_) {
    row_loop_.push_back(loop_of_row(r));
    row_what_.push_back("loop '" + row_loop_.back() + "'");
  }
  for (int r : redundant_) redundant_loops_.push_back(loop_of_row(r));
  for (int k = 0; k < model.num_driven; ++k) {
    const std::string& name = coordinates_.position_columns[drive_q_[k]];
    row_loop_.push_back(name);
    row_what_.push_back("the motion of '" + name + "'");
  }
  motion_q_.resize(model.num_driven);
  motion_qd_.resize(model.num_driven);
  motion_qdd_.resize(model.num_driven);
  full_phi_.resize(nl_);
  full_j_.resize(nl_, nv_);
}

void LoopClosure::select_rows(const double* q_given) {
  // The loops' rows as columns, their rank among themselves (the drives are
  // not in it: a drive that repeats a loop is an error of the model, below).
  const auto rows_qr = [&](const double* q) {
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> jl(nl_, nv_);
    model_.loop_jacobian(q, jl.data());
    Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(Eigen::MatrixXd(jl.transpose()));
    qr.setThreshold(kRedundantRow);
    return std::make_pair(qr, jl.allFinite());
  };
  std::vector<double> q(q_given, q_given + coordinates_.nq);
  normalize_quaternions(coordinates_, q.data());
  const auto [at_q, finite] = rows_qr(q.data());
  if (!finite) return;  // the run's own checks say what is wrong with q
  // A repetition of the linkage's geometry holds everywhere, a dead point's
  // at one configuration only: the rows are counted here and a little way
  // off, and the larger rank (the configuration off a dead point) decides.
  Eigen::VectorXd offset(nv_);
  for (int i = 0; i < nv_; ++i) offset[i] = kRedundancyProbe * (1.0 + 0.5 * std::sin(1.0 + i));
  displace(coordinates_, q.data(), offset);
  const auto [off_q, finite_off] = rows_qr(q.data());
  const auto& qr = finite_off && off_q.rank() > at_q.rank() ? off_q : at_q;
  const Eigen::Index rank = qr.rank();
  // Rank limited by the velocities, not by small pivots: rows that fix more
  // than the tree can move, refused as such, not left out.
  if (rank == nl_ || rank == nv_) return;
  std::vector<bool> kept(static_cast<std::size_t>(nl_), false);
  for (Eigen::Index i = 0; i < rank; ++i) kept[static_cast<std::size_t>(qr.colsPermutation().indices()[i])] = true;
  rows_.clear();
  for (int r = 0; r < nl_; ++r) (kept[static_cast<std::size_t>(r)] ? rows_ : redundant_).push_back(r);
}

void LoopClosure::motion(double t) const {
  if (nc_ > na_) model_.motion(t, motion_q_.data(), motion_qd_.data(), motion_qdd_.data());
}

void LoopClosure::phi(const double* q, double t, Eigen::VectorXd& out) const {
  out.resize(nc_);
  model_.loop_constraints(q, full_phi_.data());
  for (int i = 0; i < na_; ++i) out[i] = full_phi_[rows_[i]];
  if (nc_ == na_) return;
  motion(t);
  for (int k = 0; k < nc_ - na_; ++k) out[na_ + k] = q[drive_q_[k]] - motion_q_[k];
}

void LoopClosure::jacobian(const double* q, Eigen::MatrixXd& out) const {
  model_.loop_jacobian(q, full_j_.data());
  out.setZero(nc_, nv_);
  for (int i = 0; i < na_; ++i) out.row(i) = full_j_.row(rows_[i]);
  for (int k = 0; k < nc_ - na_; ++k) out(na_ + k, drive_v_[k]) = 1.0;
}

void LoopClosure::gamma(const double* q, const double* v, double t, Eigen::VectorXd& out) const {
  out.resize(nc_);
  model_.loop_gamma(q, v, full_phi_.data());
  for (int i = 0; i < na_; ++i) out[i] = full_phi_[rows_[i]];
  if (nc_ == na_) return;
  motion(t);
  out.tail(nc_ - na_) = motion_qdd_;
}

void LoopClosure::velocity_target(double t, Eigen::VectorXd& out) const {
  out.setZero(nc_);
  if (nc_ == na_) return;
  motion(t);
  out.tail(nc_ - na_) = motion_qd_;
}

void LoopClosure::impose_motion(double t, double* q, double* v) const {
  if (nc_ == na_) return;
  motion(t);
  for (int k = 0; k < nc_ - na_; ++k) {
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
      for (int k = 0; k < nc_ - na_; ++k) q[drive_q_[k]] = motion_q_[k];
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
      for (int k = 0; k < nc_ - na_; ++k) q[drive_q_[k]] = motion_q_[k];
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
