#include "runtime/damping/beam_model.h"

#include <algorithm>
#include <atomic>
#include <exception>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>

#include "runtime/modal/modal_analysis.h"
#include "runtime/platform/thread_budget.h"

namespace mbfe::runtime {

namespace {

// The modes of the adjusted beam: part.adjusted.modes, less the removed ones
// under policy truncate (the beam moves in its kept modes alone), so its
// adjusted spectrum is that of the beam that runs.
std::vector<ModalDynamics> adjusted_model_modes(const BeamPart& part) {
  if (part.adjusted.policy != ir::AdjustmentPolicy::kTruncate) return part.adjusted.modes;
  std::vector<ModalDynamics> kept;
  for (std::size_t j = 0; j < part.adjusted.modes.size(); ++j)
    if (part.adjusted.change[j] != ModeChange::kAdjusted) kept.push_back(part.adjusted.modes[j]);
  return kept;
}

}  // namespace

BeamPart analyse_beam(const ir::Beam& beam, const ir::Vec2& gravity, const BeamAnalysisOptions& options) {
  BeamPart part;
  part.system = assemble_beam(beam, gravity);
  const int n = static_cast<int>(part.system.M.rows());
  part.dense = n <= options.dense_limit;
  if (!part.dense && options.sparse_modes <= 0)
    throw std::invalid_argument("beam '" + beam.name + "' has " + std::to_string(n) +
                                " DOFs; time integration and the stability advisor use every mode and "
                                "handle at most " +
                                std::to_string(options.dense_limit) + " per beam");
  ModalOptions mo;
  mo.dense_limit = options.dense_limit;
  mo.num_modes = part.dense ? 0 : std::min(options.sparse_modes, n - 1);
  const ir::Adjustment& adj = beam.adjustment;
  if (!part.dense && options.modes_kept_by_cap && adj.active() &&
      (adj.policy == ir::AdjustmentPolicy::kCap || adj.policy == ir::AdjustmentPolicy::kMass ||
       adj.policy == ir::AdjustmentPolicy::kTruncate) &&
      adj.scope == ir::AdjustmentScope::kBeam && adj.omega_limit > 0.0) {
    // A kept mode has |r_fast| <= omega_limit, so omega <= omega_limit.
    ModalOptions sliced = mo;
    sliced.up_to_omega = adj.omega_limit;
    sliced.slice_modes = options.slice_modes;
    try {
      std::string inputs;
      if (options.modes_store) {
        inputs = sliced_modes_inputs(part.system, sliced);
        if (std::optional<ModalBasis> kept = options.modes_store->find(inputs, n)) part.basis = std::move(*kept);
      }
      if (part.basis.omega.size() == 0) {
        part.basis = modal_analysis(part.system, sliced);
        if (options.modes_store) options.modes_store->keep(inputs, part.basis);
      }
    } catch (const std::exception& e) {
      // The original model does not need these modes: it still runs.
      part.kept_modes_unavailable = e.what();
    }
  }
  if (part.basis.omega.size() == 0) {
    const bool stored = part.dense && options.modes_store && n >= options.dense_store_from;
    std::string inputs;
    if (stored) {
      inputs = dense_modes_inputs(part.system);
      if (std::optional<ModalBasis> kept = options.modes_store->find(inputs, n)) part.basis = std::move(*kept);
    }
    if (part.basis.omega.size() == 0) {
      part.basis = modal_analysis(part.system, mo);
      if (stored) options.modes_store->keep(inputs, part.basis);
    }
  }
  part.original = rayleigh_modes(part.basis.omega, part.system.rayleigh_alpha, part.system.rayleigh_beta);
  part.has_adjustment = beam.adjustment.active();
  try {
    ir::Adjustment none;
    none.policy = ir::AdjustmentPolicy::kNone;
    part.adjusted = adjust_modes(part.original, part.has_adjustment ? beam.adjustment : none);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument("beam '" + beam.name + "': " + e.what());
  }
  part.original_spectrum = state_spectrum(part.original, part.basis.complete);
  part.adjusted_spectrum = state_spectrum(adjusted_model_modes(part), part.basis.complete);
  return part;
}

BeamModel analyse_beams(const ir::Model& model, const BeamAnalysisOptions& options) {
  // The beams are independent: a model with a large one (seconds of spectrum
  // slicing each) analyses them on threads of their own. Each beam's result
  // is the same bits either way.
  const std::size_t count = model.beams.size();
  std::vector<BeamPart> parts(count);
  std::vector<std::exception_ptr> failures(count);
  const auto analyse = [&](std::size_t k) {
    try {
      parts[k] = analyse_beam(model.beams[k], model.gravity, options);
    } catch (...) {
      failures[k] = std::current_exception();
    }
  };
  const bool large = std::any_of(model.beams.begin(), model.beams.end(), [&](const ir::Beam& b) {
    return 2 * (b.elements + 1) > options.dense_limit;
  });
  const std::size_t threads =
      large ? std::min<std::size_t>(count, static_cast<std::size_t>(thread_budget())) : 1;
  if (threads > 1) {
    std::atomic<std::size_t> next{0};
    std::vector<std::thread> pool;
    for (std::size_t t = 0; t < threads; ++t)
      pool.emplace_back([&]() {
        for (std::size_t k = next++; k < count; k = next++) analyse(k);
      });
    for (std::thread& t : pool) t.join();
  } else {
    for (std::size_t k = 0; k < count; ++k) analyse(k);
  }
  for (const std::exception_ptr& failure : failures)
    if (failure) std::rethrow_exception(failure);  // the first beam's in model order, as a serial loop would

  BeamModel out;
  // Reserved: BeamPart's move may throw (Eigen's sparse matrices), so a
  // regrown vector would copy its parts, every basis with them.
  out.beams.reserve(count);
  std::vector<ModalDynamics> all_original, all_adjusted;
  bool complete = true;
  for (BeamPart& part : parts) {
    part.offset = out.dof;
    out.dof += static_cast<int>(part.system.M.rows());
    out.any_adjustment = out.any_adjustment || part.has_adjustment;
    complete = complete && part.basis.complete;
    all_original.insert(all_original.end(), part.original.begin(), part.original.end());
    const std::vector<ModalDynamics> adjusted = adjusted_model_modes(part);
    all_adjusted.insert(all_adjusted.end(), adjusted.begin(), adjusted.end());
    out.beams.push_back(std::move(part));
  }
  out.original = state_spectrum(all_original, complete);
  out.adjusted = state_spectrum(all_adjusted, complete);
  return out;
}

void readjust_beams(BeamModel& beams, const ir::Model& model, const std::vector<std::size_t>& which) {
  for (const std::size_t i : which) {
    BeamPart& part = beams.beams.at(i);
    const ir::Beam& beam = model.beams.at(i);
    part.has_adjustment = beam.adjustment.active();
    try {
      ir::Adjustment none;
      none.policy = ir::AdjustmentPolicy::kNone;
      part.adjusted = adjust_modes(part.original, part.has_adjustment ? beam.adjustment : none);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument("beam '" + beam.name + "': " + e.what());
    }
    part.adjusted_spectrum = state_spectrum(adjusted_model_modes(part), part.basis.complete);
  }
  std::vector<ModalDynamics> all;
  bool complete = true;
  beams.any_adjustment = false;
  for (const BeamPart& part : beams.beams) {
    const std::vector<ModalDynamics> adjusted = adjusted_model_modes(part);
    all.insert(all.end(), adjusted.begin(), adjusted.end());
    complete = complete && part.basis.complete;
    beams.any_adjustment = beams.any_adjustment || part.has_adjustment;
  }
  beams.adjusted = state_spectrum(all, complete);
}

std::unique_ptr<ModalBeamOde> modal_beam_ode(const BeamModel& beams, bool adjusted) {
  for (const BeamPart& b : beams.beams)
    if (!b.basis.complete)
      throw std::invalid_argument("beam '" + b.system.name + "': only its lowest modes are known; the modal form needs every mode");
  const int n = beams.dof;
  ModalBasis basis;
  basis.omega.resize(n);
  basis.phi = Eigen::MatrixXd::Zero(n, n);
  basis.complete = true;
  std::vector<Eigen::Triplet<double>> trip;
  Eigen::VectorXd P(n);
  std::vector<ModalDynamics> modes;
  for (const BeamPart& b : beams.beams) {
    const int m = static_cast<int>(b.system.M.rows());
    basis.omega.segment(b.offset, m) = b.basis.omega;
    basis.phi.block(b.offset, b.offset, m, m) = b.basis.phi;
    P.segment(b.offset, m) = b.system.P;
    for (int k = 0; k < b.system.M.outerSize(); ++k)
      for (Eigen::SparseMatrix<double>::InnerIterator it(b.system.M, k); it; ++it)
        trip.emplace_back(b.offset + it.row(), b.offset + it.col(), it.value());
    const auto& src = adjusted ? b.adjusted.modes : b.original;
    modes.insert(modes.end(), src.begin(), src.end());
  }
  Eigen::SparseMatrix<double> M(n, n);
  M.setFromTriplets(trip.begin(), trip.end());
  auto ode = std::make_unique<ModalBeamOde>(basis, modes, M, P);
  // Both models damp the modes by Rayleigh over the whole beam; the nodal C
  // damps the discrete parts otherwise (BeamSystem::damping_remainder).
  std::vector<std::pair<int, double>> remainder;
  for (const BeamPart& b : beams.beams)
    for (const auto& [dof, value] : b.system.damping_remainder) remainder.emplace_back(b.offset + dof, value);
  if (!remainder.empty()) ode->set_damping_remainder(remainder);
  if (std::any_of(beams.beams.begin(), beams.beams.end(),
                  [](const BeamPart& b) { return b.system.has_time_loads(); })) {
    ode->set_time_loads([&beams, scratch = std::vector<NodalForce>()](double t, std::vector<NodalForce>& out) mutable {
      out.clear();
      for (const BeamPart& b : beams.beams) {
        if (!b.system.has_time_loads()) continue;
        time_dependent_loads(b.system, t, scratch);
        for (const NodalForce& f : scratch) out.push_back({b.offset + f.index, f.value});
      }
    });
  }
  return ode;
}

Eigen::VectorXd modal_static_state(const BeamModel& beams, bool adjusted, ModalBeamOde& ode, double t) {
  const int n = beams.dof;
  Eigen::VectorXd y = Eigen::VectorXd::Zero(2 * n);
  Eigen::VectorXd p;
  ode.modal_load_at(t, p);
  int j = 0;
  for (const BeamPart& b : beams.beams)
    for (const ModalDynamics& m : adjusted ? b.adjusted.modes : b.original) {
      if (m.k > 0.0) y[j] = p[j] / m.k;
      ++j;
    }
  return y;
}

}  // namespace mbfe::runtime
