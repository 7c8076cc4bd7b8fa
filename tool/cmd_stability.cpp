// `mbfe stability MODEL.yaml [--json]`: the largest stable step of every
// integrator for the original and the adjusted model (beam models; coupled
// models through their linearised, partitioned system at the initial state;
// rigid-only models through their linearised ODE at the initial state, or at
// the static equilibrium when the initial state is not one).
#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "api/mbfe.h"
#include "runtime/coupled/tangent_spectrum.h"
#include "runtime/simulation/assembled_model.h"
#include "tool/cli_args.h"
#include "tool/commands.h"
#include "tool/model_warnings_notice.h"
#include "api/json_text.h"
#include "tool/linearization_notice.h"

namespace mbfe::tool {

namespace {

constexpr const char* kHelp = R"(Usage: mbfe stability MODEL.yaml [--set PATH=VALUE] [--json]

The largest stable step of each integrator, from the eigenvalues of the state
matrix (eq (28)) and each method's region of absolute stability, for the
original model (Rayleigh damping) and the adjusted one (each beam's
`adjustment:` block; see docs/damping-adjustment.md). For a coupled model
(bodies, beams and contacts) the eigenvalues are those of the linearised,
partitioned system (eqs (16)-(17)) at the model's initial state (see
docs/contacts.md); without constraint contacts, those of the model linearised
from its own tangents: every one up to 1,200 states, beyond that the 8
fastest and 12 slowest by Arnoldi, and between them the beams' own modes,
uncoupled (the report says so; forward Euler's and AB2's limits, set in that
middle, are then estimates). For a rigid-only model (bodies, no beams) they are those
of y' = f(t, y), y = [q; q'], f = [q'; M(q)^-1 (Q - F)], linearised at the
initial state: a local estimate (the limits change as the motion moves away
from that state), with no adjusted model. With closed loops, the ODE that is
integrated: the independent coordinates and their rates (the dependent ones
closed by Newton); with spherical or free joints, three rotation increments
per quaternion (docs/partitioning.md). Away from an equilibrium (rigid or
coupled models) some eigenvalues have Re > 0 (the motion itself leaves that
state); they are counted and left out, the limits come from the others. A
rigid model released away from equilibrium swings about it: it is linearised
at the static equilibrium its damped motion settles into instead (the report
says so). A "none" is explained under the table (an undamped mode, for forward
Euler and AB2).

  forward_euler      |1 + h lambda| <= 1: h < -2 Re(lambda) / |lambda|^2
  rk4                |R(h lambda)| <= 1 along each eigenvalue's ray (2.785/|lambda| on the real axis)
  explicit_midpoint  two-step y_n = y_{n-2} + 2 h f_{n-1}: "none" as soon as one
                     eigenvalue has Re < 0 (its parasitic root leaves the unit circle)
  ab2                Adams-Bashforth 2 (boundary locus + root condition)
  backward_euler, trapezoid, bdf2, generalized_alpha
                     A-stable: "unconditional"
A limit is the largest H such that every step h <= H is stable; "none" means
no positive step is.

Options:
  --json   print {"original": {"forward_euler": h, "rk4": h, ...},
           "adjusted": {...}} (steps in s; the strings "unconditional" and
           "none" where they apply; "adjusted" is null when no beam has an
           adjustment block; "warnings": the lines about likely unit
           mistakes also printed on stderr, docs/robustness.md)
  --set PATH=VALUE  replace a value of the model file first (repeatable; as
           mbfe simulate --set)

Example:
  mbfe stability models/paper_beam.yaml
  mbfe stability models/paper_beam.yaml --json
  mbfe stability models/paper_platform.yaml
  mbfe stability models/double_pendulum.yaml
  mbfe stability models/bridge_moving_mass.yaml --set beams.deck.adjustment.omega_limit=800
)";

nlohmann::json limits_json(const std::vector<runtime::StepLimitRow>& rows, bool adjusted) {
  nlohmann::json out = nlohmann::json::object();
  for (const runtime::StepLimitRow& row : rows) {
    const runtime::StepLimit& lim = adjusted ? *row.adjusted : row.original;
    if (lim.kind == runtime::StepLimit::Kind::kFinite)
      out[row.integrator.name] = lim.h;
    else
      out[row.integrator.name] = lim.text();
  }
  return out;
}

std::string cell(const runtime::StepLimit& lim) {
  if (lim.kind != runtime::StepLimit::Kind::kFinite) return lim.text();
  return lim.text() + " s";
}

}  // namespace

int cmd_stability(const Args& args) {
  const ParsedArgs parsed(args, {"set"}, {"json", "help"});
  if (parsed.has("help")) {
    std::cout << kHelp;
    return 0;
  }
  if (parsed.positional().size() != 1)
    throw UsageError("expected one MODEL.yaml, got " + std::to_string(parsed.positional().size()) +
                     " arguments (see --help)");
  const std::string& path = parsed.positional()[0];
  LoadOptions load;
  load.overrides = model_overrides(parsed);
  const Model model = Model::load(path, load);
  const std::vector<std::string> warnings = announce_model_warnings(model.ir());
  const runtime::ModelKind kind = model.kind();
  const bool coupled = kind == runtime::ModelKind::kCoupled;
  const bool rigid = kind == runtime::ModelKind::kRigid;
  const bool any_adjustment = model.assembled().has_adjustment();
  if (coupled) {
    const int coordinates = static_cast<int>(model.ir().bodies.size()) + model.assembled().beams().dof;
    if (coordinates <= runtime::kMaxLinearizedCoordinates && coordinates > kLinearizationNoticeCoordinates &&
        !runtime::linearized_from_tangents(model.assembled()))
      std::cerr << linearization_notice("stability", coordinates, any_adjustment ? 2 : 1);
  }
  const runtime::ModelSpectrum original_spectrum = model.spectrum(false);
  runtime::ModelSpectrum adjusted_spectrum;
  if (any_adjustment) adjusted_spectrum = model.spectrum(true);
  const runtime::StateSpectrum& original = original_spectrum.limiting;
  const runtime::StateSpectrum& adjusted = adjusted_spectrum.limiting;
  const int dof = original_spectrum.coordinates;
  const int growing = std::max(original_spectrum.growing, adjusted_spectrum.growing);
  const std::vector<runtime::StepLimitRow> limits =
      runtime::step_limit_table(original_spectrum, any_adjustment ? &adjusted_spectrum : nullptr);

  if (parsed.has("json")) {
    nlohmann::json root;
    root["original"] = limits_json(limits, false);
    root["adjusted"] = any_adjustment ? limits_json(limits, true) : nlohmann::json(nullptr);
    root["warnings"] = warnings_json(warnings);
    std::cout << json_text(root, 2) << "\n";
    return 0;
  }
  auto fastest = [](const runtime::StateSpectrum& s) {
    if (s.eigenvalues.empty()) return std::string("(none)");
    std::ostringstream o;
    o << std::setprecision(7) << s.eigenvalues.back().real();
    if (s.eigenvalues.back().imag() != 0.0) o << " +- " << std::abs(s.eigenvalues.back().imag()) << "i";
    return o.str();
  };
  if (rigid && original_spectrum.at_equilibrium)
    std::cout << "model '" << model.ir().name << "': rigid, " << dof << " DOF, " << 2 * dof
              << " state eigenvalues of the ODE linearised at its static equilibrium\n"
              << "  (the initial state is not one: " << original_spectrum.growing_at_start
              << " eigenvalues there have Re > 0, and their mirror images would set limits the motion "
                 "does not keep; released from there it swings about the equilibrium, whose modes set "
                 "the limits. Still a local estimate: large swings change them. A rigid model has no "
                 "damping adjustment)\n";
  else if (rigid)
    std::cout << "model '" << model.ir().name << "': rigid, " << dof << " DOF, " << 2 * dof
              << " state eigenvalues of the ODE linearised at the initial state\n"
              << "  (a local estimate: the limits change as the motion moves away from that state; "
                 "a rigid model has no damping adjustment)\n";
  if (coupled)
    std::cout << "model '" << model.ir().name << "': linearised, partitioned coupled system at the initial state, " << 2 * dof
              << " state eigenvalues (" << dof << " independent coordinates)\n";
  else if (!rigid)
    std::cout << "model '" << model.ir().name << "': " << dof << " DOF, " << 2 * dof << " state eigenvalues\n";
  if (coupled && growing > 0)
    std::cout << "  (a local estimate: the limits change as the motion moves away from the initial state)\n";
  if (growing > 0)
    std::cout << "  " << growing << " eigenvalue" << (growing == 1 ? " has" : "s have")
              << " Re > 0: the motion leaves the initial state (not an equilibrium), and every "
                 "method follows that growth; the limits are those of the others\n";
  if (!original_spectrum.full.complete) {
    std::cout << "  (the " << runtime::kFastestEigenvalues << " fastest and " << runtime::kSlowestEigenvalues
              << " slowest eigenvalues of each, by Arnoldi";
    if (original_spectrum.middle_from_beams > 0 || adjusted_spectrum.middle_from_beams > 0)
      std::cout << "; between them the beams' own modes, uncoupled (" << original_spectrum.middle_from_beams
                << (any_adjustment ? " original, " + std::to_string(adjusted_spectrum.middle_from_beams) + " adjusted"
                                   : std::string())
                << " eigenvalues), which set forward Euler's and AB2's limits to within the coupling's shift)\n";
    else
      std::cout << ": they set the limits but for a lightly damped mode in the middle of the spectrum, which "
                   "could lower forward Euler's and AB2's)\n";
  }
  std::cout << "  original: fastest eigenvalue " << fastest(original) << " 1/s\n";
  if (any_adjustment)
    std::cout << "  adjusted: fastest eigenvalue " << fastest(adjusted) << " 1/s\n";
  else if (!rigid)
    std::cout << "  (no beam has an adjustment block: only the original model)\n";
  std::cout << "\nlargest stable step\n";
  std::cout << std::left << std::setw(20) << "integrator" << std::setw(18) << "original"
            << (any_adjustment ? "adjusted" : "") << "\n";
  for (const runtime::StepLimitRow& row : limits) {
    const runtime::StepLimit& o = row.original;
    std::cout << std::left << std::setw(20) << row.integrator.name << std::setw(18) << cell(o);
    if (row.adjusted) {
      const runtime::StepLimit& a = *row.adjusted;
      std::cout << std::setw(18) << cell(a);
      if (o.kind == runtime::StepLimit::Kind::kFinite && a.kind == runtime::StepLimit::Kind::kFinite) {
        char buf[32];
        std::snprintf(buf, sizeof buf, "(%.0fx)", a.h / o.h);
        std::cout << buf;
      }
    }
    std::cout << "\n";
  }
  // Say why a method has no stable step: an undamped mode for forward Euler
  // (its region touches the imaginary axis only at 0) and for every method
  // off that axis, a damped one for the explicit midpoint rule.
  for (const runtime::StepLimitRow& row : limits) {
    if (row.original.kind != runtime::StepLimit::Kind::kNone) continue;
    const std::complex<double> l = row.original.critical;
    if (l.real() > 0.0) continue;  // counted above as growing
    std::cout << "  " << row.integrator.name << " none: ";
    if (l.real() == 0.0) {
      std::cout << "an undamped mode (lambda = +-" << std::setprecision(5) << std::abs(l.imag())
                << "i 1/s): the method's stability region touches the imaginary axis only at 0, so every "
                   "step makes it grow";
      if (row.integrator.kind == runtime::IntegratorKind::kForwardEuler)
        std::cout << " (by sqrt(1 + (h omega)^2) a step: it doubles in about 1.4 / (h omega^2) s)";
    } else {
      std::cout << "a damped mode (lambda = " << std::setprecision(5) << l.real() << " +- " << std::abs(l.imag())
                << "i 1/s) lies off the imaginary axis, the only part of its stability region";
    }
    std::cout << "\n";
  }
  return 0;
}

}  // namespace mbfe::tool
