// `train:` -> moving loads or multibody vehicles in the YAML tree
// (docs/model-format.md, "Trains").
#include "frontend/expand_train.h"

#include <charconv>
#include <cmath>
#include <unordered_map>

#include "frontend/train_description.h"
#include "frontend/yaml_reader.h"

namespace mbfe::frontend {

using ir::SourceLoc;

namespace {

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
          if (s.contact_hertz) {
            contact["law"] = "hertz";
            contact["coefficient"] = number_text(s.contact_stiffness);
          } else {
            contact["stiffness"] = number_text(s.contact_stiffness);
          }
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