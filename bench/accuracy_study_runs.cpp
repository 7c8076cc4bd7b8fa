#include "bench/accuracy_study_runs.h"

#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_types.h>
#include <sunlinsol/sunlinsol_band.h>
#include <sunmatrix/sunmatrix_band.h>

#include <chrono>
#include <cmath>
#include <ctime>
#include <stdexcept>

#include "frontend/parse_model.h"
#include "runtime/damping/beam_ode.h"
#include "runtime/structure/adjusted_parts.h"
#include "runtime/structure/nodal_beam_ode.h"
#include "runtime/fem/beam_system.h"
#include "runtime/integrators/integrator.h"
#include "runtime/integrators/simulation_driver.h"

namespace mbfe::study {

using Clock = std::chrono::steady_clock;

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

namespace {

double cpu_now() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

}  // namespace

RunResult run_fixed(const Setup& s, const std::vector<runtime::ModalDynamics>& modes, const std::string& integrator,
                    double h, double t_end, const ExactResponse& ref, bool keep_trace,
                    const std::string& form) {
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
      ode = std::make_unique<runtime::NodalBeamOde>(std::make_shared<const runtime::LowRankStructure>(runtime::adjusted_parts(
                                                        b.system.name, {{0, static_cast<int>(b.system.M.rows())}},
                                                        b.system.M, b.system.K, b.system.P, b.basis, am)));
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

namespace {

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


void cv_check(int flag, const char* what) {
  if (flag < 0) throw std::runtime_error(std::string("CVODE: ") + what + " failed with flag " + std::to_string(flag));
}

// rtol = tol, atol = tol * atol_scale (every component).
}  // namespace

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

double search_largest(const std::function<double(double)>& err, double x_hi, double factor, double target,
                      int bisections, int max_scan) {
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


}  // namespace mbfe::study
