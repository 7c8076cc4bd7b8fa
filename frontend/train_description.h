// The `train:` map of a model file read into vehicles of axles
// (docs/model-format.md, "Trains"): what the train is, before
// frontend/expand_train.cpp writes it into the YAML tree.
#pragma once

#include <string>
#include <vector>

#include "frontend/hslm_trains.h"
#include "frontend/yaml_reader.h"
#include "ir/model_error.h"

namespace mbfe::frontend {

/// What makes a group of axles a multibody vehicle (docs/model-format.md).
struct Suspension {
  bool present = false;
  double wheel_mass = 0.0, inertia = 0.0, stiffness = 0.0, damping = 0.0, height = 1.0;
  /// Each wheel's contact: stiffness (N/m), or C_H (N/m^1.5) with Hertz's law.
  double contact_stiffness = 0.0, contact_damping = 0.0;
  bool contact_hertz = false;
};

struct Vehicle {
  std::vector<TrainAxle> axles;  // positions behind the train's leading axle
  Suspension suspension;
  ir::SourceLoc loc;
};

struct Train {
  std::string name = "train";
  ir::SourceLoc name_loc;
  double speed = 0.0, front = 0.0;
  bool as_vehicles = false;
  ir::SourceLoc as_loc;
  std::vector<std::string> beams;  // empty: every beam
  std::vector<ir::SourceLoc> beam_locs;
  std::vector<Vehicle> vehicles;
  bool hslm = false;
};

/// The train described by the `train:` map `view` (positions from its leading
/// axle at 0). @throws ir::ModelError at the offending key or value.
Train read_train(const MapView& view, const std::string& file, std::size_t max_name_length);

}  // namespace mbfe::frontend
