// The beams of a model, assembled, analysed and adjusted: what simulation, the
// stability advisor and `mbfe modal` share. Beams without contacts are
// independent, so the beams of a model are block diagonal: their modes are the
// union of the beams' modes.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "ir/model.h"
#include "runtime/damping/beam_analysis_options.h"
#include "runtime/damping/beam_ode.h"
#include "runtime/damping/modal_adjustment.h"
#include "runtime/fem/beam_system.h"
#include "runtime/modal/modal_analysis.h"
#include "runtime/modal/modal_basis.h"
#include "runtime/modal/state_spectrum.h"

namespace mbfe::runtime {

/// One beam: its finite-element system, modes and modal dynamics.
struct BeamPart {
  BeamSystem system;
  ModalBasis basis;                     // every mode (dense), the modes a cap keeps (sliced) or the lowest few (sparse)
  bool dense = true;                    // which modal path gave `basis`
  /// Why the modes kept by the beam's cap were not computed although asked
  /// for (options.modes_kept_by_cap): the cap keeps nearly every mode, or the
  /// slicing failed; the basis is then the lowest sparse_modes. Empty otherwise.
  std::string kept_modes_unavailable;
  std::vector<ModalDynamics> original;  // Rayleigh, one per mode of `basis`
  AdjustedModes adjusted;               // by the beam's adjustment block; == original without one
  bool has_adjustment = false;          // the beam's adjustment block is active
  StateSpectrum original_spectrum;      // eq (28) of `original` (partial if the basis is)
  StateSpectrum adjusted_spectrum;      // eq (28) of `adjusted`
  int offset = 0;                       // first coordinate of this beam in the model's q_c
};

struct BeamModel {
  std::vector<BeamPart> beams;
  int dof = 0;
  StateSpectrum original;  // union over the beams
  StateSpectrum adjusted;  // adjusted beams adjusted, the others original
  bool any_adjustment = false;
};

/// Assembles and analyses one beam (under `gravity`, m/s^2).
/// @throws std::invalid_argument for a beam the assembly rejects, a beam above
/// options.dense_limit when options.sparse_modes is 0 (the message says so), or
/// a bad adjustment block (each message names the beam).
BeamPart analyse_beam(const ir::Beam& beam, const ir::Vec2& gravity, const BeamAnalysisOptions& options = {});

/// Every beam of `model`, in model order, with their offsets and the union of
/// their spectra. @throws as analyse_beam.
BeamModel analyse_beams(const ir::Model& model, const BeamAnalysisOptions& options = {});

/// Adjusts the beams `which` of `beams` again by their blocks in `model`
/// (after a change of omega_limit: the modes stay, their adjusted dynamics
/// and spectra are redone) and the union of the adjusted spectra.
/// @throws std::invalid_argument as analyse_beam for a bad adjustment block.
void readjust_beams(BeamModel& beams, const ir::Model& model, const std::vector<std::size_t>& which);

/// The whole model in modal coordinates, original or adjusted modes.
/// @throws std::invalid_argument if some beam has a partial basis.
std::unique_ptr<ModalBeamOde> modal_beam_ode(const BeamModel& beams, bool adjusted);

/// The static state [q_s; 0] under the load at time t, in the modal
/// coordinates of modal_beam_ode (eta_j = p_j(t) / k_j, whatever the modal
/// mass m_j: the original model's K^-1 f under policy mass): a static start, and
/// the scale a divergence bound is set against. `beams` must outlive `ode`
/// (its time loads read the beams).
Eigen::VectorXd modal_static_state(const BeamModel& beams, bool adjusted, ModalBeamOde& ode, double t = 0.0);

}  // namespace mbfe::runtime
