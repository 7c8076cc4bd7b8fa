// mbfe.Model and the functions that make one, load() and parse()
// (docs/python.md).
#pragma once

#include <pybind11/pybind11.h>

namespace mbfe::python {

namespace py = pybind11;

/// Registers mbfe.Model.
void bind_model(py::module_& module);
/// Registers mbfe.load and mbfe.parse.
void bind_model_readers(py::module_& module);

}  // namespace mbfe::python
