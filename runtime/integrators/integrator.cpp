#include "runtime/integrators/integrator.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace mbfe::runtime {

namespace {

// Newton on the implicit stage equation g(y) = y - c f(t, y) - r = 0.
// Converged when the correction is below this fraction of |y| (+ the same
// absolute amount): far below any integrator's truncation error.
constexpr double kNewtonTol = 1e-12;
constexpr int kNewtonMaxIterations = 25;

struct NewtonWork {
  Eigen::VectorXd f, g, delta;
  void resize(int n) {
    f.resize(n);
    g.resize(n);
    delta.resize(n);
  }
};

/// Solves y - c f(t, y) = r for y, starting from the y given.
void newton_solve(OdeSystem& sys, bool linear, double t, double c, const Eigen::VectorXd& r,
                  Eigen::VectorXd& y, NewtonWork& w) {
  for (int it = 0; it < kNewtonMaxIterations; ++it) {
    sys.rhs(t, y, w.f);
    w.g = y - c * w.f - r;
    sys.solve_shifted(t, y, c, w.g, w.delta);
    y -= w.delta;
    if (linear) return;  // exact for a linear f: (I - c J) is the whole Jacobian of g
    if (!(w.delta.norm() <= kNewtonTol * (1.0 + y.norm()))) continue;
    return;
  }
  std::ostringstream msg;
  msg << "implicit step at t = " << t << " s: Newton did not converge in " << kNewtonMaxIterations
      << " iterations";
  throw std::runtime_error(msg.str());
}

bool is_linear(OdeSystem& sys) { return dynamic_cast<LinearSecondOrderSystem*>(&sys) != nullptr; }

class ForwardEuler final : public Stepper {
 public:
  explicit ForwardEuler(OdeSystem& sys) : sys_(sys), f_(sys.size()) {}
  void reset(double, const Eigen::VectorXd&) override {}
  void step(double t, double h, Eigen::VectorXd& y) override {
    sys_.rhs(t, y, f_);
    y.noalias() += h * f_;
  }

 private:
  OdeSystem& sys_;
  Eigen::VectorXd f_;
};

class Rk4 final : public Stepper {
 public:
  explicit Rk4(OdeSystem& sys)
      : sys_(sys), k1_(sys.size()), k2_(sys.size()), k3_(sys.size()), k4_(sys.size()), tmp_(sys.size()) {}
  void reset(double, const Eigen::VectorXd&) override {}
  void step(double t, double h, Eigen::VectorXd& y) override {
    sys_.rhs(t, y, k1_);
    tmp_ = y + (0.5 * h) * k1_;
    sys_.rhs(t + 0.5 * h, tmp_, k2_);
    tmp_ = y + (0.5 * h) * k2_;
    sys_.rhs(t + 0.5 * h, tmp_, k3_);
    tmp_ = y + h * k3_;
    sys_.rhs(t + h, tmp_, k4_);
    y += (h / 6.0) * (k1_ + 2.0 * k2_ + 2.0 * k3_ + k4_);
  }

 private:
  OdeSystem& sys_;
  Eigen::VectorXd k1_, k2_, k3_, k4_, tmp_;
};

class BackwardEuler final : public Stepper {
 public:
  explicit BackwardEuler(OdeSystem& sys) : sys_(sys), linear_(is_linear(sys)), r_(sys.size()) {
    w_.resize(sys.size());
  }
  void reset(double, const Eigen::VectorXd&) override {}
  void step(double t, double h, Eigen::VectorXd& y) override {
    r_ = y;
    newton_solve(sys_, linear_, t + h, h, r_, y, w_);
  }

 private:
  OdeSystem& sys_;
  bool linear_;
  Eigen::VectorXd r_;
  NewtonWork w_;
};

class Trapezoid final : public Stepper {
 public:
  explicit Trapezoid(OdeSystem& sys) : sys_(sys), linear_(is_linear(sys)), r_(sys.size()), f_(sys.size()) {
    w_.resize(sys.size());
  }
  void reset(double, const Eigen::VectorXd&) override {}
  void step(double t, double h, Eigen::VectorXd& y) override {
    sys_.rhs(t, y, f_);
    r_ = y + (0.5 * h) * f_;
    newton_solve(sys_, linear_, t + h, 0.5 * h, r_, y, w_);
  }

 private:
  OdeSystem& sys_;
  bool linear_;
  Eigen::VectorXd r_, f_;
  NewtonWork w_;
};

/// y_n = y_{n-2} + 2 h f_{n-1}; the first step is forward Euler.
class ExplicitMidpoint final : public Stepper {
 public:
  explicit ExplicitMidpoint(OdeSystem& sys) : sys_(sys), prev_(sys.size()), f_(sys.size()) {}
  void reset(double, const Eigen::VectorXd&) override { started_ = false; }
  void step(double t, double h, Eigen::VectorXd& y) override {
    sys_.rhs(t, y, f_);
    if (!started_) {
      prev_ = y;
      y.noalias() += h * f_;
      started_ = true;
      return;
    }
    // new = prev + 2 h f; then prev <- old y.
    prev_.noalias() += (2.0 * h) * f_;
    prev_.swap(y);
  }

 private:
  OdeSystem& sys_;
  Eigen::VectorXd prev_, f_;
  bool started_ = false;
};

/// sum alpha_i y_{n+i} = h sum beta_i f_{n+i}, started with k - 1 RK4 steps.
class LinearMultistep final : public Stepper {
 public:
  LinearMultistep(OdeSystem& sys, const LmmCoefficients& c)
      : sys_(sys), c_(c), k_(c.steps()), linear_(is_linear(sys)), starter_(sys), rhs_(sys.size()) {
    ys_.assign(k_, Eigen::VectorXd(sys.size()));
    fs_.assign(k_, Eigen::VectorXd(sys.size()));
    w_.resize(sys.size());
  }
  void reset(double, const Eigen::VectorXd&) override { filled_ = 0; }
  void step(double t, double h, Eigen::VectorXd& y) override {
    // ys_[(head_ + i) % k_] = y_{n+i}, i = 0..k-1 (oldest first).
    if (filled_ < k_) {
      const int slot = filled_;
      ys_[slot] = y;
      sys_.rhs(t, y, fs_[slot]);
      ++filled_;
      head_ = 0;
      if (filled_ < k_) {
        starter_.step(t, h, y);
        return;
      }
    } else {
      // y (the newest value) was produced by the previous call; shift it in.
      ys_[head_] = y;
      sys_.rhs(t, y, fs_[head_]);
      head_ = (head_ + 1) % k_;
    }
    rhs_.setZero();
    for (int i = 0; i < k_; ++i) {
      const int slot = (head_ + i) % k_;
      rhs_ += (h * c_.beta[i]) * fs_[slot] - c_.alpha[i] * ys_[slot];
    }
    const double ak = c_.alpha[k_];
    rhs_ /= ak;
    if (c_.explicit_method()) {
      y = rhs_;
    } else {
      // y currently holds y_{n+k-1}: the predictor.
      newton_solve(sys_, linear_, t + h, h * c_.beta[k_] / ak, rhs_, y, w_);
    }
  }

 private:
  OdeSystem& sys_;
  LmmCoefficients c_;
  int k_;
  bool linear_;
  Rk4 starter_;
  std::vector<Eigen::VectorXd> ys_, fs_;
  Eigen::VectorXd rhs_;
  NewtonWork w_;
  int filled_ = 0;
  int head_ = 0;
};

/// Chung & Hulbert (1993), J. Appl. Mech. 60:371.
class GeneralizedAlpha final : public Stepper {
 public:
  GeneralizedAlpha(LinearSecondOrderSystem& sys, double rho_inf) : sys_(sys), n_(sys.dof()) {
    am_ = (2.0 * rho_inf - 1.0) / (rho_inf + 1.0);
    af_ = rho_inf / (rho_inf + 1.0);
    gamma_ = 0.5 - am_ + af_;
    beta_ = 0.25 * (1.0 - am_ + af_) * (1.0 - am_ + af_);
    for (auto* v : {&a_, &p_, &r_, &tmp_, &mx_, &q_, &v_, &anew_}) v->resize(n_);
  }
  void reset(double t0, const Eigen::VectorXd& y0) override {
    q_ = y0.head(n_);
    v_ = y0.tail(n_);
    sys_.load(t0, p_);
    sys_.mult_c(v_, tmp_);
    r_ = p_ - tmp_;
    sys_.mult_k(q_, tmp_);
    r_ -= tmp_;
    sys_.solve_combination(1.0, 0.0, 0.0, r_, a_);
  }
  void step(double t, double h, Eigen::VectorXd& y) override {
    q_ = y.head(n_);
    v_ = y.tail(n_);
    sys_.load(t + (1.0 - af_) * h, p_);
    // r = P - am M a_n - C[v_n + (1-af) h (1-gamma) a_n] - K[q_n + (1-af)(h v_n + h^2 (1/2 - beta) a_n)]
    r_ = p_;
    sys_.mult_m(a_, mx_);
    r_ -= am_ * mx_;
    tmp_ = v_ + ((1.0 - af_) * h * (1.0 - gamma_)) * a_;
    sys_.mult_c(tmp_, mx_);
    r_ -= mx_;
    tmp_ = q_ + (1.0 - af_) * (h * v_ + (h * h * (0.5 - beta_)) * a_);
    sys_.mult_k(tmp_, mx_);
    r_ -= mx_;
    sys_.solve_combination(1.0 - am_, (1.0 - af_) * gamma_ * h, (1.0 - af_) * beta_ * h * h, r_, anew_);
    y.head(n_) = q_ + h * v_ + (h * h) * ((0.5 - beta_) * a_ + beta_ * anew_);
    y.tail(n_) = v_ + h * ((1.0 - gamma_) * a_ + gamma_ * anew_);
    a_.swap(anew_);
  }

 private:
  LinearSecondOrderSystem& sys_;
  int n_;
  double am_, af_, gamma_, beta_;
  Eigen::VectorXd a_, p_, r_, tmp_, mx_, q_, v_, anew_;
};

struct NamedKind {
  const char* name;
  IntegratorKind kind;
};
constexpr NamedKind kNames[] = {
    {"forward_euler", IntegratorKind::kForwardEuler},
    {"backward_euler", IntegratorKind::kBackwardEuler},
    {"explicit_midpoint", IntegratorKind::kExplicitMidpoint},
    {"trapezoid", IntegratorKind::kTrapezoid},
    {"rk4", IntegratorKind::kRk4},
    {"generalized_alpha", IntegratorKind::kGeneralizedAlpha},
};

std::vector<double> parse_list(const std::string& text, const std::string& what) {
  std::vector<double> out;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    std::size_t used = 0;
    double v = 0.0;
    try {
      v = std::stod(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != item.size() || !std::isfinite(v))
      throw std::invalid_argument("integrator lmm: " + what + " entry '" + item + "' is not a number");
    out.push_back(v);
  }
  return out;
}

void validate(const LmmCoefficients& c) {
  if (c.alpha.size() < 2 || c.alpha.size() != c.beta.size())
    throw std::invalid_argument("integrator lmm: alpha and beta need the same number (k + 1 >= 2) of "
                                "entries, got " +
                                std::to_string(c.alpha.size()) + " and " + std::to_string(c.beta.size()));
  if (c.alpha.back() == 0.0) throw std::invalid_argument("integrator lmm: alpha_k (the last alpha) must not be 0");
}

}  // namespace

int IntegratorSpec::order() const {
  switch (kind) {
    case IntegratorKind::kForwardEuler:
    case IntegratorKind::kBackwardEuler:
      return 1;
    case IntegratorKind::kExplicitMidpoint:
    case IntegratorKind::kTrapezoid:
    case IntegratorKind::kGeneralizedAlpha:
      return 2;
    case IntegratorKind::kRk4:
      return 4;
    case IntegratorKind::kLinearMultistep: {
      // Largest p with C_0 = ... = C_p = 0 (Dahlquist's order conditions).
      int p = -1;
      for (int q = 0; q <= 12; ++q) {
        double cq = 0.0, scale = 0.0;
        for (int i = 0; i <= lmm.steps(); ++i) {
          const double iq = q == 0 ? 1.0 : std::pow(i, q);
          const double iq1 = q == 0 ? 0.0 : q * std::pow(i, q - 1);
          cq += lmm.alpha[i] * iq - lmm.beta[i] * iq1;
          scale += std::abs(lmm.alpha[i] * iq) + std::abs(lmm.beta[i] * iq1);
        }
        if (std::abs(cq) > 1e-10 * (1.0 + scale)) break;
        p = q;
      }
      return p;
    }
  }
  return 0;
}

bool IntegratorSpec::implicit() const {
  switch (kind) {
    case IntegratorKind::kBackwardEuler:
    case IntegratorKind::kTrapezoid:
    case IntegratorKind::kGeneralizedAlpha:
      return true;
    case IntegratorKind::kLinearMultistep:
      return !lmm.explicit_method();
    default:
      return false;
  }
}

std::vector<std::string> integrator_names() {
  std::vector<std::string> out;
  for (const auto& n : kNames) out.emplace_back(n.name);
  out.emplace_back("ab2");
  out.emplace_back("bdf2");
  return out;
}

IntegratorSpec parse_integrator(const std::string& text) {
  IntegratorSpec spec;
  for (const auto& n : kNames) {
    if (text == n.name) {
      spec.kind = n.kind;
      spec.name = n.name;
      return spec;
    }
  }
  spec.kind = IntegratorKind::kLinearMultistep;
  spec.name = text;
  if (text == "ab2") {
    spec.lmm = {{0.0, -1.0, 1.0}, {-0.5, 1.5, 0.0}};
    return spec;
  }
  if (text == "bdf2") {
    spec.lmm = {{0.5, -2.0, 1.5}, {0.0, 0.0, 1.0}};
    return spec;
  }
  if (text.rfind("lmm:", 0) == 0) {
    const auto a = text.find("alpha=");
    const auto b = text.find(":beta=");
    if (a != 4 || b == std::string::npos)
      throw std::invalid_argument("integrator '" + text + "': expected lmm:alpha=a0,...,ak:beta=b0,...,bk");
    spec.lmm.alpha = parse_list(text.substr(10, b - 10), "alpha");
    spec.lmm.beta = parse_list(text.substr(b + 6), "beta");
    validate(spec.lmm);
    return spec;
  }
  std::string names;
  for (const auto& n : integrator_names()) names += (names.empty() ? "" : ", ") + n;
  throw std::invalid_argument("unknown integrator '" + text + "' (expected one of " + names +
                              ", or lmm:alpha=a0,..,ak:beta=b0,..,bk)");
}

std::unique_ptr<Stepper> make_stepper(const IntegratorSpec& spec, OdeSystem& system) {
  switch (spec.kind) {
    case IntegratorKind::kForwardEuler:
      return std::make_unique<ForwardEuler>(system);
    case IntegratorKind::kBackwardEuler:
      return std::make_unique<BackwardEuler>(system);
    case IntegratorKind::kExplicitMidpoint:
      return std::make_unique<ExplicitMidpoint>(system);
    case IntegratorKind::kTrapezoid:
      return std::make_unique<Trapezoid>(system);
    case IntegratorKind::kRk4:
      return std::make_unique<Rk4>(system);
    case IntegratorKind::kLinearMultistep:
      validate(spec.lmm);
      return std::make_unique<LinearMultistep>(system, spec.lmm);
    case IntegratorKind::kGeneralizedAlpha: {
      auto* second = dynamic_cast<LinearSecondOrderSystem*>(&system);
      if (!second)
        throw std::invalid_argument(
            "integrator generalized_alpha needs a linear second-order system (M q'' + C q' + K q = P); "
            "this model is not one");
      if (!(spec.rho_inf >= 0.0 && spec.rho_inf <= 1.0))
        throw std::invalid_argument("generalized_alpha: rho_inf must be in [0, 1]");
      return std::make_unique<GeneralizedAlpha>(*second, spec.rho_inf);
    }
  }
  throw std::invalid_argument("unknown integrator kind");
}

}  // namespace mbfe::runtime

namespace mbfe::runtime {

void LinearSecondOrderSystem::rhs(double t, const Eigen::VectorXd& y, Eigen::VectorXd& ydot) {
  const int n = dof();
  w1_.resize(n);
  load(t, w1_);
  w2_ = y.tail(n);
  mult_c(w2_, w3_);
  w1_ -= w3_;
  w2_ = y.head(n);
  mult_k(w2_, w3_);
  w1_ -= w3_;
  ydot.resize(2 * n);
  ydot.head(n) = y.tail(n);
  solve_combination(1.0, 0.0, 0.0, w1_, w3_);
  ydot.tail(n) = w3_;
}

void LinearSecondOrderSystem::solve_shifted(double, const Eigen::VectorXd&, double c, const Eigen::VectorXd& b,
                                            Eigen::VectorXd& x) {
  const int n = dof();
  w2_ = b.tail(n);
  mult_m(w2_, w1_);
  w2_ = b.head(n);
  mult_k(w2_, w3_);
  w1_ -= c * w3_;
  solve_combination(1.0, c, c * c, w1_, w3_);
  x.resize(2 * n);
  x.tail(n) = w3_;
  x.head(n) = b.head(n) + c * w3_;
}

}  // namespace mbfe::runtime
