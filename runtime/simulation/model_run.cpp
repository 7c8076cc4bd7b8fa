#include "runtime/simulation/model_run.h"

#include "runtime/errors/invalid_input.h"

namespace mbfe::runtime::detail {

void ModelRun::set_beam_load(const std::string&, double, std::function<double(double)>) {
  throw InvalidInput("this model has no beams to load");
}

std::unique_ptr<ModelRun> make_model_run(const AssembledModel& model, const SimulationRequest& request) {
  switch (model.kind()) {
    case ModelKind::kRigid:
      return make_rigid_run(model, request);
    case ModelKind::kBeams:
      return make_beam_run(model, request);
    case ModelKind::kCoupled:
      return make_coupled_run(model, request);
  }
  throw InvalidInput("unknown kind of model");
}

const char* coordinate_unit(const ir::Body& body) {
  return body.joint.type == ir::JointType::kRevolute ? "rad" : "m";
}

const char* rate_unit(const ir::Body& body) {
  return body.joint.type == ir::JointType::kRevolute ? "rad/s" : "m/s";
}

// A slope w' = dw/ds is a length over a length: "1" (and "1/s" for its rate),
// in every column, sidecar and message.
const char* beam_coordinate_unit(bool slope) { return slope ? "1" : "m"; }
const char* beam_rate_unit(bool slope) { return slope ? "1/s" : "m/s"; }

}  // namespace mbfe::runtime::detail
