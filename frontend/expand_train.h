// A model file's `train:` (docs/model-format.md, "Trains"): vehicles of axles
// and axle loads, or one of the HSLM trains, written into the YAML tree as
// moving loads on the beams or as multibody vehicles with their contacts,
// before the tree is validated, so the rest of the front end sees an ordinary
// model and every error points into the file.
#pragma once

#include <yaml-cpp/yaml.h>

#include <string>
#include <vector>

#include "frontend/hslm_trains.h"
#include "ir/model_error.h"

namespace mbfe::frontend {

/// When `root` has a `train:` key: checks it (every problem a ModelError in
/// `file` at the offending key or value), writes what it expands into into
/// `root` (`beams[].loads`, or `bodies`, `loads` and `contacts`) and removes
/// the `train:` key. Generated names start with the train's `name` (default
/// `train`); one that another item of the file already has is an error at
/// the train's `name`.
/// @returns the position of the `train:` key ({0, 0} when there is none), at
///          which the caller reports an error in what was generated.
ir::SourceLoc expand_train(YAML::Node root, const std::string& file, std::size_t max_name_length);

/// The axles of the train described by the `train:` map `train` (leading axle
/// at position 0), for tests and tools. @throws ir::ModelError as above.
std::vector<TrainAxle> train_axles(const YAML::Node& train, const std::string& file, std::size_t max_name_length);

}  // namespace mbfe::frontend
