// A two-span catenary small enough to check by independent paths: two
// tensioned wires of 40 elements, six slack droppers held at a profile,
// spring supports, clamp masses and a pantograph head driven along at 20 m/s
// pressing from below (docs/catenary.md). Shared by the tests of links,
// static starts and the joined-structure adjustment.
#pragma once

#include <string>

namespace mbfe::test {

inline const std::string kTwoSpanCatenary = R"yaml(model: two_span_check
gravity: [0, -9.81]
bodies:
  - name: carriage
    parent: ground
    joint: {type: prismatic, axis: [1, 0], at: [0, 0], motion: "1.0 + 20*t"}
    mass: 10.0
    inertia: 0
  - name: head
    parent: carriage
    joint: {type: prismatic, axis: [0, 1], at: [0, 0]}
    mass: 7.0
    inertia: 0
    points: {strip: [0, 0]}
loads:
  - {type: spring_damper, joint: head, stiffness: 5000, damping: 50, rest: 0.0}
  - {type: force, body: head, value: [0, 200.0]}
beams:
  - name: messenger
    origin: [0, 1.2]
    length: 20.0
    elements: 40
    section: {area: 1.2e-4, inertia: 1.0e-9}
    material: {youngs_modulus: 1.1e11, density: 8900}
    tension: 16000
    supports: [{at: 0, type: pinned}, {at: 10, type: pinned}, {at: 20, type: pinned}]
    damping: {rayleigh: {alpha: 0.0, beta: 1.0e-4}}
  - name: contact_wire
    origin: [0, 0]
    length: 20.0
    elements: 40
    section: {area: 1.5e-4, inertia: 1.6e-9}
    material: {youngs_modulus: 1.2e11, density: 9000}
    tension: 20000
    supports:
      - {at: 0, type: spring, stiffness: 2.0e6, mass: 1.0}
      - {at: 10, type: spring, stiffness: 2.0e6, mass: 1.0}
      - {at: 20, type: spring, stiffness: 2.0e6, mass: 1.0}
    masses: [{at: 2, mass: 0.195}, {at: 5, mass: 0.195}, {at: 8, mass: 0.195}, {at: 12, mass: 0.195}, {at: 15, mass: 0.195}, {at: 18, mass: 0.195}]
    damping: {rayleigh: {alpha: 0.0, beta: 1.0e-4}}
links:
  - {name: d1, a: {beam: contact_wire, at: 2}, b: {beam: messenger, at: 2}, stiffness: 1.0e5, slack: true, hold: -0.002}
  - {name: d2, a: {beam: contact_wire, at: 5}, b: {beam: messenger, at: 5}, stiffness: 1.0e5, slack: true, hold: -0.003}
  - {name: d3, a: {beam: contact_wire, at: 8}, b: {beam: messenger, at: 8}, stiffness: 1.0e5, slack: true, hold: -0.002}
  - {name: d4, a: {beam: contact_wire, at: 12}, b: {beam: messenger, at: 12}, stiffness: 1.0e5, slack: true, hold: -0.002}
  - {name: d5, a: {beam: contact_wire, at: 15}, b: {beam: messenger, at: 15}, stiffness: 1.0e5, slack: true, hold: -0.003}
  - {name: d6, a: {beam: contact_wire, at: 18}, b: {beam: messenger, at: 18}, stiffness: 1.0e5, slack: true, hold: -0.002}
contacts:
  - {name: strip_contact, type: slider_spring, body: head, point: strip, beam: contact_wire, stiffness: 50000, damping: 0, unilateral: true, side: below}
initial: {static: true}
simulation: {integrator: rk4, step: 1.0e-5, t_end: 1.0}
)yaml";

/// kTwoSpanCatenary with `block` as both wires' adjustment, e.g.
/// "{omega_limit: 2000.0, margin: 0.1}".
inline std::string with_wire_adjustment(const std::string& block) {
  std::string text = kTwoSpanCatenary;
  const std::string damping = "damping: {rayleigh: {alpha: 0.0, beta: 1.0e-4}}";
  for (std::size_t at = text.find(damping); at != std::string::npos; at = text.find(damping, at + 1))
    text.insert(at + damping.size(), "\n    adjustment: " + block);
  return text;
}

/// `text` (kTwoSpanCatenary or a variant) with a force of 300 N running
/// along the messenger at 15 m/s: a load that changes with time.
inline std::string with_messenger_moving_load(std::string text) {
  const std::string anchor = "    tension: 16000\n";
  text.insert(text.find(anchor) + anchor.size(),
              "    loads: [{type: moving, value: -300.0, speed: 15.0, start: 0.0, t0: 0.0}]\n");
  return text;
}

}  // namespace mbfe::test
