#include "frontend/parse_sweep.h"

#include <yaml-cpp/yaml.h>

#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "frontend/capped_file.h"
#include "frontend/model_overrides.h"
#include "frontend/parse_model.h"
#include "frontend/text_guard.h"
#include "frontend/yaml_reader.h"
#include "ir/identifiers.h"

namespace mbfe::frontend {

namespace {

using ir::ModelError;
using ir::SourceLoc;

constexpr long kMaxPoints = 1000000;     // a sweep larger than this is a typo
constexpr std::size_t kMaxNameLength = 128;
// A sweep file is a few lines; its model file is bounded as any model file.
constexpr std::size_t kMaxSweepFileBytes = std::size_t{1} << 20;

/// The shortest text that reads back as v ("10", "0.0025", "1e-07").
std::string shortest(double v) {
  char buf[40];
  const auto [end, error] = std::to_chars(buf, buf + sizeof buf, v);
  return error == std::errc() ? std::string(buf, end) : std::to_string(v);
}

std::vector<std::string> split_path(const std::string& path) {
  std::vector<std::string> keys;
  std::string key;
  std::istringstream in(path);
  while (std::getline(in, key, '.')) keys.push_back(key);
  return keys;
}

/// A value of `values:` or `set:` as the text a --set VALUE would be: a
/// scalar as written, a list or map in YAML's flow form ("[0, 300]"), which
/// the point's model reads back as YAML (frontend/model_overrides.h).
std::string value_text(const YAML::Node& item) {
  if (item.IsScalar()) return item.Scalar();
  YAML::Emitter out;
  out.SetSeqFormat(YAML::Flow);
  out.SetMapFormat(YAML::Flow);
  out << item;
  return out.c_str();
}

/// `template: "{}*t"`: each value put in place of {} (a speed into a motion).
void apply_template(const MapView& view, ir::SweepVariable& v) {
  const Field* t = view.find("template");
  if (!t) return;
  const std::string text = view.text(*t);
  const auto at = text.find("{}");
  if (at == std::string::npos)
    view.fail(t->value_loc, view.prefixed("template: expected '{}' where each value goes, got '" + shown(text) + "'"));
  for (std::string& value : v.values) value = text.substr(0, at) + value + text.substr(at + 2);
}

ir::SweepVariable parse_variable(const MapView& view) {
  view.allow({"path", "values", "range", "template"});
  ir::SweepVariable v;
  const Field& path = view.require("path");
  v.path = view.text(path);
  v.loc = path.value_loc;
  v.keys = split_path(v.path);
  for (const std::string& k : v.keys)
    if (k.empty()) view.fail(path.value_loc, view.prefixed("path '" + shown(v.path) + "' has an empty key"));
  const Field* values = view.find("values");
  const Field* range = view.find("range");
  if ((values != nullptr) == (range != nullptr))
    view.fail(view.loc(), view.prefixed("give either 'values: [...]' or 'range: {from, to, count}'"));
  if (values) {
    for (const YAML::Node& item : view.list(*values)) {
      if (!item.IsScalar() && !item.IsSequence() && !item.IsMap())
        view.fail(location_of(item),
                  view.prefixed("values: expected numbers, strings, lists or maps, got " + describe(item)));
      v.values.push_back(value_text(item));
    }
    if (v.values.empty()) view.fail(values->value_loc, view.prefixed("values: the list is empty"));
    apply_template(view, v);
    return v;
  }
  const MapView r = view.sub(*range);
  r.allow({"from", "to", "count"});
  const double from = r.number(r.require("from"));
  const double to = r.number(r.require("to"));
  const Field& count_field = r.require("count");
  const long long count = r.whole_number(count_field);
  if (count < 1 || count > kMaxPoints)
    r.fail(count_field.value_loc, r.prefixed("range.count must be in 1.." + std::to_string(kMaxPoints)));
  for (long long k = 0; k < count; ++k) {
    const double x = count == 1 ? from : from + (to - from) * static_cast<double>(k) / static_cast<double>(count - 1);
    v.values.push_back(shortest(x));
  }
  apply_template(view, v);
  return v;
}

ir::SweepCollect parse_collect(const MapView& view) {
  view.allow({"name", "column", "stat", "lowpass", "order", "from", "to"});
  ir::SweepCollect c;
  c.loc = view.loc();
  c.name = view.identifier(view.require("name"), kMaxNameLength);
  c.column = view.text(view.require("column"));
  constexpr ir::SweepStat kStats[] = {ir::SweepStat::kMax,
                                      ir::SweepStat::kMin,
                                      ir::SweepStat::kAbsMax,
                                      ir::SweepStat::kMean,
                                      ir::SweepStat::kRms,
                                      ir::SweepStat::kInitial,
                                      ir::SweepStat::kFinal,
                                      ir::SweepStat::kStd,
                                      ir::SweepStat::kStatisticalMax,
                                      ir::SweepStat::kStatisticalMin,
                                      ir::SweepStat::kLossPercent};
  const Field& stat = view.require("stat");
  c.stat = kStats[view.choice(stat, {"max", "min", "absmax", "mean", "rms", "initial", "final", "std",
                                     "statistical_max", "statistical_min", "loss_percent"})];
  if (const Field* f = view.find("lowpass")) c.lowpass_hz = view.positive(*f);
  if (const Field* f = view.find("order")) {
    const long long order = view.whole_number(*f);
    if (order < 1 || order > 8)
      view.fail(f->value_loc, view.prefixed("order must be a whole number 1..8 (got " + std::to_string(order) + ")"));
    if (c.lowpass_hz == 0.0)
      view.fail(f->value_loc, view.prefixed("order is the low-pass filter's: give lowpass (Hz) too"));
    c.order = static_cast<int>(order);
  }
  if (const Field* f = view.find("from")) c.from = view.number(*f);
  if (const Field* f = view.find("to")) c.to = view.number(*f);
  if (c.from && c.to && *c.from > *c.to)
    view.fail(view.find("from")->value_loc, view.prefixed("from must not be after to"));
  if (c.as_stats() && (c.stat == ir::SweepStat::kInitial || c.stat == ir::SweepStat::kFinal))
    view.fail(stat.value_loc, view.prefixed("stat initial and final take the rows as written: no lowpass, from or to"));
  return c;
}

void parse_simulation(const MapView& view, ir::SweepSimulation& sim) {
  view.allow({"integrator", "step", "t_end", "probes", "adjust", "full_state"});
  if (const Field* f = view.find("integrator")) sim.integrator = view.text(*f);
  if (const Field* f = view.find("step")) sim.step = view.positive(*f);
  if (const Field* f = view.find("t_end")) sim.t_end = view.positive(*f);
  if (const Field* f = view.find("probes")) {
    for (const YAML::Node& item : view.list(*f)) {
      if (!item.IsScalar()) view.fail(location_of(item), view.prefixed("probes: expected 'beam@s' strings"));
      for (const std::string& earlier : sim.probes)
        if (earlier == item.Scalar())
          view.fail(location_of(item), view.prefixed("probes: '" + shown(earlier) +
                                                     "' is given twice; each probe is a column and needs a name "
                                                     "of its own"));
      sim.probes.push_back(item.Scalar());
    }
  }
  if (const Field* f = view.find("adjust")) sim.adjust = view.choice(*f, {"on", "off"}) == 0 ? "on" : "off";
  if (const Field* f = view.find("full_state")) sim.full_state = view.boolean(*f);
}

/// The node the keys lead to in `root`, or an error naming the first key that
/// does not; a list or map there takes only values that are lists or maps.
YAML::Node walk(const ir::Sweep& sweep, const ir::SweepVariable& v, const YAML::Node& root,
                const std::string& model_path) {
  YAML::Node node;
  node.reset(root);
  std::string where = "the model";
  for (const std::string& key : v.keys) {
    std::string why;
    const YAML::Node child = path_child(node, key, where, why);
    if (!child.IsDefined())
      throw ModelError(sweep.source_path, v.loc, "path '" + shown(v.path) + "': " + why + " (in " + model_path + ")");
    node.reset(child);
    where = "'" + key + "'";
  }
  if (!node.IsScalar() && !node.IsNull()) {
    for (const std::string& value : v.values)
      if (!is_flow_collection(value))
        throw ModelError(sweep.source_path, v.loc,
                         "path '" + shown(v.path) + "' leads to " + describe(node) +
                             ", not to a single value: give lists or maps as its values ([a, b]) or go on to one "
                             "of its items (" +
                             shown(v.path) + ".0)");
  }
  return node;
}

/// The model's file paths (a beam's `profile: {file: ...}`) made absolute,
/// resolved against the folder of the model file `model_path` as the model
/// resolves them: a point's model.yaml lives in another folder.
void absolute_file_paths(YAML::Node root, const std::string& model_path) {
  // Looked up through const nodes, which never add a key; the nodes found
  // still refer to the tree's own.
  const YAML::Node& model = root;
  const YAML::Node beams = model["beams"];
  if (!beams || !beams.IsSequence()) return;
  const std::filesystem::path parent = std::filesystem::path(model_path).parent_path();
  const std::filesystem::path folder =
      parent.empty() ? std::filesystem::current_path() : std::filesystem::absolute(parent);
  for (const YAML::Node& beam : beams) {
    if (!beam.IsMap() || !beam["profile"] || !beam["profile"].IsMap()) continue;
    YAML::Node file = beam["profile"]["file"];
    if (!file || !file.IsScalar() || file.Scalar().empty()) continue;
    const std::filesystem::path path(file.Scalar());
    if (path.is_relative()) file = (folder / path).lexically_normal().string();
  }
}

YAML::Node load_model_yaml(const ir::Sweep& sweep, const std::string& model_text) {
  try {
    return YAML::Load(model_text);
  } catch (const YAML::Exception& e) {
    throw ModelError(sweep_model_path(sweep), {e.mark.line + 1, e.mark.column + 1}, "invalid YAML: " + e.msg);
  }
}

}  // namespace

ir::Sweep parse_sweep_text(const std::string& text, const std::string& display_path) {
  if (auto problem = find_non_text(text)) throw ModelError(display_path, problem->loc, problem->message);
  if (auto problem = find_excess_structure(text, 64, 100000)) throw ModelError(display_path, problem->loc, problem->message);
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw ModelError(display_path, {e.mark.line + 1, e.mark.column + 1}, "invalid YAML: " + e.msg);
  }
  if (!root.IsMap()) throw ModelError(display_path, {1, 1}, "expected a sweep: a map starting with 'sweep:'");
  const MapView top(display_path, root, "", "", SourceLoc{1, 1});
  top.allow({"sweep", "description", "model", "set", "vary", "mode", "simulate", "collect"});
  ir::Sweep sweep;
  sweep.source_path = display_path;
  sweep.name = top.identifier(top.require("sweep"), kMaxNameLength);
  if (const Field* d = top.find("description")) top.text(*d);
  const Field& model = top.require("model");
  sweep.model_path = top.text(model);
  sweep.model_loc = model.value_loc;
  const Field& vary = top.require("vary");
  const std::vector<YAML::Node> items = top.list(vary);
  if (items.empty()) top.fail(vary.value_loc, "vary: the list is empty (nothing to sweep)");
  for (std::size_t i = 0; i < items.size(); ++i) {
    const MapView view(display_path, items[i], "vary #" + std::to_string(i + 1), "", vary.value_loc);
    sweep.vary.push_back(parse_variable(view));
  }
  if (const Field* set = top.find("set")) {
    const MapView view = top.sub(*set);
    for (const Field& f : view.fields()) {
      ir::SweepVariable v;
      v.path = f.key;
      v.loc = f.key_loc;
      v.keys = split_path(v.path);
      for (const std::string& k : v.keys)
        if (k.empty()) view.fail(f.key_loc, "set: path '" + shown(v.path) + "' has an empty key");
      if (!f.value.IsScalar() && !f.value.IsSequence() && !f.value.IsMap())
        view.fail(f.value_loc,
                  "set: " + shown(v.path) + ": expected a number, a string, a list or a map, got " + describe(f.value));
      v.values.push_back(value_text(f.value));
      for (const ir::SweepVariable& varied : sweep.vary)
        if (varied.path == v.path)
          view.fail(f.key_loc, "set: path '" + shown(v.path) + "' is also varied (vary at line " +
                                   std::to_string(varied.loc.line) + "): give it in one place");
      sweep.set.push_back(std::move(v));
    }
  }
  if (const Field* mode = top.find("mode")) sweep.zip = top.choice(*mode, {"product", "zip"}) == 1;
  if (sweep.zip) {
    for (const ir::SweepVariable& v : sweep.vary)
      if (v.values.size() != sweep.vary.front().values.size())
        throw ModelError(display_path, v.loc,
                         "mode zip: path '" + shown(v.path) + "' has " + std::to_string(v.values.size()) +
                             " values, the first has " + std::to_string(sweep.vary.front().values.size()));
  }
  double points = 1;
  for (const ir::SweepVariable& v : sweep.vary) points *= static_cast<double>(v.values.size());
  if (!sweep.zip && points > kMaxPoints)
    top.fail(vary.value_loc, "vary: " + shortest(points) + " points, more than " + std::to_string(kMaxPoints));
  if (const Field* sim = top.find("simulate")) parse_simulation(top.sub(*sim), sweep.simulation);
  if (const Field* collect = top.find("collect")) {
    const std::vector<YAML::Node> cs = top.list(*collect);
    for (std::size_t i = 0; i < cs.size(); ++i) {
      const MapView view(display_path, cs[i], "collect #" + std::to_string(i + 1), "", collect->value_loc);
      sweep.collect.push_back(parse_collect(view));
      for (std::size_t j = 0; j + 1 < sweep.collect.size(); ++j)
        if (sweep.collect[j].name == sweep.collect.back().name)
          view.fail(view.loc(), view.prefixed("duplicate collect name '" + sweep.collect.back().name + "'"));
    }
  }
  return sweep;
}

ir::Sweep load_sweep_file(const std::string& path) {
  // A sweep reads its files again in every point: a device such as /dev/zero,
  // a pipe or a folder is refused before reading.
  const CappedRead read = read_capped_file(path, kMaxSweepFileBytes, FileKinds::kRegularOnly);
  if (!read) throw ModelError(path, {}, read.why + " (the sweep file)");
  return parse_sweep_text(read.text, path);
}

std::string read_sweep_model(const ir::Sweep& sweep) {
  const std::string path = sweep_model_path(sweep);
  CappedRead read = read_capped_file(path, ParseLimits{}.max_file_bytes, FileKinds::kRegularOnly);
  if (!read) throw ModelError(sweep.source_path, sweep.model_loc, "model file '" + path + "': " + read.why);
  return std::move(read.text);
}

std::string sweep_model_path(const ir::Sweep& sweep) {
  const std::filesystem::path model(sweep.model_path);
  if (model.is_absolute()) return model.string();
  return (std::filesystem::path(sweep.source_path).parent_path() / model).lexically_normal().string();
}

std::string overridden_sweep_model(const ir::Sweep& sweep, const std::string& model_text,
                                   const ir::ModelOverrides& overrides) {
  if (overrides.empty()) return model_text;
  const std::string path = sweep_model_path(sweep);
  parse_model_text(model_text, path, ParseLimits{}, overrides);  // every error located in the file
  YAML::Node root = YAML::Clone(load_model_yaml(sweep, model_text));
  apply_overrides(root, overrides, path);
  YAML::Emitter out;
  out << root;
  return std::string(out.c_str()) + "\n";
}

void check_sweep_paths(const ir::Sweep& sweep, const std::string& model_text) {
  const YAML::Node root = load_model_yaml(sweep, model_text);
  for (const ir::SweepVariable& v : sweep.set) walk(sweep, v, root, sweep_model_path(sweep));
  for (const ir::SweepVariable& v : sweep.vary) walk(sweep, v, root, sweep_model_path(sweep));
}

std::string point_model_text(const ir::Sweep& sweep, const std::string& model_text, long i) {
  YAML::Node root = YAML::Clone(load_model_yaml(sweep, model_text));
  const std::string model_path = sweep_model_path(sweep);
  const auto put = [&](const ir::SweepVariable& v, const std::string& value) {
    YAML::Node node = walk(sweep, v, root, model_path);
    try {
      put_value(node, value, location_of(node), model_path, "path '" + shown(v.path) + "'");
    } catch (const ModelError& e) {  // a flow value that is not YAML: at the path in the sweep file
      throw ModelError(sweep.source_path, v.loc, e.message());
    }
  };
  for (const ir::SweepVariable& v : sweep.set) put(v, v.values.front());
  const std::vector<int> idx = sweep.indices(i);
  for (std::size_t k = 0; k < sweep.vary.size(); ++k)
    put(sweep.vary[k], sweep.vary[k].values[static_cast<std::size_t>(idx[k])]);
  absolute_file_paths(root, model_path);
  YAML::Emitter out;
  out << root;
  return std::string(out.c_str()) + "\n";
}

}  // namespace mbfe::frontend
