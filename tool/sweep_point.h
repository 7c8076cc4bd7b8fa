// One point of a sweep (docs/sweeps.md): its model file written out, the run,
// its statistics, and its result file; and the summary of all of them. Every
// point lives in DIR/points/<i>/ (model.yaml, run.csv, result.json), so that
// any run can be repeated by hand, and a result present means the point has
// been tried.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "ir/model_override.h"
#include "ir/sweep.h"

namespace mbfe::tool {

struct PointResult {
  long point = 0;
  bool done = false;          // completed; false: failed (see exit_status, message)
  int exit_status = 0;        // what `mbfe simulate` would have returned: 0, 1, 2 or 3
  std::string message;        // why it failed; empty when done
  std::vector<double> stats;  // one per collect entry; NaN when not computed
  double wall_seconds = 0.0;
};

std::string point_dir(const std::string& out_dir, long i);

/// Runs point i: writes its model.yaml, run.csv and result.json. Never throws
/// for a failure of the point itself (bad combination, divergence): that is
/// the result.
PointResult run_sweep_point(const ir::Sweep& sweep, const std::string& model_text, const std::string& out_dir,
                            long i);

/// The result file of point i, if there is one for the point's current
/// request: its model text (the base model with the point's values), the
/// sweep's simulate block and collect entries (result.json records their
/// SHA-256). A result of another request does not count (*stale, if given, is
/// set): the point runs again rather than mix old numbers into the summary.
std::optional<PointResult> read_point_result(const ir::Sweep& sweep, const std::string& model_text,
                                             const std::string& out_dir, long i, bool* stale = nullptr);

struct SweepCounts {
  long done = 0, failed = 0, missing = 0;
  long stale = 0;  // of the missing: a result of another request is there
};

/// The sweep's warnings about likely unit mistakes (api/model_warnings.h),
/// once each: those of the model file with the --set `overrides` (at its
/// file:line:col), then those that only a point's values bring (at the first
/// such point's DIR/points/<i>/model.yaml). Empty for a plausible sweep; a
/// point that does not parse adds nothing (its own run reports why).
std::vector<std::string> sweep_warnings(const ir::Sweep& sweep, const std::string& model_text,
                                        const ir::ModelOverrides& overrides, const std::string& out_dir);

/// Writes DIR/summary.csv and DIR/summary.json from the result files present;
/// summary.json lists `warnings` (sweep_warnings) under "warnings".
SweepCounts write_summary(const ir::Sweep& sweep, const std::string& model_text, const std::string& out_dir,
                          const std::vector<std::string>& warnings);

}  // namespace mbfe::tool
