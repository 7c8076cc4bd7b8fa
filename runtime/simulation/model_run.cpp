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

}  // namespace mbfe::runtime::detail
