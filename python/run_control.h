// Running a model from Python: simulate() to the end, or a Simulator stepped
// by the caller (docs/python.md); Ctrl-C stops either between steps.
#pragma once

#include <pybind11/pybind11.h>

#include <Eigen/Dense>
#include <optional>
#include <string>
#include <vector>

#include "api/mbfe.h"
#include "api/simulator.h"
#include "python/run_result.h"

namespace mbfe::python {

/// The model's request (its `simulation:` block), the arguments overriding it.
/// The runtime checks the ranges; its errors name these arguments.
rt::SimulationRequest request_of(const Model& m, const std::string& integrator, std::optional<double> step,
                                 std::optional<double> t_end, std::optional<bool> adjust,
                                 const std::vector<std::string>& probes, std::optional<long> every,
                                 std::optional<bool> static_start, const std::string& formulation);

/// Model.simulate: runs to t_end without the GIL. @throws KeyboardInterrupt
/// (its `result` the rows so far) on Ctrl-C.
Result simulate(const Model& m, const std::string& integrator, std::optional<double> step,
                std::optional<double> t_end, std::optional<bool> adjust, const std::vector<std::string>& probes,
                std::optional<long> every, std::optional<bool> static_start, const std::string& formulation);

/// A simulation stepped from Python (api/simulator.h).
class PySimulator {
 public:
  PySimulator(const Model& m, const rt::SimulationRequest& r) : sim_(m, r) {}
  mbfe::Simulator& sim() { return sim_; }
  /// Steps to t; returns the time reached. @throws KeyboardInterrupt on Ctrl-C.
  double advance_to(double t);
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

/// Registers mbfe.Simulator.
void bind_simulator(py::module_& module);

}  // namespace mbfe::python
