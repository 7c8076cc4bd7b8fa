// The static start's Newton solvers (static_start.h): the dense one with a
// difference Jacobian for small models, the sparse one with the implicit
// integrators' tangent for large ones, and their drivers per kind of model.
// One file of about 470 lines because both solvers share their convergence
// tests and their round-off floors (the constants below, each measured on a
// shipped model), and the mechanism diagnosis the drivers report; the
// seating of contacts on their running surfaces is running_surface_seat.cpp.
#include "runtime/simulation/static_start.h"

#include <Eigen/QR>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "ir/model_error.h"
#include "runtime/coupled/coupled_implicit_system.h"
#include "runtime/errors/multibody_errors.h"
#include "runtime/simulation/massless_joints.h"
#include "runtime/simulation/running_surface_seat.h"
#include "runtime/simulation/static_start_hints.h"

namespace mbfe::runtime {

namespace {

constexpr int kMaxIterations = 50;
// Central differences: the step that balances truncation (h^2) against
// round-off (eps / h), relative to the coordinate's size.
constexpr double kRelativeStep = 6e-6;
// Converged once the update is round-off of the coordinates (1e-12 relative)...
constexpr double kStepTolerance = 1e-12;
// ... or the residual has fallen by 1e-12 from its scale at the start.
constexpr double kResidualReduction = 1e-12;
// The sparse Newton of a model with low-rank adjusted beams stalls higher:
// their stiffness k* M + U diag(k_L - k*) U^T (k* = omega_l^2, 2.25e6 1/s^2
// for the catenary) cancels terms ~1e6 times the wires' lowest modal
// stiffness, which leaves updates of ~1e-11 relative. For such a model, an
// update below 1e-9 relative that no longer halves, once the residual has
// fallen by 1e-8 from the first one, is that floor.
constexpr double kStallTolerance = 1e-9;
constexpr double kStallResidualReduction = 1e-8;
// A Jacobian column space thinner than this (relative to its largest singular
// value) is a mechanism: a direction with no stiffness. Measured on the
// equilibrated Jacobian (below): the raw one spans the stiffness-to-mass
// ratios of the whole model, 80 1/s^2 for a car body on its springs against
// ~1e13 for the rotations of 0.5 m beam elements, which alone is a condition
// number the test would take for a mechanism.
constexpr double kMechanismRcond = 1e-10;
// The dense Newton's round-off floor: the residual is an acceleration, and a
// fine mesh's rotations (stiffness-to-mass ratios ~1e13 1/s^2) turn the
// round-off of the coordinates into residuals of ~1e-5 m/s^2, so updates
// stall at ~1e-11 relative instead of falling below kStepTolerance (a 30 m
// deck of 90 elements, original damping). An update below 1e-9 relative that
// no longer halves, once the residual has fallen by 1e-5 from its scale at
// the start, is that floor: the iterate is converged to its precision.
constexpr double kDenseStallTolerance = 1e-9;
constexpr double kDenseStallResidualReduction = 1e-5;
// A difference within this many ulps of the residual entry, over the step,
// is round-off: that entry does not depend on the unknown (a free body's
// acceleration g against its position: |J| ~ 2e-10 1/s^2, where the softest
// stiffness of a shipped model, 80 1/s^2, is 4e11 times more). The residual
// passes through a factorisation of M, hence a margin of 1e3 ulps.
constexpr double kDifferenceNoise = 1e3;
// Row and column scalings (Ruiz's equilibration) that bring every row's and
// column's largest entry to about 1; a mechanism, an exactly dependent set of
// columns, stays one under any such scaling.
constexpr int kEquilibrationSweeps = 4;
// A Newton step is halved at most this often (to 1e-6 of itself) before the
// failure to evaluate the residual there is the answer.
constexpr int kMaxStepHalvings = 20;

/// The mechanism found at the start: `coordinate` indexes the unknowns.
class MechanismError : public std::runtime_error {
 public:
  MechanismError(const std::string& message, std::size_t coordinate)
      : std::runtime_error(message), coordinate_(coordinate) {}
  std::size_t coordinate() const { return coordinate_; }

 private:
  std::size_t coordinate_;
};

}  // namespace

StaticSolution solve_static(const StaticResidualFn& residual, const Eigen::VectorXd& x0,
                            const std::vector<std::string>& names) {
  const Eigen::Index n = x0.size();
  StaticSolution out;
  out.x = x0;
  Eigen::VectorXd r, rp, rm;
  residual(out.x, r);
  const double scale = std::max(r.cwiseAbs().maxCoeff(), 1e-300);
  Eigen::MatrixXd J(r.size(), n);
  double last_step = std::numeric_limits<double>::infinity();
  for (int it = 0; it < kMaxIterations; ++it) {
    out.iterations = it;
    out.residual = r.cwiseAbs().maxCoeff();
    if (out.residual <= kResidualReduction * scale || n == 0) return out;
    for (Eigen::Index j = 0; j < n; ++j) {
      const double h = kRelativeStep * std::max(1.0, std::abs(out.x[j]));
      Eigen::VectorXd x = out.x;
      x[j] += h;
      residual(x, rp);
      x[j] = out.x[j] - h;
      residual(x, rm);
      J.col(j) = (rp - rm) / (2.0 * h);
      // A column whose every entry is within the round-off of its own
      // difference says that r does not depend on x_j: exactly zero, so
      // that the mechanism test below sees it (equilibration would scale the
      // noise up to 1 and Newton would step by its inverse).
      const Eigen::ArrayXd noise = kDifferenceNoise * std::numeric_limits<double>::epsilon() *
                                   rp.cwiseAbs().array().max(rm.cwiseAbs().array()) / (2.0 * h);
      if ((J.col(j).cwiseAbs().array() <= noise).all()) J.col(j).setZero();
    }
    // S = D_r^-1 J D_c^-1, J dx = r  <=>  S (D_c dx) = D_r^-1 r.
    Eigen::MatrixXd S = J;
    Eigen::VectorXd d_row = Eigen::VectorXd::Ones(S.rows()), d_col = Eigen::VectorXd::Ones(n);
    for (int sweep = 0; sweep < kEquilibrationSweeps; ++sweep) {
      for (Eigen::Index i = 0; i < S.rows(); ++i) {
        const double s = std::sqrt(S.row(i).cwiseAbs().maxCoeff());
        if (s > 0.0 && std::isfinite(s)) {
          S.row(i) /= s;
          d_row[i] *= s;
        }
      }
      for (Eigen::Index j = 0; j < n; ++j) {
        const double s = std::sqrt(S.col(j).cwiseAbs().maxCoeff());
        if (s > 0.0 && std::isfinite(s)) {
          S.col(j) /= s;
          d_col[j] *= s;
        }
      }
    }
    Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(S);
    qr.setThreshold(kMechanismRcond);
    if (qr.rank() < n) {
      // The unknown that carries most of the direction without stiffness.
      Eigen::JacobiSVD<Eigen::MatrixXd> svd(S, Eigen::ComputeFullV);
      Eigen::Index worst = 0;
      svd.matrixV().col(n - 1).cwiseAbs().maxCoeff(&worst);
      std::ostringstream os;
      if (it == 0) {
        os << "the structure is a mechanism: nothing holds '" << names[static_cast<std::size_t>(worst)]
           << "' in place (the static stiffness has rank " << qr.rank() << " of " << n
           << "); support it, or start from `initial:` as written";
        throw MechanismError(os.str(), static_cast<std::size_t>(worst));
      } else {
        // Held at the start, let go on the way: the Newton steps moved the
        // structure so far that a contact no longer touches (or no longer
        // finds its beam). Not a mechanism of the model as written.
        os << "Newton lost hold of '" << names[static_cast<std::size_t>(worst)] << "' after " << it
           << " iteration" << (it == 1 ? "" : "s") << " that moved the unknowns by up to "
           << (out.x - x0).cwiseAbs().maxCoeff()
           << " (m or rad): the equilibrium is too far from the start for the contacts to hold (a structure "
              "far softer than its loads: check the units of E, density and lengths); start from `initial:` as "
              "written";
      }
      throw std::runtime_error(os.str());
    }
    Eigen::VectorXd dx = qr.solve(r.cwiseQuotient(d_row)).cwiseQuotient(d_col);
    // A step into positions where the model has no state (a linkage the
    // loops cannot close there) is halved until it lands on one.
    for (int halving = 0;; ++halving) {
      try {
        residual(out.x - dx, r);
        break;
      } catch (const ContactError&) {
        if (halving == kMaxStepHalvings) throw;
        dx *= 0.5;
      }
    }
    out.x -= dx;
    if (!r.allFinite()) break;
    const double step = dx.cwiseAbs().maxCoeff(), size = 1.0 + out.x.cwiseAbs().maxCoeff();
    const bool stalled = step <= kDenseStallTolerance * size && step > 0.5 * last_step &&
                         r.cwiseAbs().maxCoeff() <= kDenseStallResidualReduction * scale;
    if (step <= kStepTolerance * size || stalled) {
      out.iterations = it + 1;
      out.residual = r.cwiseAbs().maxCoeff();
      return out;
    }
    last_step = step;
  }
  std::ostringstream os;
  os << "the static equilibrium at t = 0 did not converge in " << kMaxIterations
     << " Newton iterations (largest residual " << r.cwiseAbs().maxCoeff()
     << "); start from `initial:` as written, or from a state closer to equilibrium";
  throw std::runtime_error(os.str());
}

namespace {

/// The indices of 0..n-1 that are not in `driven`.
std::vector<int> free_indices(int n, const std::vector<int>& driven) {
  std::vector<int> out;
  for (int i = 0; i < n; ++i)
    if (std::find(driven.begin(), driven.end(), i) == driven.end()) out.push_back(i);
  return out;
}

/// The body whose joint owns the coordinate `name` ("wheel", or "body_x" of a
/// joint of several coordinates), -1 when none.
int body_of_coordinate(const ir::Model& model, const std::string& name) {
  for (std::size_t k = 0; k < model.bodies.size(); ++k) {
    const std::string& body = model.bodies[k].name;
    if (name == body || (name.size() > body.size() && name.compare(0, body.size(), body) == 0 && name[body.size()] == '_'))
      return static_cast<int>(k);
  }
  return -1;
}

/// Why the slider_spring contacts of the body owning the coordinate `name`
/// hold nothing at the state `dyn` was last evaluated at: "; its contact
/// 'tyre' is not over its beam at the start (s = -3 m; the beam spans 0 to 20
/// m)" or "... is 5 m clear of its beam at the start"; empty when one of them
/// touches (or the body has none).
std::string contact_hint(const ir::Model& model, const CoupledDynamics& dyn, const std::string& name) {
  const int body = body_of_coordinate(model, name);
  if (body < 0) return "";
  std::ostringstream os;
  int k = -1;
  for (const ir::Contact& c : model.contacts) {
    if (c.type != ir::ContactType::kSliderSpring) continue;
    ++k;
    if (c.body != body) continue;
    const SpringContactState& st = dyn.spring_state(k);
    if (st.on_beam && st.delta > 0.0) return "";
    const ir::Beam& beam = model.beams[static_cast<std::size_t>(c.beam)];
    os << "; its contact '" << c.name << "' ";
    if (!st.on_beam)
      os << "is not over its beam at the start (s = " << st.s << " m; beam '" << beam.name << "' spans 0 to "
         << beam.length << " m)";
    else
      os << "does not press on beam '" << beam.name << "' at the start (gap " << std::max(-st.delta, 0.0) + 0.0  // never "-0"
         << " m; the beam points (" << std::cos(beam.angle) << ", " << std::sin(beam.angle) << "))";
  }
  const std::string hint = os.str();
  return hint.empty() ? "" : hint + " (check the beam's origin and angle, in rad, and the body's position)";
}

/// `hints`: what holds nothing at the start (static_start_hints.h), found
/// before Newton. A mechanism at the start keeps its message and adds them; a
/// Newton that lost hold or did not converge is explained by them instead of
/// by its own words (which can only guess at units).
[[noreturn]] void static_start_failed(const ir::Model& model, const std::exception& e,
                                      const std::vector<std::string>& names, const std::string& hint = "",
                                      const std::vector<std::string>& hints = {}) {
  std::string what = e.what();
  if (!hint.empty()) {
    const auto cut = what.find(" in place (");
    if (cut != std::string::npos) what.insert(cut + std::string(" in place").size(), hint);
  }
  std::string causes;
  for (const std::string& h : hints) causes += (causes.empty() ? "" : "; ") + h;
  const auto* mechanism = dynamic_cast<const MechanismError*>(&e);
  if (!causes.empty())
    what =
        mechanism ? what + "; " + causes : "no equilibrium holds: " + causes + "; or start from `initial:` as written";
  // A coordinate without stiffness whose body carries no mass: its
  // acceleration, the residual, is not defined, which is not a mechanism.
  if (mechanism) {
    const std::string& name = names[mechanism->coordinate()];
    const int body = body_of_coordinate(model, name);
    if (body >= 0 && carries_no_mass(model, static_cast<std::size_t>(body)))
      what = moves_no_mass(model, name, static_cast<std::size_t>(body));
  }
  throw ir::ModelError(model.source_path, model.initial.loc, "static start of model '" + model.name + "': " + what);
}

// Newton on x, q = q0 (+) x along the velocity directions `moved` (indices
// into v): residual entry k is y'[nq + rate_entry[k]] of `system` at
// [q; w], w = y's velocity part (at rest). y's q becomes the solution.
// `closed`, when given, returns the positions the system evaluated y' at (a
// loop system closes q along its dependent directions): the next iterate
// starts from them, moved along `moved` by the change of x, so that Newton's
// closure starts near the loops however far Newton's steps go. Along plain
// coordinates that is the same chart (their `moved` entries are q0 + x).
using ClosedPositionsFn = std::function<void(const Eigen::VectorXd& state, Eigen::VectorXd& q)>;
void tangent_static_state(const ir::Model& model, OdeSystem& system, const RigidCoordinates& c,
                          const std::vector<int>& moved, const std::vector<int>& rate_entry, Eigen::VectorXd& y,
                          const ClosedPositionsFn& closed = nullptr) {
  Eigen::VectorXd start_q = y.head(c.nq);
  Eigen::VectorXd start_x = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(moved.size()));
  std::vector<std::string> names;
  for (int i : moved) names.push_back(c.rate_of[i] >= 0 ? c.position_columns[c.rate_of[i]] : c.velocity_columns[i]);
  Eigen::VectorXd state = y, ydot, dv = Eigen::VectorXd::Zero(c.nv), q_closed;
  auto place = [&](const Eigen::VectorXd& x) {
    state.head(c.nq) = start_q;
    for (std::size_t k = 0; k < moved.size(); ++k)
      dv[moved[k]] = x[static_cast<Eigen::Index>(k)] - start_x[static_cast<Eigen::Index>(k)];
    displace(c, state.data(), dv);
  };
  const StaticResidualFn residual = [&](const Eigen::VectorXd& x, Eigen::VectorXd& r) {
    place(x);
    system.rhs(0.0, state, ydot);
    if (closed) {
      closed(state, q_closed);
      start_q = q_closed;
      start_x = x;
    }
    r.resize(x.size());
    for (std::size_t k = 0; k < moved.size(); ++k) r[static_cast<Eigen::Index>(k)] = ydot[c.nq + rate_entry[k]];
  };
  try {
    const StaticSolution solution =
        solve_static(residual, Eigen::VectorXd::Zero(static_cast<Eigen::Index>(moved.size())), names);
    place(solution.x);
    normalize_quaternions(c, state.data());
    y.head(c.nq) = state.head(c.nq);
  } catch (const std::runtime_error& e) {
    static_start_failed(model, e, names);
  }
}

}  // namespace

void quaternion_static_state(const ir::Model& model, RigidSystem& system, Eigen::VectorXd& y) {
  const RigidCoordinates& c = system.coordinates();
  y.tail(c.nv).setZero();
  normalize_quaternions(c, y.data());
  system.impose_motion(0.0, y);
  const std::vector<int> moved = free_indices(c.nv, system.driven());
  tangent_static_state(model, system, c, moved, moved, y);
}

void loop_static_state(const ir::Model& model, LoopPartitionedSystem& system, Eigen::VectorXd& q,
                       Eigen::VectorXd& v) {
  const RigidCoordinates& c = system.closure().coordinates();
  v.setZero(c.nv);
  Eigen::VectorXd y = system.state_of(0.0, q, v);
  const std::vector<int> independent = system.partition().independent;
  if (independent.empty()) {  // the loops and drives fix every coordinate: nothing to solve
    system.full_state(0.0, y, q, v);
    return;
  }
  std::vector<int> entries(independent.size());
  for (std::size_t k = 0; k < entries.size(); ++k) entries[k] = static_cast<int>(k);
  Eigen::VectorXd v_closed;
  tangent_static_state(model, system, c, independent, entries, y,
                       [&](const Eigen::VectorXd& state, Eigen::VectorXd& q_closed) {
                         system.full_state(0.0, state, q_closed, v_closed);
                       });
  system.full_state(0.0, y, q, v);  // closed; at rest but for the driven joints' rates
}

void coupled_static_state(const ir::Model& model, CoupledDynamics& dyn, Eigen::VectorXd& q, Eigen::VectorXd& qd) {
  const int n = dyn.n();
  qd = Eigen::VectorXd::Zero(n);
  dyn.impose_motion(0.0, q, qd);
  seat_on_running_surfaces(model, dyn, free_indices(dyn.n(), dyn.driven()), kRelativeStep, q, qd);
  const std::vector<std::string> hints = static_start_hints(model, dyn, q, qd);
  const std::vector<std::string> all_names = dyn.model().coordinate_names();
  const std::vector<int> unknown = free_indices(n, dyn.driven());
  std::vector<std::string> names;
  for (int i : unknown) names.push_back(all_names[static_cast<std::size_t>(i)]);
  Eigen::VectorXd x0(static_cast<Eigen::Index>(unknown.size())), state = q, qdd, lambda;
  for (std::size_t k = 0; k < unknown.size(); ++k) x0[k] = q[unknown[k]];
  const StaticResidualFn residual = [&](const Eigen::VectorXd& x, Eigen::VectorXd& r) {
    for (std::size_t k = 0; k < unknown.size(); ++k) state[unknown[k]] = x[k];
    dyn.evaluate(0.0, state, qd);
    dyn.solve_augmented(0.0, qdd, lambda);
    r.resize(x.size() + dyn.m());
    for (std::size_t k = 0; k < unknown.size(); ++k) r[k] = qdd[unknown[k]];
    r.tail(dyn.m()) = dyn.values().phi;
  };
  try {
    const StaticSolution solution = solve_static(residual, x0, names);
    for (std::size_t k = 0; k < unknown.size(); ++k) q[unknown[k]] = solution.x[k];
  } catch (const std::runtime_error& e) {
    std::string hint;
    if (const auto* mechanism = dynamic_cast<const MechanismError*>(&e)) {
      Eigen::VectorXd r0;
      residual(x0, r0);  // the contacts' states at the start
      hint = contact_hint(model, dyn, names[mechanism->coordinate()]);
    }
    static_start_failed(model, e, names, hint, hints);
  }
}

void rigid_static_state(const ir::Model& model, RigidSystem& system, Eigen::VectorXd& y) {
  const int n = system.num_coordinates();
  // At rest apart from the driven joints: the free coordinates where their q'' vanish.
  y.tail(n).setZero();
  system.impose_motion(0.0, y);
  const std::vector<int> unknown = free_indices(n, system.driven());
  std::vector<std::string> names;
  for (int i : unknown) names.push_back(system.name(i));
  Eigen::VectorXd x0(static_cast<Eigen::Index>(unknown.size())), state = y, ydot;
  for (std::size_t k = 0; k < unknown.size(); ++k) x0[k] = y[unknown[k]];
  const StaticResidualFn residual = [&](const Eigen::VectorXd& x, Eigen::VectorXd& r) {
    for (std::size_t k = 0; k < unknown.size(); ++k) state[unknown[k]] = x[k];
    system.rhs(0.0, state, ydot);
    r.resize(x.size());
    for (std::size_t k = 0; k < unknown.size(); ++k) r[k] = ydot[n + unknown[k]];
  };
  try {
    const StaticSolution solution = solve_static(residual, x0, names);
    for (std::size_t k = 0; k < unknown.size(); ++k) y[unknown[k]] = solution.x[k];
  } catch (const std::runtime_error& e) {
    static_start_failed(model, e, names);
  }
}

bool rigid_settled_state(const ir::Model& model, RigidSystem& system, double omega_min, double omega_max,
                         Eigen::VectorXd& y) {
  // Settled once the rates are this small against the motion's scale.
  constexpr double kSettledRate = 1e-6;
  // At most this many periods of the slowest mode: a damped mode settles in a few.
  constexpr double kMaxPeriods = 200.0;
  if (!(omega_min > 0.0) || !(omega_max >= omega_min) || !std::isfinite(omega_max)) return false;
  const int n = system.num_coordinates();
  const double h = 0.5 / omega_max;
  const double c = 2.0 * omega_min;
  const long max_steps = static_cast<long>(kMaxPeriods * 2.0 * M_PI / omega_min / h);
  Eigen::VectorXd state = y, ydot;
  state.tail(n).setZero();
  system.impose_motion(0.0, state);
  bool settled = false;
  for (long k = 0; k < max_steps && !settled; ++k) {
    // Semi-implicit Euler with the damping -c q' taken implicitly.
    system.rhs(0.0, state, ydot);
    state.tail(n) = (state.tail(n) + h * ydot.tail(n)) / (1.0 + h * c);
    state.head(n) += h * state.tail(n);
    system.impose_motion(0.0, state);
    if (!state.allFinite()) return false;
    settled = state.tail(n).cwiseAbs().maxCoeff() <= kSettledRate * omega_min * (1.0 + state.head(n).norm());
  }
  if (!settled) return false;
  try {
    rigid_static_state(model, system, state);
  } catch (const std::exception&) {
    return false;
  }
  y = state;
  return true;
}

bool coupled_static_state_sparse(const ir::Model& model, const std::shared_ptr<CoupledDynamics>& dyn,
                                 Eigen::VectorXd& q, Eigen::VectorXd& qd) {
  std::unique_ptr<CoupledImplicitSystem> sys;
  try {
    sys = std::make_unique<CoupledImplicitSystem>(dyn);
  } catch (const std::invalid_argument&) {
    return false;  // an adjustment with no sparse C and K (eq (27) over every mode)
  }
  // A large "step" c_q: the matrix M + c_q K_t, divided by c_q, is K_t up to
  // M / c_q; the residual at a = 0 is the static one, so the iteration
  // converges to the exact equilibrium whatever that small difference.
  constexpr double kStiffnessWeight = 1e8;
  const int n = dyn->n(), m = dyn->m();
  qd = Eigen::VectorXd::Zero(n);
  dyn->impose_motion(0.0, q, qd);
  seat_on_running_surfaces(model, *dyn, free_indices(dyn->n(), dyn->driven()), kRelativeStep, q, qd);
  const std::vector<std::string> hints = static_start_hints(model, *dyn, q, qd);
  const Eigen::VectorXd a = Eigen::VectorXd::Zero(n);
  Eigen::VectorXd lambda = Eigen::VectorXd::Zero(m), r, c, da, dl;
  double last_step = std::numeric_limits<double>::infinity(), first_residual = -1.0;
  const bool low_rank = !dyn->model().structures().empty();
  for (int it = 0; it < kMaxIterations; ++it) {
    sys->residual(0.0, q, qd, a, lambda, kStiffnessWeight, r, c);
    for (int d : dyn->driven()) r[d] = 0.0;  // driven coordinates stay where the motion puts them
    sys->factorize(0.0, q, qd, a, lambda, kStiffnessWeight, 0.0);
    sys->solve(r, c, da, dl);
    const Eigen::VectorXd dq = kStiffnessWeight * da;
    q -= dq;
    lambda -= dl;
    dyn->impose_motion(0.0, q, qd);  // the solve's round-off, times the large weight, must not move them
    if (!q.allFinite()) break;
    const double step = dq.cwiseAbs().maxCoeff(), scale = 1.0 + q.cwiseAbs().maxCoeff();
    if (step <= kStepTolerance * scale) return true;
    const double residual = r.cwiseAbs().maxCoeff();
    if (first_residual < 0.0) first_residual = residual;
    if (low_rank && step <= kStallTolerance * scale && step > 0.5 * last_step &&
        residual <= kStallResidualReduction * first_residual)
      return true;
    last_step = step;
  }
  std::string causes;
  for (const std::string& h : hints) causes += "; " + h;
  throw ir::ModelError(model.source_path, model.initial.loc,
                       "static start of model '" + model.name + "': Newton on the sparse tangent did not converge in " +
                           std::to_string(kMaxIterations) + " iterations" + causes +
                           "; start from `initial:` as written");
}

void coupled_static_start(const ir::Model& model, const std::shared_ptr<CoupledDynamics>& dyn, Eigen::VectorXd& q,
                          Eigen::VectorXd& qd) {
  // The dense difference Jacobian costs n evaluations and an n^3 solve:
  // large models take the sparse tangent.
  if (dyn->n() <= kDenseStaticCoordinates || !coupled_static_state_sparse(model, dyn, q, qd))
    coupled_static_state(model, *dyn, q, qd);
}

}  // namespace mbfe::runtime
