// Warnings about input that is valid but likely not what was meant: a beam's
// Young's modulus, density or length off by a unit factor, an angle of more
// than a turn (degrees entered as radians), a free joint that moves no mass (docs/robustness.md,
// "Warnings"), and after a run the slider_spring contacts that never touched
// their beam. A warning never stops a run; `mbfe simulate` prints each on
// stderr and lists them under "warnings" in the run's sidecar.
#pragma once

#include <string>
#include <vector>

#include "ir/model.h"
#include "runtime/simulation/simulation_types.h"

namespace mbfe {

/// Plausible ranges of the beams' material and geometry (SI units); a value
/// outside is named, with the unit mistake that would explain it when a
/// factor of 1e3, 1e6 or 1e9 brings it into the range.
struct PlausibleRange {
  double low, high;
};
/// Pa: rubber (1e6 and more) to above diamond (1.2e12); steel in MPa (2.1e5)
/// falls below.
inline constexpr PlausibleRange kPlausibleYoungsModulus{1e6, 1.5e12};
/// kg/m^3: light timber and foams (~100), to the densest metals (osmium
/// 22,590) with a margin; a density that smears ballast or equipment over a
/// section stays far inside.
inline constexpr PlausibleRange kPlausibleDensity{50.0, 3e4};
/// m: a 1 mm specimen to a 10 km line.
inline constexpr PlausibleRange kPlausibleBeamLength{1e-3, 1e4};

/// One line per body whose free joint moves no mass (it and every body it
/// carries have mass 0 and inertia 0), then one per implausible value, `file:line:col: warning: beam 'deck': E =
/// 210 Pa is 1e9 times below steel's 2.1e11 Pa: GPa entered as Pa?`, in
/// file order; empty for a plausible model.
std::vector<std::string> model_warnings(const ir::Model& model);

/// A body that fell through space (docs/robustness.md, "A vehicle falling
/// through space"): in a completed run none of its slider_spring contacts
/// touched a beam, and at the run's end the contact point nearest to a beam
/// of its contacts is farther from that beam (its undeformed segment) than the
/// structure's size, the largest distance between two ends of the model's
/// beams.
struct FreeFall {
  std::string body, point, beam;  // the body, its contact point nearest a beam, that beam
  double distance = 0.0;          // m, from the point to the beam at the end of the run
  double size = 0.0;              // m, the structure's size
  double fallen = 0.0;            // m, how far the point moved along gravity during the run (0 without gravity)
  double t = 0.0;                 // s, the end of the run
};

/// The bodies of a completed run that fell through space (FreeFall), in
/// model order; none for a run that diverged, failed or was interrupted.
std::vector<FreeFall> free_falls(const ir::Model& model, const runtime::SimulationReport& report);

/// The warnings of a completed run (none for a run that diverged, failed or
/// was interrupted): "body 'wheel' fell through space: ..." for each FreeFall, then "contact 'X' never touched the beam
/// during the run" for each slider_spring contact that never touched its
/// beam while its point was over it, or whose body touched no beam at all
/// during the run (a vehicle falling past the bridge). Not for a contact
/// whose point never came over its beam while another contact of its body
/// carried it (the exit beam of a short run).
std::vector<std::string> run_warnings(const ir::Model& model, const runtime::SimulationReport& report);

}  // namespace mbfe
