#include "runtime/multibody/rigid_system.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "runtime/multibody/driven_coordinates.h"
#include "runtime/errors/multibody_errors.h"

namespace mbfe::runtime {

namespace {

void check_model(const mbfe_model_v1& model) {
  if (model.abi_version != MBFE_MODEL_ABI_VERSION) {
    std::ostringstream os;
    os << "model '" << (model.model_name ? model.model_name : "?") << "' has ABI version "
       << model.abi_version << ", expected " << MBFE_MODEL_ABI_VERSION
       << " (regenerate the solver with this mbfe)";
    throw std::invalid_argument(os.str());
  }
}

std::string coordinate_name(const mbfe_model_v1& model, int i) {
  if (model.coordinate_names != nullptr && model.coordinate_names[i] != nullptr) {
    return model.coordinate_names[i];
  }
  return "q" + std::to_string(i);
}

/// The name of velocity coordinate i, a row of M (a quaternion joint's are
/// not its position coordinates: <body>_wx, not <body>_qw).
std::string velocity_name(const mbfe_model_v1& model, int i) {
  if (model.velocity_names != nullptr && model.velocity_names[i] != nullptr) return model.velocity_names[i];
  return coordinate_name(model, i);  // nv = nq: the same names
}

}  // namespace

std::vector<BodyInertia> body_inertias(const ir::Model& model) {
  std::vector<BodyInertia> out;
  out.reserve(model.bodies.size());
  for (const ir::Body& b : model.bodies)
    out.push_back({b.name, b.mass, model.dimension == 3 ? b.inertia3[0] + b.inertia3[1] + b.inertia3[2] : b.inertia});
  return out;
}

void evaluate_dynamics(const mbfe_model_v1& model, const double* q, const double* qd, double t,
                       double* M_row_major, double* F, double* Q) {
  if (model.dynamics != nullptr) {
    model.dynamics(q, qd, t, M_row_major, F, Q);
    return;
  }
  model.mass_matrix(q, M_row_major);
  model.inertial_forces(q, qd, F);
  model.generalized_forces(q, qd, t, Q);
}

void evaluate_rigid_terms(const mbfe_model_v1& model, const Eigen::VectorXd& q,
                          const Eigen::VectorXd& qd, double t, RigidTerms& out) {
  const int n = model.num_coordinates;
  const int nv = model.num_velocities > 0 ? model.num_velocities : n;
  if (q.size() != n || qd.size() != nv) {
    std::ostringstream os;
    os << "q has " << q.size() << " and qd " << qd.size() << " entries, expected " << n << " and " << nv
       << " (the position and velocity coordinates of model '" << model.model_name << "' in model order)";
    throw std::invalid_argument(os.str());
  }
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> m_row(nv, nv);
  out.F.resize(nv);
  out.Q.resize(nv);
  evaluate_dynamics(model, q.data(), qd.data(), t, m_row.data(), out.F.data(), out.Q.data());
  out.M = m_row;
}

void throw_singular_mass_matrix(const mbfe_model_v1& model,
                                const std::vector<BodyInertia>& bodies,
                                const Eigen::MatrixXd& M, double t) {
  const int n = static_cast<int>(M.rows());
  std::vector<std::string> coords;
  std::ostringstream os;
  os << "model '" << (model.model_name ? model.model_name : "?")
     << "': mass matrix M(q) is singular or not positive definite at t = " << t << " s";
  if (M.allFinite()) {
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(0.5 * (M + M.transpose()));
    const Eigen::VectorXd& lam = eig.eigenvalues();
    const double scale = std::max(lam.cwiseAbs().maxCoeff(), 1e-300);
    // A direction of (near) zero or negative kinetic energy.
    const double kNullRel = 1e-10;
    std::vector<bool> in_null(n, false);
    for (int k = 0; k < n; ++k) {
      if (lam(k) > kNullRel * scale) continue;
      for (int i = 0; i < n; ++i) {
        if (std::abs(eig.eigenvectors()(i, k)) > 0.1) in_null[i] = true;
      }
    }
    for (int i = 0; i < n; ++i) {
      if (in_null[i]) coords.push_back(velocity_name(model, i));
    }
    os << " (eigenvalues from " << lam(0) << " to " << lam(n - 1) << ")";
  } else {
    os << " (M has non-finite entries: the state is not finite)";
  }
  // A coordinate that moves no mass has a zero diagonal entry (every term of
  // M_ii is a mass or inertia times a square); one with M_ii > 0 in the null
  // direction moves mass, and M is singular only numerically: a state grown
  // so large (a step beyond the stable limit) that M's spread of eigenvalues
  // exceeds double precision, or a kinematic singularity.
  std::vector<std::string> no_mass;
  for (int i = 0; i < n; ++i)
    if (M.allFinite() && !(M(i, i) > 0.0)) no_mass.push_back(velocity_name(model, i));
  std::vector<std::string> massless;
  for (const BodyInertia& b : bodies) {
    if (b.mass == 0.0 && b.inertia == 0.0) massless.push_back(b.name);
  }
  if (!no_mass.empty()) {
    os << "; these coordinates move no mass: ";
    for (std::size_t i = 0; i < no_mass.size(); ++i) os << (i ? ", " : "") << no_mass[i];
    if (!massless.empty()) {
      os << "; bodies with mass 0 and inertia 0: ";
      for (std::size_t i = 0; i < massless.size(); ++i) os << (i ? ", " : "") << massless[i];
    }
    os << ". Give the bodies that these coordinates move a mass or inertia (massless, "
          "fictitious bodies need a massive successor that moves with every one of their "
          "coordinates), or constrain the coordinate.";
  } else if (!coords.empty()) {
    os << "; numerically only: ";
    for (std::size_t i = 0; i < coords.size(); ++i) os << (i ? ", " : "") << coords[i];
    os << " move mass (M's diagonal is positive), but at this state M's eigenvalues span more than double "
          "precision holds. A state grown that far is usually a step beyond the integrator's stable limit: take "
          "the step `mbfe advise` or `mbfe stability` gives; otherwise the mechanism is at a kinematic "
          "singularity.";
  } else {
    os << ".";
  }
  throw SingularMassMatrixError(os.str(), t, std::move(coords), std::move(massless));
}

RigidSystem::RigidSystem(const mbfe_model_v1& model, std::vector<BodyInertia> bodies, RigidCoordinates coordinates)
    : model_(model), bodies_(std::move(bodies)), coordinates_(std::move(coordinates)), nq_(model.num_coordinates) {
  check_model(model);
  nv_ = model.num_velocities > 0 ? model.num_velocities : nq_;
  if (coordinates_.nq == 0) {
    if (nv_ != nq_) {
      std::ostringstream os;
      os << "RigidSystem: model '" << model.model_name << "' has " << nq_ << " position and " << nv_
         << " velocity coordinates: give its coordinate layout (rigid_coordinates)";
      throw std::invalid_argument(os.str());
    }
    coordinates_.nq = coordinates_.nv = nq_;
    for (int i = 0; i < nq_; ++i) {
      coordinates_.rate_of.push_back(i);
      coordinates_.rotation_of.push_back(-1);
      coordinates_.rotation_axis.push_back(-1);
    }
  } else if (coordinates_.nq != nq_ || coordinates_.nv != nv_) {
    std::ostringstream os;
    os << "RigidSystem: the coordinate layout has " << coordinates_.nq << " / " << coordinates_.nv
       << " position / velocity coordinates, the solver of '" << model.model_name << "' " << nq_ << " / " << nv_;
    throw std::invalid_argument(os.str());
  }
  if (!bodies_.empty() && model.dimension != 3 && static_cast<int>(bodies_.size()) != nq_) {
    std::ostringstream os;
    os << "RigidSystem: " << bodies_.size() << " body inertias given, expected " << nq_
       << " (one per body of model '" << model.model_name << "')";
    throw std::invalid_argument(os.str());
  }
  m_row_.resize(nv_, nv_);
  m_.resize(nv_, nv_);
  f_.resize(nv_);
  q_force_.resize(nv_);
  rhs_.resize(nv_);
  qdd_.resize(nv_);
  // Allocates the factor's storage once. Not `llt_ = LLT(nv_)`: Eigen's sized
  // constructor leaves its `info` uninitialised and the assignment copies it,
  // which UndefinedBehaviorSanitizer reports (invalid enum load, LLT.h:66).
  llt_.compute(Eigen::MatrixXd::Identity(nv_, nv_));
  for (int i = 0; i < model.num_driven; ++i) {
    driven_.push_back(model.driven_coordinates[i]);
    driven_positions_.push_back(model.driven_positions ? model.driven_positions[i] : model.driven_coordinates[i]);
  }
  drive_q_.resize(static_cast<Eigen::Index>(driven_.size()));
  drive_qd_.resize(drive_q_.size());
  drive_qdd_.resize(drive_q_.size());
}

void RigidSystem::rhs(double t, const Eigen::VectorXd& y, Eigen::VectorXd& ydot) {
  if (y.size() != nq_ + nv_) {
    std::ostringstream os;
    os << "RigidSystem: y has " << y.size() << " entries, expected " << nq_ + nv_ << " ([q; v])";
    throw std::invalid_argument(os.str());
  }
  const double* q = y.data();
  const double* qd = y.data() + nq_;
  if (!driven_.empty()) {
    // Driven coordinates follow their motion whatever y says.
    y_motion_ = y;
    impose_motion(t, y_motion_);
    q = y_motion_.data();
    qd = y_motion_.data() + nq_;
  }
  evaluate_dynamics(model_, q, qd, t, m_row_.data(), f_.data(), q_force_.data());
  m_ = m_row_;
  rhs_ = q_force_ - f_;
  eliminate_driven(m_, rhs_, driven_, drive_qdd_);
  llt_.compute(m_);
  if (llt_.info() != Eigen::Success || !(llt_.rcond() >= kMassRcondFloor)) {
    throw_singular_mass_matrix(model_, bodies_, m_, t);
  }
  qdd_ = llt_.solve(rhs_);
  ydot.resize(nq_ + nv_);
  if (model_.position_derivative != nullptr) model_.position_derivative(q, qd, ydot.data());
  else ydot.head(nq_) = Eigen::Map<const Eigen::VectorXd>(qd, nv_);
  ydot.tail(nv_) = qdd_;
}

void RigidSystem::after_step(double, Eigen::VectorXd& y) {
  if (coordinates_.has_quaternions()) normalize_quaternions(coordinates_, y.data());
}

void RigidSystem::impose_motion(double t, Eigen::VectorXd& y) const {
  if (driven_.empty()) return;
  model_.motion(t, drive_q_.data(), drive_qd_.data(), drive_qdd_.data());
  for (std::size_t k = 0; k < driven_.size(); ++k) {
    y[driven_positions_[k]] = drive_q_[k];
    y[nq_ + driven_[k]] = drive_qd_[k];
  }
}

void RigidSystem::drive_reactions(double t, const Eigen::VectorXd& y, Eigen::VectorXd& out) {
  out.resize(static_cast<Eigen::Index>(driven_.size()));
  if (driven_.empty()) return;
  Eigen::VectorXd ydot;
  rhs(t, y, ydot);  // q'' of the free coordinates; the motion's for the driven ones
  const double* q = y_motion_.data();
  const double* qd = y_motion_.data() + nq_;
  evaluate_dynamics(model_, q, qd, t, m_row_.data(), f_.data(), q_force_.data());
  for (std::size_t k = 0; k < driven_.size(); ++k) {
    const int d = driven_[k];
    out[static_cast<Eigen::Index>(k)] = m_row_.row(d).dot(ydot.tail(nv_)) + f_[d] - q_force_[d];
  }
}

std::string RigidSystem::name(int i) const {
  if (i < nq_) {
    if (static_cast<int>(coordinates_.position_columns.size()) == nq_) return coordinates_.position_columns[i];
    return coordinate_name(model_, i);
  }
  if (static_cast<int>(coordinates_.velocity_columns.size()) == nv_) return coordinates_.velocity_columns[i - nq_];
  return coordinate_name(model_, i - nq_) + "_dot";
}

double RigidSystem::kinetic_energy(const Eigen::VectorXd& y) {
  model_.mass_matrix(y.data(), m_row_.data());
  m_ = m_row_;
  return 0.5 * y.tail(nv_).dot(m_ * y.tail(nv_));
}

}  // namespace mbfe::runtime
