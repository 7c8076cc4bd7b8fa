// ContactTallies: lift-offs and time off of slider_spring contacts,
// slackenings and time slack of links, and where each contact point starts
// and ends, over a sequence of accepted states set here by hand (the force
// elements' states written into the dynamics' data, as an evaluation would
// leave them). Oracle: the same sequence counted by hand in the comments,
// each step's interval counted with the state that ends it.
#include "runtime/simulation/contact_tallies.h"

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "ir/model.h"
#include "runtime/abi/mbfe_model_abi.h"
#include "runtime/coupled/coupled_dynamics.h"
#include "runtime/coupled/coupled_model.h"
#include "runtime/coupled/link_force.h"
#include "runtime/coupled/slider_spring_force.h"
#include "tests/runtime/coupled/test_beam.h"

namespace mbfe::runtime {
namespace {

// Sums of a few differences of decimal times: round-off.
constexpr double kTimeTol = 1e-12;  // s

// --- Kernels of two rigid coordinates and four slider_spring contacts. The
// states are set by hand, so the contact kernels are never called; they
// exist because a model must have them.
double no_position(const double*) { return 0.0; }
void no_phi(const double*, const double*, double, double, double* phi) { phi[0] = 0.0; }
void no_jacobians(const double*, const double*, double, double, double*, double*) {}
void no_gamma(const double*, const double*, const double*, const double*, double, double, double* gamma) {
  gamma[0] = 0.0;
}
// Point `point` of body `body`: (q_body + point, 0.25 body - point), a
// placement the test can compute and that tells bodies and points apart.
void point_position(const double* q, int body, int point, double* xy) {
  xy[0] = q[body] + point;
  xy[1] = 0.25 * body - point;
}
constexpr mbfe_contact_kernels_v1 spring(const char* name) {
  return {name, 2, 0, 0.0, 1, no_position, no_phi, no_jacobians, no_gamma, 1.0e6, 0.0, 1, 0};
}
const mbfe_contact_kernels_v1 kSprings[] = {spring("front"), spring("rear"), spring("idle"), spring("hover")};
// The body and point of each contact in the IR (what place() reads).
constexpr int kSpringBody[] = {1, 0, 1, 0}, kSpringPoint[] = {0, 2, 1, 0};
const char* const kNames[] = {"carriage", "bogie"};

ir::Link beam_link(const std::string& name, double a, double b, bool slack) {
  ir::Link l;
  l.name = name;
  l.a = {0, a};
  l.b = {0, b};
  l.stiffness = 1.0e4;
  l.slack = slack;
  return l;
}

/// A model with the first `springs` of kSprings and `links` between points
/// of one beam; its dynamics, whose force states the tests set.
class Rig {
 public:
  Rig(int springs, const std::vector<ir::Link>& links, bool point_kernel = true) {
    kernels_.abi_version = MBFE_MODEL_ABI_VERSION;
    kernels_.model_name = "tallied";
    kernels_.num_coordinates = 2;
    kernels_.coordinate_names = kNames;
    kernels_.point_position = point_kernel ? point_position : nullptr;
    kernels_.num_contacts = springs;
    kernels_.contacts = kSprings;
    for (int k = 0; k < springs; ++k) {
      ir::Contact c;
      c.name = kSprings[k].name;
      c.type = ir::ContactType::kSliderSpring;
      c.body = kSpringBody[k];
      c.point = kSpringPoint[k];
      c.beam = 0;
      c.unilateral = true;
      ir_.contacts.push_back(c);
    }
    ir_.links = links;
    CoupledBeams beams;
    beams.beams.push_back(testing::pinned_pinned_beam("deck", 10.0, 10, 1.0e7, 60.0, 0.0, 0.0, 0.0).beam);
    model_ = std::make_shared<const CoupledModel>(kernels_, std::move(beams), std::vector<BodyInertia>{}, links);
    dyn_ = std::make_unique<CoupledDynamics>(model_);
  }
  Rig(const Rig&) = delete;
  Rig& operator=(const Rig&) = delete;

  const CoupledModel& model() const { return *model_; }
  const ir::Model& ir() const { return ir_; }
  const CoupledDynamics& dynamics() const { return *dyn_; }

  /// Spring k's state: off its beam, or on it with penetration delta (m).
  void set_spring(int k, bool on_beam, double delta) {
    const int element = model_->slider_spring_elements()[static_cast<std::size_t>(k)];
    SpringContactState& st = static_cast<SliderSpringForce::State&>(*dyn_->data().forces[element]).contact;
    st = SpringContactState{};
    st.on_beam = on_beam;
    st.delta = on_beam ? delta : 0.0;  // as an evaluation leaves it off the beam
  }
  /// Link k's (model order) state.
  void set_link(int k, bool slack) {
    const int element = model_->link_elements()[static_cast<std::size_t>(k)];
    static_cast<LinkForce::State&>(*dyn_->data().forces[element]).link.slack = slack;
  }

 private:
  mbfe_model_v1 kernels_{};
  ir::Model ir_;
  std::shared_ptr<const CoupledModel> model_;
  std::unique_ptr<CoupledDynamics> dyn_;
};

// A contact's state at one step: pressing (delta > 0), exactly touching
// (delta = 0, not in contact), apart (delta < 0), or off its beam.
enum class Touch { kPress, kZero, kApart, kOff };

struct Step {
  double t;
  Touch front, rear, idle, hover;
  bool stitch_slack, dropper_slack, hanger_slack;
};

void set(Rig& rig, int k, Touch touch) {
  const double delta = touch == Touch::kPress ? 1e-4 : touch == Touch::kApart ? -2e-4 : 0.0;  // m
  rig.set_spring(k, touch != Touch::kOff, delta);
}

TEST(ContactTallies, CountsTheHandMadeSequenceAsCountedByHand) {
  // Links: 'stitch' cannot go slack (no tally; its state says slack, which
  // a tally reading the wrong link would count), 'dropper' and 'hanger' can.
  Rig rig(4, {beam_link("stitch", 1.0, 2.0, false), beam_link("dropper", 3.0, 4.0, true),
              beam_link("hanger", 5.0, 6.0, true)});
  ContactTallies tallies(rig.model(), rig.ir());
  ASSERT_FALSE(tallies.empty());
  using T = Touch;
  // clang-format off
  const Step steps[] = {
      // t    front      rear       idle     hover      stitch dropper hanger
      {0.0,  T::kPress, T::kOff,   T::kOff, T::kApart, true,  true,   false},
      {0.1,  T::kPress, T::kOff,   T::kOff, T::kApart, true,  false,  false},
      {0.25, T::kApart, T::kOff,   T::kOff, T::kApart, true,  true,   false},
      {0.3,  T::kApart, T::kOff,   T::kOff, T::kApart, true,  true,   false},
      {0.5,  T::kPress, T::kApart, T::kOff, T::kApart, true,  false,  false},
      {0.55, T::kZero,  T::kApart, T::kOff, T::kApart, true,  true,   false},
      {0.7,  T::kOff,   T::kPress, T::kOff, T::kApart, true,  false,  false},
      {0.8,  T::kApart, T::kPress, T::kOff, T::kApart, true,  false,  false},
      {1.0,  T::kPress, T::kPress, T::kOff, T::kApart, true,  false,  false},
      {1.2,  T::kApart, T::kPress, T::kOff, T::kApart, true,  true,   false},
  };
  // clang-format on
  for (const Step& s : steps) {
    set(rig, 0, s.front);
    set(rig, 1, s.rear);
    set(rig, 2, s.idle);
    set(rig, 3, s.hover);
    rig.set_link(0, s.stitch_slack);
    rig.set_link(1, s.dropper_slack);
    rig.set_link(2, s.hanger_slack);
    tallies.count(s.t, rig.dynamics());
  }
  ASSERT_EQ(tallies.springs().size(), 4u);
  const SpringContactTally& front = tallies.springs()[0];
  const SpringContactTally& rear = tallies.springs()[1];
  const SpringContactTally& idle = tallies.springs()[2];
  const SpringContactTally& hover = tallies.springs()[3];
  EXPECT_EQ(front.name, "front");
  EXPECT_EQ(hover.name, "hover");
  // front: lifts off at 0.25 (after pressing), at 0.55 (delta = 0 is not in
  // contact) and at 1.2; not at 0.8, after a step off the beam. Off over the
  // intervals ending at 0.25, 0.3, 0.55, 0.8, 1.2: 0.15 + 0.05 + 0.05 + 0.1 + 0.2.
  EXPECT_EQ(front.lift_offs, 3);
  EXPECT_NEAR(front.time_off, 0.55, kTimeTol);
  EXPECT_FALSE(front.in_contact);
  EXPECT_TRUE(front.seen);
  EXPECT_TRUE(front.touched);
  // rear: arrives apart at 0.5, lands at 0.7 and stays: off 0.2 + 0.05.
  EXPECT_EQ(rear.lift_offs, 0);
  EXPECT_NEAR(rear.time_off, 0.25, kTimeTol);
  EXPECT_TRUE(rear.in_contact);
  EXPECT_TRUE(rear.seen);
  EXPECT_TRUE(rear.touched);
  // idle: never over its beam.
  EXPECT_EQ(idle.lift_offs, 0);
  EXPECT_EQ(idle.time_off, 0.0);
  EXPECT_FALSE(idle.in_contact);
  EXPECT_FALSE(idle.seen);
  EXPECT_FALSE(idle.touched);
  // hover: over its beam and apart throughout: off the whole 1.2 s, never touched.
  EXPECT_EQ(hover.lift_offs, 0);
  EXPECT_NEAR(hover.time_off, 1.2, kTimeTol);
  EXPECT_FALSE(hover.in_contact);
  EXPECT_TRUE(hover.seen);
  EXPECT_FALSE(hover.touched);

  ASSERT_EQ(tallies.links().size(), 2u);
  const LinkSlackTally& dropper = tallies.links()[0];
  const LinkSlackTally& hanger = tallies.links()[1];
  EXPECT_EQ(dropper.name, "dropper");
  EXPECT_EQ(hanger.name, "hanger");
  // dropper: slack from the start (not a slackening), then slackens at 0.25,
  // 0.55 and 1.2; slack over the intervals ending at 0.25, 0.3, 0.55, 1.2.
  EXPECT_EQ(dropper.slackenings, 3);
  EXPECT_NEAR(dropper.time_slack, 0.15 + 0.05 + 0.05 + 0.2, kTimeTol);
  EXPECT_TRUE(dropper.slack);
  EXPECT_TRUE(dropper.seen);
  EXPECT_EQ(hanger.slackenings, 0);
  EXPECT_EQ(hanger.time_slack, 0.0);
  EXPECT_FALSE(hanger.slack);
  EXPECT_TRUE(hanger.seen);
}

TEST(ContactTallies, PlaceKeepsTheFirstPositionAndTheLast) {
  Rig rig(4, {});
  ContactTallies tallies(rig.model(), rig.ir());
  for (const SpringContactTally& t : tallies.springs()) EXPECT_TRUE(std::isnan(t.start[0]) && std::isnan(t.end[0]));
  const Eigen::Vector2d q_first(1.5, -0.25), q_middle(2.0, 3.0), q_last(7.5, 4.25);
  tallies.place(rig.dynamics(), q_first);
  tallies.place(rig.dynamics(), q_middle);
  tallies.place(rig.dynamics(), q_last);
  for (int k = 0; k < 4; ++k) {
    const SpringContactTally& t = tallies.springs()[static_cast<std::size_t>(k)];
    const int body = kSpringBody[k], point = kSpringPoint[k];
    EXPECT_EQ(t.start[0], q_first[body] + point) << t.name;
    EXPECT_EQ(t.start[1], 0.25 * body - point) << t.name;
    EXPECT_EQ(t.end[0], q_last[body] + point) << t.name;
    EXPECT_EQ(t.end[1], 0.25 * body - point) << t.name;
  }
}

TEST(ContactTallies, WithoutAPlanarPointKernelPositionsStayUnknown) {
  Rig rig(2, {}, false);
  ContactTallies tallies(rig.model(), rig.ir());
  tallies.place(rig.dynamics(), Eigen::Vector2d(1.0, 2.0));
  for (const SpringContactTally& t : tallies.springs()) {
    EXPECT_TRUE(std::isnan(t.start[0]) && std::isnan(t.start[1])) << t.name;
    EXPECT_TRUE(std::isnan(t.end[0]) && std::isnan(t.end[1])) << t.name;
  }
}

TEST(ContactTallies, NothingToCountWithoutSpringsOrLinksThatGoSlack) {
  {
    Rig rig(0, {beam_link("stitch", 1.0, 2.0, false)});
    const ContactTallies tallies(rig.model(), rig.ir());
    EXPECT_TRUE(tallies.empty());
    EXPECT_TRUE(tallies.links().empty());
  }
  {
    Rig rig(0, {beam_link("stitch", 1.0, 2.0, false), beam_link("dropper", 3.0, 4.0, true)});
    const ContactTallies tallies(rig.model(), rig.ir());
    EXPECT_FALSE(tallies.empty());
    ASSERT_EQ(tallies.links().size(), 1u);
    EXPECT_EQ(tallies.links()[0].name, "dropper");
  }
  {
    Rig rig(1, {});
    const ContactTallies tallies(rig.model(), rig.ir());
    EXPECT_FALSE(tallies.empty());
    ASSERT_EQ(tallies.springs().size(), 1u);
    EXPECT_EQ(tallies.springs()[0].name, "front");
  }
}

}  // namespace
}  // namespace mbfe::runtime
