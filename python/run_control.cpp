// simulate() and Simulator: a model run from Python, Ctrl-C between steps.
#include "python/run_control.h"

#include <pybind11/complex.h>
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "api/model_warnings.h"

namespace mbfe::python {

namespace {

/// Ctrl-C between steps: every this many steps the run looks for a Python
/// signal (the interpreter's handler has only set a flag).
constexpr std::int64_t kSignalCheckSteps = 1024;

/// A monitor that asks Python for pending signals (taking the GIL when it
/// was released); a KeyboardInterrupt stops the run and is kept in `caught`.
rt::StepMonitor signal_monitor(std::optional<py::error_already_set>& caught, bool gil_released) {
  return [&caught, gil_released](double, std::int64_t steps) {
    if (steps % kSignalCheckSteps != 0 || caught) return !caught;
    std::optional<py::gil_scoped_acquire> gil;
    if (gil_released) gil.emplace();
    if (PyErr_CheckSignals() != 0) caught.emplace();  // fetches the exception the handler raised
    return !caught;
  };
}

}  // namespace

rt::SimulationRequest request_of(const Model& m, const std::string& integrator, std::optional<double> step,
                                 std::optional<double> t_end, std::optional<bool> adjust,
                                 const std::vector<std::string>& probes, std::optional<long> every,
                                 std::optional<bool> static_start, const std::string& formulation) {
  // The command line's rule for --every: a positive whole number when given;
  // absent, at most about 10,000 rows.
  if (every && *every < 1) throw rt::InvalidRequest("every", "must be a positive integer, got " + std::to_string(*every));
  rt::SimulationRequest r = m.request();
  if (!integrator.empty()) r.integrator = rt::parse_integrator(integrator);
  if (step) r.step = *step;
  if (t_end) r.t_end = *t_end;
  r.adjust = adjust;
  for (const std::string& p : probes) r.probes.push_back(rt::parse_probe(p));
  r.every = every.value_or(0);  // 0: the runtime's automatic choice
  r.static_start = static_start;
  if (formulation == "augmented") r.formulation = rt::CoupledFormulation::kAugmented;
  else if (formulation != "partitioned")
    throw rt::InvalidRequest("formulation", "is partitioned or augmented, got '" + formulation + "'");
  return r;
}

Result simulate(const Model& m, const std::string& integrator, std::optional<double> step,
                std::optional<double> t_end, std::optional<bool> adjust, const std::vector<std::string>& probes,
                std::optional<long> every, std::optional<bool> static_start, const std::string& formulation) {
  const rt::SimulationRequest r =
      request_of(m, integrator, step, t_end, adjust, probes, every, static_start, formulation);
  Columns rows;
  rt::SimulationReport report;
  std::optional<py::error_already_set> caught;
  {
    py::gil_scoped_release release;  // a long run does not hold up other Python threads
    report = m.simulate(r, rows, signal_monitor(caught, true));
  }
  Result out = result_of(rows, report);
  out.warnings = mbfe::model_warnings(m.ir());
  for (const std::string& w : mbfe::run_warnings(m.ir(), report)) out.warnings.push_back(w);
  if (caught) {
    // Ctrl-C: the interpreter's KeyboardInterrupt, carrying the rows so far.
    caught->value().attr("result") = py::cast(out);
    throw *caught;
  }
  return out;
}

double PySimulator::advance_to(double t) {
  // The GIL stays held: a load given as a Python function is called at
  // every stage of every step.
  std::optional<py::error_already_set> caught;
  sim_.advance_to(t, signal_monitor(caught, false));
  if (caught) throw *caught;
  return sim_.time();
}

void bind_simulator(py::module_& module) {
  py::class_<PySimulator>(module, "Simulator",
                          "A simulation stepped from Python: advance_to(t), state(), set_state(q, qd), outputs(), "
                          "set_beam_load(beam, s, value or function of t), report()")
      .def("advance_to", &PySimulator::advance_to, py::arg("t"),
           "steps to the last step time at or before t (and t_end); returns the time reached")
      .def_property_readonly("time", [](PySimulator& s) { return s.sim().time(); })
      .def_property_readonly("step", [](PySimulator& s) { return s.sim().step(); })
      .def_property_readonly("t_end", [](PySimulator& s) { return s.sim().t_end(); })
      .def_property_readonly("steps", [](PySimulator& s) { return s.sim().steps(); })
      .def_property_readonly("finished", [](PySimulator& s) { return s.sim().finished(); })
      .def_property_readonly("columns", [](PySimulator& s) { return s.sim().layout().columns; })
      .def_property_readonly("units", [](PySimulator& s) { return s.sim().layout().units; })
      .def_property_readonly("notices", [](PySimulator& s) { return s.sim().notices(); })
      .def("outputs", &PySimulator::outputs, "the output columns at the current state, by name")
      .def("state", &PySimulator::state, "(q, qd): the full coordinates [q_b; q_c] and rates, numpy arrays")
      .def(
          "set_state", [](PySimulator& s, const Eigen::VectorXd& q, const Eigen::VectorXd& qd) { s.sim().set_state(q, qd); },
          py::arg("q"), py::arg("qd"), "sets the state (projected onto the contacts)")
      .def(
          "set_beam_load",
          [](PySimulator& s, const std::string& beam, double at, py::object value) {
            if (PyCallable_Check(value.ptr())) {
              s.sim().set_beam_load(beam, at, [value](double t) { return value(t).cast<double>(); });
            } else {
              const double v = value.cast<double>();
              s.sim().set_beam_load(beam, at, [v](double) { return v; });
            }
          },
          py::arg("beam"), py::arg("s"), py::arg("value"),
          "a point load (N) on a beam at s m from now on: a number, or a function of t")
      .def(
          "report",
          [](PySimulator& s) {
            const rt::SimulationReport r = s.sim().report();
            py::dict d;
            d["status"] = rt::status_name(r);
            d["message"] = r.message;
            d["variant"] = r.variant;
            d["steps"] = r.run.steps;
            d["t_reached"] = r.run.t;
            d["springs"] = tallies(r);
            d["links"] = link_tallies(r);
            d["adjustment_estimate"] = estimate_of(r);
            return d;
          },
          "the run so far: status, message, steps, tallies");
}

}  // namespace mbfe::python
