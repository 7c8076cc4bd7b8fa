// The three runs behind simulate() (simulate.cpp validates the request and
// picks one). Internal to runtime/simulation/.
#pragma once

#include "runtime/simulation/simulate.h"

namespace mbfe::runtime::detail {

/// The driver's options from a validated request.
SimulationOptions driver_options(const SimulationRequest& request);

/// Bodies only: y = [q; q'] of M(q) q'' + F = Q (rigid_run.cpp).
SimulationReport run_rigid(const AssembledModel& model, const SimulationRequest& request,
                           SimulationObserver& observer);
/// Beams only, in modal coordinates (beam_run.cpp).
SimulationReport run_beams(const AssembledModel& model, const SimulationRequest& request,
                           SimulationObserver& observer);
/// Bodies, beams and contacts (coupled_run.cpp).
SimulationReport run_coupled(const AssembledModel& model, const SimulationRequest& request,
                             SimulationObserver& observer);

/// Units of a rigid coordinate and of its rate: rad, rad/s (revolute) or m, m/s (prismatic).
const char* coordinate_unit(const ir::Body& body);
const char* rate_unit(const ir::Body& body);

}  // namespace mbfe::runtime::detail
