// `train:` -> vehicles of axles and their suspensions (docs/model-format.md,
// "Trains").
#include "frontend/train_description.h"

namespace mbfe::frontend {

using ir::SourceLoc;

namespace {

// More axles than any train has (HSLM-A1 has 50); each becomes a moving load
// per beam or a body and a contact per beam, so this bounds the expansion.
constexpr long kMaxTrainAxles = 1000;
constexpr long long kMaxVehicleCount = 1000;

Suspension read_suspension(const MapView& view) {
  view.allow({"wheel_mass", "inertia", "stiffness", "damping", "height", "contact"});
  Suspension s;
  s.present = true;
  s.wheel_mass = view.positive(view.require("wheel_mass"));
  s.inertia = view.positive(view.require("inertia"));
  s.stiffness = view.positive(view.require("stiffness"));
  if (const Field* f = view.find("damping")) s.damping = view.number_at_least(*f, 0.0);
  if (const Field* f = view.find("height")) s.height = view.positive(*f);
  // The wheel's contact, as a slider_spring takes it: linear (stiffness) or
  // Hertz's law (coefficient, N/m^1.5), each refusing the other's constant.
  const MapView contact = view.sub(view.require("contact"));
  contact.allow({"law", "stiffness", "coefficient", "damping"});
  if (const Field* f = contact.find("law")) s.contact_hertz = contact.choice(*f, {"linear", "hertz"}) == 1;
  const char* constant = s.contact_hertz ? "coefficient" : "stiffness";
  const char* other = s.contact_hertz ? "stiffness" : "coefficient";
  if (const Field* f = contact.find(other))
    contact.fail(f->key_loc,
                 contact.prefixed(std::string(other) + " belongs to law " + (s.contact_hertz ? "linear" : "hertz") +
                                  "; law " + (s.contact_hertz ? "hertz" : "linear") + " takes " + constant +
                                  (s.contact_hertz ? " (C_H, N/m^1.5)" : " (N/m)")));
  s.contact_stiffness = contact.positive(contact.require(constant));
  if (const Field* f = contact.find("damping")) s.contact_damping = contact.number_at_least(*f, 0.0);
  return s;
}

/// The list under `field` as numbers, any length from 1.
std::vector<double> number_list(const MapView& view, const Field& field, const char* shape) {
  const std::size_t count = view.list(field).size();
  if (count == 0)
    view.fail(field.value_loc, view.prefixed(view.what(field) + ": expected " + shape + ", got an empty list"));
  return view.numbers(field, count, shape);
}

/// Appends the `count` copies of one vehicle of `vehicles:`; `offset` is the
/// distance from the train's front to this vehicle's front, and grows.
void read_vehicle(const MapView& view, const Suspension& train_suspension, double& offset, Train& train,
                  long& axle_count) {
  view.allow({"axles", "loads", "load", "length", "count", "suspension"});
  const Field& axles_field = view.require("axles");
  const std::vector<double> axles = number_list(view, axles_field, "[a1, a2, ...] (m from the vehicle's front)");
  for (std::size_t j = 0; j < axles.size(); ++j) {
    if (axles[j] < 0.0 || (j > 0 && !(axles[j] > axles[j - 1]))) {
      view.fail(axles_field.value_loc,
                view.prefixed("axles: expected positions from the vehicle's front, >= 0 and increasing (got " +
                              format_number(axles[j]) + " as axle " + std::to_string(j + 1) + ")"));
    }
  }
  std::vector<double> loads;
  const Field* loads_field = view.find("loads");
  const Field* load_field = view.find("load");
  if ((loads_field != nullptr) == (load_field != nullptr)) {
    view.fail(loads_field ? loads_field->key_loc : view.loc(),
              view.prefixed("give either 'loads' (one per axle, N) or 'load' (every axle, N)"));
  }
  if (loads_field) {
    loads = view.numbers(*loads_field, axles.size(), "one load per axle (N)");
    for (const double p : loads)
      if (!(p > 0.0))
        view.fail(loads_field->value_loc,
                  view.prefixed("loads: every axle load must be > 0 (got " + format_number(p) + ")"));
  } else {
    loads.assign(axles.size(), view.positive(*load_field));
  }
  double length = axles.front() + axles.back();  // the same overhang at both ends
  if (const Field* f = view.find("length")) {
    length = view.positive(*f);
    if (length < axles.back()) {
      view.fail(f->value_loc,
                view.prefixed("length " + format_number(length) + " m is shorter than the vehicle's last axle at " +
                              format_number(axles.back()) + " m"));
    }
  }
  long long count = 1;
  if (const Field* f = view.find("count")) {
    count = view.whole_number(*f);
    if (count < 1 || count > kMaxVehicleCount)
      view.fail(f->value_loc, view.prefixed("count must be from 1 to " + std::to_string(kMaxVehicleCount) + " (got " +
                                            std::to_string(count) + ")"));
  }
  Suspension suspension = train_suspension;
  if (const Field* f = view.find("suspension")) suspension = read_suspension(view.sub(*f));
  for (long long c = 0; c < count; ++c) {
    axle_count += static_cast<long>(axles.size());
    if (axle_count > kMaxTrainAxles) {
      view.fail(view.loc(), view.prefixed("the train has more than " + std::to_string(kMaxTrainAxles) + " axles"));
    }
    Vehicle vehicle;
    vehicle.loc = view.loc();
    vehicle.suspension = suspension;
    for (std::size_t j = 0; j < axles.size(); ++j) vehicle.axles.push_back({offset + axles[j], loads[j]});
    train.vehicles.push_back(std::move(vehicle));
    offset += length;
  }
}

}  // namespace

Train read_train(const MapView& view, const std::string& file, std::size_t max_name_length) {
  view.allow({"name", "hslm", "vehicles", "speed", "front", "on", "as", "suspension"});
  Train train;
  if (const Field* name = view.find("name")) {
    train.name = view.identifier(*name, max_name_length);
    train.name_loc = name->value_loc;
  } else {
    train.name_loc = view.loc();
  }
  const Field& speed = view.require("speed");
  train.speed = view.positive(speed);
  train.front = view.number_or("front", 0.0);
  if (const Field* as = view.find("as")) {
    train.as_vehicles = view.choice(*as, {"forces", "vehicles"}) == 1;
    train.as_loc = as->value_loc;
  }
  if (const Field* on = view.find("on")) {
    const std::vector<YAML::Node> items = view.list(*on);
    if (items.empty())
      view.fail(on->value_loc, view.prefixed("train.on: expected a list of beam names, got an empty list"));
    for (std::size_t i = 0; i < items.size(); ++i) {
      Field item{"on[" + std::to_string(i) + "]", {}, items[i], location_of(items[i]), location_of(items[i])};
      if (item.value_loc.line == 0) item.value_loc = item.key_loc = on->value_loc;
      train.beams.push_back(view.identifier(item, max_name_length));
      train.beam_locs.push_back(item.value_loc);
    }
  }
  Suspension train_suspension;
  if (const Field* f = view.find("suspension")) train_suspension = read_suspension(view.sub(*f));

  const Field* hslm = view.find("hslm");
  const Field* vehicles = view.find("vehicles");
  if ((hslm != nullptr) == (vehicles != nullptr)) {
    view.fail(hslm ? hslm->key_loc : view.loc(),
              view.prefixed("train: give either 'hslm' (A1 .. A10) or 'vehicles' (a list of vehicles)"));
  }
  if (hslm) {
    const std::string which = view.text(*hslm);
    const HslmTrain* table = find_hslm_train(which);
    if (!table) {
      view.fail(
          hslm->value_loc,
          view.prefixed("train.hslm: expected one of A1, A2, ..., A10 (EN 1991-2 HSLM-A), got '" + shown(which) + "'"));
    }
    train.hslm = true;
    Vehicle whole;
    whole.loc = hslm->value_loc;
    whole.axles = hslm_axles(*table);
    whole.suspension = train_suspension;
    train.vehicles.push_back(std::move(whole));
    return train;
  }
  const std::vector<YAML::Node> items = view.list(*vehicles);
  if (items.empty())
    view.fail(vehicles->value_loc, view.prefixed("train.vehicles: expected a list of vehicles, got an empty list"));
  double offset = 0.0;
  long axle_count = 0;
  for (std::size_t i = 0; i < items.size(); ++i) {
    const MapView vehicle(file, items[i], "train: vehicle #" + std::to_string(i + 1), "", vehicles->value_loc);
    read_vehicle(vehicle, train_suspension, offset, train, axle_count);
  }
  // Positions from the leading axle.
  const double lead = train.vehicles.front().axles.front().position;
  for (Vehicle& v : train.vehicles)
    for (TrainAxle& a : v.axles) a.position -= lead;
  return train;
}

}  // namespace mbfe::frontend
