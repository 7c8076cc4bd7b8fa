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
#include <pybind11/pybind11.h>

#include <string>

#include "api/mbfe.h"
#include "python/model_bindings.h"
#include "python/run_control.h"
#include "python/run_result.h"

namespace py = pybind11;

namespace {

namespace rt = mbfe::runtime;

/// `text` as a Python str, invalid UTF-8 (a file name's bytes) as U+FFFD: a
/// message PyErr_SetString cannot decode came out empty.
py::str message_text(const std::string& text) {
  PyObject* s = PyUnicode_DecodeUTF8(text.data(), static_cast<Py_ssize_t>(text.size()), "replace");
  if (!s) throw py::error_already_set();
  return py::reinterpret_steal<py::str>(s);
}

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

  mbfe::python::bind_result(module);
  mbfe::python::bind_model(module);
  mbfe::python::bind_simulator(module);
  mbfe::python::bind_model_readers(module);
  module.attr("__version__") = MBFE_GENERATOR_VERSION;
}
