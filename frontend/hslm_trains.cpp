// Source: EN 1991-2:2003, Eurocode 1: Actions on structures - Part 2: Traffic
// loads on bridges, 6.4.6.1.1, Table 6.3 (N, D, d, P of HSLM-A1 .. A10) and
// Figure 6.12 (the power cars and end coaches common to all ten). The
// validity limits of the model are in its Annex E. docs/trains.md repeats the
// table and the geometry.
#include "frontend/hslm_trains.h"

namespace mbfe::frontend {

namespace {

// Figure 6.12: the parts every Universal Train shares (m).
constexpr double kPowerCarBogieAxles = 3.0;     // axle spacing of a power car's bogie
constexpr double kPowerCarBogieCentres = 14.0;  // 3 + 11 + 3 - 3: bogie centre to bogie centre
constexpr double kPowerCarToEndCoach = 3.525;   // last power car axle to the end coach's first
constexpr double kEndCoachBogieAxles = 3.0;     // axle spacing of an end coach's own bogie

constexpr double kKiloNewton = 1000.0;

// EN 1991-2:2003, Table 6.3.
const std::array<HslmTrain, 10> kTrains = {{
    {"A1", 18, 18.0, 2.0, 170 * kKiloNewton},
    {"A2", 17, 19.0, 3.5, 200 * kKiloNewton},
    {"A3", 16, 20.0, 2.0, 180 * kKiloNewton},
    {"A4", 15, 21.0, 3.0, 190 * kKiloNewton},
    {"A5", 14, 22.0, 2.0, 170 * kKiloNewton},
    {"A6", 13, 23.0, 2.0, 180 * kKiloNewton},
    {"A7", 13, 24.0, 2.0, 190 * kKiloNewton},
    {"A8", 12, 25.0, 2.5, 190 * kKiloNewton},
    {"A9", 11, 26.0, 2.0, 210 * kKiloNewton},
    {"A10", 11, 27.0, 2.0, 210 * kKiloNewton},
}};

}  // namespace

const std::array<HslmTrain, 10>& hslm_trains() { return kTrains; }

const HslmTrain* find_hslm_train(const std::string& name) {
  for (const HslmTrain& train : kTrains)
    if (name == train.name) return &train;
  return nullptr;
}

std::vector<TrainAxle> hslm_axles(const HslmTrain& train) {
  // Bogie centres and axle spacings from the front, then each bogie's two axles.
  struct Bogie {
    double centre, axle_spacing;
  };
  std::vector<Bogie> bogies;
  const double half_power = kPowerCarBogieAxles / 2.0;
  bogies.push_back({half_power, kPowerCarBogieAxles});
  bogies.push_back({half_power + kPowerCarBogieCentres, kPowerCarBogieAxles});
  const double power_car_last_axle = kPowerCarBogieCentres + kPowerCarBogieAxles;
  double centre = power_car_last_axle + kPowerCarToEndCoach + kEndCoachBogieAxles / 2.0;
  bogies.push_back({centre, kEndCoachBogieAxles});
  for (int k = 0; k < train.intermediate_coaches + 1; ++k) {
    centre += train.coach_length;
    bogies.push_back({centre, train.bogie_axle_spacing});
  }
  centre += train.coach_length;
  bogies.push_back({centre, kEndCoachBogieAxles});
  const double rear_power_car_first_axle = centre + kEndCoachBogieAxles / 2.0 + kPowerCarToEndCoach;
  bogies.push_back({rear_power_car_first_axle + half_power, kPowerCarBogieAxles});
  bogies.push_back({rear_power_car_first_axle + half_power + kPowerCarBogieCentres, kPowerCarBogieAxles});

  std::vector<TrainAxle> axles;
  axles.reserve(2 * bogies.size());
  for (const Bogie& bogie : bogies) {
    axles.push_back({bogie.centre - bogie.axle_spacing / 2.0, train.axle_load});
    axles.push_back({bogie.centre + bogie.axle_spacing / 2.0, train.axle_load});
  }
  return axles;
}

}  // namespace mbfe::frontend
