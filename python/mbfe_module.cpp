// The Python module `mbfe` (pybind11): the public C++ API (api/mbfe.h) with
// numpy arrays in and out (docs/python.md).
//
//   import mbfe
//   m = mbfe.load("models/paper_platform.yaml")
//   r = m.simulate(integrator="rk4", step=2e-5, t_end=1.0, probes=["beam1@0.35"])
//   r.t, r["beam1@0.35"], r.status, r.message
//
// Bad input raises mbfe.ModelError (a ValueError) with the same
// `file:line:col: what is wrong` message as the command line.
#include <pybind11/complex.h>
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "api/mbfe.h"
#include "api/model_warnings.h"
#include "api/simulator.h"
#include "ir/coordinate_layout.h"

namespace py = pybind11;

namespace {

using mbfe::Model;
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

/// `text` as a Python str, invalid UTF-8 (a file name's bytes) as U+FFFD: a
/// message PyErr_SetString cannot decode came out empty.
py::str message_text(const std::string& text) {
  PyObject* s = PyUnicode_DecodeUTF8(text.data(), static_cast<Py_ssize_t>(text.size()), "replace");
  if (!s) throw py::error_already_set();
  return py::reinterpret_steal<py::str>(s);
}

/// A path or name that will name a file: a NUL would end it early (the C
/// library stops there), so that "ok.yaml\0junk" would load ok.yaml.
void refuse_nul(const std::string& text, const char* what) {
  const auto nul = text.find('\0');
  if (nul != std::string::npos)
    throw py::value_error(std::string(what) + " holds a NUL character (at " + std::to_string(nul) +
                          "), which no file name can hold");
}

/// `set={"loads.front_susp.stiffness": 2e6, ...}` as the command line's
/// --set PATH=VALUE flags: a number as its shortest round-trip text (Python's
/// repr), a bool as true/false, a string as written.
mbfe::ir::ModelOverrides model_overrides(const py::object& set) {
  mbfe::ir::ModelOverrides overrides;
  if (set.is_none()) return overrides;
  if (!py::isinstance<py::dict>(set)) throw py::type_error("set: expected a dict {PATH: value}");
  for (const auto& [key, value] : set.cast<py::dict>()) {
    if (!py::isinstance<py::str>(key)) throw py::type_error("set: each PATH is a string, such as 'beams.deck.section.inertia'");
    const std::string path = key.cast<std::string>();
    refuse_nul(path, "a PATH of set");
    std::string text;
    if (py::isinstance<py::bool_>(value)) text = value.cast<bool>() ? "true" : "false";
    else if (py::isinstance<py::int_>(value) || py::isinstance<py::float_>(value)) text = py::repr(value).cast<std::string>();
    else if (py::isinstance<py::str>(value)) text = value.cast<std::string>();
    else throw py::type_error("set['" + path + "']: expected a number, a bool or a string");
    refuse_nul(text, "a value of set");
    if (path.empty()) throw py::value_error("set: a PATH is empty");
    overrides.push_back({path, text});
  }
  return overrides;
}

py::object limit_value(const rt::StepLimit& l) {
  if (l.kind == rt::StepLimit::Kind::kFinite) return py::float_(l.h);
  if (l.kind == rt::StepLimit::Kind::kUnconditional) return py::float_(std::numeric_limits<double>::infinity());
  return py::float_(0.0);
}

/// The model's request (its `simulation:` block), the arguments overriding it.
/// The runtime checks the ranges; its errors name these arguments.
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

/// The run's adjustment estimate as a dict (the sidecar's
/// "adjustment_estimate"), None for a run of the original model.
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
  out["where"] = e.largest >= 0 ? py::object(py::str(e.points[static_cast<std::size_t>(e.largest)].what)) : py::none();
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

/// A simulation stepped from Python (api/simulator.h).
class PySimulator {
 public:
  PySimulator(const Model& m, const rt::SimulationRequest& r) : sim_(m, r) {}
  mbfe::Simulator& sim() { return sim_; }
  double advance_to(double t) {
    // The GIL stays held: a load given as a Python function is called at
    // every stage of every step.
    std::optional<py::error_already_set> caught;
    sim_.advance_to(t, signal_monitor(caught, false));
    if (caught) throw *caught;
    return sim_.time();
  }
  py::dict outputs() {
    const std::vector<double>& v = sim_.outputs();
    py::dict d;
    const auto& columns = sim_.layout().columns;
    for (std::size_t k = 0; k < columns.size(); ++k) d[py::str(columns[k])] = v[k];
    return d;
  }
  py::tuple state() {
    Eigen::VectorXd q, qd;
    sim_.state(q, qd);
    return py::make_tuple(q, qd);
  }

 private:
  mbfe::Simulator sim_;
};

}  // namespace

PYBIND11_MODULE(mbfe, module) {
  module.doc() = "mbfe: symbolic multibody + finite-element beam modeler (docs/python.md)";
  static py::exception<mbfe::ir::ModelError> model_error(module, "ModelError", PyExc_ValueError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const mbfe::ir::ModelError& e) {
      PyErr_SetObject(model_error.ptr(), message_text(e.what()).ptr());
    } catch (const rt::InvalidInput& e) {  // InvalidRequest too: its field is the argument's name
      PyErr_SetObject(PyExc_ValueError, message_text(e.what()).ptr());
    }
  });

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

  py::class_<Model>(module, "Model", "A model with its solver (api/mbfe.h).")
      .def_property_readonly("name", [](const Model& m) { return m.ir().name; })
      .def_property_readonly("kind", [](const Model& m) {
        switch (m.kind()) {
          case rt::ModelKind::kRigid: return "rigid";
          case rt::ModelKind::kBeams: return "beams";
          case rt::ModelKind::kCoupled: return "coupled";
        }
        return "?";
      })
      .def_property_readonly("coordinates", [](const Model& m) {
        // The position coordinates: the bodies' names, or a spatial model's
        // <body>_qw .. for quaternions (ir/coordinate_layout.h).
        return mbfe::ir::coordinate_layout(m.ir()).position_names;
      })
      .def(
          "eval",
          [](const Model& m, std::vector<double> q, std::vector<double> qd, double t, std::vector<double> qc,
             std::vector<double> qcd) {
            mbfe::State s;
            s.q = std::move(q);
            s.qd = std::move(qd);
            s.qc = std::move(qc);
            s.qcd = std::move(qcd);
            s.t = t;
            const mbfe::Evaluation e = m.evaluate(s);
            py::dict d;
            d["M"] = e.M;
            d["F"] = e.F;
            d["Q"] = e.Q;
            if (e.has_constraints) {
              d["Phi"] = e.phi;
              d["Jb"] = e.jb;
              d["Jc"] = e.jc;
              d["gamma"] = e.gamma;
            }
            return d;
          },
          py::arg("q"), py::arg("qd"), py::arg("t") = 0.0, py::arg("qc") = std::vector<double>{},
          py::arg("qcd") = std::vector<double>{},
          "M, F, Q (and the constraints Phi, Jb, Jc, gamma) at a state, as numpy arrays")
      .def("simulate", &simulate, py::arg("integrator") = "", py::arg("step") = py::none(),
           py::arg("t_end") = py::none(), py::arg("adjust") = py::none(),
           py::arg("probes") = std::vector<std::string>{}, py::arg("every") = py::none(),
           py::arg("static_start") = py::none(), py::arg("formulation") = "partitioned",
           "Integrates the model; missing arguments come from its simulation block; every: a positive "
           "integer (absent: at most about 10,000 rows)")
      .def(
          "simulator",
          [](const Model& m, const std::string& integrator, std::optional<double> step, std::optional<double> t_end,
             std::optional<bool> adjust, const std::vector<std::string>& probes, std::optional<bool> static_start,
             const std::string& formulation) {
            return std::make_unique<PySimulator>(
                m, request_of(m, integrator, step, t_end, adjust, probes, std::nullopt, static_start, formulation));
          },
          py::arg("integrator") = "", py::arg("step") = py::none(), py::arg("t_end") = py::none(),
          py::arg("adjust") = py::none(), py::arg("probes") = std::vector<std::string>{},
          py::arg("static_start") = py::none(), py::arg("formulation") = "partitioned",
          "A simulation to step from Python (Simulator): the same arguments as simulate()")
      .def(
          "spectrum",
          [](const Model& m, bool adjusted) {
            const rt::ModelSpectrum s = m.spectrum(adjusted);
            Eigen::VectorXcd ev(static_cast<Eigen::Index>(s.full.eigenvalues.size()));
            for (std::size_t k = 0; k < s.full.eigenvalues.size(); ++k) ev[static_cast<Eigen::Index>(k)] = s.full.eigenvalues[k];
            return ev;
          },
          py::arg("adjusted") = false, "the eigenvalues (1/s) of the linearised model, complex numpy array")
      .def(
          "step_limits",
          [](const Model& m) {
            py::dict d;
            for (const rt::StepLimitRow& row : m.step_limits()) {
              py::dict limits;
              limits["original"] = limit_value(row.original);
              if (row.adjusted) limits["adjusted"] = limit_value(*row.adjusted);
              d[py::str(row.integrator.name)] = limits;
            }
            return d;
          },
          "largest stable step (s) per integrator; inf: unconditional, 0: none");

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

  module.def(
      "load",
      [](const std::string& path, bool quiet, const py::object& set) {
        refuse_nul(path, "the path");
        mbfe::LoadOptions o;
        o.quiet = quiet;
        o.overrides = model_overrides(set);
        return Model::load(path, o);
      },
      py::arg("path"), py::arg("quiet") = true, py::arg("set") = py::none(),
      "Reads a model file and gets its solver (compiled and cached on first use); set={PATH: value} replaces "
      "values of the file first, as mbfe simulate --set PATH=VALUE does");
  module.def(
      "parse",
      [](const std::string& text, const std::string& name, const py::object& set) {
        refuse_nul(name, "the name");
        mbfe::LoadOptions o;
        o.overrides = model_overrides(set);
        return Model::parse(text, name, o);
      },
      py::arg("text"), py::arg("name") = "<string>", py::arg("set") = py::none(),
      "A model from YAML text (name is the file name its messages give); set= as in load");
  module.attr("__version__") = MBFE_GENERATOR_VERSION;
}
