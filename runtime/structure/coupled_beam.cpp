#include "runtime/structure/coupled_beam.h"

namespace mbfe::runtime {

BeamForceFn sparse_beam_force(Eigen::SparseMatrix<double> C, Eigen::SparseMatrix<double> K) {
  return [C = std::move(C), K = std::move(K)](const Eigen::Ref<const Eigen::VectorXd>& q,
                                              const Eigen::Ref<const Eigen::VectorXd>& qd,
                                              Eigen::Ref<Eigen::VectorXd> f) {
    f.noalias() = C * qd;
    f.noalias() += K * q;
  };
}

BeamForceFn dense_beam_force(Eigen::MatrixXd C, Eigen::MatrixXd K) {
  return [C = std::move(C), K = std::move(K)](const Eigen::Ref<const Eigen::VectorXd>& q,
                                              const Eigen::Ref<const Eigen::VectorXd>& qd,
                                              Eigen::Ref<Eigen::VectorXd> f) {
    f.noalias() = C * qd;
    f.noalias() += K * q;
  };
}

BeamMesh beam_mesh(const BeamSystem& beam) {
  BeamMesh mesh;
  mesh.name = beam.name;
  mesh.num_elements = beam.num_nodes - 1;
  mesh.element_length = beam.element_length;
  mesh.full_to_free = beam.full_to_free;
  mesh.num_free = static_cast<int>(beam.M.rows());
  return mesh;
}

CoupledBeam coupled_beam(const BeamSystem& beam) {
  CoupledBeam out = coupled_beam(beam, sparse_beam_force(beam.C, beam.K));
  out.C = beam.C;
  out.K = beam.K;
  return out;
}

CoupledBeam coupled_beam(const BeamSystem& beam, BeamForceFn force) {
  CoupledBeam out;
  out.mesh = beam_mesh(beam);
  out.M = beam.M;
  out.P = beam.P;
  out.force = std::move(force);
  return out;
}

}  // namespace mbfe::runtime
