// mbfe.Result and the report's tallies as Python objects (docs/python.md).
#include "python/run_result.h"

#include <pybind11/stl.h>

#include <algorithm>

#include "api/run_record.h"
#include "python/json_objects.h"

namespace mbfe::python {

py::list tallies(const rt::SimulationReport& report) { return py::list(python_object(spring_tallies_json(report))); }

py::list link_tallies(const rt::SimulationReport& report) {
  return py::list(python_object(link_tallies_json(report)));
}

py::object estimate_of(const rt::SimulationReport& report) {
  if (!report.adjustment_estimate) return py::none();
  return python_object(adjustment_estimate_json(*report.adjustment_estimate));
}

Result result_of(const Columns& rows, const rt::SimulationReport& report) {
  Result out;
  out.columns = rows.columns;
  out.units = rows.units;
  out.notices = rows.notices;
  for (std::size_t k = 0; k < rows.columns.size(); ++k) {
    py::array_t<double> a(static_cast<py::ssize_t>(rows.data[k].size()));
    std::copy(rows.data[k].begin(), rows.data[k].end(), a.mutable_data());
    out.arrays[rows.columns[k]] = a;
  }
  out.status = rt::status_name(report);
  out.message = report.message;
  out.variant = report.variant;
  out.steps = static_cast<long>(report.run.steps);
  out.t_reached = report.run.t;
  out.wall_seconds = report.run.wall_seconds;
  out.springs = tallies(report);
  out.links = link_tallies(report);
  out.adjustment_estimate = estimate_of(report);
  return out;
}

void bind_result(py::module_& module) {
  py::class_<Result>(module, "Result", "A run: t and the columns by name (numpy arrays), the status.")
      .def_readonly("columns", &Result::columns)
      .def_readonly("units", &Result::units)
      .def_readonly("status", &Result::status, "completed, diverged, failed or interrupted")
      .def_readonly("message", &Result::message, "empty for a completed run, else why it ended")
      .def_readonly("variant", &Result::variant)
      .def_readonly("steps", &Result::steps)
      .def_readonly("t_reached", &Result::t_reached)
      .def_readonly("wall_seconds", &Result::wall_seconds)
      .def_readonly("notices", &Result::notices)
      .def_readonly("warnings", &Result::warnings,
                    "likely unit mistakes of the model and contacts that never touched their beam (as the sidecar's)")
      .def_readonly("springs", &Result::springs, "per slider_spring: name, lift_offs, time_off, touched")
      .def_readonly("links", &Result::links, "per link that can go slack: name, slackenings, time_slack")
      .def_readonly("adjustment_estimate", &Result::adjustment_estimate,
                    "adjusted runs: what the adjustment changes where forces act (points, max, where, "
                    "not_estimated; docs/damping-adjustment.md), else None")
      .def_property_readonly("t", [](const Result& r) { return r.arrays.at("t"); })
      .def("__getitem__", [](const Result& r, const std::string& name) {
        const auto it = r.arrays.find(name);
        if (it == r.arrays.end()) throw py::key_error("no column '" + name + "'");
        return it->second;
      })
      .def("__contains__", [](const Result& r, const std::string& name) { return r.arrays.count(name) > 0; })
      .def("__repr__", [](const Result& r) {
        return "<mbfe.Result " + r.status + ", " + std::to_string(r.steps) + " steps, " +
               std::to_string(r.columns.size()) + " columns>";
      });
}

}  // namespace mbfe::python
