#include "runtime/multibody/driven_coordinates.h"

namespace mbfe::runtime {

DrivenCoordinates::DrivenCoordinates(const mbfe_model_v1& model)
    : model_(model), mask_(static_cast<std::size_t>(model.num_coordinates), false) {
  for (int i = 0; i < model.num_driven; ++i) {
    indices_.push_back(model.driven_coordinates[i]);
    mask_[static_cast<std::size_t>(model.driven_coordinates[i])] = true;
  }
}

DrivenCoordinates::Motion DrivenCoordinates::make_motion() const {
  Motion m;
  m.q.setZero(count());
  m.qd.setZero(count());
  m.qdd.setZero(count());
  return m;
}

void DrivenCoordinates::motion(double t, Motion& out) const {
  if (indices_.empty()) return;
  model_.motion(t, out.q.data(), out.qd.data(), out.qdd.data());
}

void DrivenCoordinates::impose(double t, double* q, double* qd, Motion& scratch) const {
  if (indices_.empty()) return;
  motion(t, scratch);
  for (std::size_t k = 0; k < indices_.size(); ++k) {
    q[indices_[k]] = scratch.q[static_cast<Eigen::Index>(k)];
    qd[indices_[k]] = scratch.qd[static_cast<Eigen::Index>(k)];
  }
}

}  // namespace mbfe::runtime
