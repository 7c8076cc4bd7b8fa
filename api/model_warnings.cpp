#include "api/model_warnings.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <cstdio>
#include <string>

namespace mbfe {

namespace {

/// "210", "2.1e11", "1e9": three significant digits, no '+' or leading zeros
/// in the exponent.
std::string short_number(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  std::string s = buf;
  const auto e = s.find('e');
  if (e == std::string::npos) return s;
  return s.substr(0, e) + "e" + std::to_string(std::stoi(s.substr(e + 1)));
}

bool inside(double v, PlausibleRange r) { return v >= r.low && v <= r.high; }

/// What a value outside `range` is, against a reference value: "is 1e9 times
/// below steel's 2.1e11 Pa: GPa entered as Pa?".
std::string judged(double v, PlausibleRange range, double reference, const std::string& reference_name,
                   const std::string& unit, const std::vector<std::pair<double, std::string>>& factors) {
  std::string text = v < range.low ? " is " + short_number(reference / v) + " times below " : " is " +
                                                                                                  short_number(v / reference) +
                                                                                                  " times above ";
  text += reference_name + "'s " + short_number(reference) + " " + unit;
  for (const auto& [factor, mistake] : factors) {
    if ((v < range.low && factor > 1.0 && inside(v * factor, range)) ||
        (v > range.high && factor < 1.0 && inside(v * factor, range)))
      return text + ": " + mistake + "?";
  }
  return text + " (plausible: " + short_number(range.low) + " to " + short_number(range.high) + " " + unit + ")";
}

std::string where(const ir::Model& model, ir::SourceLoc loc) {
  std::string w = model.source_path;
  if (loc.line > 0) w += ":" + std::to_string(loc.line) + ":" + std::to_string(loc.column);
  return w + ": warning: ";
}


/// Whether `body` and every body it carries have no mass and no inertia.
bool carries_no_mass(const ir::Model& model, std::size_t body) {
  const ir::Body& b = model.bodies[body];
  for (double v : b.inertia3)
    if (v != 0.0) return false;
  if (b.mass != 0.0 || b.inertia != 0.0) return false;
  for (std::size_t k = 0; k < model.bodies.size(); ++k)
    if (model.bodies[k].parent == static_cast<int>(body) && !carries_no_mass(model, k)) return false;
  return true;
}

}  // namespace

std::vector<std::string> model_warnings(const ir::Model& model) {
  std::vector<std::string> out;
  // A free joint that moves no mass: M is singular, the run cannot start.
  for (std::size_t k = 0; k < model.bodies.size(); ++k) {
    const ir::Body& b = model.bodies[k];
    if (!b.joint.motion && carries_no_mass(model, k))
      out.push_back(where(model, b.loc) + "body '" + b.name +
                    "': its joint moves no mass (it and every body it carries have mass 0 and inertia 0), so its "
                    "acceleration is not defined: give it a mass or inertia, or drive the joint");
  }
  constexpr double kSteelE = 2.1e11, kSteelDensity = 7850.0, kSpan = 20.0;
  for (const ir::Beam& b : model.beams) {
    const std::string head = where(model, b.loc) + "beam '" + b.name + "': ";
    if (!inside(b.youngs_modulus, kPlausibleYoungsModulus))
      out.push_back(head + "E = " + short_number(b.youngs_modulus) + " Pa" +
                    judged(b.youngs_modulus, kPlausibleYoungsModulus, kSteelE, "steel", "Pa",
                           {{1e9, "GPa entered as Pa"}, {1e6, "MPa (N/mm^2) entered as Pa"},
                            {1e3, "kPa entered as Pa"}, {1e-3, "Pa entered as kPa"}}));
    if (!inside(b.density, kPlausibleDensity))
      out.push_back(head + "density = " + short_number(b.density) + " kg/m^3" +
                    judged(b.density, kPlausibleDensity, kSteelDensity, "steel", "kg/m^3",
                           {{1e3, "t/m^3 or g/cm^3 entered as kg/m^3"}, {1e12, "t/mm^3 (N, mm, s units) entered as kg/m^3"},
                            {1e-3, "g/m^3 entered as kg/m^3"}}));
    if (std::abs(b.angle) > 2.0 * M_PI)
      out.push_back(head + "angle = " + short_number(b.angle) + " rad is more than a turn: degrees entered as rad? (" +
                    short_number(b.angle) + " degrees is " + short_number(b.angle * M_PI / 180.0) + " rad)");
    if (!inside(b.length, kPlausibleBeamLength))
      out.push_back(head + "length = " + short_number(b.length) + " m" +
                    judged(b.length, kPlausibleBeamLength, kSpan, "a railway span", "m",
                           {{1e-3, "mm entered as m"}, {1e-2, "cm entered as m"}, {1e3, "km entered as m"}}));
  }
  return out;
}

std::vector<FreeFall> free_falls(const ir::Model& model, const runtime::SimulationReport& report) {
  std::vector<FreeFall> out;
  if (!report.message.empty()) return out;
  std::vector<const ir::Contact*> springs;  // the tallies follow them, in file order
  for (const ir::Contact& c : model.contacts)
    if (c.type == ir::ContactType::kSliderSpring) springs.push_back(&c);
  if (springs.size() != report.springs.size() || springs.empty()) return out;
  // The structure's size: the largest distance between two beam ends.
  std::vector<ir::Vec2> ends;
  for (const ir::Beam& b : model.beams) {
    ends.push_back(b.origin);
    ends.push_back({b.origin[0] + b.length * std::cos(b.angle), b.origin[1] + b.length * std::sin(b.angle)});
  }
  double size = 0.0;
  for (const ir::Vec2& a : ends)
    for (const ir::Vec2& b : ends) size = std::max(size, std::hypot(a[0] - b[0], a[1] - b[1]));
  const double g = std::hypot(model.gravity[0], model.gravity[1]);
  for (std::size_t body = 0; body < model.bodies.size(); ++body) {
    std::optional<FreeFall> nearest;
    bool touched = false;
    for (std::size_t k = 0; k < springs.size(); ++k) {
      if (springs[k]->body != static_cast<int>(body)) continue;
      const runtime::SpringContactTally& tally = report.springs[k];
      touched = touched || tally.touched;
      if (!std::isfinite(tally.end[0]) || !std::isfinite(tally.end[1])) continue;
      // The distance from the point to the beam's undeformed segment.
      const ir::Beam& beam = model.beams[static_cast<std::size_t>(springs[k]->beam)];
      const double ca = std::cos(beam.angle), sa = std::sin(beam.angle);
      const double dx = tally.end[0] - beam.origin[0], dy = tally.end[1] - beam.origin[1];
      const double s = std::clamp(dx * ca + dy * sa, 0.0, beam.length);
      const double distance = std::hypot(dx - s * ca, dy - s * sa);
      if (nearest && nearest->distance <= distance) continue;
      FreeFall f;
      f.body = model.bodies[body].name;
      f.point = model.bodies[body].points[static_cast<std::size_t>(springs[k]->point)].name;
      f.beam = beam.name;
      f.distance = distance;
      f.size = size;
      f.fallen = g > 0.0 ? ((tally.end[0] - tally.start[0]) * model.gravity[0] +
                            (tally.end[1] - tally.start[1]) * model.gravity[1]) / g
                         : 0.0;
      f.t = report.run.t;
      nearest = f;
    }
    if (!touched && nearest && nearest->distance > size) out.push_back(*nearest);
  }
  return out;
}

std::vector<std::string> run_warnings(const ir::Model& model, const runtime::SimulationReport& report) {
  std::vector<std::string> out;
  // A run cut short (diverged at its first steps, interrupted) did not give
  // its contacts the whole run to touch.
  if (!report.message.empty()) return out;
  for (const FreeFall& f : free_falls(model, report))
    out.push_back("body '" + f.body + "' fell through space: none of its contacts touched a beam, and at t = " +
                  short_number(f.t) + " s its point '" + f.point + "' is " + short_number(f.distance) +
                  " m from beam '" + f.beam + "', farther than the structure's size (" + short_number(f.size) +
                  " m); it fell " + short_number(f.fallen) + " m: check the beams' origin and angle");
  // The tallies follow the slider_spring contacts in file order.
  std::vector<const ir::Contact*> springs;
  for (const ir::Contact& c : model.contacts)
    if (c.type == ir::ContactType::kSliderSpring) springs.push_back(&c);
  if (springs.size() != report.springs.size()) return out;
  for (std::size_t k = 0; k < springs.size(); ++k) {
    const runtime::SpringContactTally& tally = report.springs[k];
    if (tally.touched) continue;
    bool body_touched = false;
    for (std::size_t j = 0; j < springs.size(); ++j)
      if (springs[j]->body == springs[k]->body && report.springs[j].touched) body_touched = true;
    if (tally.seen || !body_touched)
      out.push_back("contact '" + tally.name + "' never touched the beam during the run" +
                    (tally.seen ? std::string() : " (its point was never over the beam)"));
  }
  return out;
}

}  // namespace mbfe
