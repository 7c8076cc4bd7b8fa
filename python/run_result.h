// A run's rows and report as the Python module returns them: mbfe.Result
// with its numpy columns, and the tallies and adjustment estimate as dicts
// (docs/python.md).
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <map>
#include <string>
#include <vector>

#include "api/mbfe.h"

namespace mbfe::python {

namespace py = pybind11;
namespace rt = mbfe::runtime;

/// The rows of a run, column by column.
class Columns : public rt::SimulationObserver {
 public:
  void begin(const rt::OutputLayout& layout) override {
    columns = layout.columns;
    units = layout.units;
    data.assign(columns.size(), {});
  }
  void row(const rt::OutputRow& row) override {
    for (std::size_t k = 0; k < row.values.size(); ++k) data[k].push_back(row.values[k]);
  }
  void notice(const std::string& text) override { notices.push_back(text); }
  std::vector<std::string> columns, units, notices;
  std::vector<std::vector<double>> data;
};

/// What simulate() returns: t, the columns by name, the status.
struct Result {
  std::vector<std::string> columns, units, notices;
  std::map<std::string, py::array_t<double>> arrays;
  std::string status, message, variant;
  std::vector<std::string> warnings;  // as the sidecar's (api/model_warnings.h)
  long steps = 0;
  double t_reached = 0.0, wall_seconds = 0.0;
  py::list springs, links;
  py::object adjustment_estimate = py::none();
};

/// The Result of a run from its rows and report (warnings left to the caller).
Result result_of(const Columns& rows, const rt::SimulationReport& report);

/// Per slider_spring: name, lift_offs, time_off, touched.
py::list tallies(const rt::SimulationReport& report);
/// Per link that can go slack: name, slackenings, time_slack.
py::list link_tallies(const rt::SimulationReport& report);
/// The run's adjustment estimate as a dict (the sidecar's
/// "adjustment_estimate"), None for a run of the original model.
py::object estimate_of(const rt::SimulationReport& report);

/// Registers mbfe.Result.
void bind_result(py::module_& module);

}  // namespace mbfe::python
