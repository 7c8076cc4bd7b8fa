#include "runtime/integrators/integrator_spec.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace mbfe::runtime {

namespace {

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


}  // namespace

void validate_lmm(const LmmCoefficients& c) {
  if (c.alpha.size() < 2 || c.alpha.size() != c.beta.size())
    throw std::invalid_argument("integrator lmm: alpha and beta need the same number (k + 1 >= 2) of "
                                "entries, got " +
                                std::to_string(c.alpha.size()) + " and " + std::to_string(c.beta.size()));
  if (c.alpha.back() == 0.0) throw std::invalid_argument("integrator lmm: alpha_k (the last alpha) must not be 0");
}

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
    validate_lmm(spec.lmm);
    return spec;
  }
  std::string names;
  for (const auto& n : integrator_names()) names += (names.empty() ? "" : ", ") + n;
  throw std::invalid_argument("unknown integrator '" + text + "' (expected one of " + names +
                              ", or lmm:alpha=a0,..,ak:beta=b0,..,bk)");
}

}  // namespace mbfe::runtime
