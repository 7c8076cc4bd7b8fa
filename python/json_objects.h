// A JSON value as the Python object json.loads would make of its text: the
// module hands out what the sidecar records (api/run_record.h) built once,
// by the same code, instead of repeating its fields.
#pragma once

#include <pybind11/pybind11.h>

#include <nlohmann/json.hpp>

namespace mbfe::python {

/// null -> None, booleans -> bool, integers -> int, other numbers -> float
/// (NaN and infinities kept, where the sidecar's text writes null), strings
/// -> str, arrays -> list, objects -> dict.
pybind11::object python_object(const nlohmann::json& value);

}  // namespace mbfe::python
