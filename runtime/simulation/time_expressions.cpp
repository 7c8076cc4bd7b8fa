#include "runtime/simulation/time_expressions.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "ir/model_error.h"

namespace mbfe::runtime {

namespace {

/// An expression and the time a run first evaluates it.
struct FirstUse {
  const ir::Expression* expression;
  double t;
};

/// The expressions of the rigid part: loads on bodies and motions.
std::vector<const ir::Expression*> rigid_expressions(const ir::Model& model) {
  std::vector<const ir::Expression*> out;
  for (const ir::Body& body : model.bodies)
    if (body.joint.motion) out.push_back(&*body.joint.motion);
  for (const ir::Load& load : model.loads) {
    if (load.type == ir::LoadType::kForce) {
      out.push_back(&load.force[0]);
      out.push_back(&load.force[1]);
    } else if (load.type == ir::LoadType::kTorque) {
      out.push_back(&load.torque);
    }
  }
  return out;
}

/// When a moving load is first on its beam, from t0 on; NaN if never before t_end.
double moving_load_entry(const ir::BeamMovingLoad& load, double length, double t0, double t_end) {
  // s(t) = start + speed (t - load.t0) is in [0, length] between t_in and t_out.
  const double at_zero = load.t0 - load.start / load.speed;
  const double at_end = load.t0 + (length - load.start) / load.speed;
  const double t_in = std::max(t0, std::min(at_zero, at_end));
  const double t_out = std::max(at_zero, at_end);
  return t_in <= std::min(t_out, t_end) ? t_in : std::nan("");
}

std::string time_text(double t) {
  char text[40];
  std::snprintf(text, sizeof text, "%.6g", t);
  return text;
}

}  // namespace

void check_time_expressions(const ir::Model& model, const mbfe_model_v1* kernels, double t0, double t_end) {
  std::vector<FirstUse> uses;
  for (const ir::Expression* e : rigid_expressions(model)) uses.push_back({e, t0});
  for (const ir::Beam& beam : model.beams) {
    for (const ir::BeamPointLoad& load : beam.loads) {
      const double t = std::max(t0, load.window.start);
      if (t <= t_end && t < load.window.stop) uses.push_back({&load.value, t});
    }
    for (const ir::BeamMovingLoad& load : beam.moving_loads) {
      const double t = moving_load_entry(load, beam.length, t0, t_end);
      if (!std::isnan(t)) uses.push_back({&load.value, t});
    }
  }
  for (const FirstUse& use : uses) {
    if (std::isfinite(use.expression->evaluate(use.t))) continue;
    const auto fault = use.expression->fault_at(use.t);
    if (!fault) continue;  // cannot happen: a non-finite value starts at some node
    const ir::Expression& e = *use.expression;
    throw ir::ModelError(e.source().file, e.nodes()[fault->node].loc,
                         ir::describe_fault(e, *fault, use.t) + "; expected a finite value where the run first uses it");
  }
  if (!kernels || kernels->num_driven <= 0) return;
  // The motion itself passed above; its derivatives exist only in the generated code.
  const std::size_t n = static_cast<std::size_t>(kernels->num_driven);
  std::vector<double> q(n), qd(n), qdd(n);
  kernels->motion(t0, q.data(), qd.data(), qdd.data());
  for (std::size_t k = 0; k < n; ++k) {
    if (std::isfinite(qd[k]) && std::isfinite(qdd[k])) continue;
    const ir::Body& body = model.bodies[static_cast<std::size_t>(kernels->driven_coordinates[k])];
    const ir::ExpressionSource& s = body.joint.motion->source();
    const bool velocity = !std::isfinite(qd[k]);
    throw ir::ModelError(s.file, s.loc,
                         s.what + " \"" + s.text + "\": its " + (velocity ? "first" : "second") + " derivative is " +
                             std::to_string(velocity ? qd[k] : qdd[k]) + " at t = " + time_text(t0) +
                             " s; expected a motion with a finite velocity and acceleration where the run starts");
  }
}

std::string non_finite_expression(const ir::Model& model, double t, double h) {
  for (const double at : {t, t + 0.5 * h, t + h}) {
    for (const ir::Expression* e : rigid_expressions(model)) {
      if (std::isfinite(e->evaluate(at))) continue;
      if (const auto fault = e->fault_at(at))
        return ir::describe_fault(*e, *fault, at) + " (" + ir::node_location(*e, fault->node) + ")";
    }
  }
  return "";
}

}  // namespace mbfe::runtime
