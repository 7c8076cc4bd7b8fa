// `mbfe stats RESULTS.csv --column NAME [--lowpass HZ] [--from T] [--to T] [--json]`:
// the contact-force statistics of EN 50318 (runtime/signal/force_statistics.h);
// without --column, the peak deck acceleration of the BEAM@S:acc columns and,
// with --en1990, its check against EN 1990 Annex A2.
#include <cmath>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "api/json_text.h"
#include "runtime/signal/force_statistics.h"
#include "tool/cli_args.h"
#include "tool/commands.h"
#include "tool/results_columns.h"

namespace mbfe::tool {

namespace {

constexpr const char* kHelp = R"(Usage: mbfe stats RESULTS.csv --column NAME [options]
       mbfe stats RESULTS.csv [--en1990 [ballasted|direct]] [--column BEAM@S:acc] [options]

Statistics of one column of a results file (the CSV, or the .npy with its
.npy.json, that mbfe simulate writes) over a time window, as EN 50318
asks of a pantograph's contact force: mean, std (population, divided by n),
statistical_max and statistical_min (mean +- 3 std), max and min, all of the
low-pass filtered signal, and loss_percent, the share of the window's samples
where the unfiltered value is <= 0 (contact lost).

The filter is a Butterworth low-pass (second-order sections) run forward and
backward (zero phase), over the whole signal before the window is cut; it
needs evenly spaced rows (write them with mbfe simulate --every N) and a
cut-off of at least 1e-5 of their rate. Times must increase strictly, and a
NaN or infinite time or value is refused with its line (exit status 2).

Options:
  --column NAME   the column (e.g. force_contact)
  --lowpass HZ    cut-off of the low-pass filter (EN 50318: 20); default none
  --order N       the filter's order (default 4; forward and backward make it 2N)
  --from T        start of the window in s (default: the first row)
  --to T          end of the window in s (default: the last row)
  --json          print {"mean", "std", "statistical_max", "statistical_min",
                  "max", "min", "loss_percent"} instead of the table

Without --column: the peak deck acceleration, the largest |a| of every
acceleration probe column of a beam (BEAM@S:acc, written by mbfe simulate
--probe deck@10:acc), each and overall, over the window and after the
low-pass filter when one is given. With --en1990 TRACK the peak is checked
against the limit of EN 1990 Annex A2 (A2.4.4.2.1(4)P): 3.5 m/s^2 for a
ballasted track, 5 m/s^2 for a direct-fastened one; --en1990 alone checks
the ballasted limit and reports the direct-fastened one too. The standard counts
frequencies up to max(30 Hz, 1.5 f0, f3) (f0, f3 the deck's first and
third bending frequencies): give that as --lowpass. --en1990 with --column
checks that one column. The check is printed ("within" or "EXCEEDS"); the
exit status stays 0. --json prints {"columns": [{"name", "peak"}],
"peak", "unit", and with --en1990 "en1990": {"track", "limit", "ok",
"checks": [{"track", "limit", "ok"}, ...]}} (checks: every limit reported,
the one of "track" first).

Examples:
  mbfe simulate models/bridge_moving_mass.yaml --every 1 --out crossing.csv
  mbfe stats crossing.csv --column force_tyre --lowpass 20 --from 0.2 --to 1.0
  mbfe simulate models/bridge_moving_mass.yaml --every 1 --probe deck@10:acc,deck@5:acc --out acc.csv
  mbfe stats acc.csv --en1990 ballasted --lowpass 30
  mbfe stats acc.csv --en1990 --lowpass 30
)";

/// EN 1990:2002+A1:2005, Annex A2, A2.4.4.2.1(4)P: the largest peak vertical
/// deck acceleration a railway bridge may see (m/s^2).
constexpr double kBallastedLimit = 3.5;      // gamma_bt, ballasted track
constexpr double kDirectFastenedLimit = 5.0;  // gamma_df, direct-fastened track

/// A column of a beam's acceleration probe: BEAM@S:acc.
bool is_deck_acceleration(const std::string& name) {
  const std::string tail = ":acc";
  return name.find('@') != std::string::npos && name.size() > tail.size() &&
         name.compare(name.size() - tail.size(), tail.size(), tail) == 0;
}

/// The statistics of `name`, bad samples named by their row.
runtime::ForceStatistics statistics_of(const ResultColumns& cols, std::size_t index, const std::string& name,
                                       const runtime::ForceStatisticsOptions& options, const std::string& path) {
  const std::vector<double>& t = cols.values[0];
  const std::vector<double>& values = cols.values[index];
  try {
    return runtime::force_statistics(t, values, options);
  } catch (const runtime::BadSample& e) {
    const std::size_t i = e.sample;
    if (!std::isfinite(t[i]) || !std::isfinite(values[i])) {
      const bool time = !std::isfinite(t[i]);
      std::ostringstream os;
      os << cols.where(i) << ": column '" << (time ? "t" : name) << "' is " << (time ? t[i] : values[i])
         << "; the statistics take finite numbers only";
      throw UsageError(os.str());
    }
    throw UsageError(cols.where(i) + ": " + e.what());
  } catch (const std::invalid_argument& e) {
    throw UsageError(path + ": " + e.what());
  }
}

/// The peak deck acceleration of `names` and, for a track, its EN 1990 check.
int deck_acceleration(const std::string& path, const std::vector<std::string>& names,
                      const std::optional<std::string>& track, const runtime::ForceStatisticsOptions& options,
                      bool json) {
  std::vector<std::string> wanted = {"t"};
  wanted.insert(wanted.end(), names.begin(), names.end());
  const ResultColumns cols = read_columns(path, wanted);
  double peak = 0.0;
  nlohmann::json columns = nlohmann::json::array();
  std::ostringstream table;
  table << std::setprecision(6);
  for (std::size_t c = 0; c < names.size(); ++c) {
    const runtime::ForceStatistics s = statistics_of(cols, c + 1, names[c], options, path);
    const double p = std::max(std::abs(s.max), std::abs(s.min));
    peak = std::max(peak, p);
    columns.push_back({{"name", names[c]}, {"peak", p}});
    table << "  " << std::left << std::setw(24) << names[c] << std::right << " " << p << " m/s^2\n";
  }
  // The track asked for (bare --en1990: ballasted), then the other one when
  // none was named: a ballasted check says how a direct-fastened deck fares.
  std::vector<std::string> tracks;
  if (track) {
    tracks.push_back(track->empty() ? "ballasted" : *track);
    if (track->empty()) tracks.push_back("direct");
  }
  nlohmann::json checks = nlohmann::json::array();
  std::ostringstream verdicts;
  for (const std::string& name : tracks) {
    const double limit = name == "ballasted" ? kBallastedLimit : kDirectFastenedLimit;
    const bool ok = peak <= limit;
    checks.push_back({{"track", name}, {"limit", limit}, {"ok", ok}});
    verdicts << "EN 1990 A2.4.4.2.1(4)P, " << (name == "ballasted" ? "ballasted" : "direct-fastened")
             << " track: limit " << limit << " m/s^2; the peak " << (ok ? "is within it" : "EXCEEDS it") << "\n";
  }
  if (json) {
    nlohmann::json j;
    j["columns"] = columns;
    j["peak"] = peak;
    j["unit"] = "m/s^2";
    if (track) {
      j["en1990"] = checks.front();
      j["en1990"]["checks"] = checks;
    }
    std::cout << json_text(j, 2) << "\n";
    return 0;
  }
  std::cout << "peak deck acceleration, " << cols.values[0].size() << " rows"
            << (options.lowpass_hz > 0.0 ? ", low-pass " : ", unfiltered");
  if (options.lowpass_hz > 0.0) std::cout << options.lowpass_hz << " Hz";
  std::cout << "\n"
            << table.str() << std::setprecision(6) << "  peak                     " << peak << " m/s^2\n"
            << verdicts.str();
  return 0;
}

}  // namespace

int cmd_stats(const Args& args) {
  const ParsedArgs parsed(args, {"column", "lowpass", "order", "from", "to"}, {"json", "help"},
                          {{"en1990", {"ballasted", "direct"}}});
  if (parsed.has("help")) {
    std::cout << kHelp;
    return 0;
  }
  const auto track = parsed.value("en1990");
  if (parsed.positional().size() != 1) {
    std::string got;
    for (const std::string& p : parsed.positional()) got += (got.empty() ? "" : ", ") + p;
    // `--en1990 slab`: a word that is no track became an argument of its own.
    throw UsageError("expected one RESULTS.csv, got " + std::to_string(parsed.positional().size()) + " arguments" +
                     (got.empty() ? std::string() : " (" + got + ")") +
                     (track && track->empty() ? "; --en1990 takes ballasted (3.5 m/s^2), direct (direct-fastened, "
                                                "5 m/s^2) or nothing (ballasted, and direct-fastened reported too)"
                                              : " (see --help)"));
  }
  const auto column = parsed.value("column");
  if (column && column->empty()) throw UsageError("--column: expected a column name, got an empty one");
  if (track && !track->empty() && *track != "ballasted" && *track != "direct")
    throw UsageError("--en1990 takes ballasted (3.5 m/s^2) or direct (direct-fastened, 5 m/s^2), got '" + *track + "'");
  runtime::ForceStatisticsOptions options;
  if (const auto hz = parsed.number("lowpass")) {
    if (!(*hz > 0.0)) throw UsageError("--lowpass must be > 0 Hz");
    options.lowpass_hz = *hz;
  }
  if (const auto order = parsed.number("order")) {
    if (*order != static_cast<int>(*order) || *order < 1 || *order > 8)
      throw UsageError("--order must be a whole number 1..8");
    options.order = static_cast<int>(*order);
  }
  if (const auto from = parsed.number("from")) options.from = *from;
  if (const auto to = parsed.number("to")) options.to = *to;
  if (options.from > options.to) throw UsageError("--from must not be after --to");
  const std::string& path = parsed.positional()[0];
  if (!column || track) {
    std::vector<std::string> names;
    if (column) {
      names.push_back(*column);
    } else {
      for (const std::string& name : result_column_names(path))
        if (is_deck_acceleration(name)) names.push_back(name);
      if (names.empty())
        throw UsageError("--column NAME is required: " + path +
                         " has no deck acceleration column (BEAM@S:acc, from --probe deck@10:acc), whose peak "
                         "mbfe stats gives without one");
    }
    return deck_acceleration(path, names, track, options, parsed.has("json"));
  }
  const ResultColumns cols = read_columns(path, {"t", *column});
  const runtime::ForceStatistics s = statistics_of(cols, 1, *column, options, path);
  if (parsed.has("json")) {
    nlohmann::json j;
    j["mean"] = s.mean;
    j["std"] = s.std;
    j["statistical_max"] = s.statistical_max;
    j["statistical_min"] = s.statistical_min;
    j["max"] = s.max;
    j["min"] = s.min;
    j["loss_percent"] = s.loss_percent;
    std::cout << json_text(j, 2) << "\n";
    return 0;
  }
  std::cout << "'" << *column << "', " << s.samples << " samples"
            << (options.lowpass_hz > 0.0 ? ", low-pass " : ", unfiltered");
  if (options.lowpass_hz > 0.0) std::cout << options.lowpass_hz << " Hz (Butterworth order " << options.order << ", zero phase)";
  std::cout << "\n" << std::setprecision(6);
  std::cout << "  mean             " << s.mean << "\n"
            << "  std              " << s.std << "\n"
            << "  statistical_max  " << s.statistical_max << "   (mean + 3 std)\n"
            << "  statistical_min  " << s.statistical_min << "   (mean - 3 std)\n"
            << "  max              " << s.max << "\n"
            << "  min              " << s.min << "\n"
            << "  loss_percent     " << s.loss_percent << "   (% of samples with the unfiltered value <= 0)\n";
  return 0;
}

}  // namespace mbfe::tool
