// simulate() for a coupled model (bodies, beams and contacts), eqs (14)-(17)
// of the paper. The partitioned formulation (default) integrates
// y = [u; q_c; u'; q_c'] with the dependent rigid coordinates closed by Newton
// at every evaluation; the augmented one y = [q_b; q_c; q_b'; q_c'] with the
// multipliers (a cross-check; |Phi| drifts).
#include <algorithm>
#include <cmath>
#include <memory>
#include <sstream>

#include "runtime/multibody/augmented_system.h"
#include "runtime/multibody/coordinate_partitioning.h"
#include "runtime/multibody/coupled_implicit_system.h"
#include "runtime/multibody/linearization.h"
#include "runtime/multibody/multibody_errors.h"
#include "runtime/multibody/split_beam_system.h"
#include "runtime/simulation/invalid_input.h"
#include "runtime/simulation/run_diagnosis.h"
#include "runtime/simulation/runs.h"
#include "runtime/simulation/static_start.h"
#include "runtime/simulation/time_expressions.h"

namespace mbfe::runtime::detail {

namespace {

// Coupled models up to this many coordinates find their static start with
// the dense difference Jacobian (tested longest); larger ones with the sparse tangent.
constexpr int kDenseStaticLimit = 600;

// A projected coordinate that moved less than this (relative) moved by round-off.
constexpr double kProjectionNoise = 1e-12;

/// Multiplier columns, stacked like the constraint rows: lambda_<contact>_1/_2
/// for a pin, lambda_<contact> for a slider_pin.
std::vector<std::string> multiplier_names(const ir::Model& model) {
  std::vector<std::string> out;
  for (const ir::Contact& c : model.contacts) {
    if (!c.is_constraint()) continue;  // a spring: force_<contact>, after the multipliers
    if (c.type == ir::ContactType::kPin) {
      out.push_back("lambda_" + c.name + "_1");
      out.push_back("lambda_" + c.name + "_2");
    } else {
      out.push_back("lambda_" + c.name);
    }
  }
  return out;
}

/// "link1 by +0.0012 rad, beam_w3 by -1e-05 m": the coordinates the projection
/// onto the contacts moved (beyond round-off), for the notice.
std::string projection_moves(const AssembledModel& model, const std::vector<std::string>& names,
                             const Eigen::VectorXd& before, const Eigen::VectorXd& after) {
  std::ostringstream os;
  os.precision(6);
  const int nb = static_cast<int>(model.ir().bodies.size());
  for (Eigen::Index i = 0; i < before.size(); ++i) {
    const double moved = after[i] - before[i];
    if (!(std::abs(moved) > kProjectionNoise * (1.0 + std::abs(before[i])))) continue;
    if (os.tellp() > 0) os << ", ";
    os << names[i] << " by " << std::showpos << moved << std::noshowpos << " "
       << (i < nb ? coordinate_unit(model.ir().bodies[i]) : std::string(names[i].find("_dw") != std::string::npos ? "rad" : "m"));
  }
  return os.str();
}

/// The integrators that step the index-3 form (coupled_implicit_system.h).
bool second_order_implicit(const IntegratorSpec& spec) {
  if (spec.kind == IntegratorKind::kBackwardEuler || spec.kind == IntegratorKind::kTrapezoid ||
      spec.kind == IntegratorKind::kGeneralizedAlpha)
    return true;
  return spec.kind == IntegratorKind::kLinearMultistep && spec.name == "bdf2";
}

}  // namespace

SimulationReport run_coupled(const AssembledModel& model, const SimulationRequest& request,
                             SimulationObserver& observer) {
  const bool index3 = second_order_implicit(request.integrator);
  // The adjustment exists to widen explicit steps: an implicit integrator runs
  // the original model unless --adjust on asks otherwise (and is refused).
  const bool adjusted = index3 && !request.adjust ? false : model.resolve_adjusted(request.adjust);
  // The index-3 system takes low-rank adjusted beams (the static start uses
  // it), but each refresh of its matrix costs one sparse solve per kept mode
  // and Newton contracts slowly on them: the two-span catenary's 1.4 s took
  // 190 s against 3 s of adjusted RK4. Not offered until that is understood.
  if (index3 && adjusted)
    throw InvalidInput(model.ir().source_path + ": --adjust on with " + request.integrator.name +
                       ": the implicit integrators run the original model of a coupled model (the adjustment "
                       "exists for explicit steps); use --adjust off, or an explicit integrator such as rk4");
  const bool augmented = request.formulation == CoupledFormulation::kAugmented;
  const std::shared_ptr<CoupledDynamics> dynamics = model.make_dynamics(adjusted);
  const int nb = dynamics->nb();
  const int n = dynamics->n();
  const int m = dynamics->m();
  const std::vector<BeamProbe> probes = resolve_probes(request.probes, model.ir(), model.beams());

  std::unique_ptr<CoupledSystem> system;
  // Low-rank adjusted beams step in split coordinates when nothing is
  // partitioned: the same ODE, without passes over their kept modes.
  const bool split = !index3 && !augmented && adjusted && dynamics->split_low_rank_beams();
  if (split) {
    system = std::make_unique<SplitBeamSystem>(dynamics);
  } else if (index3) {
    try {
      system = std::make_unique<CoupledImplicitSystem>(dynamics);
    } catch (const std::invalid_argument& e) {
      throw InvalidInput(model.ir().source_path + ": " + e.what());
    }
  } else if (augmented)
    system = std::make_unique<AugmentedSystem>(dynamics);
  else
    system = std::make_unique<PartitionedSystem>(dynamics);
  Eigen::VectorXd q0, qd0, y0;
  model.initial_coordinates(q0, qd0);
  dynamics->impose_motion(0.0, q0, qd0);
  if (request.static_start.value_or(model.ir().initial.static_start)) {
    // The dense difference Jacobian costs n evaluations and an n^3 solve:
    // large models take the sparse tangent.
    if (n <= kDenseStaticLimit || !coupled_static_state_sparse(model.ir(), dynamics, q0, qd0))
      coupled_static_state(model.ir(), *dynamics, q0, qd0);
  }
  try {
    if (index3) {
      // Projected onto the contacts as the partitioned formulation does, then
      // handed over in full coordinates.
      PartitionedSystem projection(dynamics);
      Eigen::VectorXd q(n), qd(n);
      projection.full_state(0.0, projection.initial_state(0.0, q0, qd0), q, qd);
      y0 = system->initial_state(0.0, q, qd);
    } else {
      y0 = system->initial_state(0.0, q0, qd0);
    }
  } catch (const ContactError& e) {
    throw InvalidInput(model.ir().source_path + ": inconsistent initial state: " + e.what());
  }
  {
    // An initial state off the constraints is projected onto them: say so.
    Eigen::VectorXd q(n), qd(n);
    system->full_state(0.0, y0, q, qd);
    const std::vector<std::string> names = coupled_coordinate_names(*dynamics);
    const std::string moved = projection_moves(model, names, q0, q);
    const std::string moved_rates = projection_moves(model, names, qd0, qd);
    if (!moved.empty() || !moved_rates.empty()) {
      std::string text = "the initial state violates the contacts and was projected onto them:";
      if (!moved.empty()) text += " positions: " + moved + ";";
      if (!moved_rates.empty()) text += " velocities (per s): " + moved_rates + ";";
      if (request.strict) throw InvalidInput(model.ir().source_path + ": " + text + " (--strict)");
      observer.notice(text);
    }
  }

  OutputLayout layout;
  const std::vector<std::string> names = coupled_coordinate_names(*dynamics);
  std::vector<std::string> positions, units;
  for (int i = 0; i < nb; ++i) {
    positions.push_back(names[i]);
    units.push_back(coordinate_unit(model.ir().bodies[i]));
  }
  if (probes.empty()) {
    for (int i = nb; i < n; ++i) {
      positions.push_back(names[i]);
      units.push_back(names[i].find("_dw") != std::string::npos ? "1" : "m");
    }
  } else {
    for (const BeamProbe& p : probes) {
      positions.push_back(p.label);
      units.push_back("m");
    }
  }
  layout.columns.push_back("t");
  layout.units.push_back("s");
  layout.columns.insert(layout.columns.end(), positions.begin(), positions.end());
  layout.units.insert(layout.units.end(), units.begin(), units.end());
  for (std::size_t i = 0; i < positions.size(); ++i) {
    layout.columns.push_back(positions[i] + "_dot");
    layout.units.push_back(units[i] == "1" ? "1/s" : units[i] + "/s");
  }
  for (const std::string& l : multiplier_names(model.ir())) {
    layout.columns.push_back(l);
    layout.units.push_back("N");
  }
  layout.columns.push_back("phi_abs");
  layout.units.push_back("m");
  const ContactSprings& springs = dynamics->springs();
  for (int k = 0; k < springs.count(); ++k) {
    layout.columns.push_back("force_" + springs.name(k));
    layout.units.push_back("N");
  }
  for (int k = 0; k < springs.count(); ++k) {
    layout.columns.push_back("deflection_" + springs.name(k));
    layout.units.push_back("m");
  }
  const BeamLinks& links = dynamics->links();
  for (int k = 0; k < links.count(); ++k) {
    layout.columns.push_back("tension_" + links.name(k));
    layout.units.push_back("N");
  }
  const std::vector<int>& driven = dynamics->driven();
  for (int d : driven) {
    layout.columns.push_back(model.ir().bodies[d].name + "_drive");
    layout.units.push_back(model.ir().bodies[d].joint.type == ir::JointType::kRevolute ? "N m" : "N");
  }
  observer.begin(layout);

  std::vector<double> values(layout.columns.size());
  Eigen::VectorXd q(n), qd(n), reactions;
  SimulationOptions options = driver_options(request);
  // Lift-offs and time off contact, on every accepted step.
  std::vector<SpringContactTally> tally(springs.count());
  for (int k = 0; k < springs.count(); ++k) tally[k].name = springs.name(k);
  std::vector<LinkSlackTally> link_tally;
  for (int k = 0; k < links.count(); ++k)
    if (links.can_go_slack(k)) link_tally.push_back({links.name(k), 0, 0.0, false, false});
  double t_prev = 0.0;
  if (springs.count() > 0 || !link_tally.empty()) {
    options.on_step = [&](double t, const Eigen::VectorXd& y) {
      system->report(t, y);  // evaluates the springs and links at this state
      for (int k = 0, i = 0; k < links.count(); ++k) {
        if (!links.can_go_slack(k)) continue;
        LinkSlackTally& c = link_tally[static_cast<std::size_t>(i++)];
        const bool slack = links.states()[k].slack;
        if (slack) c.time_slack += t - t_prev;
        if (slack && !c.slack && c.seen) ++c.slackenings;
        c.slack = slack;
        c.seen = true;
      }
      for (int k = 0; k < springs.count(); ++k) {
        const SpringContactState& st = springs.states()[k];
        SpringContactTally& c = tally[k];
        const bool touching = st.delta > 0.0;  // in contact, pressing or not
        if (st.on_beam && !touching) c.time_off += t - t_prev;
        if (c.seen && c.in_contact && !touching && st.on_beam) ++c.lift_offs;
        c.in_contact = touching;
        c.seen = c.seen || st.on_beam;
      }
      t_prev = t;
    };
  }
  // An unstable beam mode drags the contacts along; catch it while the Newton
  // closure can still follow (a state 1e4 times the largest seen).
  options.divergence_factor = 1.0e4;
  SimulationReport report;
  report.variant = std::string(adjusted ? "adjusted" : "original") + " damping, " +
                   (index3 ? "index-3" : augmented ? "augmented" : "partitioned") + " formulation" +
                   (split ? ", low-rank beams in split coordinates" : "");
  // The beam DOFs the probes read: with split beams and probes, a row needs
  // only those nodal (unless the observer reads every coordinate).
  const bool rows_at_probes = split && !probes.empty() && !request.state_in_rows;
  std::vector<int> probe_dofs;
  for (const BeamProbe& p : probes)
    for (int a = 0; a < 4; ++a)
      if (p.weights.free_index[a] >= 0) probe_dofs.push_back(p.offset + p.weights.free_index[a]);
  const Eigen::VectorXd no_coordinates;
  if (adjusted)
    for (const JoinedStructure& s : model.joined())
      report.variant += ", joined structure " + joined_name(model.ir(), s.beams) + " (" +
                        std::to_string(s.adjusted.modes.size() - s.adjusted.adjusted) + " of " +
                        std::to_string(s.dof) + " modes kept)";
  std::string row_fault;
  try {
    report.run = run_simulation(*system, request.integrator, y0, options, [&](double t, const Eigen::VectorXd& y) {
      if (!row_fault.empty()) return;
      ContactReport contacts;
      try {
        if (rows_at_probes)
          system->full_state_at(t, y, probe_dofs, q, qd);
        else
          system->full_state(t, y, q, qd);
        contacts = system->report(t, y);
      } catch (const std::runtime_error& e) {
        row_fault = e.what();  // the step after this one fails the same way
        return;
      }
      dynamics->impose_motion(t, q, qd);
      std::size_t k = 0;
      values[k++] = t;
      for (const Eigen::VectorXd* x : {&q, &qd}) {
        for (int i = 0; i < nb; ++i) values[k++] = (*x)[i];
        if (probes.empty()) {
          for (int i = nb; i < n; ++i) values[k++] = (*x)[i];
        } else {
          for (const BeamProbe& p : probes) values[k++] = p.value(x->data() + nb);
        }
      }
      for (int r = 0; r < m; ++r) values[k++] = contacts.lambda[r];
      values[k++] = contacts.phi_max;
      for (const SpringContactState& st : springs.states()) values[k++] = st.force;
      for (const SpringContactState& st : springs.states()) values[k++] = st.w;
      for (const LinkState& st : links.states()) values[k++] = st.tension;
      if (!driven.empty()) {
        dynamics->drive_reactions(contacts.qdd, reactions);
        for (Eigen::Index i = 0; i < reactions.size(); ++i) values[k++] = reactions[i];
      }
      if (rows_at_probes)
        observer.row(OutputRow{t, values, no_coordinates, no_coordinates});
      else
        observer.row(OutputRow{t, values, q, qd});
    });
  } catch (const std::invalid_argument& e) {
    throw InvalidInput(e.what());
  }
  report.springs = tally;
  report.links = link_tally;
  if (report.run.status == SimulationStatus::kCompleted && row_fault.empty()) return report;
  if (report.run.status != SimulationStatus::kInterrupted) {
    // A load or motion of the bodies that is no longer finite broke the run, not the integrator.
    const std::string cause = non_finite_expression(model.ir(), report.run.t, report.run.step);
    if (!cause.empty()) {
      report.message = cause;
      return report;
    }
  }
  // The stable limit of the linearised system at the initial state tells an
  // instability of the integrator from a fault of the model.
  std::optional<StepLimit> limit;
  // The linearisation is a dense eigenproblem growing as n^3: a diagnosis
  // should take seconds, and at 1,927 coordinates it takes 6 minutes
  // (`mbfe stability` still gives the limits of models up to
  // kMaxLinearizedCoordinates).
  constexpr int kMaxDiagnosedCoordinates = 1000;
  if (report.run.status != SimulationStatus::kInterrupted && n <= kMaxDiagnosedCoordinates) {
    try {
      // The eigenvalues `mbfe stability` takes: a real part at round-off of
      // the modulus is zero (an undamped mode), not growth.
      const StateSpectrum spectrum = linearized_spectrum(model.make_dynamics(adjusted), 0.0, q0, qd0);
      limit = stable_step(request.integrator, split_growing(spectrum).limiting.eigenvalues);
    } catch (const std::exception&) {
      // No limit known: the message says only what happened.
    }
  }
  report.message = diagnose_run(report.run, limit, row_fault);
  return report;
}

}  // namespace mbfe::runtime::detail
