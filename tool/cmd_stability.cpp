// `mbfe stability MODEL.yaml [--json]`: the largest stable step of every
// integrator for the original and the adjusted model (beam models; coupled
// models through their linearised, partitioned system at the initial state).
#include <cstdio>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "cli_args.h"
#include "commands.h"
#include "coupled_model.h"
#include "damping/beam_model.h"
#include "multibody/multibody_errors.h"
#include "model/parse_model.h"
#include "stability/step_limits.h"

namespace mbfe::tool {

namespace {

constexpr const char* kHelp = R"(Usage: mbfe stability MODEL.yaml [--json]

The largest stable step of each integrator, from the eigenvalues of the state
matrix (eq (28)) and each method's region of absolute stability, for the
original model (Rayleigh damping) and the adjusted one (each beam's
`adjustment:` block; see docs/damping-adjustment.md). For a coupled model
(bodies, beams and contacts) the eigenvalues are those of the linearised,
partitioned system (eqs (16)-(17)) at the model's initial state (see
docs/contacts.md).

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
           adjustment block)

Example:
  mbfe stability models/paper_beam.yaml
  mbfe stability models/paper_beam.yaml --json
  mbfe stability models/paper_platform.yaml
)";

nlohmann::json limits_json(const runtime::StateSpectrum& spectrum) {
  nlohmann::json out = nlohmann::json::object();
  for (const auto& m : runtime::advisor_integrators()) {
    const runtime::StepLimit lim = runtime::stable_step(m, spectrum.eigenvalues);
    if (lim.kind == runtime::StepLimit::Kind::kFinite)
      out[m.name] = lim.h;
    else
      out[m.name] = lim.text();
  }
  return out;
}

std::string cell(const runtime::StepLimit& lim) {
  if (lim.kind != runtime::StepLimit::Kind::kFinite) return lim.text();
  return lim.text() + " s";
}

}  // namespace

int cmd_stability(const Args& args) {
  const ParsedArgs parsed(args, {}, {"json", "help"});
  if (parsed.has("help")) {
    std::cout << kHelp;
    return 0;
  }
  if (parsed.positional().size() != 1)
    throw UsageError("expected one MODEL.yaml, got " + std::to_string(parsed.positional().size()) +
                     " arguments (see --help)");
  const std::string& path = parsed.positional()[0];
  const model::Model m = model::load_model_file(path);
  if (m.beams.empty()) {
    std::cerr << "mbfe stability: " << path << ": model '" << m.name << "' has no beams"
              << (m.bodies.empty() ? "" : " (the stability advisor handles beam and coupled models)") << "\n";
    return 2;
  }
  // Beam models: the beams' modal spectra. Coupled models (bodies + beams):
  // the linearised, partitioned system at the initial state
  // (runtime/multibody/linearization.h).
  const bool coupled = is_coupled(m);
  runtime::StateSpectrum original, adjusted;
  bool any_adjustment = false;
  int dof = 0;
  try {
    if (coupled) {
      for (const auto& b : m.beams)
        any_adjustment = any_adjustment || (b.adjustment.present && b.adjustment.policy != model::AdjustmentPolicy::kNone);
      original = coupled_spectrum(m, false);
      if (any_adjustment) adjusted = coupled_spectrum(m, true);
      dof = static_cast<int>(original.eigenvalues.size()) / 2;
    } else {
      runtime::BeamModel beams = runtime::analyse_beams(m);
      original = beams.original;
      adjusted = beams.adjusted;
      any_adjustment = beams.any_adjustment;
      dof = beams.dof;
    }
  } catch (const std::invalid_argument& e) {
    std::cerr << "mbfe stability: " << path << ": " << e.what() << "\n";
    return 2;
  } catch (const runtime::ContactError& e) {
    std::cerr << "mbfe stability: " << path << ": at the initial state: " << e.what() << "\n";
    return 2;
  }

  if (parsed.has("json")) {
    nlohmann::json root;
    root["original"] = limits_json(original);
    root["adjusted"] = any_adjustment ? limits_json(adjusted) : nlohmann::json(nullptr);
    std::cout << root.dump(2) << "\n";
    return 0;
  }
  auto fastest = [](const runtime::StateSpectrum& s) {
    std::ostringstream o;
    o << std::setprecision(7) << s.eigenvalues.back().real();
    if (s.eigenvalues.back().imag() != 0.0) o << " +- " << std::abs(s.eigenvalues.back().imag()) << "i";
    return o.str();
  };
  if (coupled)
    std::cout << "model '" << m.name << "': linearised, partitioned coupled system at the initial state, " << 2 * dof
              << " state eigenvalues (" << dof << " independent coordinates)\n";
  else
    std::cout << "model '" << m.name << "': " << dof << " DOF, " << 2 * dof << " state eigenvalues\n";
  std::cout << "  original: fastest eigenvalue " << fastest(original) << " 1/s\n";
  if (any_adjustment)
    std::cout << "  adjusted: fastest eigenvalue " << fastest(adjusted) << " 1/s\n";
  else
    std::cout << "  (no beam has an adjustment block: only the original model)\n";
  std::cout << "\nlargest stable step\n";
  std::cout << std::left << std::setw(20) << "integrator" << std::setw(18) << "original"
            << (any_adjustment ? "adjusted" : "") << "\n";
  for (const auto& integ : runtime::advisor_integrators()) {
    const auto o = runtime::stable_step(integ, original.eigenvalues);
    std::cout << std::left << std::setw(20) << integ.name << std::setw(18) << cell(o);
    if (any_adjustment) {
      const auto a = runtime::stable_step(integ, adjusted.eigenvalues);
      std::cout << std::setw(18) << cell(a);
      if (o.kind == runtime::StepLimit::Kind::kFinite && a.kind == runtime::StepLimit::Kind::kFinite) {
        char buf[32];
        std::snprintf(buf, sizeof buf, "(%.0fx)", a.h / o.h);
        std::cout << buf;
      }
    }
    std::cout << "\n";
  }
  return 0;
}

}  // namespace mbfe::tool
