#include "runtime/stability/step_limits.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace mbfe::runtime {

namespace {

using cplx = std::complex<double>;

// Root-condition tolerances: a root counts as on the unit circle within
// kCircleTol (companion-matrix eigenvalues of a degree <= 10 polynomial are
// good to ~1e-13 here), and two roots on it as one repeated root within kRepeatTol.
constexpr double kCircleTol = 1e-9;
constexpr double kRepeatTol = 1e-6;
// Boundary-locus sampling of theta in [0, 2 pi) before bisection.
constexpr int kLocusSamples = 8192;
// Every locus passes through z = 0 (rho(1) = 0), and near it a multistep
// method's boundary hugs the imaginary axis (AB2: Re z ~ -|z|^4 / 4), so along
// an imaginary ray rounding makes "crossings" at |z| ~ 1e-5. Crossings closer
// to the origin than this are taken as the origin itself.
constexpr double kOriginTol = 1e-3;
// The last interval, beyond every crossing, is unbounded: it is probed this far
// out (|z|), where a weakly unstable root (AB2 on the imaginary axis) is no
// longer within the root-condition tolerance.
constexpr double kFarProbe = 1e3;

bool root_condition(const LmmCoefficients& c, cplx z) {
  const int k = c.steps();
  std::vector<cplx> poly(k + 1);
  for (int i = 0; i <= k; ++i) poly[i] = c.alpha[i] - z * c.beta[i];
  // Leading coefficient vanishing = a root at infinity: unstable.
  int deg = k;
  while (deg > 0 && std::abs(poly[deg]) <= 1e-14 * (std::abs(c.alpha[k]) + std::abs(z * c.beta[k]))) --deg;
  if (deg < k) return false;
  const auto roots = polynomial_roots(poly);
  for (std::size_t i = 0; i < roots.size(); ++i) {
    const double m = std::abs(roots[i]);
    if (m > 1.0 + kCircleTol) return false;
    if (m > 1.0 - kCircleTol) {
      for (std::size_t j = 0; j < roots.size(); ++j)
        if (j != i && std::abs(roots[j] - roots[i]) < kRepeatTol) return false;
    }
  }
  return true;
}

cplx rk4_r(cplx z) { return 1.0 + z * (1.0 + z * (0.5 + z * (1.0 / 6.0 + z / 24.0))); }

const LmmCoefficients& midpoint_lmm() {
  static const LmmCoefficients c{{-1.0, 0.0, 1.0}, {0.0, 2.0, 0.0}};
  return c;
}

/// Positive s where the ray s * d crosses the stability boundary (candidates).
std::vector<double> crossings(const IntegratorSpec& m, cplx d) {
  std::vector<double> out;
  if (m.kind == IntegratorKind::kForwardEuler) {
    // |1 + s d|^2 = 1  =>  s = -2 Re d.
    if (-2.0 * d.real() > 0.0) out.push_back(-2.0 * d.real());
    return out;
  }
  if (m.kind == IntegratorKind::kRk4) {
    // |R(s d)|^2 - 1 = sum_{j,k} a_j a_k Re(d^j conj(d)^k) s^(j+k) - 1; drop s = 0.
    const double a[5] = {1.0, 1.0, 0.5, 1.0 / 6.0, 1.0 / 24.0};
    std::vector<cplx> p(9, 0.0);
    cplx dj = 1.0;
    for (int j = 0; j <= 4; ++j, dj *= d) {
      cplx dk = 1.0;
      for (int k = 0; k <= 4; ++k, dk *= d) p[j + k] += a[j] * a[k] * (dj * std::conj(dk)).real();
    }
    p[0] -= 1.0;
    std::vector<cplx> q(p.begin() + 1, p.end());  // divided by s
    for (const cplx& r : polynomial_roots(q))
      if (std::abs(r.imag()) <= 1e-8 * std::max(1.0, std::abs(r)) && r.real() > 0.0) out.push_back(r.real());
    return out;
  }
  // Multistep: the boundary locus w(theta) = rho/sigma; crossings where w / d is real positive.
  const LmmCoefficients& c = m.kind == IntegratorKind::kExplicitMidpoint ? midpoint_lmm() : m.lmm;
  auto locus = [&](double th) {
    const cplx e = std::polar(1.0, th);
    cplx rho = 0.0, sigma = 0.0, p = 1.0;
    for (int i = 0; i <= c.steps(); ++i, p *= e) {
      rho += c.alpha[i] * p;
      sigma += c.beta[i] * p;
    }
    return rho / sigma / d;  // s where it crosses, if real
  };
  const double dth = 2.0 * M_PI / kLocusSamples;
  cplx prev = locus(0.0);
  for (int i = 1; i <= kLocusSamples; ++i) {
    const double th = i * dth;
    const cplx cur = locus(th);
    if (std::isfinite(prev.imag()) && std::isfinite(cur.imag()) &&
        ((prev.imag() <= 0.0) != (cur.imag() <= 0.0) || cur.imag() == 0.0)) {
      double lo = th - dth, hi = th;
      double flo = prev.imag();
      for (int it = 0; it < 60; ++it) {
        const double mid = 0.5 * (lo + hi);
        const double fm = locus(mid).imag();
        if ((fm <= 0.0) == (flo <= 0.0)) {
          lo = mid;
          flo = fm;
        } else {
          hi = mid;
        }
      }
      const cplx w = locus(0.5 * (lo + hi));
      if (std::isfinite(w.real()) && w.real() > kOriginTol && std::abs(w.imag()) <= 1e-6 * std::abs(w))
        out.push_back(w.real());
    }
    prev = cur;
  }
  return out;
}

}  // namespace

std::vector<std::complex<double>> polynomial_roots(const std::vector<std::complex<double>>& c) {
  const int n = static_cast<int>(c.size()) - 1;
  if (n < 1) return {};
  Eigen::MatrixXcd comp = Eigen::MatrixXcd::Zero(n, n);
  for (int i = 1; i < n; ++i) comp(i, i - 1) = 1.0;
  for (int i = 0; i < n; ++i) comp(i, n - 1) = -c[i] / c[n];
  Eigen::ComplexEigenSolver<Eigen::MatrixXcd> es(comp, false);
  std::vector<std::complex<double>> out(n);
  for (int i = 0; i < n; ++i) out[i] = es.eigenvalues()[i];
  return out;
}

std::string StepLimit::text() const {
  if (kind == Kind::kUnconditional) return "unconditional";
  if (kind == Kind::kNone) return "none";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.5g", h);
  return buf;
}

bool stable_at(const IntegratorSpec& m, std::complex<double> z) {
  // |R| <= 1 + edge counts as on the boundary. The edge shrinks with |z|^2:
  // near z = 0 every method's |R| - 1 is itself O(|z|^2) (for a lightly damped
  // oscillatory eigenvalue, |1 + z| - 1 ~ Re z + |z|^2 / 2), and a fixed 1e-12
  // would call a growing step stable there.
  const double kEdge = 1e-12 * std::min(1.0, std::max(std::norm(z), 1e-4));
  switch (m.kind) {
    case IntegratorKind::kForwardEuler:
      return std::abs(1.0 + z) <= 1.0 + kEdge;
    case IntegratorKind::kRk4:
      return std::abs(rk4_r(z)) <= 1.0 + kEdge;
    case IntegratorKind::kBackwardEuler:
      return std::abs(1.0 - z) >= 1.0 - kEdge;
    case IntegratorKind::kTrapezoid:
    case IntegratorKind::kGeneralizedAlpha:
      return z.real() <= kEdge;
    case IntegratorKind::kExplicitMidpoint:
      return root_condition(midpoint_lmm(), z);
    case IntegratorKind::kLinearMultistep:
      return root_condition(m.lmm, z);
  }
  return false;
}

StepLimit stable_step(const IntegratorSpec& m, std::complex<double> lambda) {
  StepLimit lim;
  lim.critical = lambda;
  const double mag = std::abs(lambda);
  if (mag == 0.0) return lim;  // a rigid mode constrains nothing
  if (lambda.real() > 0.0) {
    lim.kind = StepLimit::Kind::kNone;
    return lim;
  }
  if (m.kind == IntegratorKind::kBackwardEuler || m.kind == IntegratorKind::kTrapezoid ||
      m.kind == IntegratorKind::kGeneralizedAlpha)
    return lim;  // A-stable, and Re(lambda) <= 0
  const cplx d = lambda / mag;
  auto cand = crossings(m, d);
  std::sort(cand.begin(), cand.end());
  cand.erase(std::unique(cand.begin(), cand.end(),
                         [](double a, double b) { return std::abs(a - b) <= 1e-12 * std::max(a, b); }),
             cand.end());
  // Walk the intervals (0, s1), (s1, s2), ... while they are stable.
  double lo = 0.0;
  for (std::size_t i = 0; i <= cand.size(); ++i) {
    const double hi = i < cand.size() ? cand[i] : std::max(4.0 * lo, kFarProbe);
    const double mid = i < cand.size() ? 0.5 * (lo + hi) : hi;
    if (!stable_at(m, mid * d)) {
      if (lo == 0.0) {
        lim.kind = StepLimit::Kind::kNone;
      } else {
        lim.kind = StepLimit::Kind::kFinite;
        lim.h = lo / mag;
      }
      return lim;
    }
    lo = hi;
  }
  return lim;  // stable beyond the last crossing: unconditional along this ray
}

StepLimit stable_step(const IntegratorSpec& m, const std::vector<std::complex<double>>& spectrum) {
  // Every region here is symmetric about the real axis (real coefficients):
  // one of each conjugate pair, and each distinct value once, is enough.
  std::vector<cplx> distinct;
  distinct.reserve(spectrum.size());
  for (const auto& l : spectrum) distinct.emplace_back(l.real(), std::abs(l.imag()));
  std::sort(distinct.begin(), distinct.end(),
            [](const cplx& a, const cplx& b) { return a.real() != b.real() ? a.real() < b.real() : a.imag() < b.imag(); });
  distinct.erase(std::unique(distinct.begin(), distinct.end()), distinct.end());
  StepLimit out;
  for (const auto& l : distinct) {
    const StepLimit one = stable_step(m, l);
    if (one.kind == StepLimit::Kind::kNone) return one;
    if (one.kind == StepLimit::Kind::kFinite &&
        (out.kind == StepLimit::Kind::kUnconditional || one.h < out.h))
      out = one;
  }
  return out;
}

std::vector<IntegratorSpec> advisor_integrators() {
  std::vector<IntegratorSpec> out;
  for (const char* n : {"forward_euler", "rk4", "explicit_midpoint", "ab2", "backward_euler", "trapezoid", "bdf2",
                        "generalized_alpha"})
    out.push_back(parse_integrator(n));
  return out;
}

}  // namespace mbfe::runtime
