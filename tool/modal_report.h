// What `mbfe modal` computes for one beam and how it prints it: the paper's
// Table 1 (text) and the JSON contract of issue 3. One spectrum block is built
// by one function, so an "adjusted" block can sit next to "original".
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "runtime/fem/beam_system.h"
#include "runtime/modal/modal_basis.h"
#include "runtime/modal/state_spectrum.h"
#include "ir/model.h"

namespace mbfe::tool {

struct BeamModalOptions {
  int dense_limit = 2000;  // DOFs; above it the sparse path finds `sparse_modes`
  int sparse_modes = 20;   // lowest modes for large beams
};

/// One beam, assembled and analysed.
struct BeamModalResult {
  std::string name;
  runtime::BeamSystem system;
  runtime::ModalBasis basis;          // every mode (dense) or the lowest few (sparse)
  runtime::StateSpectrum original;    // Rayleigh damping, eq (28)
  bool dense = true;                  // which modal path was used
};

/// Assembles `beam` and analyses it (dense for small beams, sparse Lanczos for
/// the lowest modes of large ones). @throws std::invalid_argument on a beam
/// the assembly rejects.
BeamModalResult analyse_beam(const ir::Beam& beam, const ir::Vec2& gravity,
                             const BeamModalOptions& options = {});

/// {"eigenvalues": [[re, im], ...], "oscillatory_pairs": n,
///  "h_max": {"forward_euler": h}, "complete": bool}; h is null when the
/// spectrum is partial (unknown) or no eigenvalue limits the step.
nlohmann::json spectrum_json(const runtime::StateSpectrum& spectrum);

/// The table of the paper's Table 1 for one spectrum: a header line, then one
/// line per real eigenvalue or conjugate pair; unless `all`, the first and the
/// last `edge_rows` rows with a "..." line between. Every line has the same
/// width (spectrum_table_width()), so two tables can be printed side by side.
std::vector<std::string> spectrum_table_lines(const runtime::StateSpectrum& spectrum, bool all,
                                              int edge_rows = 5);
int spectrum_table_width();

/// "100 DOF, 13 oscillatory pairs, fastest eigenvalue -1.314938e+08 1/s,
/// forward-Euler h_max = 1.52098e-08 s".
std::string spectrum_summary(const runtime::StateSpectrum& spectrum, int dof);

}  // namespace mbfe::tool
