// The beams of a model (no bodies), assembled, analysed, adjusted and ready to
// integrate: what `mbfe simulate`, `mbfe stability` and the benchmarks share.
// Beams without contacts are independent, so the whole model is block
// diagonal: its modes are the union of the beams' modes.
#pragma once

#include <memory>
#include <vector>

#include "runtime/damping/beam_ode.h"
#include "runtime/damping/modal_adjustment.h"
#include "runtime/fem/beam_system.h"
#include "runtime/modal/modal_basis.h"
#include "runtime/modal/state_spectrum.h"
#include "ir/model.h"

namespace mbfe::runtime {

struct BeamPart {
  BeamSystem system;
  ModalBasis basis;                    // every mode (dense path)
  std::vector<ModalDynamics> original; // Rayleigh
  AdjustedModes adjusted;              // by the beam's adjustment block; == original without one
  bool has_adjustment = false;
  int offset = 0;                      // first coordinate of this beam in the model's q
};

struct BeamModel {
  std::vector<BeamPart> beams;
  int dof = 0;
  StateSpectrum original;  // union over the beams
  StateSpectrum adjusted;  // adjusted beams adjusted, the others original
  bool any_adjustment = false;
};

/// Assembles and analyses every beam of `model` (dense modal analysis: at most
/// `dense_limit` DOFs per beam). @throws std::invalid_argument for a beam the
/// assembly rejects, a beam above dense_limit (message says so) or a bad
/// adjustment block.
BeamModel analyse_beams(const ir::Model& model, int dense_limit = 2000);

/// The whole model in modal coordinates, original or adjusted modes.
std::unique_ptr<ModalBeamOde> modal_beam_ode(const BeamModel& beams, bool adjusted);

/// The static state [q_s; 0] in the modal coordinates of modal_beam_ode
/// (eta_j = p_j / k_j): the scale a divergence bound is set against.
Eigen::VectorXd modal_static_state(const BeamModel& beams, bool adjusted, const ModalBeamOde& ode);

}  // namespace mbfe::runtime
