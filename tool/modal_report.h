// How `mbfe modal` prints a spectrum: the paper's Table 1 (text) and the JSON
// blocks of `mbfe modal --json`. One spectrum block is built by one function,
// so an "adjusted" block can sit next to "original".
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "ir/model.h"
#include "runtime/damping/beam_model.h"
#include "runtime/modal/state_spectrum.h"

namespace mbfe::tool {

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
/// forward-Euler h_max = 1.52098e-08 s". A partial spectrum says which part
/// it holds (`partial`).
std::string spectrum_summary(const runtime::StateSpectrum& spectrum, int dof,
                             const std::string& partial = "lowest modes only");

/// "cap", "paper_eq25", "keep_slow", "none", "mass", "truncate".
const char* policy_name(ir::AdjustmentPolicy policy);

/// One beam of `mbfe modal --json`: name, dof, modal_path, natural
/// frequencies and the "original" spectrum block.
nlohmann::json beam_json(const runtime::BeamPart& beam);

/// The "adjusted" block next to "original" when the beam's adjustment is active.
void add_adjusted_json(nlohmann::json& json, const ir::Beam& beam, const runtime::BeamPart& part);

/// One beam as text: a heading, its Table 1 (both halves when adjusted) and
/// the summary lines.
void print_beam_text(std::ostream& out, const ir::Beam& beam, const runtime::BeamPart& part, bool all);

}  // namespace mbfe::tool
