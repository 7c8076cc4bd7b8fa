// The stepper of the linearised run (linearised_run.h): one class whose
// state (modes, bodies, elements) every part of a step reads and writes;
// split in files it would pass all of it around, so it is about 500 lines.
// The Newton update of a step's small system is linearised_step_solve.h.
#include "runtime/simulation/linearised_run.h"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "runtime/simulation/linearised_step_solve.h"

namespace mbfe::runtime {

namespace {

// Newton iterations over the element laws of one step: a linear law settles
// in one (two when a contact or link changes state); Hertz's converges
// quadratically from the last step's forces.
constexpr int kMaxNewton = 30;
// A Hertzian force has settled when the last Newton update moved it by no
// more than this share of the largest force (quadratic convergence gets
// there in a step or two from the last step's forces).
constexpr double kSettledForce = 1e-10;
// Passes of the static start with damped moving contacts: the rate at rest
// depends on the deflection through the slope under the contact, a small
// correction the second pass takes; the third leaves round-off.
constexpr int kStaticRatePasses = 3;
/// F and dF/dx of a law at x with the rate x' = rate (dx'/dx = rate_slope).
struct LawValue {
  double force = 0.0, slope = 0.0;
  bool on = false;
};

LawValue evaluate_law(const ElementLaw& law, double x, double rate, double rate_slope) {
  LawValue out;
  if (law.compression_only && !(x > 0.0)) return out;
  double spring = 0.0, spring_slope = 0.0;
  if (law.hertz > 0.0) {
    if (!(x > 0.0)) return out;  // a Hertzian contact apart is no spring at all
    const double root = std::sqrt(x);
    spring = law.hertz * x * root;
    spring_slope = 1.5 * law.hertz * root;
  } else {
    spring = law.stiffness * x;
    spring_slope = law.stiffness;
  }
  out.force = spring + law.damping * rate;
  if (law.no_pull && out.force < 0.0) return LawValue{};
  out.slope = spring_slope + law.damping * rate_slope;
  out.on = true;
  return out;
}

/// One active contact at one step: its modes' weights p (its beam's block).
struct ActiveContact {
  int index = 0;  // contact
  int block = 0;
  Eigen::VectorXd p;  // m_b: Phi_b^T g
  Eigen::VectorXd r;  // n_r
  double offset = 0.0;
};

class Runner {
 public:
  Runner(const LinearisedStructure& s, const ModalDynamicsSet& d, const LinearisedExcitation& x)
      : s_(s),
        d_(d),
        x_(x),
        ns_(s.modes),
        nr_(static_cast<int>(s.mass.rows())),
        nc_(static_cast<int>(s.contact_laws.size())),
        nf_(static_cast<int>(s.fixed.size())),
        step_solve_(nr_, nf_) {
    check_sizes();
    block_of_dof_.assign(static_cast<std::size_t>(s.dofs), -1);
    for (std::size_t b = 0; b < s.blocks.size(); ++b) {
      const auto& blk = s.blocks[b];
      for (int i = 0; i < blk.phi->rows(); ++i)
        block_of_dof_[static_cast<std::size_t>(blk.dof_offset + i)] = static_cast<int>(b);
    }
    // Each fixed element's modal weights, Phi^T g_e over every mode: the
    // rows of the modes at the DOFs it touches, weighted, computed once so
    // a step passes over the modes once per element, not once per DOF.
    hf_.setZero(nf_, ns_);
    off_f_.resize(nf_);
    for (int f = 0; f < nf_; ++f) {
      const FixedElement& e = s.fixed[static_cast<std::size_t>(f)];
      off_f_[f] = e.offset;
      for (const auto& [dof, w] : e.dofs) {
        const auto& blk = s.blocks[static_cast<std::size_t>(block_of_dof_[static_cast<std::size_t>(check_dof(dof))])];
        hf_.block(f, blk.mode_offset, 1, blk.phi->cols()) += w * blk.phi->row(dof - blk.dof_offset);
      }
    }
    // The constant modal load Phi^T P.
    constant_modal_.setZero(ns_);
    for (const auto& blk : s.blocks)
      constant_modal_.segment(blk.mode_offset, blk.phi->cols()) =
          blk.phi->transpose() * x.constant_load.segment(blk.dof_offset, blk.phi->rows());
    m_ = d.m;
    c_ = d.c;
    for (int j = 0; j < ns_; ++j)
      if (d.kind[static_cast<std::size_t>(j)] != ModalDynamicsSet::kDynamic) m_[j] = c_[j] = 0.0;
  }

  LinearisedHistory run(const LinearisedStart& start) {
    LinearisedHistory out;
    out.force.assign(static_cast<std::size_t>(nc_), std::vector<double>(static_cast<std::size_t>(x_.steps) + 1, 0.0));
    out.compression = out.force;
    const double h = x_.step;
    eta_.setZero(ns_);
    v_.setZero(ns_);
    a_.setZero(ns_);
    y_.setZero(nr_);
    yd_.setZero(nr_);
    ydd_.setZero(nr_);
    xf_.setZero(nf_);
    xdf_.setZero(nf_);
    zf_.setZero(nf_);
    xc_.assign(static_cast<std::size_t>(nc_), 0.0);
    xdc_ = xc_;
    zc_ = xc_;
    static_rate_ = xc_;
    was_active_.assign(static_cast<std::size_t>(nc_), false);
    if (start.static_start)
      static_start(out);
    else
      given_start(start, out);

    // Newmark's average acceleration: the step's coefficients.
    gain_ = 2.0 / h;
    const double a4 = 4.0 / (h * h), a5 = 4.0 / h;
    set_inverse(/*statics=*/false);
    const Eigen::MatrixXd B = s_.stiffness + gain_ * s_.damping + a4 * s_.mass;
    step_solve_.start_steps(B);
    Eigen::VectorXd fs(ns_), rq(ns_), ry(nr_), eta_p(ns_), force_on_modes(ns_);
    for (int k = 1; k <= x_.steps; ++k) {
      modal_load(k, fs);
      rq = fs + m_.cwiseProduct(a4 * eta_ + a5 * v_ + a_) + c_.cwiseProduct(gain_ * eta_ + v_);
      eta_p = inv_d_.cwiseProduct(rq);
      ry = x_.rigid_loads.col(k) + s_.mass * (a4 * y_ + a5 * yd_ + ydd_) + s_.damping * (gain_ * y_ + yd_);
      gather_contacts(k);
      if (!solve_step(B, ry, eta_p, /*statics=*/false)) ++out.unconverged_steps;
      // The modes under the elements' forces.
      modal_force(force_on_modes);
      Eigen::VectorXd eta1 = eta_p - inv_d_.cwiseProduct(force_on_modes);
      Eigen::VectorXd v1 = gain_ * (eta1 - eta_) - v_;
      Eigen::VectorXd a1 = a4 * (eta1 - eta_) - a5 * v_ - a_;
      for (int j = 0; j < ns_; ++j)
        if (d_.kind[static_cast<std::size_t>(j)] != ModalDynamicsSet::kDynamic) v1[j] = a1[j] = 0.0;
      eta_ = std::move(eta1);
      v_ = std::move(v1);
      a_ = std::move(a1);
      const Eigen::VectorXd yd1 = gain_ * (y_new_ - y_) - yd_;
      ydd_ = a4 * (y_new_ - y_) - a5 * yd_ - ydd_;
      yd_ = yd1;
      y_ = y_new_;
      remember(k, out);
    }
    return out;
  }

 private:
  void check_sizes() const {
    const auto bad = [](const std::string& what) { throw std::invalid_argument("linearised run: " + what); };
    if (s_.mass.cols() != nr_ || s_.damping.rows() != nr_ || s_.damping.cols() != nr_ || s_.stiffness.rows() != nr_ ||
        s_.stiffness.cols() != nr_)
      bad("the bodies' M, C, K are not all " + std::to_string(nr_) + " square");
    if (d_.m.size() != ns_ || d_.c.size() != ns_ || d_.k.size() != ns_ || static_cast<int>(d_.kind.size()) != ns_)
      bad("the modal dynamics do not have " + std::to_string(ns_) + " modes");
    int modes = 0;
    for (const auto& blk : s_.blocks) {
      if (blk.phi == nullptr || blk.mode_offset != modes || blk.dof_offset < 0 ||
          blk.dof_offset + blk.phi->rows() > s_.dofs)
        bad("a block's modes or DOFs are out of place");
      modes += static_cast<int>(blk.phi->cols());
    }
    if (modes != ns_) bad("the blocks hold " + std::to_string(modes) + " modes, not " + std::to_string(ns_));
    const std::size_t points = static_cast<std::size_t>(x_.steps + 1);
    if (x_.steps < 1 || !(x_.step > 0.0) || x_.geometry.size() != points * static_cast<std::size_t>(nc_) ||
        x_.rigid_gradients.rows() != nr_ || x_.rigid_gradients.cols() != static_cast<Eigen::Index>(points) * nc_ ||
        x_.rigid_loads.rows() != nr_ || x_.rigid_loads.cols() != static_cast<Eigen::Index>(points) ||
        x_.constant_load.size() != s_.dofs || (!x_.timed_loads.empty() && x_.timed_loads.size() != points) ||
        static_cast<int>(s_.contact_names.size()) != nc_)
      bad("the excitation does not fit the structure and its grid");
  }

  int check_dof(int dof) const {
    if (dof < 0 || dof >= s_.dofs || block_of_dof_[static_cast<std::size_t>(dof)] < 0)
      throw std::invalid_argument("linearised run: an element acts on DOF " + std::to_string(dof) +
                                  ", which no block holds");
    return dof;
  }

  /// inv_d_ and the fixed elements' coupling for the step's (or the statics') modal stiffness.
  void set_inverse(bool statics) {
    inv_d_.resize(ns_);
    for (int j = 0; j < ns_; ++j) {
      const unsigned char kind = d_.kind[static_cast<std::size_t>(j)];
      const double dj = statics ? d_.k[j] : d_.k[j] + gain_ * c_[j] + gain_ * gain_ * m_[j];  // k + 2c/h + 4m/h^2
      inv_d_[j] = kind == ModalDynamicsSet::kAbsent ? 0.0 : 1.0 / dj;
    }
    g_ff_ = hf_ * inv_d_.asDiagonal() * hf_.transpose();
  }

  void modal_load(int k, Eigen::VectorXd& fs) const {
    fs = constant_modal_;
    if (x_.timed_loads.empty()) return;
    for (const auto& [dof, value] : x_.timed_loads[static_cast<std::size_t>(k)]) {
      const auto& blk = s_.blocks[static_cast<std::size_t>(block_of_dof_[static_cast<std::size_t>(dof)])];
      fs.segment(blk.mode_offset, blk.phi->cols()).noalias() += value * blk.phi->row(dof - blk.dof_offset).transpose();
    }
  }

  /// Contact i's modal weights at step k (false when off its beam).
  bool contact_at(int k, int i, ActiveContact& out) const {
    const ContactGeometry& g = x_.geometry[static_cast<std::size_t>(k) * nc_ + i];
    if (!g.active) return false;
    out.index = i;
    out.block = -1;
    for (int a = 0; a < 4; ++a) {
      if (g.dofs[a] < 0) continue;
      const int b = block_of_dof_[static_cast<std::size_t>(check_dof(g.dofs[a]))];
      if (out.block >= 0 && b != out.block)
        throw std::invalid_argument("linearised run: contact " + s_.contact_names[static_cast<std::size_t>(i)] +
                                    " acts on two beams at once");
      out.block = b;
    }
    if (out.block < 0) out.block = 0;
    const auto& blk = s_.blocks[static_cast<std::size_t>(out.block)];
    out.p.setZero(blk.phi->cols());
    for (int a = 0; a < 4; ++a)
      if (g.dofs[a] >= 0) out.p.noalias() += g.weights[a] * blk.phi->row(g.dofs[a] - blk.dof_offset).transpose();
    out.r = x_.rigid_gradients.col(static_cast<Eigen::Index>(k) * nc_ + i);
    out.offset = g.offset;
    return true;
  }

  /// The compression of a contact at step k's place with the state (eta, y) held.
  double frozen_compression(const ActiveContact& c, const Eigen::VectorXd& eta, const Eigen::VectorXd& y) const {
    const auto& blk = s_.blocks[static_cast<std::size_t>(c.block)];
    return c.offset + c.p.dot(eta.segment(blk.mode_offset, c.p.size())) + c.r.dot(y);
  }

  /// The rate of contact i's compression at step k from its motion along the
  /// beam alone (the state held): one-sided second-order differences.
  double geometric_rate(int k, int i) const {
    ActiveContact c;
    double x[3];
    int have = 0;
    for (int j = 0; j < 3 && k + j <= x_.steps; ++j) {
      if (!contact_at(k + j, i, c)) break;
      x[j] = frozen_compression(c, eta_, y_);
      ++have;
    }
    if (have == 3) return (-3.0 * x[0] + 4.0 * x[1] - x[2]) / (2.0 * x_.step);
    if (have == 2) return (x[1] - x[0]) / x_.step;
    return 0.0;
  }

  /// The contacts on their beam at step k, with their couplings.
  void gather_contacts(int k) {
    active_.clear();
    for (int i = 0; i < nc_; ++i) {
      ActiveContact c;
      if (!contact_at(k, i, c)) continue;
      if (!was_active_[static_cast<std::size_t>(i)]) {
        // Just arrived on its beam: its compression and rate with the
        // state of the last step.
        xc_[static_cast<std::size_t>(i)] = frozen_compression(c, eta_, y_);
        const auto& blk = s_.blocks[static_cast<std::size_t>(c.block)];
        xdc_[static_cast<std::size_t>(i)] =
            c.p.dot(v_.segment(blk.mode_offset, c.p.size())) + c.r.dot(yd_) + geometric_rate(k, i);
      }
      active_.push_back(std::move(c));
    }
  }

  /// Solves for y_new_, zf_ and the active contacts' forces; false when the
  /// laws did not settle.
  bool solve_step(const Eigen::MatrixXd& B, const Eigen::VectorXd& ry, const Eigen::VectorXd& eta_p, bool statics) {
    const int na = static_cast<int>(active_.size()), nz = nf_ + na, n = nr_ + nz;
    // Predicted elongations (no element force, the bodies where y = 0) and
    // the couplings G (x = x_p - G z + E^T y).
    Eigen::VectorXd xp(nz);
    xp.head(nf_) = off_f_ + hf_ * eta_p;
    Eigen::MatrixXd G(nz, nz), E = Eigen::MatrixXd::Zero(nr_, nz);
    G.topLeftCorner(nf_, nf_) = g_ff_;
    for (int a = 0; a < na; ++a) {
      const ActiveContact& c = active_[static_cast<std::size_t>(a)];
      const auto& blk = s_.blocks[static_cast<std::size_t>(c.block)];
      const auto inv = inv_d_.segment(blk.mode_offset, c.p.size());
      xp[nf_ + a] = c.offset + c.p.dot(eta_p.segment(blk.mode_offset, c.p.size()));
      const Eigen::VectorXd weighted = inv.cwiseProduct(c.p);
      if (nf_ > 0) {
        const Eigen::VectorXd gcf = hf_.middleCols(blk.mode_offset, c.p.size()) * weighted;
        G.block(nf_ + a, 0, 1, nf_) = gcf.transpose();
        G.block(0, nf_ + a, nf_, 1) = gcf;
      }
      for (int b2 = 0; b2 <= a; ++b2) {
        const ActiveContact& o = active_[static_cast<std::size_t>(b2)];
        const double g = o.block == c.block ? weighted.dot(o.p) : 0.0;
        G(nf_ + a, nf_ + b2) = G(nf_ + b2, nf_ + a) = g;
      }
      E.col(nf_ + a) = c.r;
    }
    // The iterate: the last step's forces and bodies.
    Eigen::VectorXd y = y_, z(nz);
    z.head(nf_) = zf_;
    for (int a = 0; a < na; ++a) z[nf_ + a] = zc_[static_cast<std::size_t>(active_[static_cast<std::size_t>(a)].index)];
    const double rate_gain = statics ? 0.0 : gain_;
    std::vector<LawValue> laws(static_cast<std::size_t>(nz));
    auto evaluate = [&](const Eigen::VectorXd& x) {
      for (int e = 0; e < nz; ++e) {
        const bool fixed = e < nf_;
        const int i = fixed ? e : active_[static_cast<std::size_t>(e - nf_)].index;
        const ElementLaw& law =
            fixed ? s_.fixed[static_cast<std::size_t>(e)].law : s_.contact_laws[static_cast<std::size_t>(i)];
        const double prev = fixed ? xf_[e] : xc_[static_cast<std::size_t>(i)];
        const double prev_rate = fixed ? xdf_[e] : xdc_[static_cast<std::size_t>(i)];
        const double rate =
            statics ? (fixed ? 0.0 : static_rate_[static_cast<std::size_t>(i)]) : rate_gain * (x[e] - prev) - prev_rate;
        laws[static_cast<std::size_t>(e)] = evaluate_law(law, x[e], rate, rate_gain);
      }
    };
    Eigen::VectorXd residual(n), slopes(nz);
    Eigen::VectorXd x = xp - G * z + E.transpose() * y;
    evaluate(x);
    bool settled = false;
    for (int it = 0; it < kMaxNewton && !settled; ++it) {
      residual.head(nr_) = B * y + E * z - ry;
      for (int e = 0; e < nz; ++e) {
        residual[nr_ + e] = z[e] - laws[static_cast<std::size_t>(e)].force;
        slopes[e] = laws[static_cast<std::size_t>(e)].slope;
      }
      const Eigen::VectorXd delta = statics ? step_solve_.equilibrated(B, E, G, slopes, residual)
                                            : step_solve_.by_blocks(E, G, slopes, residual);
      y += delta.head(nr_);
      z += delta.tail(nz);
      x = xp - G * z + E.transpose() * y;
      const std::vector<LawValue> before = laws;
      evaluate(x);
      // A linear law is met exactly once no element changes state; Hertz's
      // when the forces stop moving.
      settled = true;
      double largest_force = 0.0;
      for (int e = 0; e < nz; ++e) largest_force = std::max(largest_force, std::abs(z[e]));
      for (int e = 0; e < nz; ++e) {
        const LawValue &now = laws[static_cast<std::size_t>(e)], &was = before[static_cast<std::size_t>(e)];
        const ElementLaw& law =
            e < nf_ ? s_.fixed[static_cast<std::size_t>(e)].law
                    : s_.contact_laws[static_cast<std::size_t>(active_[static_cast<std::size_t>(e - nf_)].index)];
        if (now.on != was.on || (law.hertz > 0.0 && std::abs(delta[nr_ + e]) > kSettledForce * largest_force))
          settled = false;
      }
    }
    // The forces of the laws at the final elongations (an element off carries none).
    for (int e = 0; e < nz; ++e) z[e] = laws[static_cast<std::size_t>(e)].force;
    y_new_ = y;
    zf_ = z.head(nf_);
    x_new_ = x;
    for (int a = 0; a < na; ++a) zc_[static_cast<std::size_t>(active_[static_cast<std::size_t>(a)].index)] = z[nf_ + a];
    return settled;
  }

  /// Phi^T sum_e g_e F_e over every mode.
  void modal_force(Eigen::VectorXd& out) const {
    out.noalias() = hf_.transpose() * zf_;
    for (const ActiveContact& c : active_) {
      const auto& blk = s_.blocks[static_cast<std::size_t>(c.block)];
      out.segment(blk.mode_offset, c.p.size()).noalias() += zc_[static_cast<std::size_t>(c.index)] * c.p;
    }
  }

  /// The elements' elongations and rates at the new step, and the record.
  void remember(int k, LinearisedHistory& out) {
    const double gain = gain_;
    for (int f = 0; f < nf_; ++f) {
      const double x1 = x_new_[f];
      xdf_[f] = gain * (x1 - xf_[f]) - xdf_[f];
      xf_[f] = x1;
    }
    std::vector<bool> active(static_cast<std::size_t>(nc_), false);
    for (std::size_t a = 0; a < active_.size(); ++a) {
      const auto i = static_cast<std::size_t>(active_[a].index);
      const double x1 = x_new_[nf_ + static_cast<int>(a)];
      xdc_[i] = gain * (x1 - xc_[i]) - xdc_[i];
      xc_[i] = x1;
      active[i] = true;
      out.force[i][static_cast<std::size_t>(k)] = zc_[i];
      out.compression[i][static_cast<std::size_t>(k)] = x1;
    }
    for (int i = 0; i < nc_; ++i)
      if (!active[static_cast<std::size_t>(i)]) zc_[static_cast<std::size_t>(i)] = 0.0;
    was_active_ = active;
  }

  /// The static equilibrium under the loads at t = 0 (no rate anywhere).
  void static_start(LinearisedHistory& out) {
    gain_ = 0.0;
    set_inverse(/*statics=*/true);
    Eigen::VectorXd fs(ns_), force_on_modes(ns_);
    modal_load(0, fs);
    const Eigen::VectorXd eta_p = inv_d_.cwiseProduct(fs);
    gather_contacts(0);
    // A contact moving along the deflected beam has a rate at rest, and its
    // damper a force, as the model's own static start has: the equilibrium
    // with the dampers at the rates of the last pass (the rates depend on
    // the deflection only through the slope under the contact).
    bool damped = false;
    for (const ActiveContact& c : active_)
      damped = damped || s_.contact_laws[static_cast<std::size_t>(c.index)].damping != 0.0;
    for (int pass = 0; pass < (damped ? kStaticRatePasses : 1); ++pass) {
      solve_step(s_.stiffness, x_.rigid_loads.col(0), eta_p, /*statics=*/true);
      modal_force(force_on_modes);
      eta_ = eta_p - inv_d_.cwiseProduct(force_on_modes);
      y_ = y_new_;
      for (const ActiveContact& c : active_)
        static_rate_[static_cast<std::size_t>(c.index)] = geometric_rate(0, c.index);
    }
    // The contacts' rates at rest come from their motion along the beam.
    for (int f = 0; f < nf_; ++f) xf_[f] = x_new_[f];
    std::vector<bool> active(static_cast<std::size_t>(nc_), false);
    for (std::size_t a = 0; a < active_.size(); ++a) {
      const int i = active_[a].index;
      xc_[static_cast<std::size_t>(i)] = x_new_[nf_ + static_cast<int>(a)];
      active[static_cast<std::size_t>(i)] = true;
      out.force[static_cast<std::size_t>(i)][0] = zc_[static_cast<std::size_t>(i)];
      out.compression[static_cast<std::size_t>(i)][0] = xc_[static_cast<std::size_t>(i)];
    }
    for (std::size_t a = 0; a < active_.size(); ++a) {
      const int i = active_[a].index;
      xdc_[static_cast<std::size_t>(i)] = static_rate_[static_cast<std::size_t>(i)];
    }
    was_active_ = active;
  }

  /// A given state, its element forces and accelerations from the equations of motion.
  void given_start(const LinearisedStart& start, LinearisedHistory& out) {
    if (start.eta.size() != ns_ || start.eta_dot.size() != ns_ || start.y.size() != nr_ || start.y_dot.size() != nr_)
      throw std::invalid_argument("linearised run: the given start does not fit the structure");
    eta_ = start.eta;
    v_ = start.eta_dot;
    y_ = start.y;
    yd_ = start.y_dot;
    for (int j = 0; j < ns_; ++j)
      if (d_.kind[static_cast<std::size_t>(j)] == ModalDynamicsSet::kAbsent) eta_[j] = v_[j] = 0.0;
    gather_contacts(0);
    const Eigen::VectorXd x_f = hf_ * eta_, xd_f = hf_ * v_;
    for (int f = 0; f < nf_; ++f) {
      xf_[f] = off_f_[f] + x_f[f];
      xdf_[f] = xd_f[f];
      zf_[f] = evaluate_law(s_.fixed[static_cast<std::size_t>(f)].law, xf_[f], xdf_[f], 0.0).force;
    }
    std::vector<bool> active(static_cast<std::size_t>(nc_), false);
    for (const ActiveContact& c : active_) {
      const auto i = static_cast<std::size_t>(c.index);
      const ElementLaw& law = s_.contact_laws[i];
      zc_[i] = evaluate_law(law, xc_[i], xdc_[i], 0.0).force;
      active[i] = true;
      out.force[i][0] = zc_[i];
      out.compression[i][0] = xc_[i];
    }
    was_active_ = active;
    Eigen::VectorXd fs(ns_), force_on_modes(ns_);
    modal_load(0, fs);
    modal_force(force_on_modes);
    a_ = Eigen::VectorXd::Zero(ns_);
    for (int j = 0; j < ns_; ++j)
      if (d_.kind[static_cast<std::size_t>(j)] == ModalDynamicsSet::kDynamic)
        a_[j] = (fs[j] - force_on_modes[j] - d_.c[j] * v_[j] - d_.k[j] * eta_[j]) / d_.m[j];
    if (nr_ > 0) {
      Eigen::VectorXd fr = x_.rigid_loads.col(0) - s_.damping * yd_ - s_.stiffness * y_;
      for (const ActiveContact& c : active_) fr -= zc_[static_cast<std::size_t>(c.index)] * c.r;
      ydd_ = s_.mass.partialPivLu().solve(fr);
    }
  }

  const LinearisedStructure& s_;
  const ModalDynamicsSet& d_;
  const LinearisedExcitation& x_;
  const int ns_, nr_, nc_, nf_;
  std::vector<int> block_of_dof_;
  Eigen::MatrixXd hf_;    // nf x ns: each fixed element's Phi^T g_e
  Eigen::MatrixXd g_ff_;  // nf x nf: hf_ D^-1 hf_^T
  LinearisedStepSolve step_solve_;
  Eigen::VectorXd off_f_, constant_modal_, m_, c_, inv_d_;
  double gain_ = 0.0;  // 2 / h (0 in statics)
  // The state.
  Eigen::VectorXd eta_, v_, a_, y_, yd_, ydd_, y_new_, x_new_;
  Eigen::VectorXd xf_, xdf_, zf_;      // fixed elements: elongation, rate, force
  std::vector<double> xc_, xdc_, zc_;  // contacts
  std::vector<double> static_rate_;    // contacts: the rate at rest of the static start (m/s)
  std::vector<bool> was_active_;
  std::vector<ActiveContact> active_;
};

}  // namespace

LinearisedHistory run_linearised(const LinearisedStructure& structure, const ModalDynamicsSet& modes,
                                 const LinearisedExcitation& excitation, const LinearisedStart& start) {
  Runner runner(structure, modes, excitation);
  return runner.run(start);
}

}  // namespace mbfe::runtime
