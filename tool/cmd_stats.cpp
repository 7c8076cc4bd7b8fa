// `mbfe stats RESULTS.csv --column NAME [--lowpass HZ] [--from T] [--to T] [--json]`:
// the contact-force statistics of EN 50318 (runtime/signal/force_statistics.h).
#include <cmath>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

#include "runtime/signal/force_statistics.h"
#include "tool/cli_args.h"
#include "tool/commands.h"
#include "api/json_text.h"
#include "tool/results_columns.h"

namespace mbfe::tool {

namespace {

constexpr const char* kHelp = R"(Usage: mbfe stats RESULTS.csv --column NAME [options]

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

Example:
  mbfe simulate models/bridge_moving_mass.yaml --every 1 --out crossing.csv
  mbfe stats crossing.csv --column force_tyre --lowpass 20 --from 0.2 --to 1.0
)";

}  // namespace

int cmd_stats(const Args& args) {
  const ParsedArgs parsed(args, {"column", "lowpass", "order", "from", "to"}, {"json", "help"});
  if (parsed.has("help")) {
    std::cout << kHelp;
    return 0;
  }
  if (parsed.positional().size() != 1)
    throw UsageError("expected one RESULTS.csv, got " + std::to_string(parsed.positional().size()) +
                     " arguments (see --help)");
  const auto column = parsed.value("column");
  if (!column || column->empty()) throw UsageError("--column NAME is required");
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
  const ResultColumns cols = read_columns(parsed.positional()[0], {"t", *column});
  const std::vector<double>& t = cols.values[0];
  const std::vector<double>& values = cols.values[1];
  runtime::ForceStatistics s;
  try {
    s = runtime::force_statistics(t, values, options);
  } catch (const runtime::BadSample& e) {
    const std::size_t i = e.sample;
    if (!std::isfinite(t[i]) || !std::isfinite(values[i])) {
      const bool time = !std::isfinite(t[i]);
      std::ostringstream os;
      os << cols.where(i) << ": column '" << (time ? "t" : *column) << "' is " << (time ? t[i] : values[i])
         << "; the statistics take finite numbers only";
      throw UsageError(os.str());
    }
    throw UsageError(cols.where(i) + ": " + e.what());
  } catch (const std::invalid_argument& e) {
    throw UsageError(parsed.positional()[0] + ": " + e.what());
  }
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
