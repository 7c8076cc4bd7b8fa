// `train:` -> moving loads or multibody vehicles in the YAML tree
// (docs/model-format.md, "Trains").
#include "frontend/expand_train.h"

#include <charconv>
#include <cmath>
#include <unordered_map>

#include "frontend/yaml_reader.h"

namespace mbfe::frontend {

using ir::SourceLoc;

namespace {

// More axles than any train has (HSLM-A1 has 50); each becomes a moving load
// per beam or a body and a contact per beam, so this bounds the expansion.
constexpr long kMaxTrainAxles = 1000;
constexpr long long kMaxVehicleCount = 1000;

/// The shortest text that reads back as `value` (the generated tree holds text).
std::string number_text(double value) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

YAML::Node pair_node(double a, double b) {
  YAML::Node node(YAML::NodeType::Sequence);
  node.push_back(number_text(a));
  node.push_back(number_text(b));
  return node;
}

/// What makes a group of axles a multibody vehicle (docs/model-format.md).
struct Suspension {
  bool present = false;
  double wheel_mass = 0.0, inertia = 0.0, stiffness = 0.0, damping = 0.0, height = 1.0;
  double contact_stiffness = 0.0, contact_damping = 0.0;
};

struct Vehicle {
  std::vector<TrainAxle> axles;  // positions behind the train's leading axle
  Suspension suspension;
  SourceLoc loc;
};

struct Train {
  std::string name = "train";
  SourceLoc name_loc;
  double speed = 0.0, front = 0.0;
  bool as_vehicles = false;
  SourceLoc as_loc;
  std::vector<std::string> beams;  // empty: every beam
  std::vector<SourceLoc> beam_locs;
  std::vector<Vehicle> vehicles;
  bool hslm = false;
};

Suspension read_suspension(const MapView& view) {
  view.allow({"wheel_mass", "inertia", "stiffness", "damping", "height", "contact"});
  Suspension s;
  s.present = true;
  s.wheel_mass = view.positive(view.require("wheel_mass"));
  s.inertia = view.positive(view.require("inertia"));
  s.stiffness = view.positive(view.require("stiffness"));
  if (const Field* f = view.find("damping")) s.damping = view.number_at_least(*f, 0.0);
  if (const Field* f = view.find("height")) s.height = view.positive(*f);
  const MapView contact = view.sub(view.require("contact"));
  contact.allow({"stiffness", "damping"});
  s.contact_stiffness = contact.positive(contact.require("stiffness"));
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

}  // namespace

namespace {

/// A beam the train runs on: its node in the tree and where its s = 0 is.
struct TrackBeam {
  std::string name;
  YAML::Node node;
  double origin_x = 0.0, origin_y = 0.0;
};

/// The names the file's bodies, beams, contacts and loads already use, with
/// their lines.
std::unordered_map<std::string, int> names_in_use(const YAML::Node& root) {
  std::unordered_map<std::string, int> names;
  for (const char* section : {"bodies", "beams", "contacts", "loads"}) {
    const YAML::Node list = root[section];
    if (!list || !list.IsSequence()) continue;
    for (const YAML::Node& item : list) {
      if (!item.IsMap() || !item["name"] || !item["name"].IsScalar()) continue;
      names.emplace(item["name"].Scalar(), location_of(item["name"]).line);
      if (std::string(section) != "beams" || !item["loads"] || !item["loads"].IsSequence()) continue;
      for (const YAML::Node& load : item["loads"])
        if (load.IsMap() && load["name"] && load["name"].IsScalar())
          names.emplace(load["name"].Scalar(), location_of(load["name"]).line);
    }
  }
  return names;
}

class Expander {
 public:
  Expander(YAML::Node root, std::string file, std::size_t max_name_length, const MapView& top,
           const MapView& train_view, const Train& train)
      : file_(std::move(file)),
        max_name_length_(max_name_length),
        root_(root),
        top_(top),
        view_(train_view),
        train_(train),
        taken_(names_in_use(root)) {}

  void run() {
    find_beams();
    if (train_.as_vehicles) {
      write_vehicles();
    } else {
      write_forces();
    }
  }

 private:
  /// `name`, refused when the file already uses it.
  std::string fresh(const std::string& name) const {
    if (const auto it = taken_.find(name); it != taken_.end()) {
      view_.fail(train_.name_loc,
                 view_.prefixed("the train generates the name '" + name + "', which the file already uses at line " +
                                std::to_string(it->second) + "; give the train another train.name"));
    }
    return name;
  }

  void find_beams() {
    const YAML::Node beams = root_["beams"];
    std::vector<TrackBeam> all;
    if (beams && beams.IsSequence()) {
      std::size_t index = 0;
      for (YAML::Node item : beams) {
        const MapView beam(file(), item, item_context(item, "beam", index++, max_name_length_), "", top_.loc());
        const Field* name = beam.find("name");
        if (!name || !name->value.IsScalar()) continue;  // the validation says what is wrong
        TrackBeam track;
        track.name = name->value.Scalar();
        track.node = item;
        const ir::Vec2 origin = beam.vec2_or("origin", {0.0, 0.0});
        track.origin_x = origin[0];
        track.origin_y = origin[1];
        if (const Field* angle = beam.find("angle")) {
          if (beam.number(*angle) != 0.0 && runs_on(track.name)) {
            beam.fail(angle->value_loc,
                      beam.prefixed("angle: a train runs along the ground x axis; the beams it runs on need angle 0 "
                                    "(got " +
                                    format_number(beam.number(*angle)) + ")"));
          }
        }
        all.push_back(track);
      }
    }
    if (train_.beams.empty()) {
      beams_ = all;
    } else {
      for (std::size_t i = 0; i < train_.beams.size(); ++i) {
        bool found = false;
        for (const TrackBeam& b : all)
          if (b.name == train_.beams[i]) {
            beams_.push_back(b);
            found = true;
          }
        if (!found)
          view_.fail(train_.beam_locs[i],
                     view_.prefixed("train.on: the model has no beam '" + shown(train_.beams[i]) + "'"));
      }
    }
    if (beams_.empty()) view_.fail(view_.loc(), view_.prefixed("train: the model has no beam for the train to run on"));
  }

  bool runs_on(const std::string& beam) const {
    if (train_.beams.empty()) return true;
    for (const std::string& name : train_.beams)
      if (name == beam) return true;
    return false;
  }

  const std::string& file() const { return file_; }

  /// One moving load per axle per beam: value -P (down), entering where the
  /// axle is at t = 0 relative to the beam's s = 0.
  void write_forces() {
    std::vector<TrainAxle> axles;
    for (const Vehicle& v : train_.vehicles) axles.insert(axles.end(), v.axles.begin(), v.axles.end());
    for (TrackBeam& beam : beams_) {
      YAML::Node loads = beam.node["loads"];
      if (loads && !loads.IsNull() && !loads.IsSequence()) continue;  // the validation says what is wrong
      if (!loads || loads.IsNull()) {
        beam.node["loads"] = YAML::Node(YAML::NodeType::Sequence);
        loads = beam.node["loads"];
      }
      for (std::size_t i = 0; i < axles.size(); ++i) {
        YAML::Node load(YAML::NodeType::Map);
        load["name"] = fresh(train_.name + "_a" + std::to_string(i + 1));
        load["type"] = "moving";
        load["value"] = number_text(-axles[i].load);
        load["speed"] = number_text(train_.speed);
        load["start"] = number_text(train_.front - axles[i].position - beam.origin_x);
        loads.push_back(load);
      }
    }
  }

  /// Per vehicle: a body on a bounce and a pitch joint, a wheel per axle on
  /// a vertical slide with its suspension spring, one unilateral contact per
  /// wheel and beam; all vehicles ride on one carriage driven at the speed.
  void write_vehicles() {
    if (train_.hslm) {
      view_.fail(train_.as_loc, view_.prefixed("train.as: vehicles: an HSLM train is a load model of point forces "
                                               "(EN 1991-2); it expands as: forces only"));
    }
    const ir::Vec2 gravity = top_.vec2_or("gravity", {0.0, 0.0});
    const double g = std::hypot(gravity[0], gravity[1]);
    if (!(g > 0.0)) {
      view_.fail(train_.as_loc, view_.prefixed("train.as: vehicles: the vehicles' masses come from the axle loads "
                                               "and gravity, and the model has no gravity"));
    }
    YAML::Node bodies = section("bodies");
    YAML::Node loads = section("loads");
    YAML::Node contacts = section("contacts");
    const std::string carriage = fresh(train_.name + "_carriage");
    {
      YAML::Node body(YAML::NodeType::Map);
      body["name"] = carriage;
      body["parent"] = "ground";
      YAML::Node joint(YAML::NodeType::Map);
      joint["type"] = "prismatic";
      joint["axis"] = pair_node(1.0, 0.0);
      joint["at"] = pair_node(train_.front, beams_.front().origin_y);
      joint["motion"] = number_text(train_.speed) + "*t";
      body["joint"] = joint;
      body["mass"] = "0";
      body["inertia"] = "0";
      bodies.push_back(body);
    }
    for (std::size_t k = 0; k < train_.vehicles.size(); ++k) {
      const Vehicle& vehicle = train_.vehicles[k];
      const Suspension& s = vehicle.suspension;
      if (!s.present) {
        view_.fail(vehicle.loc, view_.prefixed("train.as: vehicles: vehicle #" + std::to_string(k + 1) +
                                               " needs a suspension: (wheel_mass, inertia, stiffness, contact)"));
      }
      if (vehicle.axles.size() < 2) {
        view_.fail(vehicle.loc,
                   view_.prefixed("train.as: vehicles: vehicle #" + std::to_string(k + 1) +
                                  " has one axle, which cannot hold its body's pitch; give it two or more"));
      }
      // The body carries each axle's load less its wheel's weight; its
      // centre of mass is where those loads balance.
      double body_weight = 0.0, moment = 0.0;
      for (const TrainAxle& a : vehicle.axles) {
        const double share = a.load - s.wheel_mass * g;
        if (!(share > 0.0)) {
          view_.fail(vehicle.loc,
                     view_.prefixed("vehicle #" + std::to_string(k + 1) + ": an axle load of " + format_number(a.load) +
                                    " N does not carry a wheel of " + format_number(s.wheel_mass) + " kg (" +
                                    format_number(s.wheel_mass * g) + " N)"));
        }
        body_weight += share;
        moment += share * a.position;
      }
      const double centre = moment / body_weight;  // behind the leading axle
      const std::string prefix = train_.name + "_v" + std::to_string(k + 1);
      const std::string bounce = fresh(prefix + "_bounce");
      bodies.push_back(slide(bounce, carriage, {-centre, 0.0}, 0.0, 0.0, false));
      const std::string body_name = fresh(prefix);
      {
        YAML::Node body(YAML::NodeType::Map);
        body["name"] = body_name;
        body["parent"] = bounce;
        YAML::Node joint(YAML::NodeType::Map);
        joint["type"] = "revolute";
        joint["at"] = pair_node(0.0, s.height);
        body["joint"] = joint;
        body["mass"] = number_text(body_weight / g);
        body["inertia"] = number_text(s.inertia);
        bodies.push_back(body);
      }
      for (std::size_t j = 0; j < vehicle.axles.size(); ++j) {
        const std::string wheel = fresh(prefix + "_w" + std::to_string(j + 1));
        bodies.push_back(
            slide(wheel, body_name, {centre - vehicle.axles[j].position, -s.height}, s.wheel_mass, 0.0, true));
        YAML::Node spring(YAML::NodeType::Map);
        spring["name"] = fresh(prefix + "_s" + std::to_string(j + 1));
        spring["type"] = "spring_damper";
        spring["joint"] = wheel;
        spring["stiffness"] = number_text(s.stiffness);
        spring["damping"] = number_text(s.damping);
        spring["rest"] = "0";
        loads.push_back(spring);
        for (const TrackBeam& beam : beams_) {
          YAML::Node contact(YAML::NodeType::Map);
          contact["name"] = fresh(wheel + "_" + beam.name);
          contact["type"] = "slider_spring";
          contact["body"] = wheel;
          contact["point"] = "contact";
          contact["beam"] = beam.name;
          contact["stiffness"] = number_text(s.contact_stiffness);
          contact["damping"] = number_text(s.contact_damping);
          contact["unilateral"] = "true";
          contacts.push_back(contact);
        }
      }
    }
  }

  /// A body on a vertical prismatic joint at `at` in its parent's frame;
  /// a wheel gets the point `contact` at its centre.
  static YAML::Node slide(const std::string& name, const std::string& parent, ir::Vec2 at, double mass, double inertia,
                          bool wheel) {
    YAML::Node body(YAML::NodeType::Map);
    body["name"] = name;
    body["parent"] = parent;
    YAML::Node joint(YAML::NodeType::Map);
    joint["type"] = "prismatic";
    joint["axis"] = pair_node(0.0, 1.0);
    joint["at"] = pair_node(at[0], at[1]);
    body["joint"] = joint;
    body["mass"] = number_text(mass);
    body["inertia"] = number_text(inertia);
    if (wheel) {
      YAML::Node points(YAML::NodeType::Map);
      points["contact"] = pair_node(0.0, 0.0);
      body["points"] = points;
    }
    return body;
  }

  /// The top-level list `key`, created when the file has none.
  YAML::Node section(const char* key) {
    YAML::Node list = root_[key];
    if (list && !list.IsNull()) {
      if (!list.IsSequence()) {
        const Field* field = top_.find(key);
        top_.fail(field ? field->value_loc : top_.loc(), std::string(key) + ": expected a list, got " + describe(list));
      }
      return list;
    }
    root_[key] = YAML::Node(YAML::NodeType::Sequence);
    return root_[key];
  }

 private:
  std::string file_;
  std::size_t max_name_length_;
  YAML::Node root_;
  const MapView& top_;
  const MapView& view_;
  const Train& train_;
  std::unordered_map<std::string, int> taken_;
  std::vector<TrackBeam> beams_;
};

}  // namespace

SourceLoc expand_train(YAML::Node root, const std::string& file, std::size_t max_name_length) {
  if (!root.IsMap() || !root["train"]) return {};
  const MapView top(file, root, "", "", SourceLoc{1, 1});
  const Field& field = top.require("train");
  if (const Field* dimension = top.find("dimension");
      dimension && dimension->value.IsScalar() && dimension->value.Scalar() == "3") {
    top.fail(field.key_loc, "train: trains run on the beams of planar models; this model is spatial (dimension: 3)");
  }
  const MapView view = top.sub(field);
  const Train train = read_train(view, file, max_name_length);
  Expander(root, file, max_name_length, top, view, train).run();
  root.remove("train");
  return field.key_loc;
}

std::vector<TrainAxle> train_axles(const YAML::Node& node, const std::string& file, std::size_t max_name_length) {
  const MapView view(file, node, "train", "", SourceLoc{1, 1});
  const Train train = read_train(view, file, max_name_length);
  std::vector<TrainAxle> axles;
  for (const Vehicle& v : train.vehicles) axles.insert(axles.end(), v.axles.begin(), v.axles.end());
  return axles;
}

}  // namespace mbfe::frontend
