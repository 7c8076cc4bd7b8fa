// What a sweep point keeps of its run (docs/sweeps.md): the rows in run.csv
// (without the beams' coordinates unless the sweep asks for full_state) and
// the statistics of its `collect:` entries.
#pragma once

#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include "api/results_output.h"
#include "ir/model.h"
#include "ir/sweep.h"
#include "runtime/simulation/simulation_types.h"

namespace mbfe::tool {

/// Whether `column` is a beam's coordinate or its rate ("deck_w3",
/// "deck_dw3_dot"): what a sweep's run.csv leaves out unless full_state.
bool is_beam_coordinate(const ir::Model& model, const std::string& column);

/// The run's rows into run.csv (without the beams' coordinates unless the
/// sweep asks for full_state), and the statistics of the collected columns
/// (over every column): over the rows as written, or, for an entry with a
/// low-pass filter, a window or an EN 50318 statistic, by the code of
/// `mbfe stats` (runtime/signal/force_statistics.h) on the column's samples.
class SweepStatsObserver : public runtime::SimulationObserver {
 public:
  SweepStatsObserver(const ir::Sweep& sweep, const ir::Model& model, ResultsOutput& csv)
      : sweep_(sweep), model_(model), csv_(csv) {}

  /// @throws runtime::InvalidInput for a collected column the run does not have.
  void begin(const runtime::OutputLayout& layout) override;
  void row(const runtime::OutputRow& row) override;

  /// One value per collect entry, NaN where there were no rows. An entry the
  /// statistics of `mbfe stats` refuse (uneven rows under a filter, an empty
  /// window) is NaN too, and `errors` (when given) gets "collect 'x': why".
  std::vector<double> stats(std::vector<std::string>* errors = nullptr) const;

 private:
  struct Acc {
    double max = -std::numeric_limits<double>::infinity();
    double min = std::numeric_limits<double>::infinity();
    double absmax = 0.0, sum = 0.0, sum2 = 0.0, first = std::numeric_limits<double>::quiet_NaN(),
           last = std::numeric_limits<double>::quiet_NaN();
    long n = 0;
  };
  const ir::Sweep& sweep_;
  const ir::Model& model_;
  ResultsOutput& csv_;
  std::vector<std::size_t> kept_;     // the columns of run.csv, indices into a row
  std::vector<double> kept_values_;
  std::vector<int> columns_;
  std::vector<Acc> acc_;
  // The samples of the entries taken as `mbfe stats` takes them (empty for
  // the others): times, and per entry its column's values.
  std::vector<double> times_;
  std::vector<std::vector<double>> samples_;
  bool any_samples_ = false;
};

}  // namespace mbfe::tool
