#include "runtime/simulation/adjustment_estimate.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <memory>
#include <sstream>
#include <utility>
#include <stdexcept>

#include "runtime/damping/compliance_change.h"
#include "runtime/errors/invalid_input.h"
#include "runtime/simulation/limit_search.h"
#include "runtime/simulation/linearised_estimate.h"

namespace mbfe::runtime {

namespace {

// Points on a moving point's path: nodes spread along the beam, and the
// middle of the element after each. The change is largest inside elements,
// not at nodes: the modes a cap changes carry the element-scale part of the
// compliance (on the 30 m bridge, 30 elements, cap at 2000 rad/s: 3.9 % at
// an element's middle against 3.1 % at the nodes).
constexpr int kPathSamples = 33;

/// A place (or a path) on one beam and what acts there.
struct Place {
  std::string what;
  int beam = -1;
  double s = 0.0;
  bool moving = false;
  double series = 0.0;
  double omega = 0.0;  // rad/s, the force's frequency (0: quasi-static)
};

std::vector<Place> places(const ir::Model& model, const std::vector<ProbeSpec>& probes) {
  std::vector<Place> out;
  for (const ir::Contact& c : model.contacts) {
    const char* type = c.type == ir::ContactType::kPin ? "pin" : c.type == ir::ContactType::kSliderPin ? "slider_pin" : "slider_spring";
    Place p{"contact '" + c.name + "' (" + type + ")", c.beam, c.at, c.type != ir::ContactType::kPin, 0.0};
    if (c.type == ir::ContactType::kSliderSpring && c.stiffness > 0.0) {
      p.series = 1.0 / c.stiffness;
      // The body bouncing on the contact spring: the fastest force a
      // penalty contact carries (a wheel on the rail, a pantograph head on
      // the wire), with the structure taken rigid, which overestimates it.
      const double mass = c.body >= 0 ? model.bodies[static_cast<std::size_t>(c.body)].mass : 0.0;
      if (mass > 0.0) p.omega = std::sqrt(c.stiffness / mass);
    }
    out.push_back(p);
  }
  for (const ir::Link& l : model.links) {
    const double series = l.stiffness > 0.0 ? 1.0 / l.stiffness : 0.0;
    out.push_back({"link '" + l.name + "' end a", l.a.beam, l.a.at, false, series});
    out.push_back({"link '" + l.name + "' end b", l.b.beam, l.b.at, false, series});
  }
  for (std::size_t i = 0; i < model.beams.size(); ++i) {
    const int beam = static_cast<int>(i);
    for (const ir::BeamPointLoad& load : model.beams[i].loads) out.push_back({"point load", beam, load.at, false, 0.0});
    for (std::size_t k = 0; k < model.beams[i].moving_loads.size(); ++k)
      out.push_back({"moving load", beam, 0.0, true, 0.0});
  }
  for (const ProbeSpec& probe : probes)
    for (std::size_t i = 0; i < model.beams.size(); ++i)
      if (model.beams[i].name == probe.beam) out.push_back({"probe " + probe.label, static_cast<int>(i), probe.s, false, 0.0});
  return out;
}

/// The weights e (w = e^T q) of the deflection at s over the beam's free DOFs.
Eigen::VectorXd deflection_weights(const BeamSystem& system, double s) {
  Eigen::VectorXd e = Eigen::VectorXd::Zero(system.M.rows());
  const BeamPointWeights w = point_weights(system, s);
  for (int a = 0; a < 4; ++a)
    if (w.free_index[a] >= 0) e[w.free_index[a]] += w.w[a];
  return e;
}

/// Where a place is evaluated: its s, or for a moving place nodes spread along the beam.
std::vector<double> positions(const Place& place, const BeamSystem& system) {
  if (!place.moving) return {place.s};
  std::vector<double> path;
  const int samples = std::min(kPathSamples, system.num_nodes);
  for (int k = 0; k < samples; ++k) {
    const int node = samples == 1 ? 0 : static_cast<int>(std::lround(double(k) * (system.num_nodes - 1) / (samples - 1)));
    path.push_back(std::min(system.length, node * system.element_length));
    if (node + 1 < system.num_nodes) path.push_back((node + 0.5) * system.element_length);
  }
  return path;
}

// A place on a moving point's path whose static compliance (with the spring
// in series) is below this share of the path's largest is one the supports
// hold: its relative change is round-off over round-off, and it is skipped.
constexpr double kHeldShare = 1e-9;

/// Each place's points (its positions), without the ones the supports hold
/// on a moving place's path; all places' points computed as one batch.
std::vector<std::vector<std::pair<double, ComplianceChangeEstimator::Point>>> place_points(
    const ComplianceChangeEstimator& estimator, const std::vector<Place>& on_beam, const BeamSystem& system) {
  std::vector<CompliancePoint> batch;
  std::vector<std::vector<double>> where;
  for (const Place& place : on_beam) {
    where.push_back(positions(place, system));
    for (const double s : where.back()) batch.push_back({deflection_weights(system, s), place.series, place.omega});
  }
  std::vector<ComplianceChangeEstimator::Point> computed = estimator.points(batch);
  std::vector<std::vector<std::pair<double, ComplianceChangeEstimator::Point>>> out(on_beam.size());
  std::size_t next = 0;
  for (std::size_t i = 0; i < on_beam.size(); ++i) {
    const Place& place = on_beam[i];
    double largest = 0.0;
    for (const double s : where[i]) {
      out[i].emplace_back(s, std::move(computed[next++]));
      largest = std::max(largest, place.series + out[i].back().second.compliance);
    }
    if (place.moving)
      out[i].erase(std::remove_if(out[i].begin(), out[i].end(),
                                  [&](const auto& p) { return place.series + p.second.compliance < kHeldShare * largest; }),
                   out[i].end());
  }
  return out;
}

/// The places on one beam.
std::vector<Place> places_on(const std::vector<Place>& all, std::size_t beam) {
  std::vector<Place> out;
  for (const Place& place : all)
    if (place.beam == static_cast<int>(beam)) out.push_back(place);
  return out;
}

/// Why a beam's adjustment cannot be estimated, or empty.
std::string unsupported(const ir::Beam& beam, const BeamPart& part) {
  if (beam.adjustment.scope == ir::AdjustmentScope::kJoined) return "scope joined";
  // The estimate is of a change of the modes' dynamics; a truncation removes them.
  if (beam.adjustment.policy == ir::AdjustmentPolicy::kTruncate) return "policy truncate";
  if (!part.basis.complete) {
    const auto policy = part.adjusted.policy;
    if (policy != ir::AdjustmentPolicy::kCap && policy != ir::AdjustmentPolicy::kMass)
      return "a partial modal basis with a policy other than cap or mass";
    if (part.adjusted.change.empty() || part.adjusted.change.back() == ModeChange::kKept)
      return "its partial modal basis ends in a mode the policy keeps";
  }
  return {};
}

}  // namespace

AdjustmentEstimate estimate_adjustment(const AssembledModel& model, const std::vector<ProbeSpec>& probes,
                                       const LinearisationPoint* start) {
  AdjustmentEstimate out;
  const ir::Model& ir = model.ir();
  const BeamModel& beams = model.beams();
  const std::vector<Place> all = places(ir, probes);
  for (std::size_t i = 0; i < beams.beams.size() && i < ir.beams.size(); ++i) {
    const BeamPart& part = beams.beams[i];
    if (!part.has_adjustment) continue;
    const std::string name = "'" + ir.beams[i].name + "'";
    out.limits.push_back({ir.beams[i].name, ir.beams[i].adjustment.omega_limit, ir.beams[i].adjustment.omega_limit_auto});
    if (const std::string why = unsupported(ir.beams[i], part); !why.empty()) {
      out.not_estimated.push_back(name + ": " + why);
      continue;
    }
    std::unique_ptr<ComplianceChangeEstimator> estimator;
    try {
      estimator = std::make_unique<ComplianceChangeEstimator>(part.system.M, part.system.K, part.system.C, part.basis,
                                                              part.original);
    } catch (const std::exception& e) {
      out.not_estimated.push_back(name + ": " + e.what());
      continue;
    }
    const std::vector<Place> on_beam = places_on(all, i);
    const auto computed = place_points(*estimator, on_beam, part.system);
    for (std::size_t k = 0; k < on_beam.size(); ++k) {
      const Place& place = on_beam[k];
      AdjustmentEstimatePoint best;
      best.what = place.what;
      best.beam = ir.beams[i].name;
      best.s = place.s;
      best.moving = place.moving;
      best.series_compliance = place.series;
      best.omega = place.omega;
      bool first = true;
      for (const auto& [s, point] : computed[k]) {
        const ComplianceChange change = estimator->evaluate(point, part.adjusted, /*band=*/true);
        const double estimate = std::max(change.static_change, change.change);
        if (change.band_change > best.band_change) {
          best.band_change = change.band_change;
          best.omega_band = change.band_omega;
        }
        if (first || estimate > best.estimate) {
          best.s = s;
          best.compliance = change.compliance;
          best.static_change = change.static_change;
          best.dynamic_change = change.change;
          best.changed_share = change.changed_share;
          best.estimate = estimate;
          first = false;
        }
      }
      out.points.push_back(best);
      if (out.largest < 0 || best.estimate > out.max) {
        out.largest = static_cast<int>(out.points.size()) - 1;
        out.max = best.estimate;
      }
    }
  }
  if (out.largest >= 0) out.where = out.points[static_cast<std::size_t>(out.largest)].what;
  if (out.limits.empty()) return out;
  // The linearised run, where it applies, is the estimate.
  out.linearised_unavailable = linearised_run_unavailable(model);
  if (!out.linearised_unavailable.empty()) return out;
  try {
    const LinearisedEstimate lms = linearised_estimate(model, start != nullptr ? *start : model_start(model));
    if (lms.worst >= 0) {
      out.max = lms.contacts[static_cast<std::size_t>(lms.worst)].relative;
      out.where = "contact '" + lms.contacts[static_cast<std::size_t>(lms.worst)].contact + "' (slider_spring)";
    } else {
      out.max = 0.0;
      out.where.clear();
    }
    out.linearised = lms;
  } catch (const std::exception& e) {
    out.linearised_unavailable = e.what();
  }
  return out;
}

namespace {

/// Where choose_omega_limit's grid ends (rad/s): the limit whose capped root
/// equals the fastest bounce sqrt(k / m) of a body on a linear contact spring
/// of the model, or half the beam's lowest mode `omega_1` without one.
double grid_bottom(const ir::Model& model, const ir::Adjustment& adjustment, double omega_1) {
  double bounce = 0.0;
  for (const Place& place : places(model, {})) bounce = std::max(bounce, place.omega);
  if (!(bounce > 0.0)) return 0.5 * omega_1;
  // The capped root per rad/s of limit, (zeta + sqrt(zeta^2 - 1)) with
  // zeta = 1 + margin / 2 (cap and mass alike).
  const double zeta = 1.0 + 0.5 * adjustment.margin;
  return bounce / (zeta + std::sqrt(zeta * zeta - 1.0));
}

}  // namespace

double choose_omega_limit(const ir::Model& model, std::size_t beam, const BeamAnalysisOptions& options) {
  const ir::Beam& given = model.beams.at(beam);
  const auto where = [&]() {
    return model.source_path + ":" + std::to_string(given.adjustment.omega_limit_loc.line) + ":" +
           std::to_string(given.adjustment.omega_limit_loc.column) + ": beam '" + given.name + "': omega_limit: auto ";
  };
  if (given.adjustment.scope == ir::AdjustmentScope::kJoined)
    throw InvalidInput(where() + "takes scope beam (the estimate covers one beam's modes), got scope joined");
  // The beam's every mode, unadjusted: the limit far above its fastest root.
  ir::Beam b = given;
  b.adjustment.omega_limit_auto = false;
  b.adjustment.policy = ir::AdjustmentPolicy::kNone;
  BeamAnalysisOptions every_mode = options;
  every_mode.modes_kept_by_cap = false;
  const BeamPart part = analyse_beam(b, model.gravity, every_mode);
  if (!part.basis.complete)
    throw InvalidInput(where() + "needs every mode of the beam: it has " + std::to_string(part.system.M.rows()) +
                       " DOFs, beyond the dense modal analysis (" + std::to_string(options.dense_limit) +
                       "); give omega_limit in rad/s");
  const ComplianceChangeEstimator estimator(part.system.M, part.system.K, part.system.C, part.basis, part.original);
  std::vector<ComplianceChangeEstimator::Point> points;
  for (auto& on_place : place_points(estimator, places_on(places(model, {}), beam), part.system))
    for (auto& [s, point] : on_place) points.push_back(std::move(point));
  ir::Adjustment adjustment = given.adjustment;
  adjustment.omega_limit_auto = false;
  const auto largest = [&](double omega_limit) {
    adjustment.omega_limit = omega_limit;
    const AdjustedModes adjusted = adjust_modes(part.original, adjustment);
    double worst = 0.0;
    for (const auto& point : points) {
      const ComplianceChange change = estimator.evaluate(point, adjusted);
      worst = std::max({worst, change.static_change, change.change});
    }
    return worst;
  };
  double fastest = 0.0;
  for (const ModalDynamics& mode : part.original) fastest = std::max(fastest, fastest_root(mode));
  const double tolerance = given.adjustment.tolerance;
  // Above the fastest root nothing is capped; what is left is the damping floor's.
  const double top = 1.01 * fastest;
  if (const double floor_only = largest(top); floor_only > tolerance)
    throw InvalidInput(where() + "no limit meets tolerance " + std::to_string(tolerance) +
                       ": the damping floor zeta_min alone changes the receptance by " + std::to_string(floor_only) +
                       "; lower zeta_min or raise the tolerance");
  // A log grid down from the top: the lowest grid point from which every
  // higher one meets the tolerance (the estimate need not fall monotonically
  // with the limit), then bisection towards the grid point below it. The
  // grid goes below the beam's lowest mode (every mode capped, as a stiff
  // slab's adjustment often is) down to where the capped root meets the
  // fastest bounce of a body on a contact spring: a lower limit would not
  // lengthen any stable step, which that root then sets. Without such a
  // contact it stops at half the lowest mode.
  // Each probe evaluates a few receptances: the search can be fine.
  constexpr LimitSearchResolution kPointFigureSearch{40, 40};
  const double bottom = grid_bottom(model, adjustment, part.basis.omega[0]);
  return lowest_limit_within(largest, tolerance, top, bottom, kPointFigureSearch);
}

std::string adjustment_notice(const AdjustmentEstimate& estimate, const ir::Model& model) {
  if (!(estimate.max > kAdjustmentNoticeThreshold)) return {};
  const auto policy_name = [](ir::AdjustmentPolicy p) {
    return p == ir::AdjustmentPolicy::kMass        ? "mass"
           : p == ir::AdjustmentPolicy::kCap       ? "cap"
           : p == ir::AdjustmentPolicy::kPaperEq25 ? "paper_eq25"
           : p == ir::AdjustmentPolicy::kTruncate  ? "truncate"
                                                   : "keep_slow";
  };
  const auto remedy = [](ir::AdjustmentPolicy p) {
    return p == ir::AdjustmentPolicy::kMass || p == ir::AdjustmentPolicy::kTruncate
               ? "raise omega_limit"
               : "raise omega_limit or use policy: mass";
  };
  std::ostringstream line;
  line << std::setprecision(3);
  if (estimate.linearised && estimate.linearised->worst >= 0) {
    const LinearisedContactChange& c =
        estimate.linearised->contacts[static_cast<std::size_t>(estimate.linearised->worst)];
    // The run is the whole model's: the change at one contact may come from
    // another beam's adjustment (a wheel leaving a capped deck), so every
    // adjusted beam is named, and the remedy suits the policies among them.
    line << "adjustment estimate: the adjustment changes the force of " << estimate.where << " by "
         << 100.0 * c.relative << " % of its peak over the run (peak " << std::showpos << 100.0 * c.peak_change
         << std::noshowpos << " %; a linearised run of both models; adjusted beams:";
    bool first = true, only_mass = true;
    for (const ir::Beam& beam : model.beams) {
      if (!beam.adjustment.active()) continue;
      line << (first ? " '" : ", '") << beam.name << "' " << policy_name(beam.adjustment.policy) << " at "
           << beam.adjustment.omega_limit << " rad/s";
      first = false;
      only_mass = only_mass && (beam.adjustment.policy == ir::AdjustmentPolicy::kMass ||
                                beam.adjustment.policy == ir::AdjustmentPolicy::kTruncate);
    }
    line << "); " << (only_mass ? "raise omega_limit" : "raise omega_limit or use policy: mass");
    line << " (docs/damping-adjustment.md, \"The accuracy estimate\")";
    return line.str();
  }
  if (estimate.largest < 0) return {};
  const AdjustmentEstimatePoint& p = estimate.points[static_cast<std::size_t>(estimate.largest)];
  const ir::Beam* beam = nullptr;
  for (const ir::Beam& b : model.beams)
    if (b.name == p.beam) beam = &b;
  const ir::Adjustment a = beam ? beam->adjustment : ir::Adjustment{};
  line << "adjustment estimate: the adjusted modes of beam '" << p.beam
       << "' change the compliance at " << p.what << " (" << (p.moving ? "largest at " : "") << "s = " << p.s
       << " m";
  if (p.omega > 0.0) line << ", at " << p.omega << " rad/s";
  line << ") by " << 100.0 * p.estimate << " % (policy " << policy_name(a.policy) << ", omega_limit " << a.omega_limit
       << " rad/s); " << remedy(a.policy) << " (docs/damping-adjustment.md, \"The accuracy estimate\")";
  return line.str();
}

}  // namespace mbfe::runtime
