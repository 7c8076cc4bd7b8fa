#include "api/run_record.h"

#include <filesystem>
#include <fstream>

#include "api/json_text.h"
#include "api/model_warnings.h"

namespace mbfe {

nlohmann::json adjustment_estimate_json(const runtime::AdjustmentEstimate& estimate) {
  nlohmann::json points = nlohmann::json::array();
  for (const runtime::AdjustmentEstimatePoint& p : estimate.points)
    points.push_back({{"what", p.what},
                      {"beam", p.beam},
                      {"s", p.s},
                      {"moving", p.moving},
                      {"series_compliance", p.series_compliance},
                      {"omega", p.omega},
                      {"compliance", p.compliance},
                      {"static_change", p.static_change},
                      {"dynamic_change", p.dynamic_change},
                      {"changed_share", p.changed_share},
                      {"estimate", p.estimate},
                      {"band_change", p.band_change},
                      {"omega_band", p.omega_band}});
  nlohmann::json j = {{"points", points}, {"max", estimate.max}};
  j["where"] = estimate.where.empty() ? nlohmann::json() : nlohmann::json(estimate.where);
  if (estimate.linearised) {
    const runtime::LinearisedEstimate& l = *estimate.linearised;
    nlohmann::json contacts = nlohmann::json::array();
    for (const runtime::LinearisedContactChange& c : l.contacts)
      contacts.push_back(
          {{"contact", c.contact}, {"relative", c.relative}, {"peak_change", c.peak_change}, {"peak", c.peak}});
    const bool any = l.worst >= 0;
    const runtime::LinearisedContactChange worst = any ? l.contacts[static_cast<std::size_t>(l.worst)]
                                                       : runtime::LinearisedContactChange{};
    j["linearised"] = {{"contact_force",
                        {{"relative", worst.relative},
                         {"contact", any ? nlohmann::json(worst.contact) : nlohmann::json()}}},
                       {"peak_change", worst.peak_change},
                       {"contacts", contacts},
                       {"step", l.step},
                       {"steps", l.steps},
                       {"omega_excitation", l.omega_excitation},
                       {"seconds", l.seconds},
                       {"unconverged_steps", l.unconverged_steps}};
  } else if (!estimate.linearised_unavailable.empty()) {
    j["linearised"] = {{"not_estimated", estimate.linearised_unavailable}};
  }
  j["not_estimated"] = estimate.not_estimated;
  nlohmann::json limits = nlohmann::json::array();
  for (const runtime::AdjustmentEstimate::Limit& l : estimate.limits)
    limits.push_back({{"beam", l.beam}, {"omega_limit", l.omega_limit}, {"chosen", l.chosen}});
  j["omega_limits"] = limits;
  return j;
}

nlohmann::json spring_tallies_json(const runtime::SimulationReport& report) {
  nlohmann::json springs = nlohmann::json::array();
  for (const runtime::SpringContactTally& c : report.springs)
    springs.push_back({{"name", c.name}, {"lift_offs", c.lift_offs}, {"time_off", c.time_off}, {"touched", c.touched}});
  return springs;
}

nlohmann::json link_tallies_json(const runtime::SimulationReport& report) {
  nlohmann::json links = nlohmann::json::array();
  for (const runtime::LinkSlackTally& l : report.links)
    links.push_back({{"name", l.name}, {"slackenings", l.slackenings}, {"time_slack", l.time_slack}});
  return links;
}

nlohmann::json run_record(const Model& model, const runtime::SimulationRequest& request,
                          const runtime::SimulationReport& report, const runtime::OutputLayout& layout,
                          std::size_t rows) {
  nlohmann::json j;
  j["mbfe"] = MBFE_GENERATOR_VERSION;
  j["model"] = {{"name", model.ir().name}, {"file", model.ir().source_path}, {"sha256", model.ir().source_sha256}};
  j["integrator"] = request.integrator.name;
  j["step"] = request.step;
  j["t_end"] = request.t_end;
  j["variant"] = report.variant;
  nlohmann::json columns = nlohmann::json::array();
  for (std::size_t k = 0; k < layout.columns.size(); ++k)
    columns.push_back({{"name", layout.columns[k]}, {"unit", k < layout.units.size() ? layout.units[k] : ""}});
  j["columns"] = columns;
  j["rows"] = rows;
  j["status"] = runtime::status_name(report);
  j["message"] = report.message;
  j["steps"] = report.run.steps;
  j["t_reached"] = report.run.t;
  j["wall_seconds"] = report.run.wall_seconds;
  if (report.run.newton.iterations > 0)
    j["newton"] = {{"iterations", report.run.newton.iterations},
                   {"factorizations", report.run.newton.factorizations}};
  if (!report.springs.empty()) j["springs"] = spring_tallies_json(report);
  if (!report.links.empty()) j["links"] = link_tallies_json(report);
  nlohmann::json warnings = nlohmann::json::array();
  for (const std::string& w : model_warnings(model.ir())) warnings.push_back(w);
  for (const std::string& w : run_warnings(model.ir(), report)) warnings.push_back(w);
  j["warnings"] = warnings;
  nlohmann::json falls = nlohmann::json::array();
  for (const FreeFall& f : free_falls(model.ir(), report))
    falls.push_back({{"body", f.body}, {"point", f.point}, {"beam", f.beam}, {"distance", f.distance},
                     {"structure_size", f.size}, {"fallen", f.fallen}, {"t", f.t}});
  if (!falls.empty()) j["free_falls"] = falls;
  if (report.adjustment_estimate) j["adjustment_estimate"] = adjustment_estimate_json(*report.adjustment_estimate);
  return j;
}

void write_run_record(const std::string& results_path, const nlohmann::json& record) {
  std::error_code not_a_file;
  if (!std::filesystem::is_regular_file(results_path, not_a_file)) return;
  std::ofstream out(results_path + ".json");
  out << json_text(record, 2) << "\n";
}

}  // namespace mbfe
