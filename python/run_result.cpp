// mbfe.Result and the report's tallies as Python objects (docs/python.md).
#include "python/run_result.h"

#include <pybind11/stl.h>

#include <algorithm>

namespace mbfe::python {

py::list tallies(const rt::SimulationReport& report) {
  py::list out;
  for (const rt::SpringContactTally& s : report.springs) {
    py::dict d;
    d["name"] = s.name;
    d["lift_offs"] = s.lift_offs;
    d["time_off"] = s.time_off;
    d["touched"] = s.touched;
    out.append(d);
  }
  return out;
}

py::list link_tallies(const rt::SimulationReport& report) {
  py::list out;
  for (const rt::LinkSlackTally& l : report.links) {
    py::dict d;
    d["name"] = l.name;
    d["slackenings"] = l.slackenings;
    d["time_slack"] = l.time_slack;
    out.append(d);
  }
  return out;
}

py::object estimate_of(const rt::SimulationReport& report) {
  if (!report.adjustment_estimate) return py::none();
  const rt::AdjustmentEstimate& e = *report.adjustment_estimate;
  py::list points;
  for (const rt::AdjustmentEstimatePoint& p : e.points) {
    py::dict d;
    d["what"] = p.what;
    d["beam"] = p.beam;
    d["s"] = p.s;
    d["moving"] = p.moving;
    d["series_compliance"] = p.series_compliance;
    d["omega"] = p.omega;
    d["compliance"] = p.compliance;
    d["static_change"] = p.static_change;
    d["dynamic_change"] = p.dynamic_change;
    d["changed_share"] = p.changed_share;
    d["estimate"] = p.estimate;
    d["band_change"] = p.band_change;
    d["omega_band"] = p.omega_band;
    points.append(d);
  }
  py::dict out;
  out["points"] = points;
  out["max"] = e.max;
  out["where"] = e.where.empty() ? py::object(py::none()) : py::object(py::str(e.where));
  if (e.linearised) {
    const rt::LinearisedEstimate& l = *e.linearised;
    py::list contacts;
    for (const rt::LinearisedContactChange& c : l.contacts) {
      py::dict d;
      d["contact"] = c.contact;
      d["relative"] = c.relative;
      d["peak_change"] = c.peak_change;
      d["peak"] = c.peak;
      contacts.append(d);
    }
    const bool any = l.worst >= 0;
    py::dict force;
    force["relative"] = any ? l.contacts[static_cast<std::size_t>(l.worst)].relative : 0.0;
    force["contact"] = any ? py::object(py::str(l.contacts[static_cast<std::size_t>(l.worst)].contact))
                           : py::object(py::none());
    py::dict block;
    block["contact_force"] = force;
    block["peak_change"] = any ? l.contacts[static_cast<std::size_t>(l.worst)].peak_change : 0.0;
    block["contacts"] = contacts;
    block["step"] = l.step;
    block["steps"] = l.steps;
    block["omega_excitation"] = l.omega_excitation;
    block["seconds"] = l.seconds;
    block["unconverged_steps"] = l.unconverged_steps;
    out["linearised"] = block;
  } else if (!e.linearised_unavailable.empty()) {
    py::dict block;
    block["not_estimated"] = e.linearised_unavailable;
    out["linearised"] = block;
  }
  out["not_estimated"] = e.not_estimated;
  py::list limits;
  for (const rt::AdjustmentEstimate::Limit& l : e.limits) {
    py::dict d;
    d["beam"] = l.beam;
    d["omega_limit"] = l.omega_limit;
    d["chosen"] = l.chosen;
    limits.append(d);
  }
  out["omega_limits"] = limits;
  return out;
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
