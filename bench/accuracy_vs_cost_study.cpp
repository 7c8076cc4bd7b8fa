// Is the modal adjustment worth it? (issue 4, docs/accuracy-vs-cost.md)
//
// The paper beam (models/paper_beam.yaml: gravity + 10 N at midspan, stepped
// on at t = 0, from rest). For every run: the midspan deflection w(t) over
// 0..1 s against the exact response of the ORIGINAL model (modal
// superposition of eq (28): each mode's step response from rest is closed
// form), error = max |w - w_exact| over the run's output times, also divided
// by the exact peak |w|; and wall / CPU time of the integration.
//
//   (a) original + forward Euler at 1.5e-8 (66.7 million steps)
//   (b) adjusted (cap, omega_limit 1e5, margin 0.1; zeta_min 0.05 and 0) +
//       forward Euler at 1.4e-5
//   (c) original + generalized-alpha at the largest step whose error is at
//       most (b)'s (bisection over h); and at most (d)'s
//   (d) adjusted + RK4 at 2.0e-5 (its limit is 2.0328e-5)
//   (e) original + SUNDIALS CVODE (BDF, band linear solver on the modal
//       form, whose Jacobian is tridiagonal when each mode's (eta, eta') are
//       adjacent) at the loosest tolerance whose error is at most (b)'s; and (d)'s
//
// Every fixed-step run integrates the same modal form (ModalBeamOde: the model
// in mass-normalised coordinates, O(n) per right-hand side), the cheapest form
// of each model, so the comparison is between integrators and models, not
// between implementations. (a) is also timed in nodal coordinates (sparse
// LDLT of M per step, the form of a general FE code) on a shorter run.
//
//   accuracy_vs_cost_study [--markdown FILE] [--csv-dir DIR] [--a-t-end T]
//                          [--a-nodal-t-end T] [--repeat N]
//
// --a-t-end T: run (a) only to T and scale its time to 1 s (default 1: the
// whole second). The markdown table goes to FILE (default: stdout only).
#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_types.h>
#include <sunlinsol/sunlinsol_band.h>
#include <sunmatrix/sunmatrix_band.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <functional>
#include <iomanip>
#include <iostream>
#include <limits>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "runtime/damping/beam_model.h"
#include "runtime/damping/beam_ode.h"
#include "runtime/damping/modal_adjustment.h"
#include "runtime/fem/beam_system.h"
#include "runtime/integrators/integrator.h"
#include "runtime/integrators/simulation_driver.h"
#include "frontend/parse_model.h"

namespace {

using namespace mbfe;
using Clock = std::chrono::steady_clock;

constexpr double kTEnd = 1.0;         // s
constexpr double kModelGrid = 1e-5;   // s, grid of the exact-vs-exact model error
constexpr double kCvodeGrid = 1e-4;   // s, CVODE output times
constexpr std::int64_t kMaxRows = 10000;  // fixed-step runs: at most ~this many sampled times

// ---------------------------------------------------------------------------
// Exact response of decoupled modes eta'' + c eta' + k eta = p from rest.
struct ExactResponse {
  std::vector<runtime::ModalDynamics> modes;
  Eigen::VectorXd p;  // modal load
  Eigen::VectorXd g;  // midspan weights of the modes: w = g . eta

  double eta(int j, double t) const {
    const double k = modes[j].k, c = modes[j].c;
    const double st = p[j] / k;
    const auto r = runtime::modal_roots(c, k);
    if (r.first.imag() != 0.0) {
      const double s = -r.first.real(), wd = r.first.imag();
      return st * (1.0 - std::exp(-s * t) * (std::cos(wd * t) + s / wd * std::sin(wd * t)));
    }
    const double a = std::abs(r.first.real()), b = std::abs(r.second.real());  // slow, fast
    if (b - a <= 1e-7 * b) return st * (1.0 - (1.0 + a * t) * std::exp(-a * t));
    return st * (1.0 - (b * std::exp(-a * t) - a * std::exp(-b * t)) / (b - a));
  }
  double w(double t) const {
    double s = 0.0;
    for (int j = 0; j < static_cast<int>(modes.size()); ++j) s += g[j] * eta(j, t);
    return s;
  }
  double w_static() const {
    double s = 0.0;
    for (int j = 0; j < static_cast<int>(modes.size()); ++j) s += g[j] * p[j] / modes[j].k;
    return s;
  }
};

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

Setup make_setup() {
  Setup s;
  const ir::Model m = frontend::load_model_file(std::string(MBFE_SOURCE_DIR) + "/models/paper_beam.yaml");
  s.beams = runtime::analyse_beams(m);
  const runtime::BeamPart& b = s.beams.beams.at(0);
  const runtime::BeamPointWeights pw = runtime::point_weights(b.system, 0.5 * b.system.length);
  s.g = Eigen::VectorXd::Zero(b.basis.phi.cols());
  for (int i = 0; i < 4; ++i)
    if (pw.free_index[i] >= 0) s.g += pw.w[i] * b.basis.phi.row(pw.free_index[i]).transpose();
  s.original = b.original;
  ir::Adjustment a = m.beams.at(0).adjustment;  // cap, 1e5, 0.1, 0.05
  s.adj_floor = runtime::adjust_modes(b.original, a);
  s.cap_floor = s.adj_floor.modes;
  a.zeta_min = 0.0;
  s.adj_nofloor = runtime::adjust_modes(b.original, a);
  s.cap_nofloor = s.adj_nofloor.modes;
  return s;
}

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

double cpu_now() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

// form: "modal" (ModalBeamOde, every mode) or "nodal" (NodalBeamOde: the
// original with sparse K, C and an LDLT of M; the adjusted cap in the low-rank
// form of method-notes section 3, which needs no solve with M).
RunResult run_fixed(const Setup& s, const std::vector<runtime::ModalDynamics>& modes, const std::string& integrator,
                    double h, double t_end, const ExactResponse& ref, bool keep_trace = false,
                    const std::string& form = "modal") {
  const auto& b = s.beams.beams.at(0);
  std::unique_ptr<runtime::LinearSecondOrderSystem> ode;
  Eigen::VectorXd weights;  // w = weights . y.head(n)
  if (form == "modal") {
    ode = std::make_unique<runtime::ModalBeamOde>(b.basis, modes, b.system.M, b.system.P);
    weights = s.g;
  } else {
    const bool original = &modes == &s.original;
    if (original) {
      ode = std::make_unique<runtime::NodalBeamOde>(b.system.M, b.system.K, b.system.C, b.system.P);
    } else {
      const runtime::AdjustedModes& am = &modes == &s.cap_floor ? s.adj_floor : s.adj_nofloor;
      ode = std::make_unique<runtime::NodalBeamOde>(b.system.M, runtime::low_rank_adjusted(b.system.M, b.basis, am),
                                                    b.system.P);
    }
    const runtime::BeamPointWeights pw = runtime::point_weights(b.system, 0.5 * b.system.length);
    weights = Eigen::VectorXd::Zero(ode->dof());
    for (int i = 0; i < 4; ++i)
      if (pw.free_index[i] >= 0) weights[pw.free_index[i]] += pw.w[i];
  }
  const int n = ode->dof();
  runtime::SimulationOptions opt;
  opt.step = h;
  opt.t_end = t_end;
  opt.max_rows = kMaxRows;
  opt.quiet = true;
  opt.handle_sigint = false;
  opt.reference_norm = 1.0;  // states are O(1e-2) (m, or modal); 1e6 flags any blow-up early
  RunResult out;
  const auto spec = runtime::parse_integrator(integrator);
  const Eigen::VectorXd y0 = Eigen::VectorXd::Zero(2 * n);
  std::vector<std::pair<double, double>> rows;
  rows.reserve(kMaxRows + 16);
  const double c0 = cpu_now();
  const auto t0 = Clock::now();
  const auto r = runtime::run_simulation(*ode, spec, y0, opt, [&](double t, const Eigen::VectorXd& y) {
    rows.emplace_back(t, weights.dot(y.head(n)));
  });
  out.wall = std::chrono::duration<double>(Clock::now() - t0).count();
  out.cpu = cpu_now() - c0;
  out.steps = r.steps;
  out.completed = r.status == runtime::SimulationStatus::kCompleted;
  for (const auto& [t, w] : rows) {
    const double e = std::abs(w - ref.w(t));
    if (!(e <= out.err.max_abs)) {
      out.err.max_abs = e;
      out.err.at = t;
    }
  }
  out.err.samples = static_cast<int>(rows.size());
  if (!out.completed) out.err.max_abs = std::numeric_limits<double>::infinity();
  if (keep_trace) out.trace = std::move(rows);
  return out;
}

// Nodal original + forward Euler (sparse LDLT solve with M per step), short run.
RunResult run_nodal_original_fe(const Setup& s, double h, double t_end) {
  const auto& b = s.beams.beams.at(0);
  runtime::NodalBeamOde ode(b.system.M, b.system.K, b.system.C, b.system.P);
  runtime::SimulationOptions opt;
  opt.step = h;
  opt.t_end = t_end;
  opt.every = 1000;
  opt.quiet = true;
  opt.handle_sigint = false;
  RunResult out;
  const double c0 = cpu_now();
  const auto t0 = Clock::now();
  const auto r = runtime::run_simulation(ode, runtime::parse_integrator("forward_euler"),
                                         Eigen::VectorXd::Zero(ode.size()), opt,
                                         [&](double, const Eigen::VectorXd&) {});
  out.wall = std::chrono::duration<double>(Clock::now() - t0).count();
  out.cpu = cpu_now() - c0;
  out.steps = r.steps;
  out.completed = r.status == runtime::SimulationStatus::kCompleted;
  return out;
}

// ---------------------------------------------------------------------------
// CVODE (BDF) on the original modal form, state ordered [eta_1, eta_1', eta_2, ...]
// so that the (constant) Jacobian is tridiagonal: band solver, mu = ml = 1.
struct CvodeData {
  const std::vector<runtime::ModalDynamics>* modes;
  const Eigen::VectorXd* p;
};

int cv_rhs(realtype, N_Vector y, N_Vector ydot, void* user) {
  const auto* d = static_cast<const CvodeData*>(user);
  const realtype* yv = N_VGetArrayPointer(y);
  realtype* f = N_VGetArrayPointer(ydot);
  const int n = static_cast<int>(d->modes->size());
  for (int j = 0; j < n; ++j) {
    const auto& m = (*d->modes)[j];
    f[2 * j] = yv[2 * j + 1];
    f[2 * j + 1] = (*d->p)[j] - m.c * yv[2 * j + 1] - m.k * yv[2 * j];
  }
  return 0;
}

int cv_jac(realtype, N_Vector, N_Vector, SUNMatrix J, void* user, N_Vector, N_Vector, N_Vector) {
  const auto* d = static_cast<const CvodeData*>(user);
  const int n = static_cast<int>(d->modes->size());
  SUNMatZero(J);
  for (int j = 0; j < n; ++j) {
    const auto& m = (*d->modes)[j];
    SM_ELEMENT_B(J, 2 * j, 2 * j + 1) = 1.0;
    SM_ELEMENT_B(J, 2 * j + 1, 2 * j) = -m.k;
    SM_ELEMENT_B(J, 2 * j + 1, 2 * j + 1) = -m.c;
  }
  return 0;
}

struct CvodeResult {
  RunResult run;
  long nst = 0, nfe = 0, nje = 0, nsetups = 0;
};

void cv_check(int flag, const char* what) {
  if (flag < 0) throw std::runtime_error(std::string("CVODE: ") + what + " failed with flag " + std::to_string(flag));
}

// rtol = tol, atol = tol * atol_scale (every component).
CvodeResult run_cvode(const Setup& s, double tol, double atol_scale, const ExactResponse& ref) {
  const int n = static_cast<int>(s.original.size());
  const Eigen::VectorXd p = s.modal_load();
  CvodeData data{&s.original, &p};
  CvodeResult out;
  const double c0 = cpu_now();
  const auto t0 = Clock::now();
  SUNContext ctx = nullptr;
  cv_check(SUNContext_Create(nullptr, &ctx), "SUNContext_Create");
  N_Vector y = N_VNew_Serial(2 * n, ctx);
  N_VConst(0.0, y);
  void* mem = CVodeCreate(CV_BDF, ctx);
  if (!mem) throw std::runtime_error("CVodeCreate failed");
  SUNMatrix A = SUNBandMatrix(2 * n, 1, 1, ctx);
  SUNLinearSolver LS = SUNLinSol_Band(y, A, ctx);
  cv_check(CVodeInit(mem, cv_rhs, 0.0, y), "CVodeInit");
  cv_check(CVodeSStolerances(mem, tol, tol * atol_scale), "CVodeSStolerances");
  cv_check(CVodeSetUserData(mem, &data), "CVodeSetUserData");
  cv_check(CVodeSetLinearSolver(mem, LS, A), "CVodeSetLinearSolver");
  cv_check(CVodeSetJacFn(mem, cv_jac), "CVodeSetJacFn");
  cv_check(CVodeSetMaxNumSteps(mem, 100000000L), "CVodeSetMaxNumSteps");
  std::vector<std::pair<double, double>> rows;
  const int outputs = static_cast<int>(std::lround(kTEnd / kCvodeGrid));
  rows.reserve(outputs + 1);
  rows.emplace_back(0.0, 0.0);
  realtype t = 0.0;
  const realtype* yv = N_VGetArrayPointer(y);
  for (int i = 1; i <= outputs; ++i) {
    const double tout = i * kCvodeGrid;
    cv_check(CVode(mem, tout, y, &t, CV_NORMAL), "CVode");
    double w = 0.0;
    for (int j = 0; j < n; ++j) w += s.g[j] * yv[2 * j];
    rows.emplace_back(t, w);
  }
  CVodeGetNumSteps(mem, &out.nst);
  CVodeGetNumRhsEvals(mem, &out.nfe);
  CVodeGetNumJacEvals(mem, &out.nje);
  CVodeGetNumLinSolvSetups(mem, &out.nsetups);
  CVodeFree(&mem);
  SUNLinSolFree(LS);
  SUNMatDestroy(A);
  N_VDestroy(y);
  SUNContext_Free(&ctx);
  out.run.wall = std::chrono::duration<double>(Clock::now() - t0).count();
  out.run.cpu = cpu_now() - c0;
  out.run.steps = out.nst;
  out.run.rhs = out.nfe;
  for (const auto& [tt, w] : rows) {
    const double e = std::abs(w - ref.w(tt));
    if (!(e <= out.run.err.max_abs)) {
      out.run.err.max_abs = e;
      out.run.err.at = tt;
    }
  }
  out.run.err.samples = static_cast<int>(rows.size());
  return out;
}

// ---------------------------------------------------------------------------
// Searches: the largest h (loosest tol) whose error is at most `target`.
// err(x) is assumed to grow with x on the whole; a geometric scan from above
// finds the first x inside, then bisection (in log x) between it and the last
// x outside. Returns the best x found inside.
double search_largest(const std::function<double(double)>& err, double x_hi, double factor, double target,
                      int bisections, int max_scan = 40) {
  double outside = x_hi, inside = 0.0;
  double x = x_hi;
  for (int i = 0; i < max_scan; ++i) {
    if (err(x) <= target) {
      inside = x;
      break;
    }
    outside = x;
    x /= factor;
  }
  if (inside == 0.0) throw std::runtime_error("search: no step/tolerance reaches the target error");
  if (inside == x_hi) return inside;
  for (int i = 0; i < bisections; ++i) {
    const double mid = std::sqrt(inside * outside);
    if (err(mid) <= target)
      inside = mid;
    else
      outside = mid;
  }
  return inside;
}

// Best of `repeat` timings of the same run (the machine is shared).
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

std::string sci(double x, int digits = 2) {
  if (std::isinf(x)) return "inf";
  std::ostringstream o;
  o << std::scientific << std::setprecision(digits) << x;
  return o.str();
}

std::string fixed_time(double s) {
  std::ostringstream o;
  if (s >= 10.0)
    o << std::fixed << std::setprecision(1) << s << " s";
  else if (s >= 0.1)
    o << std::fixed << std::setprecision(2) << s << " s";
  else
    o << std::fixed << std::setprecision(1) << s * 1e3 << " ms";
  return o.str();
}

std::string with_commas(std::int64_t v) {
  std::string s = std::to_string(v), out;
  int c = 0;
  for (auto it = s.rbegin(); it != s.rend(); ++it) {
    if (c && c % 3 == 0) out.insert(out.begin(), ',');
    out.insert(out.begin(), *it);
    ++c;
  }
  return out;
}

struct Row {
  std::string label, model, method, step, steps, error_abs, error_rel, wall, cpu, nodal, note;
};

void write_trace(const std::string& dir, const std::string& name, const std::vector<std::pair<double, double>>& rows) {
  std::ofstream f(dir + "/" + name);
  f << "t,w\n" << std::setprecision(12);
  for (const auto& [t, w] : rows) f << t << ',' << w << '\n';
}

}  // namespace

int main(int argc, char** argv) {
  std::string markdown, csv_dir;
  double a_t_end = kTEnd, a_nodal_t_end = 2e-4;
  int repeat = 3;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto next = [&]() -> std::string {
      if (i + 1 >= argc) throw std::invalid_argument(arg + " needs a value");
      return argv[++i];
    };
    if (arg == "--markdown") markdown = next();
    else if (arg == "--csv-dir") csv_dir = next();
    else if (arg == "--a-t-end") a_t_end = std::stod(next());
    else if (arg == "--a-nodal-t-end") a_nodal_t_end = std::stod(next());
    else if (arg == "--repeat") repeat = std::stoi(next());
    else {
      std::cerr << "usage: accuracy_vs_cost_study [--markdown FILE] [--csv-dir DIR] [--a-t-end T] "
                   "[--a-nodal-t-end T] [--repeat N]\n";
      return 2;
    }
  }

  const Setup s = make_setup();
  const ExactResponse ref = s.exact_original();
  const ExactResponse ref_floor{s.cap_floor, s.modal_load(), s.g};
  const ExactResponse ref_nofloor{s.cap_nofloor, s.modal_load(), s.g};

  // Reference: peak and static midspan deflection, and the model error of the
  // adjusted models (exact vs exact) on a 1e-5 s grid.
  double peak = 0.0, t_peak = 0.0;
  Error model_floor, model_nofloor, coarse_floor, coarse_nofloor;  // coarse: 1e-3 s grid
  const int grid = static_cast<int>(std::lround(kTEnd / kModelGrid));
  std::vector<std::pair<double, double>> ref_trace;
  for (int i = 0; i <= grid; ++i) {
    const double t = i * kModelGrid;
    const double w = ref.w(t);
    if (std::abs(w) > peak) {
      peak = std::abs(w);
      t_peak = t;
    }
    const double ef = std::abs(ref_floor.w(t) - w), en = std::abs(ref_nofloor.w(t) - w);
    if (ef > model_floor.max_abs) model_floor = {ef, t, grid + 1};
    if (en > model_nofloor.max_abs) model_nofloor = {en, t, grid + 1};
    if (i % 100 == 0 && ef > coarse_floor.max_abs) coarse_floor = {ef, t, grid / 100 + 1};
    if (i % 100 == 0 && en > coarse_nofloor.max_abs) coarse_nofloor = {en, t, grid / 100 + 1};
    if (i % 10 == 0) ref_trace.emplace_back(t, w);
  }
  std::cerr << std::setprecision(6) << "reference: peak |w| = " << peak << " m at t = " << t_peak
            << " s, static w = " << ref.w_static() << " m\n"
            << "model error (exact vs exact, 1e-5 s grid): cap+floor " << model_floor.max_abs << " m ("
            << model_floor.max_abs / peak << " of peak, at t = " << model_floor.at << " s), cap alone "
            << model_nofloor.max_abs << " m (" << model_nofloor.max_abs / peak << ", at t = " << model_nofloor.at
            << " s)\n"
            << "static change: cap+floor " << std::abs(ref_floor.w_static() - ref.w_static()) / std::abs(ref.w_static())
            << ", cap alone " << std::abs(ref_nofloor.w_static() - ref.w_static()) / std::abs(ref.w_static())
            << " relative\n";

  std::vector<Row> rows;
  // nodal: wall/CPU of the same run in nodal coordinates (nullptr: not run).
  auto add = [&](const std::string& label, const std::string& model, const std::string& method,
                 const std::string& step, std::int64_t steps, const RunResult& r, const RunResult* nodal,
                 const std::string& note) {
    std::string nodal_text = "-";
    if (nodal) {
      nodal_text = fixed_time(nodal->wall) + " / " + fixed_time(nodal->cpu);
      // Same model in other coordinates: the error must agree to round-off.
      if (std::isfinite(nodal->err.max_abs) && std::abs(nodal->err.max_abs - r.err.max_abs) > 1e-2 * r.err.max_abs + 1e-12)
        std::cerr << "WARNING: " << label << " nodal error " << nodal->err.max_abs << " differs from modal "
                  << r.err.max_abs << "\n";
    }
    rows.push_back({label, model, method, step, steps > 0 ? with_commas(steps) : "-", sci(r.err.max_abs),
                    sci(r.err.max_abs / peak), fixed_time(r.wall), fixed_time(r.cpu), nodal_text, note});
    std::cerr << label << ' ' << model << ' ' << method << " h/tol " << step << ": error " << r.err.max_abs
              << " m (" << r.err.max_abs / peak << " of peak, at t = " << r.err.at << " s, " << r.err.samples
              << " samples), wall " << r.wall << " s, cpu " << r.cpu << " s, steps " << steps;
    if (nodal) std::cerr << "; nodal wall " << nodal->wall << " s, cpu " << nodal->cpu << " s, error " << nodal->err.max_abs;
    std::cerr << "\n";
  };
  auto timed = [&](const std::vector<runtime::ModalDynamics>& modes, const std::string& integ, double h,
                   bool trace, const std::string& form) {
    return best_of(repeat, [&] { return run_fixed(s, modes, integ, h, kTEnd, ref, trace, form); });
  };

  // (b) adjusted + forward Euler at 1.4e-5: both adjusted models.
  const double h_b = 1.4e-5;
  RunResult b_floor = timed(s.cap_floor, "forward_euler", h_b, true, "modal");
  RunResult b_nofloor = timed(s.cap_nofloor, "forward_euler", h_b, true, "modal");
  RunResult b_floor_n = timed(s.cap_floor, "forward_euler", h_b, false, "nodal");
  RunResult b_nofloor_n = timed(s.cap_nofloor, "forward_euler", h_b, false, "nodal");
  // (d) adjusted + RK4 at 2.0e-5 (limit 2.0328e-5).
  const double h_d = 2.0e-5;
  RunResult d_floor = timed(s.cap_floor, "rk4", h_d, true, "modal");
  RunResult d_nofloor = timed(s.cap_nofloor, "rk4", h_d, true, "modal");
  RunResult d_floor_n = timed(s.cap_floor, "rk4", h_d, false, "nodal");
  RunResult d_nofloor_n = timed(s.cap_nofloor, "rk4", h_d, false, "nodal");

  // (c) generalized-alpha (rho_inf 0.9) on the original: largest h whose error
  // is at most (b)'s (no floor: the floor's error is the model's, 0.34 of the
  // peak whatever the integrator), and (d)'s.
  auto ga_err = [&](double h) {
    const double e = run_fixed(s, s.original, "generalized_alpha", h, kTEnd, ref).err.max_abs;
    std::cerr << "  generalized_alpha h = " << h << ": error " << e << "\n";
    return e;
  };
  const double target_b = b_nofloor.err.max_abs, target_d = d_nofloor.err.max_abs;
  const double h_c_b = search_largest(ga_err, 1e-2, 2.0, target_b, 8);
  const double h_c_d = search_largest(ga_err, h_c_b, 2.0, target_d, 8);
  RunResult c_b = timed(s.original, "generalized_alpha", h_c_b, false, "modal");
  RunResult c_d = timed(s.original, "generalized_alpha", h_c_d, false, "modal");
  RunResult c_b_n = timed(s.original, "generalized_alpha", h_c_b, false, "nodal");
  RunResult c_d_n = timed(s.original, "generalized_alpha", h_c_d, false, "nodal");

  // (e) CVODE BDF on the original: rtol scanned at 4 per decade from 1e-1 down
  // (atol = 1e-3 rtol; the modal coordinates are ~1e-2 at most); the loosest
  // whose error is at most (b)'s, (d)'s. The error is not monotone in rtol
  // (BDF order and step changes), so no bisection: the scan is reported.
  const double atol_scale = 1e-3;
  // "Reliable": the loosest scanned rtol at and below which every scanned rtol
  // meets the target (a looser lucky one, e.g. 5.6e-3, is not picked).
  std::ostringstream scan;
  std::vector<std::pair<double, double>> scanned;  // (tol, error), tol decreasing
  int below_d = 0;
  for (int k = 4; k <= 48 && below_d < 3; ++k) {
    const double tol = std::pow(10.0, -k / 4.0);
    const double e = run_cvode(s, tol, atol_scale, ref).run.err.max_abs;
    std::cerr << "  cvode rtol = " << tol << ": error " << e << "\n";
    scan << (k > 4 ? ", " : "") << sci(tol, 1) << ": " << sci(e / peak, 1);
    scanned.emplace_back(tol, e);
    below_d = e <= target_d ? below_d + 1 : 0;
  }
  auto reliable = [&](double target) {
    double tol = 0.0;
    for (auto it = scanned.rbegin(); it != scanned.rend() && it->second <= target; ++it) tol = it->first;
    return tol;
  };
  const double tol_e_b = reliable(target_b), tol_e_d = reliable(target_d);
  if (tol_e_b == 0.0 || tol_e_d == 0.0) throw std::runtime_error("CVODE: no tolerance down to 1e-12 reaches the target");
  CvodeResult e_b = run_cvode(s, tol_e_b, atol_scale, ref), e_d = run_cvode(s, tol_e_d, atol_scale, ref);
  for (int i = 1; i < repeat; ++i) {
    const CvodeResult x = run_cvode(s, tol_e_b, atol_scale, ref), y = run_cvode(s, tol_e_d, atol_scale, ref);
    e_b.run.wall = std::min(e_b.run.wall, x.run.wall);
    e_b.run.cpu = std::min(e_b.run.cpu, x.run.cpu);
    e_d.run.wall = std::min(e_d.run.wall, y.run.wall);
    e_d.run.cpu = std::min(e_d.run.cpu, y.run.cpu);
  }

  // (a) original + forward Euler at 1.5e-8 (once: it is long), and nodal timing.
  const double h_a = 1.5e-8;
  std::cerr << "(a) forward Euler at 1.5e-8 to t = " << a_t_end << " s ...\n";
  RunResult a = run_fixed(s, s.original, "forward_euler", h_a, a_t_end, ref);
  const double a_scale = kTEnd / a_t_end;
  RunResult a_nodal = run_nodal_original_fe(s, h_a, a_nodal_t_end);
  a_nodal.wall *= kTEnd / a_nodal_t_end;
  a_nodal.cpu *= kTEnd / a_nodal_t_end;
  a_nodal.err.max_abs = std::numeric_limits<double>::quiet_NaN();

  // Rows.
  const bool a_full = a_t_end >= kTEnd;
  const std::int64_t a_steps = static_cast<std::int64_t>(std::ceil(kTEnd / h_a - 1e-9));
  {
    RunResult shown = a;
    shown.wall *= a_scale;
    shown.cpu *= a_scale;
    add("(a)", "original", "forward Euler", "1.5e-8", a_full ? a.steps : a_steps, shown, &a_nodal,
        std::string(a_full ? "whole second run (modal)" : "modal: ESTIMATE, run to " + sci(a_t_end, 1) +
                                                              " s, time x " + sci(a_scale, 1) +
                                                              ", error over that part only") +
            "; nodal: ESTIMATE, run to " + sci(a_nodal_t_end, 1) + " s, time x " + sci(kTEnd / a_nodal_t_end, 1));
  }
  add("(b)", "adjusted, zeta_min 0.05", "forward Euler", "1.4e-5", b_floor.steps, b_floor, &b_floor_n,
      "the paper's model and step; error = the floor's model error");
  add("(b)", "adjusted, no floor", "forward Euler", "1.4e-5", b_nofloor.steps, b_nofloor, &b_nofloor_n,
      "error = forward Euler's own");
  add("(c)", "original", "generalized-alpha (rho_inf 0.9)", sci(h_c_b, 3), c_b.steps, c_b, &c_b_n,
      "largest h with error <= (b, no floor)");
  add("(d)", "adjusted, zeta_min 0.05", "RK4", "2.0e-5", d_floor.steps, d_floor, &d_floor_n, "limit 2.0328e-5");
  add("(d)", "adjusted, no floor", "RK4", "2.0e-5", d_nofloor.steps, d_nofloor, &d_nofloor_n, "limit 2.0328e-5");
  add("(c')", "original", "generalized-alpha (rho_inf 0.9)", sci(h_c_d, 3), c_d.steps, c_d, &c_d_n,
      "largest h with error <= (d, no floor)");
  add("(e)", "original", "CVODE BDF, band (modal)", "rtol " + sci(tol_e_b, 2), e_b.nst, e_b.run, nullptr,
      "loosest scanned rtol at and below which error <= (b, no floor); " + std::to_string(e_b.nfe) + " f evals, " +
          std::to_string(e_b.nsetups) + " LU setups");
  add("(e')", "original", "CVODE BDF, band (modal)", "rtol " + sci(tol_e_d, 2), e_d.nst, e_d.run, nullptr,
      "loosest scanned rtol at and below which error <= (d, no floor); " + std::to_string(e_d.nfe) + " f evals, " +
          std::to_string(e_d.nsetups) + " LU setups");

  std::ostringstream md;
  md << "Reference (exact modal superposition of the original model): peak |w| = " << sci(peak, 4) << " m at t = "
     << std::fixed << std::setprecision(5) << t_peak << " s, static w = " << sci(std::abs(ref.w_static()), 4)
     << " m.\n\n";
  md << "Model error of the adjustment alone (exact adjusted vs exact original, max over a 1e-5 s grid, "
        "relative to the peak): cap alone "
     << sci(model_nofloor.max_abs / peak) << " (" << sci(model_nofloor.max_abs) << " m), cap + zeta_min 0.05 "
     << sci(model_floor.max_abs / peak) << " (" << sci(model_floor.max_abs) << " m, at t = " << std::setprecision(3)
     << model_floor.at << " s). On a 1e-3 s grid (which misses the first half millisecond): cap alone "
     << sci(coarse_nofloor.max_abs / peak) << ", cap + zeta_min 0.05 " << sci(coarse_floor.max_abs / peak)
     << ". Static midspan deflection changed by the cap: "
     << sci(std::abs(ref_nofloor.w_static() - ref.w_static()) / std::abs(ref.w_static())) << " relative.\n\n";
  md << "| run | model | integrator | step / tol | steps | max error (m) | error / peak | wall | CPU | "
        "nodal form: wall / CPU | note |\n"
     << "|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const Row& r : rows)
    md << "| " << r.label << " | " << r.model << " | " << r.method << " | " << r.step << " | " << r.steps << " | "
       << r.error_abs << " | " << r.error_rel << " | " << r.wall << " | " << r.cpu << " | " << r.nodal << " | "
       << r.note << " |\n";
  md << "\nCVODE scan (rtol: error / peak, atol = 1e-3 rtol): " << scan.str() << ".\n";
  std::cout << md.str();
  if (!markdown.empty()) {
    std::ofstream f(markdown);
    f << md.str();
  }
  if (!csv_dir.empty()) {
    write_trace(csv_dir, "reference.csv", ref_trace);
    write_trace(csv_dir, "b_adjusted_floor_fe.csv", b_floor.trace);
    write_trace(csv_dir, "b_adjusted_nofloor_fe.csv", b_nofloor.trace);
    write_trace(csv_dir, "d_adjusted_floor_rk4.csv", d_floor.trace);
    write_trace(csv_dir, "d_adjusted_nofloor_rk4.csv", d_nofloor.trace);
    auto errors = [&](const std::vector<std::pair<double, double>>& rows) {
      std::vector<std::pair<double, double>> e;
      for (const auto& [t, w] : rows) e.emplace_back(t, std::max(std::abs(w - ref.w(t)), 1e-12));
      return e;
    };
    write_trace(csv_dir, "err_b_floor.csv", errors(b_floor.trace));
    write_trace(csv_dir, "err_b_nofloor.csv", errors(b_nofloor.trace));
    write_trace(csv_dir, "err_d_floor.csv", errors(d_floor.trace));
    write_trace(csv_dir, "err_d_nofloor.csv", errors(d_nofloor.trace));
  }
  return 0;
}
