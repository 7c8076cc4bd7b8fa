// The runs of the accuracy-vs-cost study (accuracy_vs_cost_study.cpp): the
// paper beam's models (original, adjusted with and without the damping
// floor), its exact step response, fixed-step runs in modal or nodal
// coordinates, CVODE on the original, and the searches for the step or
// tolerance that meets a target error.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "runtime/damping/beam_model.h"
#include "runtime/damping/modal_adjustment.h"
#include "runtime/modal/step_response.h"

namespace mbfe::study {

constexpr double kTEnd = 1.0;         // s
constexpr double kModelGrid = 1e-5;   // s, grid of the exact-vs-exact model error
constexpr double kCvodeGrid = 1e-4;   // s, CVODE output times
constexpr std::int64_t kMaxRows = 10000;  // fixed-step runs: at most ~this many sampled times

using ExactResponse = runtime::ModalStepResponse;

struct Setup {
  runtime::BeamModel beams;
  Eigen::VectorXd g;  // midspan modal weights
  std::vector<runtime::ModalDynamics> original, cap_floor, cap_nofloor;
  runtime::AdjustedModes adj_floor, adj_nofloor;
  ExactResponse exact_original() const { return {original, modal_load(), g}; }
  Eigen::VectorXd modal_load() const {
    const auto& b = beams.beams.at(0);
    return b.basis.phi.transpose() * b.system.P;
  }
};

/// The paper beam of models/paper_beam.yaml, analysed; the midspan modal weights.
Setup make_setup();

struct Error {
  double max_abs = 0.0;  // m
  double at = 0.0;       // s
  int samples = 0;
};

// ---------------------------------------------------------------------------
// Fixed-step runs on the modal form.
struct RunResult {
  Error err;
  double wall = 0.0, cpu = 0.0;  // s
  std::int64_t steps = 0;
  std::int64_t rhs = 0;          // right-hand sides (or implicit solves) per run
  bool completed = true;
  std::vector<std::pair<double, double>> trace;  // (t, w) when asked
};

/// A fixed-step run over the modal form of `modes` ("modal": ModalBeamOde,
/// every mode) or the nodal one ("nodal": NodalBeamOde: the original with
/// sparse K, C and an LDLT of M; the adjusted cap in the low-rank form of
/// docs/damping-adjustment.md, which needs no solve with M), its midspan
/// error against `ref` on the run's output times.
RunResult run_fixed(const Setup& s, const std::vector<runtime::ModalDynamics>& modes, const std::string& integrator,
                    double h, double t_end, const ExactResponse& ref, bool keep_trace = false,
                    const std::string& form = "modal");

/// Nodal original + forward Euler (a sparse LDLT solve with M per step), timed.
RunResult run_nodal_original_fe(const Setup& s, double h, double t_end);

struct CvodeResult {
  RunResult run;
  long nst = 0, nfe = 0, nje = 0, nsetups = 0;
};

/// CVODE (BDF, band solver) on the original modal form; rtol = tol,
/// atol = tol * atol_scale.
CvodeResult run_cvode(const Setup& s, double tol, double atol_scale, const ExactResponse& ref);

/// The largest x (a step, a tolerance) whose error err(x) is at most
/// `target`: a geometric scan down from x_hi by `factor`, then `bisections`
/// bisections in log x.
double search_largest(const std::function<double(double)>& err, double x_hi, double factor, double target,
                      int bisections, int max_scan = 40);

/// Best of `repeat` timings of the same run (the machine is shared).
template <class F>
RunResult best_of(int repeat, F run) {
  RunResult best = run();
  for (int i = 1; i < repeat; ++i) {
    RunResult r = run();
    if (r.wall < best.wall) best.wall = r.wall;
    if (r.cpu < best.cpu) best.cpu = r.cpu;
  }
  return best;
}

}  // namespace mbfe::study
