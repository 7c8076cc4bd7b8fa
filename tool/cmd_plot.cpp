// `mbfe plot results.csv -o out.png [--columns a,b] [--x COLUMN] [--title T]`:
// columns of a simulation CSV drawn by gnuplot, one panel per kind of quantity,
// axes labelled with their units.
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "tool/cli_args.h"
#include "tool/commands.h"
#include "tool/file_checks.h"
#include "tool/plot_columns.h"
#include "tool/plot_gnuplot.h"
#include "tool/results_columns.h"

namespace mbfe::tool {

namespace {

constexpr const char* kHelp = R"(Usage: mbfe plot RESULTS.csv -o OUT.png [--columns NAME,...] [--x NAME] [--title TEXT]

Draws columns of a CSV written by `mbfe simulate` into a PNG, with gnuplot
(Debian: gnuplot-nox): one panel per kind of quantity (displacements, angles,
forces, ...), each axis labelled with its unit. Units come from RESULTS.csv.json,
which mbfe simulate writes beside the CSV, or else from the column names.

Options:
  -o, --out OUT.png   the picture to write (required)
  --columns A,B,...   the columns to draw (default: every column after the
                      first, at most 8; a beam CSV has one per coordinate, so
                      name the ones you want, or simulate with --probe)
  --x NAME            the column on the horizontal axis (default: the first, t),
                      e.g. a vehicle's position
  --title TEXT        title of the plot (default: the CSV's file name)

Exit status: 0 drawn; 2 bad input (a missing or unreadable CSV, a .npy, an
unknown column, -o into a missing folder, onto a folder or onto the CSV
itself) or gnuplot missing; 1 gnuplot failed.

Example:
  mbfe simulate models/paper_beam.yaml --integrator forward_euler --step 1.4e-5 --t-end 1 \
      --probe beam1@0.5 --out midspan.csv
  mbfe plot midspan.csv -o midspan.png
  mbfe simulate models/bridge_moving_mass.yaml --probe deck@10 --out crossing.csv
  mbfe plot crossing.csv -o crossing.png --x carriage --columns deflection_tyre,force_tyre
)";

constexpr std::size_t kDefaultColumns = 8;

std::vector<std::string> split(const std::string& text, char sep) {
  std::vector<std::string> out;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, sep)) {
    if (!item.empty() && item.back() == '\r') item.pop_back();
    out.push_back(item);
  }
  return out;
}

}  // namespace

int cmd_plot(const Args& raw) {
  Args args;
  for (const std::string& a : raw) args.push_back(a == "-o" ? "--out" : a);
  const ParsedArgs parsed(args, {"out", "columns", "title", "x"}, {"help"});
  if (parsed.has("help")) {
    std::cout << kHelp;
    return 0;
  }
  if (parsed.positional().size() != 1)
    throw UsageError("expected one RESULTS.csv, got " + std::to_string(parsed.positional().size()) +
                     " arguments (see --help)");
  const auto out = parsed.value("out");
  if (!out || out->empty()) throw UsageError("-o OUT.png is required");
  const std::string& csv = parsed.positional()[0];
  if (csv.size() >= 4 && csv.compare(csv.size() - 4, 4, ".npy") == 0)
    throw UsageError(csv + ": mbfe plot draws a CSV (gnuplot reads its rows); write one with mbfe simulate --out "
                           "FILE.csv (mbfe stats reads a .npy)");
  // The picture must not land on the CSV it draws, or on its sidecar, and
  // must have a folder to go into: bad input, before gnuplot starts.
  check_output_file(*out, "-o", {csv, csv + ".json"});
  bool has_rows = false;
  const std::vector<std::string> header = read_csv_header(csv, has_rows);
  if (header.size() < 2 || !has_rows)
    throw UsageError(csv + ": expected a header line with at least two columns and one data row");
  auto index_of = [&](const std::string& name, const char* flag) {
    std::size_t i = 0;
    while (i < header.size() && header[i] != name) ++i;
    if (i == header.size()) {
      std::string some;
      for (std::size_t k = 1; k < header.size() && k <= 6; ++k) some += (k > 1 ? ", " : "") + header[k];
      throw UsageError(std::string(flag) + ": no column '" + name + "' in " + csv + " (it has " +
                       std::to_string(header.size()) + " columns: " + some + (header.size() > 7 ? ", ..." : "") + ")");
    }
    return i;
  };
  const std::size_t x = parsed.value("x") ? index_of(*parsed.value("x"), "--x") : 0;
  std::vector<std::size_t> chosen;  // 0-based column indices
  if (const auto cols = parsed.value("columns")) {
    for (const std::string& name : split(*cols, ',')) chosen.push_back(index_of(name, "--columns"));
  } else {
    for (std::size_t i = 1; i < header.size() && chosen.size() < kDefaultColumns; ++i)
      if (i != x) chosen.push_back(i);
    if (header.size() - 1 > kDefaultColumns)
      std::cerr << "mbfe plot: drawing the first " << kDefaultColumns << " of " << header.size() - 1
                << " columns; choose with --columns\n";
  }
  const std::map<std::string, std::string> sidecar = sidecar_units(csv);
  std::vector<std::string> units;
  for (const std::string& h : header) units.push_back(column_unit(h, sidecar));
  const std::vector<std::vector<std::size_t>> panels = panels_by_unit(chosen, units);
  auto axis_label = [&](const std::vector<std::size_t>& cols) {
    const std::string& unit = units[cols.front()];
    std::string label = cols.size() == 1 ? header[cols.front()] : quantity_of(unit);
    return unit.empty() ? label : label + " [" + unit + "]";
  };

  const auto gnuplot = find_gnuplot();
  if (!gnuplot) {
    std::cerr << "mbfe plot: " << gnuplot_missing_message() << "\n";
    return 2;
  }
  // One panel per unit, stacked, sharing the horizontal axis; the CSV's
  // header line gives gnuplot the column names (`every ::1` skips it).
  const int height = 300 + 260 * static_cast<int>(panels.size());
  std::ostringstream s;
  s << "set terminal pngcairo size 1000," << height << " enhanced font 'sans,10'\n"
    << "set output " << gnuplot_quote(*out) << "\n"
    << "set datafile separator ','\n"
    << "set grid\nset key outside right noenhanced\nset format y '%g'\n"
    << "set lmargin at screen 0.09\nset rmargin at screen 0.80\n"  // panels aligned whatever their keys
    << "set multiplot layout " << panels.size() << ",1 title " << gnuplot_quote(parsed.value("title").value_or(csv))
    << " noenhanced\n";
  const std::string x_label = units[x].empty() ? header[x] : header[x] + " [" + units[x] + "]";
  for (std::size_t p = 0; p < panels.size(); ++p) {
    s << "set ylabel " << gnuplot_quote(axis_label(panels[p])) << " noenhanced\n"
      << "set xlabel " << gnuplot_quote(p + 1 == panels.size() ? x_label : "") << " noenhanced\n"
      << "plot ";
    for (std::size_t k = 0; k < panels[p].size(); ++k) {
      const std::size_t c = panels[p][k];
      s << (k ? ", " : "") << gnuplot_quote(csv) << " every ::1 using " << x + 1 << ":" << c + 1
        << " with lines lw 1.5 title " << gnuplot_quote(header[c]);
    }
    s << "\n";
  }
  s << "unset multiplot\n";
  const int status = run_gnuplot(*gnuplot, s.str());
  if (status != 0) {
    std::cerr << "mbfe plot: gnuplot " << (status < 0 ? "could not be started" : "failed (exit status " +
                                                                                  std::to_string(status) + ")")
              << "\n";
    return 1;
  }
  std::cerr << "mbfe plot: wrote " << *out << "\n";
  return 0;
}

}  // namespace mbfe::tool
