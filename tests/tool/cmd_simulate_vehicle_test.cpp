// `mbfe simulate` and `mbfe eval` on the vehicle features, through the real
// binary: a static start of a mechanism (exit 2 at the `static:` key, no output
// file left), the projection of an inconsistent initial state (a notice, or
// exit 2 with --strict), a driven joint in `eval --t`, the columns of a
// crossing, and a vehicle falling through space named (exit 2 with --strict).
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "tests/support/cli.h"
#include "tests/support/process.h"

namespace mbfe::test {
namespace {

// A value printed as shortest round-trip text and read back, against the
// same formula here: round-off on O(10) numbers.
constexpr double kPrintedRoundOff = 1e-12;

std::string source(const std::string& relative) { return std::string(MBFE_SOURCE_DIR) + "/" + relative; }

TEST(SimulateVehicle, StaticStartOfAMechanismIsBadInputAndLeavesNoFile) {
  TempDir dir;
  const fs::path model = dir / "mechanism.yaml";
  spit(model, R"(model: loose_cart
gravity: [0, -9.81]
bodies:
  - name: cart
    parent: ground
    joint: {type: prismatic, axis: [1, 0]}
    mass: 1.0
    inertia: 0
  - name: arm
    parent: cart
    joint: {type: revolute}
    mass: 1.0
    inertia: 0.1
    com: [0.5, 0]
initial: {q: {arm: -1.0}, static: true}
)");
  const fs::path csv = dir / "out.csv";
  const CliRun r = run_cli("simulate " + shell_quote(model.string()) + " --quiet --out " + shell_quote(csv.string()));
  EXPECT_EQ(r.status, 2) << r.all();
  // The `static: true` value on line 15, column 35; the coordinate nothing holds.
  EXPECT_NE(r.err.find("mechanism.yaml:15:35: static start of model 'loose_cart': the structure is a mechanism: "
                       "nothing holds 'cart' in place"),
            std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(csv));
  // --start given runs the same file from `initial:` as written.
  const CliRun given = run_cli("simulate " + shell_quote(model.string()) + " --quiet --start given --t-end 0.01 --out " +
                               shell_quote(csv.string()));
  EXPECT_EQ(given.status, 0) << given.all();
}

TEST(SimulateVehicle, StaticStartOfAFineOrStiffDeckFindsTheClosedFormSag) {
  // The moving-mass bridge meshed finely (and stiffened), original model: a
  // mesh-convergence study's runs. The wheel stands on the left support, so
  // the midspan sag is the deck's own weight's, 5 q L^4 / (384 E I) (Hermite
  // elements are exact at the nodes under a uniform load).
  constexpr double kL = 20.0, kE = 2.1e11, kArea = 0.01, kRho = 7850.0, kG = 9.81;
  // Newton stops at its round-off floor, ~1e-9 of the coordinates.
  constexpr double kSagTol = 1e-7;
  TempDir dir;
  const fs::path csv = dir / "fine.csv";
  for (const auto& [elements, inertia] : {std::pair{160, 1.0e-4}, std::pair{160, 1.0e-2}, std::pair{90, 1.0e-4}}) {
    std::ostringstream flags;
    flags << " --set beams.deck.elements=" << elements << " --set beams.deck.section.inertia=" << inertia;
    const CliRun r = run_cli("simulate models/bridge_moving_mass.yaml --adjust off --step 1e-8 --t-end 1e-8 --quiet" +
                             flags.str() + " --probe deck@10 --out " + quote(csv.string()));
    ASSERT_EQ(r.status, 0) << flags.str() << "\n" << r.all();
    EXPECT_EQ(r.err.find("mechanism"), std::string::npos) << r.err;
    const Csv c = read_csv(csv.string());
    ASSERT_GE(c.rows.size(), 1u);
    const double sag = 5.0 * kRho * kArea * kG * std::pow(kL, 4) / (384.0 * kE * inertia);
    EXPECT_NEAR(c.rows[0][static_cast<std::size_t>(c.column("deck@10"))], -sag, kSagTol * sag) << flags.str();
  }
}

TEST(SimulateVehicle, AStructureTooSoftForItsLoadsIsNotCalledAMechanism) {
  // E entered in GPa: the deck sags 7.6e7 m under its own weight, and the
  // first Newton step carries the tyre's contact away. The wheel was held
  // at the start; the message says what happened instead of "mechanism".
  TempDir dir;
  const CliRun r = run_cli("simulate models/bridge_moving_mass.yaml --adjust off --set "
                           "beams.deck.material.youngs_modulus=210 --quiet --out " +
                           quote((dir / "soft.csv").string()));
  EXPECT_EQ(r.status, 2) << r.all();
  EXPECT_EQ(r.err.find("mechanism"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("Newton lost hold of 'wheel' after 1 iteration"), std::string::npos) << r.err;
}

TEST(SimulateVehicle, AZeroMassWheelIsNotCalledAMechanism) {
  // The tyre holds the wheel; with mass 0 its acceleration is undefined.
  TempDir dir;
  const CliRun r = run_cli("simulate models/bridge_moving_mass.yaml --set bodies.wheel.mass=0 --quiet --out " +
                           quote((dir / "m0.csv").string()));
  EXPECT_EQ(r.status, 2) << r.all();
  EXPECT_EQ(r.err.find("mechanism"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("bridge_moving_mass.yaml:39:19: static start of model 'bridge_moving_mass': 'wheel' moves no "
                       "mass: body 'wheel' and every body it carries have mass 0 and inertia 0"),
            std::string::npos)
      << r.err;
  // Started as written, the first step would divide by the zero mass (a run
  // of NaN): refused before it, with the static start's words, at the body.
  const std::string csv = (dir / "given.csv").string();
  const CliRun given = run_cli(
      "simulate models/bridge_moving_mass.yaml --set bodies.wheel.mass=0 --start given "
      "--quiet --out " +
      quote(csv));
  EXPECT_EQ(given.status, 2) << given.all();
  EXPECT_NE(given.err.find("bridge_moving_mass.yaml:20:5: model 'bridge_moving_mass': 'wheel' moves no mass: body "
                           "'wheel' and every body it carries have mass 0 and inertia 0"),
            std::string::npos)
      << given.err;
  EXPECT_EQ(given.err.find("nan"), std::string::npos) << given.err;
  EXPECT_FALSE(fs::exists(csv)) << "a refused run leaves no file";
}

TEST(SimulateVehicle, AVehicleThatNeverTouchesItsBeamIsWarnedAbout) {
  // `angle: 180` meant as degrees: the deck points down and to the left, the
  // wheel never rides on it and falls; the run completes (exit 0) but says so.
  TempDir dir;
  const fs::path csv = dir / "fall.csv";
  const std::string run = "simulate models/bridge_moving_mass.yaml --set beams.deck.angle=180 --t-end 0.2 --quiet --out " +
                          quote(csv.string());
  const CliRun given = run_cli(run + " --start given");
  EXPECT_EQ(given.status, 0) << given.all();
  EXPECT_NE(given.err.find("warning: beam 'deck': angle = 180 rad is more than a turn: degrees entered as rad?"),
            std::string::npos)
      << given.err;
  EXPECT_NE(given.err.find("mbfe: warning: contact 'tyre' never touched the beam during the run"), std::string::npos)
      << given.err;
  const std::string meta = slurp(csv.string() + ".json");
  EXPECT_NE(meta.find("\"touched\": false"), std::string::npos) << meta;
  EXPECT_NE(meta.find("contact 'tyre' never touched the beam during the run"), std::string::npos) << meta;
  // The static start names the contact that holds nothing.
  const CliRun fixed = run_cli(run);
  EXPECT_EQ(fixed.status, 2) << fixed.all();
  EXPECT_NE(fixed.err.find("nothing holds 'wheel' in place; its contact 'tyre' does not press on beam 'deck' at the "
                           "start (gap 0 m; the beam points (-0.59846, -0.801153))"),
            std::string::npos)
      << fixed.err;
  // The shipped crossing touches, and says nothing of it.
  const CliRun crossing = run_cli("simulate models/bridge_moving_mass.yaml --quiet --out " + quote(csv.string()));
  EXPECT_EQ(crossing.status, 0) << crossing.all();
  EXPECT_EQ(crossing.err.find("warning"), std::string::npos) << crossing.err;
  EXPECT_NE(slurp(csv.string() + ".json").find("\"touched\": true"), std::string::npos);
}

TEST(SimulateVehicle, FreeFallOfAVehicleWhoseBridgeIsFarAwayIsNamed) {
  // The shipped crossing with its deck's origin mistyped 100 m below the
  // wheel, started as written: the wheel falls, nothing touches, the run
  // completes. Closed form at t_end = 1.2 s: the wheel at (20 t, -g t^2 / 2)
  // = (24, -7.063) m, 93.02 m from the deck's segment (0..20, -100) (its end
  // (20, -100) is nearest), and fallen g (t^2 - h^2) / 2 since the first
  // accepted step (h = 1e-3 s), which RK4 integrates exactly.
  TempDir dir;
  std::string yaml = slurp(source("models/bridge_moving_mass.yaml"));
  const std::string from = "    origin: [0.0, 0.0]";
  ASSERT_NE(yaml.find(from), std::string::npos);
  yaml.replace(yaml.find(from), from.size(), "    origin: [0.0, -100.0]");
  const fs::path model = dir / "far.yaml";
  spit(model, yaml);
  const fs::path csv = dir / "far.csv";
  const std::string run =
      "simulate " + shell_quote(model.string()) + " --start given --quiet --out " + shell_quote(csv.string());
  const CliRun given = run_cli(run);
  EXPECT_EQ(given.status, 0) << given.all();
  const double g = 9.81, t = 1.2, h = 1e-3;
  const double distance = std::hypot(24.0 - 20.0, 100.0 - 0.5 * g * t * t), fallen = 0.5 * g * (t * t - h * h);
  constexpr double kFallTol = 1e-9;  // m: RK4 exact on the quadratic, the points from the generated kernels
  EXPECT_NE(given.err.find("mbfe: warning: body 'wheel' fell through space: none of its contacts touched a beam, "
                           "and at t = 1.2 s its point 'contact' is 93 m from beam 'deck', farther than the "
                           "structure's size (20 m); it fell 7.06 m: check the beams' origin and angle"),
            std::string::npos)
      << given.err;
  EXPECT_EQ(given.err.find("fell through space", given.err.find("fell through space") + 1), std::string::npos);
  const nlohmann::json meta = nlohmann::json::parse(slurp(csv.string() + ".json"));
  ASSERT_TRUE(meta.contains("free_falls")) << meta.dump(2);
  ASSERT_EQ(meta["free_falls"].size(), 1u);
  const nlohmann::json& fall = meta["free_falls"][0];
  EXPECT_EQ(fall["body"], "wheel");
  EXPECT_EQ(fall["point"], "contact");
  EXPECT_EQ(fall["beam"], "deck");
  EXPECT_NEAR(fall["distance"].get<double>(), distance, kFallTol);
  EXPECT_NEAR(fall["fallen"].get<double>(), fallen, kFallTol);
  EXPECT_EQ(fall["structure_size"].get<double>(), 20.0);
  EXPECT_EQ(fall["t"].get<double>(), t);
  EXPECT_NE(meta["warnings"].dump().find("fell through space"), std::string::npos);
  // --strict: an error after the run (exit 2), its rows and record kept.
  const CliRun strict = run_cli(run + " --strict");
  EXPECT_EQ(strict.status, 2) << strict.all();
  EXPECT_NE(strict.err.find("mbfe simulate: --strict: body 'wheel' fell through space"), std::string::npos)
      << strict.err;
  EXPECT_EQ(read_csv(csv.string()).rows.size(), 1201u);
  EXPECT_NE(slurp(csv.string() + ".json").find("free_falls"), std::string::npos);
  // The shipped crossing (touching) and a fall shorter than the structure
  // (degrees typed as rad, 0.2 s: 0.2 m of fall near the deck's end) are not named.
  const CliRun crossing = run_cli("simulate models/bridge_moving_mass.yaml --quiet --strict --out " +
                                  shell_quote(csv.string()));
  EXPECT_EQ(crossing.status, 0) << crossing.all();
  EXPECT_EQ(slurp(csv.string() + ".json").find("free_falls"), std::string::npos);
  const CliRun short_fall = run_cli("simulate models/bridge_moving_mass.yaml --set beams.deck.angle=180 --t-end 0.2 "
                                    "--start given --quiet --strict --out " + shell_quote(csv.string()));
  EXPECT_EQ(short_fall.status, 0) << short_fall.all();
  EXPECT_EQ(short_fall.err.find("fell through space"), std::string::npos) << short_fall.err;
}

TEST(SimulateVehicle, AnInconsistentInitialStateIsAnnouncedOrRefused) {
  // The double pendulum on the beam, its tip lifted off the beam by turning link1.
  TempDir dir;
  std::string yaml = slurp(source("models/double_pendulum_beam.yaml"));
  const std::string from = "initial: {q: {link1: -1.3874443249943893";
  ASSERT_NE(yaml.find(from), std::string::npos);
  yaml.replace(yaml.find(from), from.size(), "initial: {q: {link1: -1.3");
  const fs::path model = dir / "lifted.yaml";
  spit(model, yaml);
  const std::string args = "simulate " + shell_quote(model.string()) + " --quiet --t-end 1e-4 --out " +
                           shell_quote((dir / "out.csv").string());
  const CliRun r = run_cli(args);
  EXPECT_EQ(r.status, 0) << r.all();
  EXPECT_NE(r.err.find("the initial state violates the contacts and was projected onto them: positions: "),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("link2 by "), std::string::npos) << r.err;  // the dependent coordinate moved
  const CliRun strict = run_cli(args + " --strict");
  EXPECT_EQ(strict.status, 2) << strict.all();
  EXPECT_NE(strict.err.find("(strict)"), std::string::npos) << strict.err;
  // The shipped, consistent start says nothing.
  const CliRun consistent = run_cli("simulate models/double_pendulum_beam.yaml --quiet --t-end 1e-4 --out " +
                                    shell_quote((dir / "ok.csv").string()));
  EXPECT_EQ(consistent.status, 0) << consistent.all();
  EXPECT_EQ(consistent.err.find("projected"), std::string::npos) << consistent.err;
}

TEST(SimulateVehicle, EvalTakesTheDrivenCoordinateFromTheMotionAtT) {
  // A spring-damper on the driven joint sees the motion: Q_cart = -k x(t) - c x'(t)
  // with x = 0.3 sin(2 t), whatever --q and --qd say.
  TempDir dir;
  const fs::path model = dir / "driven.yaml";
  spit(model, R"yaml(model: driven_spring
bodies:
  - name: cart
    parent: ground
    joint: {type: prismatic, axis: [1, 0], motion: "0.3*sin(2*t)"}
    mass: 1.0
    inertia: 0
  - name: arm
    parent: cart
    joint: {type: revolute}
    mass: 1.0
    inertia: 0.1
loads:
  - {type: spring_damper, joint: cart, stiffness: 100.0, damping: 10.0}
)yaml");
  const CliRun r = run_cli("eval " + shell_quote(model.string()) + " --q 3,0 --qd 7,0 --t 0.5 --json --quiet");
  ASSERT_EQ(r.status, 0) << r.all();
  const std::string key = "\"Q\":[";
  const auto at = r.out.find(key);
  ASSERT_NE(at, std::string::npos) << r.out;
  const double q_cart = std::stod(r.out.substr(at + key.size()));
  const double expected = -100.0 * 0.3 * std::sin(1.0) - 10.0 * 0.6 * std::cos(1.0);
  EXPECT_NEAR(q_cart, expected, kPrintedRoundOff) << r.out;
}

TEST(SimulateVehicle, ADivergenceIsBlamedOnTheStepNotOnAnUndampedMode) {
  // The original (unadjusted) bridge at 2e-4 s: RK4's limit is 2.7e-5 s
  // (mbfe stability); the undamped beam modes, whose real parts compute to
  // round-off (1e-12), must not read as "no stable step".
  test::TempDir dir;
  const CliRun r = run_cli("simulate models/bridge_moving_mass.yaml --adjust off --step 2e-4 --t-end 0.05 --quiet --out " +
                           shell_quote((dir / "x.csv").string()));
  EXPECT_EQ(r.status, 3) << r.all();
  EXPECT_NE(r.err.find("step 0.0002 exceeds rk4's stable limit 2.7234e-05"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("no stable step"), std::string::npos) << r.err;
}

TEST(SimulateVehicle, CrossingColumnsAndTally) {
  TempDir dir;
  const fs::path csv = dir / "crossing.csv";
  const CliRun r = run_cli("simulate models/bridge_moving_mass.yaml --probe deck@10 --out " + shell_quote(csv.string()));
  ASSERT_EQ(r.status, 0) << r.all();
  const Csv c = read_csv(csv.string());
  EXPECT_EQ(c.header, (std::vector<std::string>{"t", "carriage", "wheel", "deck@10", "carriage_dot", "wheel_dot",
                                                "deck@10_dot", "phi_abs", "force_tyre", "deflection_tyre",
                                                "carriage_drive"}));
  ASSERT_EQ(c.rows.size(), 1201u);
  for (const auto& row : c.rows) {
    EXPECT_NEAR(row[1], 20.0 * row[0], kPrintedRoundOff);  // the carriage follows its motion
    EXPECT_EQ(row[4], 20.0);
    EXPECT_GE(row[8], 0.0);  // the tyre never pulls
  }
  EXPECT_NE(r.err.find("mbfe: contact 'tyre': "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(" off contact while over the beam"), std::string::npos) << r.err;
  // The sidecar says what the CSV holds.
  const std::string meta = slurp(csv.string() + ".json");
  EXPECT_NE(meta.find("\"name\": \"bridge_moving_mass\""), std::string::npos) << meta;
  EXPECT_NE(meta.find("\"sha256\": \""), std::string::npos) << meta;
  EXPECT_NE(meta.find("\"integrator\": \"rk4\""), std::string::npos) << meta;
  EXPECT_NE(meta.find("\"step\": 0.001"), std::string::npos) << meta;
  EXPECT_NE(meta.find("\"name\": \"force_tyre\",\n      \"unit\": \"N\""), std::string::npos) << meta;
  EXPECT_NE(meta.find("\"rows\": 1201"), std::string::npos) << meta;
  EXPECT_NE(meta.find("\"status\": \"completed\""), std::string::npos) << meta;
  EXPECT_NE(meta.find("\"variant\": \"adjusted damping, partitioned formulation, low-rank beams in split coordinates\""),
            std::string::npos)
      << meta;
}

TEST(SimulateVehicle, PolicyMassRunsAndKeepsTheStaticDeflection) {
  // Policy mass keeps the structure's stiffness (K_adj = K): the static start
  // of the adjusted model is the original model's, where the cap's is softer
  // under the wheel (docs/damping-adjustment.md, "Policy mass"). The wheel
  // stands still at a quarter of the deck, where the capped modes' share of
  // the point load's deflection shows.
  TempDir dir;
  std::string yaml = slurp(source("models/bridge_moving_mass.yaml"));
  const std::string from = "policy: mass}", moving = "motion: \"20*t\"";
  ASSERT_NE(yaml.find(from), std::string::npos);
  ASSERT_NE(yaml.find(moving), std::string::npos);
  yaml.replace(yaml.find(moving), moving.size(), "motion: \"5.0\"");
  const fs::path model = dir / "mass.yaml";
  spit(model, yaml);
  yaml.replace(yaml.find(from), from.size(), "policy: cap}");
  const fs::path cap_model = dir / "cap.yaml";
  spit(cap_model, yaml);
  const auto first_deflection = [&](const fs::path& m, const std::string& flags) {
    const fs::path csv = dir / "out.csv";
    const CliRun r = run_cli("simulate " + quote(m.string()) + " --quiet --t-end 0.001 --probe deck@5 " + flags +
                             " --out " + quote(csv.string()));
    EXPECT_EQ(r.status, 0) << r.all();
    std::istringstream in(slurp(csv.string()));
    std::string header, row, cell;
    std::getline(in, header);
    std::getline(in, row);
    std::istringstream names(header), values(row);
    while (std::getline(names, cell, ',')) {
      std::string value;
      std::getline(values, value, ',');
      if (cell == "deck@5") return std::stod(value);
    }
    ADD_FAILURE() << "no column deck@5 in " << header;
    return 0.0;
  };
  const double original = first_deflection(model, "--adjust off");
  const double mass = first_deflection(model, "");
  const double cap = first_deflection(cap_model, "");
  // The static start's Newton stops at ~1e-9 of the deflection.
  constexpr double kStaticTol = 1e-8;
  EXPECT_NEAR(mass, original, kStaticTol * std::abs(original));
  EXPECT_GT(std::abs(cap - original), 1e-6 * std::abs(original));  // the cap's softer compliance
}

}  // namespace
}  // namespace mbfe::test
