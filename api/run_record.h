// What a results file holds and how its run ended: the record written beside
// it (FILE.csv.json, FILE.npy.json; docs/model-format.md "Results"), for
// whoever reads the results later (a person, a notebook, a sweep, mbfe stats
// and mbfe plot, which read the columns' names and units from it).
#pragma once

#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>

#include "api/mbfe.h"

namespace mbfe {

/// {"mbfe", "model": {name, file, sha256}, "integrator", "step", "t_end",
/// "variant", "columns": [{name, unit}], "rows", "status", "message",
/// "steps", "t_reached", "wall_seconds", "newton"?, "springs"?, "links"?,
/// "adjustment_estimate"? (adjusted runs: adjustment_estimate_json)}.
nlohmann::json run_record(const Model& model, const runtime::SimulationRequest& request,
                          const runtime::SimulationReport& report, const runtime::OutputLayout& layout,
                          std::size_t rows);

/// {"points": [{what, beam, s (m), moving, series_compliance (m/N), omega
/// (rad/s), compliance (m/N), static_change, dynamic_change, changed_share,
/// estimate, band_change, omega_band (rad/s)}], "max", "where" (the
/// what of the largest, null without points), "not_estimated": [text],
/// "omega_limits": [{beam, omega_limit (rad/s), chosen (omega_limit: auto)}]}.
nlohmann::json adjustment_estimate_json(const runtime::AdjustmentEstimate& estimate);

/// [{name, lift_offs, time_off (s), touched}], a slider_spring's each.
nlohmann::json spring_tallies_json(const runtime::SimulationReport& report);

/// [{name, slackenings, time_slack (s)}], each link that can go slack.
nlohmann::json link_tallies_json(const runtime::SimulationReport& report);

/// Writes `record` to results_path + ".json", unless the results went to a
/// device or a pipe (--out /dev/null: no file to describe, and no
/// "/dev/null.json" to leave behind).
void write_run_record(const std::string& results_path, const nlohmann::json& record);

}  // namespace mbfe
