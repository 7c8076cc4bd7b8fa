// The ten Universal Trains HSLM-A1 .. HSLM-A10 of EN 1991-2 (the High Speed
// Load Model A, a train of point forces used in the dynamic analysis of
// railway bridges for speeds over 200 km/h), as a table and as axles.
#pragma once

#include <array>
#include <string>
#include <vector>

namespace mbfe::frontend {

/// One axle of a train: where it is and what it weighs.
struct TrainAxle {
  double position = 0.0;  // m behind the train's leading axle (>= 0)
  double load = 0.0;      // N, pressing down (> 0)
};

/// One row of the table of Universal Trains (EN 1991-2:2003, Table 6.3).
struct HslmTrain {
  const char* name;           // "A1" .. "A10"
  int intermediate_coaches;   // N
  double coach_length;        // D, m: the spacing of the articulated bogies
  double bogie_axle_spacing;  // d, m: the axle spacing of an articulated bogie
  double axle_load;           // P, N: every axle of the train
};

/// The ten rows, A1 first.
const std::array<HslmTrain, 10>& hslm_trains();

/// The row named `name` ("A1" .. "A10"), or nullptr.
const HslmTrain* find_hslm_train(const std::string& name);

/// The train's 2 N + 14 axles, leading axle first (position 0), laid out as
/// EN 1991-2:2003 Figure 6.12 draws every Universal Train (docs/trains.md):
/// a power car (axles 3 m, 11 m, 3 m apart), 3.525 m to an end coach whose
/// leading bogie has its axles 3 m apart, N + 1 articulated bogies (axles d
/// apart) D from bogie centre to bogie centre starting D behind that bogie's
/// centre, the other end coach's bogie D behind the last, and the other power
/// car as the first seen from behind. Every axle carries P.
std::vector<TrainAxle> hslm_axles(const HslmTrain& train);

}  // namespace mbfe::frontend
