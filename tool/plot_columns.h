// What the columns of a results CSV are, for `mbfe plot`: each column's unit
// (from the FILE.csv.json that `mbfe simulate` writes beside the CSV, or from
// its name), the quantity a unit measures, and the panels that group columns
// of one kind so that a 1e4 N force does not flatten millimetres.
#pragma once

#include <map>
#include <string>
#include <vector>

namespace mbfe::tool {

/// Units by column name from CSV_PATH.json; empty when there is none or it
/// cannot be read.
std::map<std::string, std::string> sidecar_units(const std::string& csv_path);

/// The unit of a column: the sidecar's, else what its name says (t: s,
/// lambda_* and force_*: N, *_drive: N or N m, deflection_*, probes b@s,
/// *_w<node>, phi_abs: m, *_dw<node>: 1, a rate *_dot: the unit per s), else
/// "" (a body coordinate without a sidecar: m or rad).
std::string column_unit(const std::string& column, const std::map<std::string, std::string>& sidecar);

/// "displacement", "angle", "force", "torque", "velocity", ... for a unit;
/// "value" when unknown.
std::string quantity_of(const std::string& unit);

/// The chosen columns grouped by unit, in order of first appearance: one
/// panel each.
std::vector<std::vector<std::size_t>> panels_by_unit(const std::vector<std::size_t>& columns,
                                                     const std::vector<std::string>& units);

}  // namespace mbfe::tool
