#include "runtime/simulation/model_run.h"

#include <sstream>

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

void announce_scaled_quaternions(const ir::Model& model, bool strict, std::vector<std::string>& notices) {
  for (const ir::Initial::ScaledQuaternion& scaled : model.initial.scaled_quaternions) {
    std::ostringstream os;
    os.precision(10);  // a norm 1e-6 off 1 shows as such
    os << "initial.q." << scaled.body << ": the quaternion has norm " << scaled.norm
       << ", not 1, and was scaled to unit length";
    if (strict)
      throw InvalidInput(model.source_path + ":" + std::to_string(scaled.loc.line) + ":" +
                         std::to_string(scaled.loc.column) + ": " + os.str() +
                         " (strict: write a unit quaternion, w^2 + x^2 + y^2 + z^2 = 1)");
    notices.push_back(os.str());
  }
}

}  // namespace mbfe::runtime::detail
