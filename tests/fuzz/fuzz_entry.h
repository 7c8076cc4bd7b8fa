// The body of the model fuzzer, shared by the libFuzzer target
// (tests/fuzz/model_fuzz.cpp, built by scripts/fuzz.sh) and the regression
// replay in the normal test suite (tests/fuzz/fuzz_regressions_test.cpp).
//
// One input: bytes -> parse_model_text (parse + validate) -> on success, the
// IR invariants model.h promises are checked -> gen::generate_solver when the
// model has 1..kMaxFuzzBodies bodies. Expected outcomes: success, a ModelError
// (bad input, exit status 2 in the CLI) or std::invalid_argument (a model the
// generator refuses). Anything else escaping -- another exception, a
// FuzzInvariantError, a sanitizer report, a crash, a hang -- is a bug.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "generator/emit/generate_solver.h"
#include "ir/coordinate_layout.h"
#include "ir/model.h"
#include "frontend/expression_parser.h"
#include "frontend/parse_model.h"
#include "ir/identifiers.h"

namespace mbfe::fuzz {

/// Larger models are parsed and validated but not derived, so that one input
/// stays well under a second (derivation grows quickly with the chain length).
constexpr std::size_t kMaxFuzzBodies = 8;

/// The parser accepted a model that breaks a promise of model.h.
class FuzzInvariantError : public std::logic_error {
 public:
  using std::logic_error::logic_error;
};

namespace detail {

inline void require(bool ok, const std::string& what) {
  if (!ok) throw FuzzInvariantError("accepted model breaks an IR invariant: " + what);
}

inline bool finite2(const ir::Vec2& v) { return std::isfinite(v[0]) && std::isfinite(v[1]); }
inline bool finite3(const ir::Vec3& v) { return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]); }

/// Every number written in the expression is finite (its value at some t may
/// not be), no part without t is infinite or undefined, and the tree keeps
/// within the parser's limits.
inline bool finite_numbers(const ir::Expression& e) {
  for (const ir::ExpressionNode& n : e.nodes())
    if (n.kind == ir::ExpressionNode::Kind::kNumber && !std::isfinite(n.value)) return false;
  return !e.constant_fault() && e.depth() <= frontend::kMaxExpressionTreeDepth &&
         e.nodes().size() <= static_cast<std::size_t>(frontend::kMaxExpressionNodes);
}

inline void check_invariants(const ir::Model& m) {
  using ir::is_identifier;
  require(is_identifier(m.name), "model name '" + m.name + "' is not an identifier");
  require(finite2(m.gravity) && finite3(m.gravity3), "gravity not finite");
  require(m.dimension == 2 || m.dimension == 3, "dimension");
  const int nb = static_cast<int>(m.bodies.size());
  for (int i = 0; i < nb; ++i) {
    const ir::Body& b = m.bodies[i];
    require(is_identifier(b.name), "body name '" + b.name + "' is not an identifier");
    require(b.parent >= -1 && b.parent < i, "body '" + b.name + "': parent index out of order");
    require(std::isfinite(b.mass) && b.mass >= 0, "body '" + b.name + "': mass");
    require(std::isfinite(b.inertia) && b.inertia >= 0, "body '" + b.name + "': inertia");
    require(finite2(b.com) && finite2(b.joint.at) && finite2(b.joint.axis), "body '" + b.name + "': vector");
    require(finite3(b.com3) && finite3(b.joint.at3) && finite3(b.joint.axis3) && finite3(b.joint.rotation),
            "body '" + b.name + "': spatial vector");
    for (double x : b.inertia3) require(std::isfinite(x), "body '" + b.name + "': inertia tensor");
    require(m.dimension == 3 || (b.joint.type != ir::JointType::kSpherical && b.joint.type != ir::JointType::kFree),
            "body '" + b.name + "': a quaternion joint in a planar model");
    require(!b.joint.motion || finite_numbers(*b.joint.motion), "body '" + b.name + "': motion");
    for (const auto& p : b.points) {
      require(is_identifier(p.name), "point name '" + p.name + "' is not an identifier");
      require(finite2(p.position) && finite3(p.position3), "point '" + p.name + "' not finite");
    }
  }
  for (const ir::Load& l : m.loads) {
    require(l.body >= 0 && l.body < nb, "load body index out of range");
    require(l.point >= -1 && l.point < static_cast<int>(m.bodies[l.body].points.size()),
            "load point index out of range");
    require(finite_numbers(l.force[0]) && finite_numbers(l.force[1]) && finite_numbers(l.torque) &&
                finite_numbers(l.force3[0]) && finite_numbers(l.force3[1]) && finite_numbers(l.force3[2]) &&
                finite_numbers(l.torque3[0]) && finite_numbers(l.torque3[1]) && finite_numbers(l.torque3[2]) &&
                std::isfinite(l.stiffness) &&
                std::isfinite(l.damping) && std::isfinite(l.rest),
            "load value not finite");
  }
  for (const ir::Beam& beam : m.beams) {
    require(is_identifier(beam.name), "beam name '" + beam.name + "' is not an identifier");
    require(beam.elements > 0, "beam '" + beam.name + "': elements <= 0");
    require(std::isfinite(beam.length) && beam.length > 0, "beam '" + beam.name + "': length");
    for (const auto& s : beam.supports)
      require(s.node >= 0 && s.node <= beam.elements, "beam '" + beam.name + "': support node");
    for (const auto& l : beam.loads)
      require(l.node >= 0 && l.node <= beam.elements && finite_numbers(l.value),
              "beam '" + beam.name + "': load node");
    for (const auto& l : beam.moving_loads)
      require(finite_numbers(l.value) && std::isfinite(l.speed) && l.speed != 0.0 && std::isfinite(l.start) &&
                  std::isfinite(l.t0),
              "beam '" + beam.name + "': moving load");
  }
  const int nbeams = static_cast<int>(m.beams.size());
  for (const ir::Contact& c : m.contacts) {
    require(is_identifier(c.name), "contact name '" + c.name + "' is not an identifier");
    require(c.body >= 0 && c.body < nb, "contact body index out of range");
    require(c.point >= 0 && c.point < static_cast<int>(m.bodies[c.body].points.size()),
            "contact point index out of range");
    require(c.beam >= 0 && c.beam < nbeams, "contact beam index out of range");
  }
  for (const ir::LoopConstraint& c : m.constraints) {
    require(is_identifier(c.name), "constraint name '" + c.name + "' is not an identifier");
    for (const ir::LoopEnd* end : {&c.a, &c.b}) {
      require(end->body >= -1 && end->body < nb, "constraint body index out of range");
      require(end->point == -1 || (end->body >= 0 && end->point < static_cast<int>(m.bodies[end->body].points.size())),
              "constraint point index out of range");
      require(finite3(end->at), "constraint point not finite");
    }
    require(c.a.body != c.b.body && finite3(c.axis), "constraint '" + c.name + "'");
  }
  const ir::CoordinateLayout layout = ir::coordinate_layout(m);
  require(static_cast<int>(m.initial.q.size()) == layout.num_positions &&
              static_cast<int>(m.initial.qd.size()) == layout.num_velocities,
          "initial state size");
  for (double x : m.initial.q) require(std::isfinite(x), "initial state not finite");
  for (double x : m.initial.qd) require(std::isfinite(x), "initial state not finite");
  require(std::isfinite(m.simulation.step) && m.simulation.step > 0, "simulation step");
  require(std::isfinite(m.simulation.t_end) && m.simulation.t_end > 0, "simulation t_end");
}

}  // namespace detail

/// What one input did (for statistics and the regression test's messages).
enum class FuzzOutcome { kRejected, kParsed, kGenerated, kGeneratorRefused };

/// Runs one input. Returns the outcome; lets every unexpected exception escape.
inline FuzzOutcome fuzz_one_input(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  ir::Model m;
  try {
    m = frontend::parse_model_text(text, "fuzz.yaml");
  } catch (const ir::ModelError& e) {
    // Bad input must say where: "fuzz.yaml:" opens every message.
    const std::string what = e.what();
    if (what.rfind("fuzz.yaml:", 0) != 0)
      throw FuzzInvariantError("ModelError without the file name in front: " + what);
    return FuzzOutcome::kRejected;
  }
  detail::check_invariants(m);
  if (m.bodies.empty() || m.bodies.size() > kMaxFuzzBodies) return FuzzOutcome::kParsed;
  try {
    const gen::GeneratedSolver solver = gen::generate_solver(m);
    if (solver.files.empty()) throw FuzzInvariantError("generate_solver returned no files");
    // Nothing of the file is pasted as text: names are identifiers, numbers
    // are printed by the generator, so the sources are plain printable ASCII.
    for (const gen::GeneratedFile& file : solver.files)
      for (const char c : file.text)
        detail::require(c == '\n' || (c >= ' ' && c <= '~'),
                        "generated " + file.name + " holds a byte outside printable ASCII");
  } catch (const std::invalid_argument&) {
    return FuzzOutcome::kGeneratorRefused;
  } catch (const ir::ModelError&) {
    return FuzzOutcome::kGeneratorRefused;
  }
  return FuzzOutcome::kGenerated;
}

}  // namespace mbfe::fuzz
