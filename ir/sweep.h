// A parameter study: one model file, some of its values varied, each point
// simulated and reduced to a few statistics (docs/sweeps.md). The front end
// fills it from a sweep file (frontend/parse_sweep.h); `mbfe sweep` runs it.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "ir/source_loc.h"

namespace mbfe::ir {

/// One varied value: a key of the model file addressed by names
/// (`bodies.carriage.joint.motion`), and the values it takes, as YAML scalars.
struct SweepVariable {
  std::string path;                 // as written
  std::vector<std::string> keys;    // path split at '.'
  std::vector<std::string> values;  // each a YAML scalar (number or string)
  SourceLoc loc;                    // of the path
};

/// kStd .. kLossPercent are the contact-force statistics of EN 50318 as
/// `mbfe stats` gives them (runtime/signal/force_statistics.h).
enum class SweepStat {
  kMax,
  kMin,
  kAbsMax,
  kMean,
  kRms,
  kInitial,
  kFinal,
  kStd,
  kStatisticalMax,
  kStatisticalMin,
  kLossPercent
};

/// One statistic of one output column over a run: a column of the summary.
struct SweepCollect {
  std::string name;    // summary column, an identifier
  std::string column;  // CSV column of the run, e.g. "deck@10.0"
  SweepStat stat = SweepStat::kMax;
  /// As `mbfe stats --lowpass --order --from --to`: the column low-pass
  /// filtered (Butterworth, zero phase; Hz, 0: none) over the whole run, then
  /// the window [from, to] (s) cut. Absent (0, and both unset): the stat over
  /// every row as written.
  double lowpass_hz = 0.0;
  int order = 4;
  std::optional<double> from, to;
  SourceLoc loc;

  /// Whether the stat is taken as `mbfe stats` takes it: filtered or
  /// windowed, or one of the EN 50318 statistics.
  bool as_stats() const {
    return lowpass_hz > 0.0 || from || to || stat == SweepStat::kStd || stat == SweepStat::kStatisticalMax ||
           stat == SweepStat::kStatisticalMin || stat == SweepStat::kLossPercent;
  }
};

/// The `simulate:` block: what `mbfe simulate` would take as flags.
struct SweepSimulation {
  std::string integrator;  // empty: the model's
  double step = 0.0;       // s; 0: the model's
  double t_end = 0.0;      // s; 0: the model's
  std::vector<std::string> probes;  // "beam@s"
  std::string adjust;      // "", "on" or "off"
  /// run.csv keeps every beam coordinate and rate; false (the default): the
  /// other columns only (probes, rigid coordinates, contact forces, ...), the
  /// statistics still taken over every column.
  bool full_state = false;
};

struct Sweep {
  std::string name;          // identifier
  std::string source_path;   // the sweep file, as given
  std::string model_path;    // the model file, relative to the sweep file's folder when not absolute
  SourceLoc model_loc;
  std::vector<SweepVariable> vary;
  /// `set:`: values every point takes (one value each), applied before the
  /// points' `vary` values, as `mbfe sweep --set` would be.
  std::vector<SweepVariable> set;
  bool zip = false;          // false: every combination (product); true: the i-th values together
  SweepSimulation simulation;
  std::vector<SweepCollect> collect;

  /// Number of points: the product of the value counts, or (zip) the common count.
  long points() const;
  /// The value index of each variable at point `i` (0-based; the last
  /// variable varies fastest in a product).
  std::vector<int> indices(long i) const;
};

}  // namespace mbfe::ir
