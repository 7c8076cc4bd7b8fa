#include "runtime/structure/adjusted_structures.h"

#include "runtime/structure/adjusted_parts.h"

namespace mbfe::runtime {

CoupledBeams coupled_beams(const BeamModel& beams, bool adjusted, const std::vector<JoinedStructure>& joined) {
  CoupledBeams out;
  std::vector<int> structure_of(beams.beams.size(), -1);
  if (adjusted) {
    for (const JoinedStructure& s : joined) {
      for (int b : s.beams) structure_of[b] = static_cast<int>(out.structures.size());
      out.structures.push_back(s.structure);
    }
  }
  for (std::size_t k = 0; k < beams.beams.size(); ++k) {
    const BeamPart& b = beams.beams[k];
    out.beams.push_back(coupled_beam(b.system, b.offset));
    CoupledBeam& beam = out.beams.back();
    if (adjusted && structure_of[k] < 0 && b.has_adjustment) {
      structure_of[k] = static_cast<int>(out.structures.size());
      out.structures.push_back(std::make_shared<const LowRankStructure>(
          adjusted_parts(b.system.name, {{b.offset, static_cast<int>(b.system.M.rows())}}, b.system.M, b.system.K,
                         b.system.P, b.basis, b.adjusted)));
      // Its kept modes are damped by Rayleigh over the whole beam; the
      // original C damps the discrete parts otherwise. (A joined structure
      // damps each mode by the diagonal of Phi^T C Phi instead.)
      beam.damping_remainder = b.system.damping_remainder;
    }
    beam.structure = structure_of[k];
    if (beam.structure >= 0) {
      beam.C = Eigen::SparseMatrix<double>();
      beam.K = Eigen::SparseMatrix<double>();
    }
  }
  return out;
}

}  // namespace mbfe::runtime
