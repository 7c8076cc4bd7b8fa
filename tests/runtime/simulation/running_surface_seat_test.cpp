// Seating compression-only slider_spring contacts on their beam's running
// surface before the static start (seat_on_running_surfaces), on a bogie
// written here as ABI kernels: a carriage at x carrying two wheels on
// vertical prismatic joints, at x - 1 m (height y1) and x + 1 m (height y2),
// over an undeformed straight rail whose profile r(s) is constant, linear or
// a sine. Oracle: there the penetration is r(s) - y (side() * that pressed
// from below), so the seat position is r(s) -+ the seat depth for a wheel
// that moves vertically, and the minimum-norm step of a linear profile is the
// closed form of the 1 x 2 or 2 x 3 least-norm problem, written out by hand.
#include "runtime/simulation/running_surface_seat.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <array>
#include <cmath>
#include <memory>
#include <vector>

#include "ir/expression.h"
#include "ir/model.h"
#include "runtime/abi/mbfe_model_abi.h"
#include "runtime/coupled/coupled_dynamics.h"
#include "runtime/coupled/coupled_model.h"
#include "runtime/fem/running_surface.h"
#include "tests/runtime/coupled/test_beam.h"

namespace mbfe::runtime {
namespace {

// How deep the unit seats a contact (its documented 1e-5 m).
constexpr double kSeatDepth = 1e-5;
// The central-difference step relative to a coordinate's size.
constexpr double kRelativeStep = 1e-6;
// A linear profile makes the penetration linear in q: the differences are
// exact but for round-off of mm-size penetrations over a 4e-6 m step (1e-13
// of the slope), the seat exact to that times a mm-size step.
constexpr double kSeatTol = 1e-12;  // m

// A wheel to be seated presses the rail's axis (its smooth line) by this:
// clear of round-off at the axis, far from its running surface (mm).
constexpr double kIntoAxis = 1e-4;    // m
constexpr double kHalfBase = 1.0;     // m, wheel to carriage
constexpr double kRailLength = 10.0;  // m
constexpr int kRailElements = 10;
constexpr double kEI = 1.0e7, kRhoA = 60.0;  // N m^2, kg/m
constexpr double kG = 9.81;

// --- The bogie's kernels. q_b = (x, y1, y2); wheel k (0 at x - 1, 1 at x + 1).

// Hermite cubic on an element of length le at xi in [0, 1], and d/ds of it.
std::array<double, 4> shape(double xi, double le) {
  const double x2 = xi * xi, x3 = x2 * xi;
  return {1 - 3 * x2 + 2 * x3, le * (xi - 2 * x2 + x3), 3 * x2 - 2 * x3, le * (x3 - x2)};
}
std::array<double, 4> shape_slope(double xi, double le) {
  const double x2 = xi * xi;
  return {(6 * x2 - 6 * xi) / le, 1 - 4 * xi + 3 * x2, (6 * xi - 6 * x2) / le, 3 * x2 - 2 * xi};
}
double dot4(const std::array<double, 4>& a, const double* b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3];
}

template <int Wheel>
double wheel_s(const double* q) {
  return q[0] + (Wheel == 0 ? -kHalfBase : kHalfBase);
}
// Phi = w(s) - y_wheel (the runtime turns the sign for a contact pressed from below).
template <int Wheel>
void wheel_phi(const double* q, const double* qe, double s0, double le, double* phi) {
  phi[0] = dot4(shape((wheel_s<Wheel>(q) - s0) / le, le), qe) - q[1 + Wheel];
}
template <int Wheel>
void wheel_jacobians(const double* q, const double* qe, double s0, double le, double* jb, double* je) {
  const double xi = (wheel_s<Wheel>(q) - s0) / le;
  jb[0] = dot4(shape_slope(xi, le), qe);
  jb[1] = Wheel == 0 ? -1.0 : 0.0;
  jb[2] = Wheel == 1 ? -1.0 : 0.0;
  const std::array<double, 4> n = shape(xi, le);
  for (int j = 0; j < 4; ++j) je[j] = n[j];
}
// A slider_spring is a force, not a constraint row: the runtime asks for no gamma.
void no_gamma(const double*, const double*, const double*, const double*, double, double, double* gamma) {
  gamma[0] = 0.0;
}
void bogie_mass(const double*, double* M) {
  Eigen::Map<Eigen::Matrix3d>{M} = Eigen::Vector3d(500.0, 100.0, 100.0).asDiagonal().toDenseMatrix();
}
void bogie_inertial(const double*, const double*, double* F) { Eigen::Map<Eigen::Vector3d>(F).setZero(); }
void bogie_forces(const double*, const double*, double, double* Q) {
  Eigen::Map<Eigen::Vector3d>{Q} = Eigen::Vector3d(0.0, -100.0 * kG, -100.0 * kG);
}
const char* const kBogieNames[] = {"carriage", "front", "rear"};

struct ContactSetup {
  bool unilateral = true;
  bool hertz = false;
  bool from_below = false;
};

template <int Wheel>
mbfe_contact_kernels_v1 wheel_kernels(const char* name, const ContactSetup& setup) {
  mbfe_contact_kernels_v1 k{};
  k.name = name;
  k.type = 2;  // slider_spring
  k.beam = 0;
  k.rows = 1;
  k.position = wheel_s<Wheel>;
  k.phi = wheel_phi<Wheel>;
  k.jacobians = wheel_jacobians<Wheel>;
  k.gamma = no_gamma;
  k.stiffness = 1.0e7;  // N/m
  k.unilateral = setup.unilateral;
  k.from_below = setup.from_below;
  return k;
}
const ContactSetup kBilateral{false, false, false};

/// The bogie on its rail: kernels, IR contacts and dynamics. Holds what the
/// coupled model refers to: make it in place, do not copy it.
class Bogie {
 public:
  Bogie(const ir::BeamProfile& profile, ContactSetup front, ContactSetup rear) {
    const ContactSetup setups[2] = {front, rear};
    contacts_[0] = wheel_kernels<0>("front_wheel", front);
    contacts_[1] = wheel_kernels<1>("rear_wheel", rear);
    kernels_.abi_version = MBFE_MODEL_ABI_VERSION;
    kernels_.model_name = "bogie";
    kernels_.num_coordinates = 3;
    kernels_.coordinate_names = kBogieNames;
    kernels_.mass_matrix = bogie_mass;
    kernels_.inertial_forces = bogie_inertial;
    kernels_.generalized_forces = bogie_forces;
    kernels_.num_contacts = 2;
    kernels_.contacts = contacts_.data();
    for (int k = 0; k < 2; ++k) {
      ir::Contact c;
      c.name = contacts_[k].name;
      c.type = ir::ContactType::kSliderSpring;
      c.body = 1 + k;
      c.point = 0;
      c.beam = 0;
      c.unilateral = setups[k].unilateral;
      c.from_below = setups[k].from_below;
      c.law = setups[k].hertz ? ir::ContactLaw::kHertz : ir::ContactLaw::kLinear;
      c.coefficient = setups[k].hertz ? 1.0e10 : 0.0;
      c.stiffness = setups[k].hertz ? 0.0 : 1.0e7;
      ir_.contacts.push_back(c);
    }
    testing::TestBeam rail = testing::pinned_pinned_beam("rail", kRailLength, kRailElements, kEI, kRhoA, 0.0, 0.0, 0.0);
    rail.beam.mesh.surface =
        std::make_shared<const RunningSurface>(profile, kRailLength, kRailElements, Eigen::VectorXd());
    CoupledBeams beams;
    beams.beams.push_back(rail.beam);
    dyn_ = std::make_unique<CoupledDynamics>(
        std::make_shared<const CoupledModel>(kernels_, std::move(beams), std::vector<BodyInertia>{},
                                             std::vector<ir::Link>{}, std::vector<double>{}, ir_.contacts));
  }
  Bogie(const Bogie&) = delete;
  Bogie& operator=(const Bogie&) = delete;

  int n() const { return dyn_->n(); }
  /// (x, y1, y2) with the rail undeformed.
  Eigen::VectorXd state(double x, double y1, double y2) const {
    Eigen::VectorXd q = Eigen::VectorXd::Zero(n());
    q.head<3>() << x, y1, y2;
    return q;
  }
  /// seat_on_running_surfaces at rest, `unknown` the coordinates it may move.
  void seat(Eigen::VectorXd& q, const std::vector<int>& unknown) {
    seat_on_running_surfaces(ir_, *dyn_, unknown, kRelativeStep, q, Eigen::VectorXd::Zero(n()));
  }
  std::vector<int> every_coordinate() const {
    std::vector<int> all(static_cast<std::size_t>(n()));
    for (int i = 0; i < n(); ++i) all[static_cast<std::size_t>(i)] = i;
    return all;
  }

 private:
  std::array<mbfe_contact_kernels_v1, 2> contacts_{};
  mbfe_model_v1 kernels_{};
  ir::Model ir_;
  std::unique_ptr<CoupledDynamics> dyn_;
};

// r(s) = r0 + slope s: a table of two rows over the rail (linear between).
ir::BeamProfile linear_profile(double r0, double slope) {
  ir::BeamProfile p;
  p.kind = ir::ProfileKind::kTable;
  p.table_s = {0.0, kRailLength};
  p.table_offset = {r0, r0 + slope * kRailLength};
  return p;
}

// r(s) = mean + amplitude sin(wavenumber s), as the expression the parser
// would build (postfix; the tree's variable is t, read as s).
ir::BeamProfile sine_profile(double mean, double amplitude, double wavenumber) {
  using Kind = ir::ExpressionNode::Kind;
  const auto node = [](Kind kind, double value = 0.0) {
    ir::ExpressionNode n;
    n.kind = kind;
    n.value = value;
    return n;
  };
  ir::ExpressionNode sine = node(Kind::kCall);
  sine.function = ir::Function::kSin;
  ir::BeamProfile p;
  p.kind = ir::ProfileKind::kExpression;
  p.expression =
      ir::Expression({node(Kind::kNumber, mean), node(Kind::kNumber, amplitude), node(Kind::kNumber, wavenumber),
                      node(Kind::kTime), node(Kind::kMultiply), sine, node(Kind::kMultiply), node(Kind::kAdd)});
  return p;
}

void expect_unchanged(const Eigen::VectorXd& q, const Eigen::VectorXd& q0) {
  for (Eigen::Index i = 0; i < q.size(); ++i) EXPECT_EQ(q[i], q0[i]) << "coordinate " << i;
}

TEST(RunningSurfaceSeat, AWheelOnAConstantOffsetSinksToItsSeatDepth) {
  // The rail's surface 2 mm below its axis; the front wheel presses the
  // smooth line but not the rail; the rear wheel is in the air.
  const double r = -2e-3;
  Bogie bogie(linear_profile(r, 0.0), {}, {});
  const Eigen::VectorXd q0 = bogie.state(4.0, -kIntoAxis, 0.05);
  Eigen::VectorXd q = q0;
  bogie.seat(q, {1});
  EXPECT_NEAR(q[1], r - kSeatDepth, kSeatTol);
  q[1] = q0[1];
  expect_unchanged(q, q0);
}

TEST(RunningSurfaceSeat, OnASlopeTheLeastChangeMovesAlongTheSurfaceNormal) {
  // r(s) = r0 + b s; the front wheel alone is compression-only (the rear one
  // bilateral, which is never seated nor kept). Unknowns x and y1: the
  // penetration r0 + b (x - 1) - y1 changes by b dx - dy1, and the least
  // (dx, dy1) that changes it by c is (b, -1) c / (1 + b^2).
  const double r0 = -0.02, b = 0.005;
  Bogie bogie(linear_profile(r0, b), {}, kBilateral);
  const double x = 4.0, y1 = -kIntoAxis;
  const Eigen::VectorXd q0 = bogie.state(x, y1, 0.05);
  Eigen::VectorXd q = q0;
  bogie.seat(q, {0, 1, 2});
  const double c = kSeatDepth - (r0 + b * (x - kHalfBase) - y1);
  EXPECT_NEAR(q[0], x + b * c / (1 + b * b), kSeatTol);
  EXPECT_NEAR(q[1], y1 - c / (1 + b * b), kSeatTol);
  EXPECT_NEAR(r0 + b * (q[0] - kHalfBase) - q[1], kSeatDepth, kSeatTol);
  for (int i = 2; i < q.size(); ++i) EXPECT_EQ(q[i], q0[i]) << "coordinate " << i;
}

TEST(RunningSurfaceSeat, AContactAlreadyPressingKeepsItsPenetration) {
  // Both wheels compression-only; the rear one presses the rail (5 mm), the
  // front one presses the axis, 5 mm above the rail. Rows (b, -1, 0) and (b, 0, -1)
  // over (x, y1, y2), changes (c, 0): the least step J^T (J J^T)^-1 (c, 0) is
  // (b, -(1 + b^2), b^2) c / (1 + 2 b^2). Every coordinate is an unknown: the
  // rail's are not moved (only the rigid ones are).
  const double r0 = -0.02, b = 0.005, x = 4.0, y1 = -kIntoAxis;
  Bogie bogie(linear_profile(r0, b), {}, {});
  const Eigen::VectorXd q0 = bogie.state(x, y1, 0.0);
  const double rear_before = r0 + b * (x + kHalfBase) - 0.0;
  ASSERT_GT(rear_before, 0.0);
  Eigen::VectorXd q = q0;
  bogie.seat(q, bogie.every_coordinate());
  const double c = kSeatDepth - (r0 + b * (x - kHalfBase) - y1);
  const double det = 1 + 2 * b * b;
  EXPECT_NEAR(q[0], x + b * c / det, kSeatTol);
  EXPECT_NEAR(q[1], y1 - (1 + b * b) * c / det, kSeatTol);
  EXPECT_NEAR(q[2], b * b * c / det, kSeatTol);
  EXPECT_NEAR(r0 + b * (q[0] - kHalfBase) - q[1], kSeatDepth, kSeatTol);
  EXPECT_NEAR(r0 + b * (q[0] + kHalfBase) - q[2], rear_before, kSeatTol);
  for (int i = 3; i < q.size(); ++i) EXPECT_EQ(q[i], q0[i]) << "rail coordinate " << i;
}

TEST(RunningSurfaceSeat, OnASineTheWheelSinksToTheProfileUnderIt) {
  // r(s) = -3 mm + 1 mm sin(0.7 s), with only y1 free: y1 = r(x - 1) - depth.
  const double mean = -3e-3, amplitude = 1e-3, k = 0.7, x = 5.3;
  Bogie bogie(sine_profile(mean, amplitude, k), {}, {});
  Eigen::VectorXd q = bogie.state(x, -kIntoAxis, 0.05);
  bogie.seat(q, {1});
  EXPECT_NEAR(q[1], mean + amplitude * std::sin(k * (x - kHalfBase)) - kSeatDepth, kSeatTol);
  EXPECT_EQ(q[0], x);
}

TEST(RunningSurfaceSeat, AHertzianContactIsCompressionOnlyEvenBilateral) {
  const double r = -2e-3;
  Bogie bogie(linear_profile(r, 0.0), {false, true, false}, kBilateral);
  Eigen::VectorXd q = bogie.state(4.0, -kIntoAxis, 0.05);
  bogie.seat(q, {1});
  EXPECT_NEAR(q[1], r - kSeatDepth, kSeatTol);
}

TEST(RunningSurfaceSeat, AContactPressedFromBelowRisesToItsSurface) {
  // A pantograph under a wire whose running surface is 2 mm above the axis:
  // delta = y - (w + r), seated at y = r + depth.
  const double r = 2e-3;
  Bogie bogie(linear_profile(r, 0.0), {true, false, true}, kBilateral);
  Eigen::VectorXd q = bogie.state(4.0, kIntoAxis, 0.05);  // pressing the axis from below
  bogie.seat(q, {1});
  EXPECT_NEAR(q[1], r + kSeatDepth, kSeatTol);
}

TEST(RunningSurfaceSeat, LeavesQAloneWhenNoContactNeedsIt) {
  const double r = -2e-3;
  const std::vector<int> unknown = {0, 1, 2};
  {
    SCOPED_TRACE("in the air: apart from the smooth line too");
    Bogie bogie(linear_profile(r, 0.0), {}, {});
    const Eigen::VectorXd q0 = bogie.state(4.0, 1e-3, 0.05);
    Eigen::VectorXd q = q0;
    bogie.seat(q, unknown);
    expect_unchanged(q, q0);
  }
  {
    SCOPED_TRACE("pressing its running surface already");
    Bogie bogie(linear_profile(r, 0.0), {}, {});
    const Eigen::VectorXd q0 = bogie.state(4.0, -3e-3, 0.05);
    Eigen::VectorXd q = q0;
    bogie.seat(q, unknown);
    expect_unchanged(q, q0);
  }
  {
    SCOPED_TRACE("bilateral: it has stiffness apart");
    Bogie bogie(linear_profile(r, 0.0), kBilateral, kBilateral);
    const Eigen::VectorXd q0 = bogie.state(4.0, -kIntoAxis, -kIntoAxis);
    Eigen::VectorXd q = q0;
    bogie.seat(q, unknown);
    expect_unchanged(q, q0);
  }
  {
    SCOPED_TRACE("off the rail");
    Bogie bogie(linear_profile(r, 0.0), {}, {});
    const Eigen::VectorXd q0 = bogie.state(0.5, -kIntoAxis, 0.05);  // the front wheel at s = -0.5 m
    Eigen::VectorXd q = q0;
    bogie.seat(q, unknown);
    expect_unchanged(q, q0);
  }
  {
    SCOPED_TRACE("no rigid unknown, only the rail's DOFs under the wheel");
    Bogie bogie(linear_profile(r, 0.0), {}, {});
    const Eigen::VectorXd q0 = bogie.state(4.0, -kIntoAxis, 0.05);
    // The front wheel at s = 3 m is on element 3: w and w' at nodes 3 and 4,
    // free DOFs 5 to 8 of the rail (its w0 is held by the support).
    const int w3 = 3 + 2 * 3 - 1;
    Eigen::VectorXd q = q0;
    bogie.seat(q, {w3, w3 + 1, w3 + 2, w3 + 3});
    expect_unchanged(q, q0);
  }
}

TEST(RunningSurfaceSeat, WheelsTheUnknownsCannotSeatTogetherLeaveTheStartAsGiven) {
  // Both wheels on the axis over r(s) = -60 mm + 0.01 s, only x free: each
  // penetration changes by b dx, the two need different dx (3 and 1 cm of
  // rise over b = 0.01), and the least-squares compromise dx = 2 m seats
  // the rear wheel but not the front one. The start is restored for Newton
  // to say why.
  Bogie bogie(linear_profile(-0.06, 0.01), {}, {});
  const Eigen::VectorXd q0 = bogie.state(4.0, -kIntoAxis, -kIntoAxis);
  Eigen::VectorXd q = q0;
  bogie.seat(q, {0});
  expect_unchanged(q, q0);
}

}  // namespace
}  // namespace mbfe::runtime
