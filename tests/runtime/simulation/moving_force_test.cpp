// A constant force crossing a simply supported beam: the finite-element run
// (moving load through the shape functions, modal integration) against the
// closed-form modal series of the continuous Euler-Bernoulli beam.
//
// Series: w(x, t) = sum_j q_j(t) sin(j pi x / L) with modal mass mu L / 2, so
//   q_j'' + 2 zeta_j w_j q_j' + w_j^2 q_j = (2 P / (mu L)) sin(Omega_j t),  0 <= t <= L / v,
// Omega_j = j pi v / L, from rest; free vibration after the force has left.
// The speed parameter alpha = v / (2 L f1) sets the dynamic amplification
// factor DAF = max_t w(L/2, t) / (P L^3 / 48 EI).
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <string>
#include <vector>

#include "api/mbfe.h"

namespace mbfe {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kLength = 20.0, kArea = 0.01, kInertia = 1e-4, kYoung = 2.1e11, kDensity = 7850.0;
constexpr double kForce = 9810.0;
// 40 elements represent the modes that carry the midspan response (j <= 5)
// to ~1e-7 in frequency; a step of 1/2000 of the first period keeps the
// trapezoid rule's phase error below 1e-5. What is left is the series'
// truncation (60 terms: below 1e-7) and the sampling of the maximum.
constexpr double kDafTolerance = 0.005;  // the required 0.5 %
constexpr double kHistoryTolerance = 0.005;  // of the static deflection, at every step
constexpr int kSeriesTerms = 60;

double mu() { return kDensity * kArea; }
double omega(int j) { return std::pow(j * kPi / kLength, 2) * std::sqrt(kYoung * kInertia / mu()); }
double static_deflection() { return kForce * std::pow(kLength, 3) / (48.0 * kYoung * kInertia); }

/// Closed-form midspan deflection (positive down) at t for speed v and Rayleigh
/// alpha, beta, and (when asked) its acceleration from each mode's equation,
/// q_j'' = force_j(t) - 2 zeta_j w_j q_j' - w_j^2 q_j. The free part is
/// a e^(r1 s) + b e^(r2 s) with the complex roots
/// r = -zeta w +- i w sqrt(1 - zeta^2), so that overdamped high modes
/// (zeta > 1) need no other formula and nothing overflows.
double series_midspan(double t, double v, double ra, double rb, double* acceleration = nullptr) {
  using C = std::complex<double>;
  const double T = kLength / v;
  double w = 0.0, a = 0.0;
  for (int j = 1; j <= kSeriesTerms; j += 2) {  // even modes have a node at midspan
    const double wj = omega(j), zeta = ra / (2.0 * wj) + rb * wj / 2.0;
    const C root = C(0.0, 1.0) * wj * std::sqrt(C(1.0 - zeta * zeta));
    const C r1 = -zeta * wj + root, r2 = -zeta * wj - root;
    // Free motion from (q0, v0) after time s (needs r1 != r2: zeta != 1, true here).
    auto free_motion = [&](double q0, double v0, double s, double& q, double& qd) {
      const C a = (v0 - r2 * q0) / (r1 - r2), b = q0 - a;
      q = (a * std::exp(r1 * s) + b * std::exp(r2 * s)).real();
      qd = (a * r1 * std::exp(r1 * s) + b * r2 * std::exp(r2 * s)).real();
    };
    const double Om = j * kPi * v / kLength;
    const double F = 2.0 * kForce / (mu() * kLength);
    const double D = std::pow(wj * wj - Om * Om, 2) + std::pow(2.0 * zeta * wj * Om, 2);
    auto forced = [&](double s, double& q, double& qd) {
      if (D < 1e-12 * std::pow(wj, 4)) {  // undamped resonance, Omega = omega
        q = F / (2.0 * wj * wj) * (std::sin(wj * s) - wj * s * std::cos(wj * s));
        qd = F / 2.0 * s * std::sin(wj * s);
        return;
      }
      // Particular solution A sin + B cos, plus the free motion that starts it from rest.
      const double A = F * (wj * wj - Om * Om) / D, B = -F * 2.0 * zeta * wj * Om / D;
      double qh = 0.0, qhd = 0.0;
      free_motion(-B, -A * Om, s, qh, qhd);
      q = A * std::sin(Om * s) + B * std::cos(Om * s) + qh;
      qd = A * Om * std::cos(Om * s) - B * Om * std::sin(Om * s) + qhd;
    };
    double q = 0.0, qd = 0.0;
    if (t <= T) {
      forced(t, q, qd);
    } else {
      double q0 = 0.0, v0 = 0.0;
      forced(T, q0, v0);
      free_motion(q0, v0, t - T, q, qd);
    }
    w += q * std::sin(j * kPi / 2.0);
    const double load = t <= T ? F * std::sin(Om * t) : 0.0;
    a += (load - 2.0 * zeta * wj * qd - wj * wj * q) * std::sin(j * kPi / 2.0);
  }
  if (acceleration) *acceleration = a;
  return w;
}

std::string bridge(double v, double ra, double rb) {
  return "model: moving_force_check\n"
         "beams:\n"
         "  - name: deck\n    origin: [0, 0]\n"
         "    length: 20.0\n"
         "    elements: 40\n"
         "    section: {area: 0.01, inertia: 1.0e-4}\n"
         "    material: {youngs_modulus: 2.1e11, density: 7850}\n"
         "    supports: [{at: 0.0, type: pinned}, {at: 20.0, type: pinned}]\n"
         "    damping: {rayleigh: {alpha: " + std::to_string(ra) + ", beta: " + std::to_string(rb) + "}}\n"
         "    loads:\n"
         "      - {type: moving, value: \"-9810\", speed: " + std::to_string(v) + "}\n";
}

class Midspan : public runtime::SimulationObserver {
 public:
  void row(const runtime::OutputRow& row) override {
    t.push_back(row.t);
    w.push_back(-row.values[1]);  // positive down
  }
  std::vector<double> t, w;
};

struct Case {
  double alpha, ra, rb;
};

class MovingForce : public ::testing::TestWithParam<Case> {};

TEST_P(MovingForce, MidspanHistoryAndDafMatchTheSeries) {
  const Case c = GetParam();
  const double f1 = omega(1) / (2.0 * kPi);
  const double v = c.alpha * 2.0 * kLength * f1;
  const Model model = Model::parse(bridge(v, c.ra, c.rb), "moving_force_check.yaml");
  runtime::SimulationRequest request;
  request.integrator = runtime::parse_integrator("trapezoid");
  request.step = 1.0 / (2000.0 * f1);
  request.t_end = kLength / v + 1.0 / f1;  // the crossing and one free period
  request.every = 1;
  request.probes = {runtime::parse_probe("deck@10")};
  Midspan mid;
  const runtime::SimulationReport report = model.simulate(request, mid);
  ASSERT_TRUE(report.message.empty()) << report.message;
  double fe_max = 0.0, series_max = 0.0, worst = 0.0;
  for (std::size_t i = 0; i < mid.t.size(); ++i) {
    const double s = series_midspan(mid.t[i], v, c.ra, c.rb);
    fe_max = std::max(fe_max, mid.w[i]);
    series_max = std::max(series_max, s);
    worst = std::max(worst, std::abs(mid.w[i] - s));
  }
  const double daf_fe = fe_max / static_deflection(), daf_series = series_max / static_deflection();
  EXPECT_NEAR(daf_fe / daf_series, 1.0, kDafTolerance) << "alpha " << c.alpha << ": DAF " << daf_fe
                                                        << " vs series " << daf_series;
  EXPECT_LT(worst / static_deflection(), kHistoryTolerance) << "alpha " << c.alpha;
}

INSTANTIATE_TEST_SUITE_P(SpeedParameters, MovingForce,
                         ::testing::Values(Case{0.1, 0, 0}, Case{0.2, 0, 0}, Case{0.3, 0, 0}, Case{0.4, 0, 0},
                                           Case{0.5, 0, 0}, Case{0.6, 0, 0}, Case{0.7, 0, 0}, Case{0.8, 0, 0},
                                           Case{0.9, 0, 0}, Case{1.0, 0, 0},
                                           // Rayleigh damping: zeta_1 = 2.2 %, growing with the mode.
                                           Case{0.25, 0.2, 1e-3}, Case{0.5, 0.2, 1e-3}, Case{1.0, 0.2, 1e-3}));

/// The midspan acceleration (probe deck@10:acc, m/s^2) against the same
/// series, with Rayleigh damping so that the modes the 40 elements get wrong
/// (j > 10 or so, the acceleration's slowly converging tail) are damped out.
TEST(MovingForce, MidspanAccelerationMatchesTheSeries) {
  const double f1 = omega(1) / (2.0 * kPi);
  const double v = 0.5 * 2.0 * kLength * f1;
  const Model model = Model::parse(bridge(v, 0.2, 1e-3), "moving_force_check.yaml");
  runtime::SimulationRequest request;
  request.integrator = runtime::parse_integrator("trapezoid");
  request.step = 1.0 / (2000.0 * f1);
  request.t_end = kLength / v + 1.0 / f1;
  request.every = 1;
  request.probes = {runtime::parse_probe("deck@10:acc"), runtime::parse_probe("deck@10")};
  Midspan mid;  // w holds minus the first probe: the acceleration, positive down
  const runtime::SimulationReport report = model.simulate(request, mid);
  ASSERT_TRUE(report.message.empty()) << report.message;
  double peak_fe = 0.0, peak_series = 0.0, worst = 0.0;
  for (std::size_t i = 0; i < mid.t.size(); ++i) {
    double a = 0.0;
    series_midspan(mid.t[i], v, 0.2, 1e-3, &a);
    peak_fe = std::max(peak_fe, std::abs(mid.w[i]));
    peak_series = std::max(peak_series, std::abs(a));
    worst = std::max(worst, std::abs(mid.w[i] - a));
  }
  // The peak is about 1 m/s^2; the elements' frequency error in the damped
  // modes 3..9 and the trapezoid rule's phase error leave about 1 %.
  constexpr double kAccelerationTolerance = 0.03;  // of the peak, at every step
  EXPECT_GT(peak_series, 0.1);
  EXPECT_NEAR(peak_fe / peak_series, 1.0, kAccelerationTolerance);
  EXPECT_LT(worst / peak_series, kAccelerationTolerance);
}

/// Before the load enters, the beam sees nothing (a beam at rest stays
/// exactly at rest); once it is on, the midspan moves.
TEST(MovingForce, NothingBeforeEntry) {
  const Model model = Model::parse(
      "model: late_entry\nbeams:\n  - name: deck\n    origin: [0, 0]\n    length: 20.0\n    elements: 40\n"
      "    section: {area: 0.01, inertia: 1.0e-4}\n    material: {youngs_modulus: 2.1e11, density: 7850}\n"
      "    supports: [{at: 0.0, type: pinned}, {at: 20.0, type: pinned}]\n"
      "    loads: [{type: moving, value: -9810, speed: 20.0, start: -10.0}]\n",  // enters at t = 0.5 s
      "late_entry.yaml");
  runtime::SimulationRequest request;
  request.integrator = runtime::parse_integrator("trapezoid");
  request.step = 1e-3;
  request.t_end = 0.6;
  request.every = 1;
  request.probes = {runtime::parse_probe("deck@10")};
  Midspan mid;
  ASSERT_TRUE(model.simulate(request, mid).message.empty());
  double moved = 0.0;
  for (std::size_t i = 0; i < mid.t.size(); ++i) {
    if (mid.t[i] < 0.5 - 1e-9) EXPECT_EQ(mid.w[i], 0.0) << "t = " << mid.t[i];
    else moved = std::max(moved, std::abs(mid.w[i]));
  }
  EXPECT_GT(moved, 1e-3 * static_deflection());
}

}  // namespace
}  // namespace mbfe
