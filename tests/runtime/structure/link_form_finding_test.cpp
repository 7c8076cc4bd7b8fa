// Form finding of held links against the closed form of two simply supported
// Euler-Bernoulli beams joined by droppers: a "contact" beam carrying point
// loads F_i at the droppers, held there at h_i, hung from a "messenger" beam.
// With G(x, a) the closed-form deflection at x of a unit load at a, the
// droppers' tensions T solve  G_c (T - F) = h, the messenger sags
// w_m = -G_m T, and each rest offset is  w_m(x_i) - h_i - T_i / k.
// Hermite elements are exact at the nodes for point loads there.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <string>
#include <vector>

#include "ir/model.h"
#include "runtime/damping/beam_model.h"
#include "runtime/errors/invalid_input.h"
#include "runtime/fem/beam_system.h"
#include "runtime/structure/link_form_finding.h"

namespace mbfe::runtime {
namespace {

// Static solutions of 40 DOF per beam with cond(K) ~ 1e6 against closed
// forms evaluated in double: 1e-9 relative is round-off with a margin.
constexpr double kClosedFormTol = 1e-9;

constexpr double kSpan = 10.0;      // m
constexpr int kElements = 20;       // 0.5 m each: the droppers sit on nodes
constexpr double kStiffness = 2e5;  // N/m, each dropper
const std::vector<double> kDropperAt = {2.0, 4.5, 7.0};
const std::vector<double> kLoad = {150.0, 220.0, 180.0};  // N, downward on the contact beam
// m, the contact beam's profile: above its sag without droppers (0.27 to
// 0.46 m) and smooth enough that every dropper pulls (93 to 240 N).
const std::vector<double> kHold = {-0.020, -0.030, -0.025};

ir::Beam simply_supported(const std::string& name, double ei) {
  ir::Beam b;
  b.name = name;
  b.length = kSpan;
  b.elements = kElements;
  b.area = 1e-4;
  b.second_moment = ei / 1e11;
  b.youngs_modulus = 1e11;
  b.density = 8900.0;
  b.supports = {{0.0, ir::SupportType::kPinned, -1, {}}, {kSpan, ir::SupportType::kPinned, -1, {}}};
  return b;
}

constexpr double kContactEi = 2.0e4;    // N m^2
constexpr double kMessengerEi = 5.0e4;  // N m^2

/// Deflection at x of a simply supported beam under a unit load at a.
double influence(double ei, double x, double a) {
  const double L = kSpan;
  if (x > a) return influence(ei, L - x, L - a);
  const double b = L - a;
  return b * x * (L * L - b * b - x * x) / (6.0 * ei * L);
}

Eigen::MatrixXd flexibility(double ei) {
  const int n = static_cast<int>(kDropperAt.size());
  Eigen::MatrixXd G(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) G(i, j) = influence(ei, kDropperAt[i], kDropperAt[j]);
  return G;
}

ir::Model two_beams_and_droppers(bool slack) {
  ir::Model m;
  m.source_path = "droppers.yaml";
  m.gravity = {0.0, 0.0};  // loads only at the nodes: the closed form stays a sum of point loads
  ir::Beam contact = simply_supported("contact", kContactEi);
  for (std::size_t i = 0; i < kDropperAt.size(); ++i)
    contact.loads.push_back({kDropperAt[i], ir::Expression::number(-kLoad[i]), -1, {}, {}, ""});
  m.beams = {contact, simply_supported("messenger", kMessengerEi)};
  for (std::size_t i = 0; i < kDropperAt.size(); ++i) {
    ir::Link l;
    l.name = "dropper" + std::to_string(i);
    l.a = {0, kDropperAt[i]};
    l.b = {1, kDropperAt[i]};
    l.stiffness = kStiffness;
    l.slack = slack;
    l.hold = kHold[i];
    m.links.push_back(l);
  }
  return m;
}

TEST(LinkFormFinding, DroppersHoldTheContactBeamAsTheClosedFormSays) {
  const ir::Model model = two_beams_and_droppers(true);
  const BeamModel beams = analyse_beams(model);
  const LinkFormFinding ff = find_link_rest_offsets(model, beams);

  const int n = static_cast<int>(kDropperAt.size());
  const Eigen::VectorXd F = Eigen::Map<const Eigen::VectorXd>(kLoad.data(), n);
  const Eigen::VectorXd h = Eigen::Map<const Eigen::VectorXd>(kHold.data(), n);
  const Eigen::VectorXd T = F + flexibility(kContactEi).partialPivLu().solve(h);
  const Eigen::VectorXd w_m = -flexibility(kMessengerEi) * T;

  const BeamPart& contact = beams.beams[0];
  const BeamPart& messenger = beams.beams[1];
  const Eigen::VectorXd u_c = ff.deflection.segment(contact.offset, contact.system.K.rows());
  const Eigen::VectorXd u_m = ff.deflection.segment(messenger.offset, messenger.system.K.rows());
  for (int i = 0; i < n; ++i) {
    SCOPED_TRACE("dropper " + std::to_string(i));
    EXPECT_NEAR(deflection_at(contact.system, u_c, kDropperAt[i]), h[i], kClosedFormTol * h.cwiseAbs().maxCoeff());
    EXPECT_NEAR(ff.tension[i], T[i], kClosedFormTol * T.maxCoeff());
    EXPECT_NEAR(ff.rest[i], w_m[i] - h[i] - T[i] / kStiffness, kClosedFormTol * w_m.cwiseAbs().maxCoeff());
  }
  // Anywhere along the messenger (its nodes; the cubic is exact between them too).
  for (double x : {0.5, 3.0, 5.5, 9.0, 9.5}) {
    double expected = 0.0;
    for (int j = 0; j < n; ++j) expected -= influence(kMessengerEi, x, kDropperAt[j]) * T[j];
    EXPECT_NEAR(deflection_at(messenger.system, u_m, x), expected, kClosedFormTol * w_m.cwiseAbs().maxCoeff())
        << "x = " << x;
  }
}

TEST(LinkFormFinding, LinksWithoutHoldKeepTheirRestOffset) {
  ir::Model model = two_beams_and_droppers(false);
  model.links[1].hold.reset();
  model.links[1].rest = -0.02;
  const BeamModel beams = analyse_beams(model);
  const LinkFormFinding ff = find_link_rest_offsets(model, beams);
  EXPECT_EQ(ff.rest[1], -0.02);
  // The held ones still sit at their hold, whatever the free one does.
  const BeamPart& contact = beams.beams[0];
  const Eigen::VectorXd u_c = ff.deflection.segment(contact.offset, contact.system.K.rows());
  for (int i : {0, 2})
    EXPECT_NEAR(deflection_at(contact.system, u_c, kDropperAt[i]), kHold[i], kClosedFormTol * 0.03);
}

TEST(LinkFormFinding, SlackDropperThatWouldPushIsRefused) {
  // Holding the contact beam 2 m down needs the droppers to push it there.
  ir::Model model = two_beams_and_droppers(true);
  model.links[1].hold = -2.0;
  const BeamModel beams = analyse_beams(model);
  try {
    find_link_rest_offsets(model, beams);
    FAIL() << "a slack dropper in compression was accepted";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("dropper1"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("push"), std::string::npos) << e.what();
  }
  // The same dropper as a spring (not slack) may push.
  model.links[1].slack = false;
  EXPECT_NO_THROW(find_link_rest_offsets(model, beams));
}


// Two tensioned wires under their own weight, the lower held at 0 at three
// droppers: given the droppers' tensions, the upper wire (a string: bending
// stiffness EI = 1 N m^2 against 15 kN, a boundary layer of sqrt(EI / H) =
// 8 mm at each kink) sags as the closed form of a string, the parabola of its
// weight plus the polygon of the droppers' pulls:
//   w(x) = -(q x (L - x) / 2 + sum_j T_j G(x, x_j)) / H,  G(x, a) = x (L - a) / L (x <= a).
// C1 Hermite elements round each dropper's kink over the elements beside
// it: the nodal error is first order in the element length (measured 3.4e-3
// of the wire's own midspan sag at 0.25 m, half that at 0.125 m). A dropper's
// pull moves the wire by ~0.6 of that sag: a tension 2 % off misses by more.
constexpr double kStringSagTol = 1e-2;
constexpr double kMessengerTension = 15000.0;  // N
constexpr double kContactTension = 20000.0;    // N

ir::Beam wire(const std::string& name, double tension) {
  ir::Beam b = simply_supported(name, 1.0);  // EI = 1 N m^2
  b.elements = 40;                           // 0.25 m: the droppers sit on nodes
  b.area = 1.2e-4;
  b.density = 8900.0;                        // 1.07 kg/m
  b.tension = tension;
  return b;
}

double string_influence(double x, double a) {
  return x <= a ? x * (kSpan - a) / kSpan : a * (kSpan - x) / kSpan;
}

TEST(LinkFormFinding, TensionedMessengerSagsAsAStringUnderItsDroppers) {
  ir::Model m;
  m.source_path = "wires.yaml";
  m.gravity = {0.0, -9.81};
  m.beams = {wire("contact", kContactTension), wire("messenger", kMessengerTension)};
  for (std::size_t i = 0; i < kDropperAt.size(); ++i) {
    ir::Link l;
    l.name = "dropper" + std::to_string(i);
    l.a = {0, kDropperAt[i]};
    l.b = {1, kDropperAt[i]};
    l.stiffness = kStiffness;
    l.slack = true;
    l.hold = 0.0;
    m.links.push_back(l);
  }
  const BeamModel beams = analyse_beams(m);
  const LinkFormFinding ff = find_link_rest_offsets(m, beams);
  const BeamPart& messenger = beams.beams[1];
  const Eigen::VectorXd u_m = ff.deflection.segment(messenger.offset, messenger.system.K.rows());
  const double q = 1.2e-4 * 8900.0 * 9.81;  // N/m
  const double mid_sag = q * kSpan * kSpan / (8.0 * kMessengerTension);
  double worst = 0.0;
  for (int k = 1; k < 40; ++k) {
    const double x = 0.25 * k;
    double expected = q * x * (kSpan - x) / 2.0;
    for (std::size_t j = 0; j < kDropperAt.size(); ++j) expected += ff.tension[j] * string_influence(x, kDropperAt[j]);
    expected /= -kMessengerTension;
    worst = std::max(worst, std::abs(deflection_at(messenger.system, u_m, x) - expected));
  }
  EXPECT_LT(worst, kStringSagTol * mid_sag);
  for (double t : ff.tension) EXPECT_GT(t, 0.0);
}

}  // namespace
}  // namespace mbfe::runtime
