// Sweep files (docs/sweeps.md) into ir::Sweep, and the model file of each
// point: the base model's YAML with the point's values put in at their paths.
#pragma once

#include <string>

#include "ir/model_error.h"
#include "ir/model_override.h"
#include "ir/sweep.h"

namespace mbfe::frontend {

/// Reads and validates a sweep file (a regular file of at most 1 MiB).
/// @throws ir::ModelError at the offending key or value.
ir::Sweep load_sweep_file(const std::string& path);
ir::Sweep parse_sweep_text(const std::string& text, const std::string& display_path);

/// The model file a sweep varies: its path as given, resolved against the
/// sweep file's folder when relative.
std::string sweep_model_path(const ir::Sweep& sweep);

/// The text of the model file a sweep varies: a regular file (not a device, a
/// pipe or a folder: every point reads it again) of at most
/// ParseLimits::max_file_bytes. @throws ir::ModelError at the sweep's
/// `model:` value naming the file and why.
std::string read_sweep_model(const ir::Sweep& sweep);

/// The model text with `overrides` (`mbfe sweep --set`) written in, as YAML,
/// the text every point then varies (unchanged when there are none).
/// @throws ir::ModelError in the model file, naming the --set, for a PATH the
///         file does not have or a value the model refuses.
std::string overridden_sweep_model(const ir::Sweep& sweep, const std::string& model_text,
                                   const ir::ModelOverrides& overrides);

/// Checks that every `vary` path names an existing key of the model text.
/// @throws ir::ModelError at the path in the sweep file ("beam 'deck' has no
/// key 'dampin'", "no body named 'cart'").
void check_sweep_paths(const ir::Sweep& sweep, const std::string& model_text);

/// The model text of point `i` (0 <= i < sweep.points()): the base model with
/// each varied key set to the point's value, written out as YAML.
std::string point_model_text(const ir::Sweep& sweep, const std::string& model_text, long i);

}  // namespace mbfe::frontend
