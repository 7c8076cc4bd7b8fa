// mbfe.Model, mbfe.load and mbfe.parse: a model with its solver, from Python.
#include "python/model_bindings.h"

#include <pybind11/complex.h>
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "api/mbfe.h"
#include "ir/coordinate_layout.h"
#include "python/run_control.h"

namespace mbfe::python {

namespace {

namespace rt = mbfe::runtime;

/// A path or name that will name a file: a NUL would end it early (the C
/// library stops there), so that "ok.yaml\0junk" would load ok.yaml.
void refuse_nul(const std::string& text, const char* what) {
  const auto nul = text.find('\0');
  if (nul != std::string::npos)
    throw py::value_error(std::string(what) + " holds a NUL character (at " + std::to_string(nul) +
                          "), which no file name can hold");
}

/// One value of `set=` as YAML text: a number as its shortest round-trip text
/// (Python's repr of the float or int), a bool as true/false; a string as
/// written at the top (the command line's VALUE) and double-quoted inside a
/// list; a list, tuple or numpy array in YAML's flow form, "[0, 300]".
std::string yaml_text(const py::handle& value, const std::string& path, bool top) {
  if (py::isinstance<py::bool_>(value)) return value.cast<bool>() ? "true" : "false";
  if (py::isinstance<py::int_>(value))
    return py::repr(py::int_(py::reinterpret_borrow<py::object>(value))).cast<std::string>();
  if (py::isinstance<py::float_>(value))
    return py::repr(py::float_(py::reinterpret_borrow<py::object>(value))).cast<std::string>();
  if (py::isinstance<py::str>(value)) {
    const std::string text = value.cast<std::string>();
    if (top) return text;
    std::string quoted = "\"";
    for (const char c : text) quoted += c == '"' || c == '\\' ? std::string("\\") + c : std::string(1, c);
    return quoted + "\"";
  }
  if (py::isinstance<py::array>(value)) return yaml_text(value.attr("tolist")(), path, top);  // numpy: as its list
  if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value)) {
    std::string text = "[";
    for (const py::handle item : value) text += (text.size() > 1 ? ", " : "") + yaml_text(item, path, false);
    return text + "]";
  }
  throw py::type_error("set['" + path + "']: expected a number, a bool, a string or a list of them, got " +
                       py::repr(py::type::of(value)).cast<std::string>());
}

/// `set={"loads.front_susp.stiffness": 2e6, "beams.deck.origin": [0, 1]}` as
/// the command line's --set PATH=VALUE flags (yaml_text).
mbfe::ir::ModelOverrides model_overrides(const py::object& set) {
  mbfe::ir::ModelOverrides overrides;
  if (set.is_none()) return overrides;
  if (!py::isinstance<py::dict>(set)) throw py::type_error("set: expected a dict {PATH: value}");
  for (const auto& [key, value] : set.cast<py::dict>()) {
    if (!py::isinstance<py::str>(key)) throw py::type_error("set: each PATH is a string, such as 'beams.deck.section.inertia'");
    const std::string path = key.cast<std::string>();
    refuse_nul(path, "a PATH of set");
    const std::string text = yaml_text(value, path, true);
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

}  // namespace

void bind_model(py::module_& module) {
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
            if (e.has_loops) {  // as `mbfe eval --json`'s "loops"
              py::dict loops;
              loops["Phi"] = e.loop_phi;
              loops["J"] = e.loop_j;
              loops["gamma"] = e.loop_gamma;
              d["loops"] = loops;
            }
            return d;
          },
          py::arg("q"), py::arg("qd"), py::arg("t") = 0.0, py::arg("qc") = std::vector<double>{},
          py::arg("qcd") = std::vector<double>{},
          "M, F, Q (and the contacts' Phi, Jb, Jc, gamma; a dict 'loops' of the closed loops' Phi, J, gamma) at a "
          "state, as numpy arrays; q with unit quaternions (empty: zeros and identity quaternions)")
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
}

void bind_model_readers(py::module_& module) {

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
}

}  // namespace mbfe::python
