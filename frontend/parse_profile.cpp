// ModelParser: a beam's running surface, `profile:` and `camber:`
// (docs/profiles.md): an expression in s, a table read from a CSV file next to
// the model, or a random profile from a track spectrum.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <optional>
#include <sstream>
#include <utility>

#include "frontend/capped_file.h"
#include "frontend/model_parser.h"
#include "frontend/text_guard.h"

namespace mbfe::frontend {

namespace {

// Points of [0, L] where a profile expression must be finite: enough to meet
// a division by zero or a log of a negative number written at a round s.
constexpr int kProfileChecks = 4000;

// A spectrum profile is a sum of n harmonics tabulated at m points (n, m grow
// as L / wavelength_min; runtime/fem/running_surface.h): n m terms, about 1 s
// at this bound.
constexpr double kMaxHarmonicTerms = 2e8;

// Bytes of a typical table row ("1234.25,-0.00123\n"), to say the size limit in rows.
constexpr std::size_t kTableRowBytes = 20;

std::string trimmed(const std::string& text) {
  const auto first = text.find_first_not_of(" \t\r");
  if (first == std::string::npos) return "";
  return text.substr(first, text.find_last_not_of(" \t\r") - first + 1);
}

/// The CSV's cells of one line, with the column where each starts (1-based).
std::vector<std::pair<std::string, int>> cells_of(const std::string& line) {
  std::vector<std::pair<std::string, int>> out;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = line.find(',', start);
    const std::string cell = line.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    const std::size_t lead = cell.find_first_not_of(" \t");
    out.emplace_back(trimmed(cell), static_cast<int>(start + (lead == std::string::npos ? 0 : lead)) + 1);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return out;
}

/// Reads the table `text` of the file `shown_path`: a header naming columns
/// `s` and `offset` (others are ignored), or none (then the first two columns
/// are s and offset), then one row of numbers per line,
/// s strictly increasing. Blank lines and lines starting with '#' are skipped.
/// @throws ir::ModelError at the table's line and column.
void read_profile_table(const std::string& text, const std::string& shown_path, std::vector<double>& s,
                        std::vector<double>& offset) {
  int line_no = 0, s_col = -1, offset_col = -1;
  std::size_t width = 0;
  std::string line;
  auto fail = [&](int column, const std::string& message) {
    throw ir::ModelError(shown_path, ir::SourceLoc{line_no, column}, "profile table: " + message);
  };
  for (std::size_t start = 0; start < text.size();) {
    const std::size_t end = std::min(text.find('\n', start), text.size());
    line.assign(text, start, end - start);
    start = end + 1;
    ++line_no;
    const std::string text = trimmed(line);
    if (text.empty() || text[0] == '#') continue;
    const auto cells = cells_of(line);
    if (s_col < 0) {  // the header, or a first row of numbers: then s and offset are columns 1 and 2
      for (std::size_t c = 0; c < cells.size(); ++c) {
        if (cells[c].first == "s") s_col = static_cast<int>(c);
        if (cells[c].first == "offset") offset_col = static_cast<int>(c);
      }
      width = cells.size();
      if (s_col >= 0 && offset_col >= 0) continue;
      if (cells.size() >= 2 && std::all_of(cells.begin(), cells.end(), [](const auto& cell) {
            double v = 0.0;
            const char* first = cell.first.data() + (!cell.first.empty() && cell.first[0] == '+');
            const char* last = cell.first.data() + cell.first.size();
            const auto [end, error] = std::from_chars(first, last, v);
            return !cell.first.empty() && error == std::errc() && end == last;
          })) {
        s_col = 0;
        offset_col = 1;
      } else {
        fail(1, "expected a header naming the columns s and offset (m), or rows of two numbers, got \"" +
                    shown(text) + "\"");
      }
    }
    if (cells.size() != width)
      fail(1, "expected " + std::to_string(width) + " cells as in the header, got " + std::to_string(cells.size()));
    double values[2] = {0.0, 0.0};
    const int cols[2] = {s_col, offset_col};
    for (int k = 0; k < 2; ++k) {
      const auto& [cell, column] = cells[static_cast<std::size_t>(cols[k])];
      const char* first = cell.data();
      const char* last = first + cell.size();
      if (!cell.empty() && *first == '+') ++first;
      const auto [end, error] = std::from_chars(first, last, values[k]);
      if (cell.empty() || error != std::errc() || end != last || !std::isfinite(values[k]))
        fail(column, std::string(k == 0 ? "s" : "offset") + ": expected a finite number, got \"" + shown(cell) + "\"");
    }
    if (!s.empty() && !(values[0] > s.back())) {
      std::ostringstream os;
      os.precision(12);
      os << "s must increase strictly from row to row: got " << values[0] << " m after " << s.back() << " m";
      fail(cells[static_cast<std::size_t>(s_col)].second, os.str());
    }
    s.push_back(values[0]);
    offset.push_back(values[1]);
  }
  ++line_no;
  if (s_col < 0) fail(1, "the file is empty; expected a header naming the columns s and offset, then rows");
  if (s.size() < 2) fail(1, "expected at least 2 rows of (s, offset), got " + std::to_string(s.size()));
}

/// A pole of a profile expression on [0, length]: a division by a part, a
/// negative power of a part, or a tan of a part, where that part (its cosine
/// for tan) changes sign between two of the sample points and vanishes there
/// (bisected to adjacent doubles, its value below 1e-9 of its largest at the
/// samples: a jump such as step(s - 5) - 0.5 changes sign without vanishing).
/// Sampling alone misses a zero between its points (1/(s - 10) sampled where
/// s = 10 is not a sample). Returns the operator's node and the s, m.
std::optional<std::pair<int, double>> find_pole(const ir::Expression& e, double length, int samples) {
  using Kind = ir::ExpressionNode::Kind;
  const std::vector<ir::ExpressionNode>& nodes = e.nodes();
  // Postfix: the subtree rooted at node j is the range [j - size[j] + 1, j].
  std::vector<int> size(nodes.size(), 1);
  std::vector<int> stack;
  for (std::size_t j = 0; j < nodes.size(); ++j) {
    for (int a = 0; a < nodes[j].arity(); ++a) {
      size[j] += size[static_cast<std::size_t>(stack.back())];
      stack.pop_back();
    }
    stack.push_back(static_cast<int>(j));
  }
  const auto subtree = [&](int root) {
    return std::vector<ir::ExpressionNode>(nodes.begin() + (root - size[static_cast<std::size_t>(root)] + 1),
                                           nodes.begin() + root + 1);
  };
  for (std::size_t j = 0; j < nodes.size(); ++j) {
    const ir::ExpressionNode& node = nodes[j];
    const int last_arg = static_cast<int>(j) - 1;  // the root of the last (or only) argument
    std::vector<ir::ExpressionNode> part;          // the part whose zero is a pole
    std::optional<ir::Expression> exponent;
    if (node.kind == Kind::kDivide) {
      part = subtree(last_arg);
    } else if (node.kind == Kind::kPower) {
      const int base = last_arg - size[static_cast<std::size_t>(last_arg)];
      part = subtree(base);
      exponent = ir::Expression(subtree(last_arg));
    } else if (node.kind == Kind::kCall && node.function == ir::Function::kTan) {
      part = subtree(last_arg);
      ir::ExpressionNode cosine;
      cosine.kind = Kind::kCall;
      cosine.function = ir::Function::kCos;
      part.push_back(cosine);
    } else {
      continue;
    }
    const ir::Expression g(std::move(part));
    if (g.is_constant()) continue;
    std::vector<double> values(static_cast<std::size_t>(samples) + 1);
    double largest = 0.0;
    for (int i = 0; i <= samples; ++i) {
      values[static_cast<std::size_t>(i)] = g.evaluate(length * i / samples);
      if (std::isfinite(values[static_cast<std::size_t>(i)]))
        largest = std::max(largest, std::abs(values[static_cast<std::size_t>(i)]));
    }
    for (int i = 0; i < samples; ++i) {
      double a = length * i / samples, b = length * (i + 1) / samples;
      double ga = values[static_cast<std::size_t>(i)], gb = values[static_cast<std::size_t>(i) + 1];
      if (!(ga * gb < 0.0)) continue;  // no sign change (a zero at a sample is the sampling's to find)
      for (int k = 0; k < 200 && b - a > 0.0; ++k) {
        const double m = 0.5 * (a + b);
        if (m <= a || m >= b) break;  // adjacent doubles
        const double gm = g.evaluate(m);
        if (gm == 0.0 || !std::isfinite(gm)) {
          a = b = m;
          ga = gb = gm;
          break;
        }
        if ((gm < 0.0) == (ga < 0.0)) {
          a = m;
          ga = gm;
        } else {
          b = m;
          gb = gm;
        }
      }
      const bool vanishes = !(std::min(std::abs(ga), std::abs(gb)) > 1e-9 * largest);
      const double at = std::abs(ga) <= std::abs(gb) ? a : b;
      if (vanishes && (!exponent || exponent->evaluate(at) < 0.0)) return std::make_pair(static_cast<int>(j), at);
    }
  }
  return std::nullopt;
}

}  // namespace

void ModelParser::parse_profile(const MapView& beam_view, Beam& beam) const {
  BeamProfile& profile = beam.profile;
  if (const Field* camber = beam_view.find("camber"))
    profile.camber_static = beam_view.choice(*camber, {"none", "static"}) == 1;
  const Field* field = beam_view.find("profile");
  if (field == nullptr) return;
  const MapView view = beam_view.sub(*field);
  profile.loc = field->value_loc;
  view.allow({"expression", "file", "psd", "class", "wavelengths", "seed"});
  const Field* expression = view.find("expression");
  const Field* file = view.find("file");
  const Field* psd = view.find("psd");
  const int forms = (expression != nullptr) + (file != nullptr) + (psd != nullptr);
  if (forms != 1)
    view.fail(view.loc(), view.prefixed("expected exactly one of expression, file or psd, got " +
                                        std::to_string(forms)));
  if (psd == nullptr)
    for (const char* key : {"class", "wavelengths", "seed"})
      if (const Field* extra = view.find(key))
        view.fail(extra->key_loc, view.prefixed(view.what(*extra) + " belongs to a psd profile; this one has " +
                                                (expression ? "an expression" : "a file")));
  if (expression != nullptr) {
    profile.kind = ProfileKind::kExpression;
    profile.expression = view.expression(*expression, "s");
    for (int i = 0; i <= kProfileChecks; ++i) {
      const double s = beam.length * i / kProfileChecks;
      if (const auto fault = profile.expression.fault_at(s)) {
        const SourceLoc where = profile.expression.nodes()[static_cast<std::size_t>(fault->node)].loc;
        view.fail(where, ir::describe_fault(profile.expression, *fault, s) + "; expected a finite offset on the beam's [0, " +
                             format_number(beam.length) + "] m");
      }
    }
    if (const auto pole = find_pole(profile.expression, beam.length, kProfileChecks)) {
      const ir::ExpressionNode& node = profile.expression.nodes()[static_cast<std::size_t>(pole->first)];
      const std::string what = node.kind == ir::ExpressionNode::Kind::kDivide  ? "a division by a part that is 0"
                               : node.kind == ir::ExpressionNode::Kind::kPower ? "a negative power of a part that is 0"
                                                                               : "a tan whose cosine is 0";
      view.fail(node.loc, view.prefixed(view.what(*expression) + " \"" + shown(profile.expression.source().text) +
                                        "\" has a pole at s = " + format_number(pole->second) + " m: " + what +
                                        " there; expected a finite offset on the beam's [0, " +
                                        format_number(beam.length) + "] m"));
    }
    return;
  }
  if (file != nullptr) {
    profile.kind = ProfileKind::kTable;
    profile.table_file = view.text(*file);
    std::filesystem::path path(profile.table_file);
    if (path.is_relative()) path = std::filesystem::path(file_).parent_path() / path;
    const std::string opened = path.lexically_normal().string();
    // Read whole and bounded: a device, or a sparse file of gigabytes that
    // takes no disk space, is refused before it is read.
    const CappedRead table = read_capped_file(opened, limits_.max_table_bytes, FileKinds::kRegularOnly);
    if (table.fault == ReadFault::kTooLarge)
      view.fail(file->value_loc,
                view.prefixed(view.what(*file) + ": \"" + shown(profile.table_file) + "\" (" + shown(opened) + "): " +
                              table.why + " (ParseLimits::max_table_bytes, about " +
                              std::to_string(limits_.max_table_bytes / kTableRowBytes / 1000000) +
                              " million rows); expected a table of s and offset"));
    if (!table) {
      std::string why = table.why;
      if (why.rfind("cannot read: ", 0) == 0) why.erase(0, 13);
      view.fail(file->value_loc, view.prefixed(view.what(*file) + ": cannot read \"" + shown(profile.table_file) +
                                               "\" (looked for " + shown(opened) + ", relative to the model file): " +
                                               why + "; expected a CSV file with columns s and offset"));
    }
    if (const auto problem = find_non_text(table.text))
      view.fail(file->value_loc,
                view.prefixed(view.what(*file) + ": \"" + shown(profile.table_file) + "\" is not a CSV table: " +
                              problem->message + " at " + shown(opened) + ":" + std::to_string(problem->loc.line) +
                              ":" + std::to_string(problem->loc.column) + "; expected text with columns s and offset"));
    read_profile_table(table.text, opened, profile.table_s, profile.table_offset);
    profile.table_path = opened;
    if (profile.table_s.front() > 0.0 || profile.table_s.back() < beam.length)
      view.fail(file->value_loc,
                view.prefixed(view.what(*file) + ": \"" + shown(profile.table_file) + "\" covers s in [" +
                              format_number(profile.table_s.front()) + ", " + format_number(profile.table_s.back()) +
                              "] m; expected it to cover the beam's [0, " + format_number(beam.length) + "] m"));
    return;
  }
  profile.kind = ProfileKind::kSpectrum;
  profile.spectrum = view.choice(*psd, {"fra", "german"}) == 0 ? TrackSpectrum::kFra : TrackSpectrum::kGerman;
  const Field& track_class = view.require("class");
  if (profile.spectrum == TrackSpectrum::kFra) {
    const long long k = view.whole_number(track_class);
    if (k < 1 || k > 6)
      view.fail(track_class.value_loc,
                view.prefixed(view.what(track_class) + ": the FRA spectrum has track classes 1 to 6, got " + shown(track_class.value.Scalar())));
    profile.spectrum_class = static_cast<int>(k);
  } else {
    profile.spectrum_class = view.choice(track_class, {"low", "high"});
  }
  const Field& wavelengths = view.require("wavelengths");
  const std::vector<double> band = view.numbers(wavelengths, 2, "[shortest, longest] (m)");
  if (!(band[0] > 0.0 && band[1] > band[0]))
    view.fail(wavelengths.value_loc, view.prefixed(view.what(wavelengths) + ": expected [shortest, longest] with 0 < shortest < "
                                                   "longest (m), got [" + format_number(band[0]) + ", " +
                                                   format_number(band[1]) + "]"));
  profile.wavelength_min = band[0];
  profile.wavelength_max = band[1];
  const double terms = std::max(200.0, 4.0 * beam.length / band[0]) * (32.0 * beam.length / band[0]);
  if (terms > kMaxHarmonicTerms)
    view.fail(wavelengths.value_loc,
              view.prefixed(view.what(wavelengths) + ": a " + format_number(beam.length) + " m beam with wavelengths down to " +
                            format_number(band[0]) + " m needs " + format_number(terms) +
                            " harmonic evaluations (at most " + format_number(kMaxHarmonicTerms) +
                            "); expected a longer shortest wavelength or a shorter beam"));
  if (const Field* seed = view.find("seed")) {
    const long long value = view.whole_number(*seed);
    if (value < 0) view.fail(seed->value_loc, view.prefixed(view.what(*seed) + ": expected a whole number >= 0, got " + shown(seed->value.Scalar())));
    profile.seed = static_cast<std::uint64_t>(value);
  }
}

}  // namespace mbfe::frontend
