#include "tool/sweep_point.h"

#include <nlohmann/json.hpp>

#include <chrono>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>

#include "api/mbfe.h"
#include "api/model_warnings.h"
#include "frontend/parse_model.h"
#include "frontend/parse_sweep.h"
#include "frontend/sha256.h"
#include "api/json_text.h"
#include "api/results_output.h"
#include "tool/sweep_stats.h"

namespace mbfe::tool {

namespace fs = std::filesystem;

namespace {

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
constexpr const char* kStaleMessage =
    "its result is of another request (the model, the point's values, simulate: or collect: changed since); "
    "running the sweep again runs it";

// A point's own files: its model.yaml (at most the 16 MiB of a model file) and
// result.json (statistics and one message).
constexpr std::uintmax_t kMaxPointFileBytes = std::uintmax_t{32} << 20;

/// A point's file, or "" when it is not a regular file of at most
/// kMaxPointFileBytes (a device put in its place is not read without end):
/// the point then counts as not run.
std::string slurp(const fs::path& p) {
  std::error_code ec;
  if (!fs::is_regular_file(p, ec) || fs::file_size(p, ec) > kMaxPointFileBytes || ec) return "";
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// Written to a temporary name and renamed: a reader never sees half a file.
void write_atomically(const fs::path& p, const std::string& text) {
  const fs::path tmp = p.string() + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary);
    out << text;
    if (!out) throw std::runtime_error(tmp.string() + ": cannot write");
  }
  fs::rename(tmp, p);
}

/// The point model's request (its `simulation:` block), the sweep's
/// `simulate:` block overriding it.
runtime::SimulationRequest request_of(const ir::Sweep& sweep, const Model& model) {
  const ir::SweepSimulation& s = sweep.simulation;
  runtime::SimulationRequest r = model.request();
  if (!s.integrator.empty()) r.integrator = runtime::parse_integrator(s.integrator);
  if (s.step > 0) r.step = s.step;
  if (s.t_end > 0) r.t_end = s.t_end;
  for (const std::string& p : s.probes) r.probes.push_back(runtime::parse_probe(p));
  if (!s.adjust.empty()) r.adjust = s.adjust == "on";
  return r;
}

nlohmann::json number_or_null(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

/// What produced a point's result, hashed: the point's model text (the varied
/// values put in), the sweep's simulate block and its collect entries. A
/// stored result of another request does not count.
std::string request_sha256(const ir::Sweep& sweep, const std::string& point_text) {
  const ir::SweepSimulation& s = sweep.simulation;
  nlohmann::json j;
  j["model"] = point_text;
  j["simulate"] = {{"integrator", s.integrator}, {"step", s.step},       {"t_end", s.t_end},
                   {"probes", s.probes},         {"adjust", s.adjust}};
  // Only when set, so that the requests of sweeps written before it keep their hash.
  if (s.full_state) j["simulate"]["full_state"] = true;
  nlohmann::json collect = nlohmann::json::array();
  for (const ir::SweepCollect& c : sweep.collect) {
    nlohmann::json entry = {{"name", c.name}, {"column", c.column}, {"stat", static_cast<int>(c.stat)}};
    // Only when given, so that the requests of sweeps written before them keep their hash.
    if (c.lowpass_hz > 0.0) entry["lowpass"] = {c.lowpass_hz, c.order};
    if (c.from) entry["from"] = *c.from;
    if (c.to) entry["to"] = *c.to;
    collect.push_back(entry);
  }
  j["collect"] = collect;
  return frontend::sha256_hex(json_text(j));
}

void write_result(const fs::path& dir, const ir::Sweep& sweep, const PointResult& r, const std::string& request) {
  nlohmann::json j;
  j["point"] = r.point;
  j["request_sha256"] = request;
  j["status"] = r.done ? "done" : "failed";
  j["exit_status"] = r.exit_status;
  j["message"] = r.message;
  j["wall_seconds"] = r.wall_seconds;
  nlohmann::json stats = nlohmann::json::object();
  for (std::size_t k = 0; k < sweep.collect.size(); ++k) stats[sweep.collect[k].name] = number_or_null(r.stats[k]);
  j["stats"] = stats;
  write_atomically(dir / "result.json", json_text(j, 2) + "\n");
}

/// A CSV field: quoted when it holds a comma, a quote or a line break.
std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string out = "\"";
  for (char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

std::string number_text(double v) {
  if (!std::isfinite(v)) return "";
  std::ostringstream os;
  os.precision(17);
  os << v;
  return os.str();
}

}  // namespace

std::string point_dir(const std::string& out_dir, long i) {
  return (fs::path(out_dir) / "points" / std::to_string(i)).string();
}

PointResult run_sweep_point(const ir::Sweep& sweep, const std::string& model_text, const std::string& out_dir,
                            long i) {
  const auto start = std::chrono::steady_clock::now();
  const fs::path dir = point_dir(out_dir, i);
  fs::create_directories(dir);
  PointResult r;
  r.point = i;
  r.stats.assign(sweep.collect.size(), kNan);
  const std::string text = frontend::point_model_text(sweep, model_text, i);
  const fs::path model_file = dir / "model.yaml";
  write_atomically(model_file, text);
  try {
    LoadOptions options;
    options.quiet = true;
    options.cache_by_sources = true;
    const Model model = Model::parse(text, model_file.string(), options);
    ResultsOutput csv((dir / "run.csv").string());
    SweepStatsObserver observer(sweep, model.ir(), csv);
    const runtime::SimulationReport report = model.simulate(request_of(sweep, model), observer);
    csv.flush();
    std::vector<std::string> refused;
    r.stats = observer.stats(&refused);
    r.done = report.message.empty();
    r.exit_status = r.done ? 0 : 3;
    r.message = report.message;
    if (r.done && !refused.empty()) {  // a statistic `mbfe stats` refuses: the request cannot be met
      r.done = false;
      r.exit_status = 2;
      for (const std::string& why : refused) r.message += (r.message.empty() ? "" : "; ") + why;
    }
  } catch (const ir::ModelError& e) {
    r.exit_status = 2;
    r.message = e.what();
  } catch (const runtime::InvalidInput& e) {
    r.exit_status = 2;
    r.message = e.what();
  } catch (const std::exception& e) {
    r.exit_status = 1;
    r.message = e.what();
  }
  r.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  write_result(dir, sweep, r, request_sha256(sweep, text));
  return r;
}

std::optional<PointResult> read_point_result(const ir::Sweep& sweep, const std::string& model_text,
                                             const std::string& out_dir, long i, bool* stale) {
  if (stale) *stale = false;
  const fs::path dir = point_dir(out_dir, i);
  if (!fs::exists(dir / "result.json") || !fs::exists(dir / "model.yaml")) return std::nullopt;
  const std::string text = frontend::point_model_text(sweep, model_text, i);
  try {
    const nlohmann::json j = nlohmann::json::parse(slurp(dir / "result.json"));
    // Another request (model, values, simulate: or collect: changed, or a
    // result written before requests were recorded): not this point's result.
    if (slurp(dir / "model.yaml") != text || !j.contains("request_sha256") ||
        j.at("request_sha256") != request_sha256(sweep, text)) {
      if (stale) *stale = true;
      return std::nullopt;
    }
    PointResult r;
    r.point = i;
    r.done = j.at("status") == "done";
    r.exit_status = j.at("exit_status");
    r.message = j.at("message");
    r.wall_seconds = j.at("wall_seconds");
    for (const ir::SweepCollect& c : sweep.collect) {
      const auto& v = j.at("stats").at(c.name);
      r.stats.push_back(v.is_number() ? v.get<double>() : kNan);
    }
    return r;
  } catch (const std::exception&) {
    return std::nullopt;  // unreadable: the point runs again
  }
}

std::vector<std::string> sweep_warnings(const ir::Sweep& sweep, const std::string& model_text,
                                        const ir::ModelOverrides& overrides, const std::string& out_dir) {
  std::vector<std::string> out;
  std::set<std::string> said;  // each warning without its file:line:col
  const auto add = [&](const std::vector<std::string>& warnings) {
    for (const std::string& w : warnings) {
      const std::size_t at = w.find("warning: ");
      if (said.insert(at == std::string::npos ? w : w.substr(at)).second) out.push_back(w);
    }
  };
  try {
    add(model_warnings(frontend::load_model_file(frontend::sweep_model_path(sweep), {}, overrides)));
  } catch (const std::exception&) {
    // The points report why the model does not load.
  }
  for (long i = 0; i < sweep.points(); ++i) {
    try {
      const std::string text = frontend::point_model_text(sweep, model_text, i);
      add(model_warnings(frontend::parse_model_text(text, point_dir(out_dir, i) + "/model.yaml")));
    } catch (const std::exception&) {
    }
  }
  return out;
}

SweepCounts write_summary(const ir::Sweep& sweep, const std::string& model_text, const std::string& out_dir,
                          const std::vector<std::string>& warnings) {
  SweepCounts counts;
  std::ostringstream csv;
  csv << "point";
  for (const ir::SweepVariable& v : sweep.vary) csv << "," << csv_field(v.path);
  csv << ",status,exit_status";
  for (const ir::SweepCollect& c : sweep.collect) csv << "," << c.name;
  csv << ",wall_s,message\n";
  nlohmann::json points = nlohmann::json::array();
  for (long i = 0; i < sweep.points(); ++i) {
    bool stale = false;
    const std::optional<PointResult> r = read_point_result(sweep, model_text, out_dir, i, &stale);
    if (stale) ++counts.stale;
    const std::string message = r ? r->message : stale ? kStaleMessage : "";
    const std::vector<int> idx = sweep.indices(i);
    nlohmann::json p;
    p["point"] = i;
    nlohmann::json values = nlohmann::json::object();
    csv << i;
    for (std::size_t k = 0; k < sweep.vary.size(); ++k) {
      const std::string& value = sweep.vary[k].values[static_cast<std::size_t>(idx[k])];
      csv << "," << csv_field(value);
      values[sweep.vary[k].path] = value;
    }
    p["values"] = values;
    const std::string status = !r ? "missing" : (r->done ? "done" : "failed");
    (r ? (r->done ? counts.done : counts.failed) : counts.missing) += 1;
    csv << "," << status << "," << (r ? std::to_string(r->exit_status) : "");
    nlohmann::json stats = nlohmann::json::object();
    for (std::size_t k = 0; k < sweep.collect.size(); ++k) {
      const double v = r ? r->stats[k] : kNan;
      csv << "," << number_text(v);
      stats[sweep.collect[k].name] = number_or_null(v);
    }
    csv << "," << (r ? number_text(r->wall_seconds) : "") << "," << csv_field(message) << "\n";
    p["status"] = status;
    p["exit_status"] = r ? nlohmann::json(r->exit_status) : nlohmann::json(nullptr);
    p["stats"] = stats;
    p["message"] = message;
    p["model"] = (fs::path("points") / std::to_string(i) / "model.yaml").string();
    points.push_back(p);
  }
  nlohmann::json summary;
  summary["sweep"] = sweep.name;
  summary["model"] = sweep.model_path;
  summary["mode"] = sweep.zip ? "zip" : "product";
  summary["points"] = points;
  summary["done"] = counts.done;
  summary["failed"] = counts.failed;
  summary["missing"] = counts.missing;
  summary["warnings"] = warnings;
  fs::create_directories(out_dir);
  write_atomically(fs::path(out_dir) / "summary.csv", csv.str());
  write_atomically(fs::path(out_dir) / "summary.json", json_text(summary, 2) + "\n");
  return counts;
}

}  // namespace mbfe::tool
