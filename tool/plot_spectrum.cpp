#include "tool/plot_spectrum.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <sstream>
#include <vector>

#include "tool/plot_gnuplot.h"

namespace mbfe::tool {

int draw_spectrum_plot(const SpectrumPlot& plot, const std::string& png_path) {
  const auto gnuplot = find_gnuplot();
  if (!gnuplot) {
    std::cerr << "mbfe modal: --plot: " << gnuplot_missing_message() << "\n";
    return 2;
  }
  // Axis ranges: -Re spans decades (0.4 .. 1.3e8 for the paper beam), Im a
  // few 1e4: log x, linear y.
  double re_min = INFINITY, re_max = 0.0, im_max = 0.0;
  for (const auto& s : plot.series)
    for (const auto& l : s.eigenvalues) {
      if (-l.real() > 0.0) {
        re_min = std::min(re_min, -l.real());
        re_max = std::max(re_max, -l.real());
      }
      im_max = std::max(im_max, std::abs(l.imag()));
    }
  const double h = plot.step;
  if (h > 0.0) re_max = std::max(re_max, 2.0 / h);
  if (!std::isfinite(re_min)) re_min = 1e-1;  // nothing damped: a frame around the marked line
  if (!(re_max > re_min)) re_max = re_min * 1e3;
  const double x_lo = std::pow(10.0, std::floor(std::log10(re_min)) - 0.3);
  const double x_hi = std::pow(10.0, std::ceil(std::log10(re_max)) + 0.3);
  double y_hi = std::max(im_max, h > 0.0 ? 1.0 / h : 0.0) * 1.15;
  if (y_hi <= 0.0) y_hi = 1.0;

  std::ostringstream s;
  s.precision(17);
  s << "set terminal pngcairo size 1100,700 enhanced font 'sans,10'\n"
    << "set output " << gnuplot_quote(png_path) << "\n"
    << "set title "
    << gnuplot_quote(plot.title + (h > 0.0 ? ": state eigenvalues and forward Euler's stability region"
                                            : ": state eigenvalues (forward Euler has no stable step)"))
    << " noenhanced\n"
    << "set logscale x\nset format x '10^{%T}'\nset grid\n"
    << "set xlabel '-Re({/Symbol l}) [1/s]  (log scale)'\nset ylabel 'Im({/Symbol l}) [1/s]'\n"
    << "set xrange [" << x_lo << ":" << x_hi << "]\nset yrange [" << -y_hi << ":" << y_hi << "]\n"
    << "set key top left box opaque noenhanced\n"
    << "set parametric\nset trange [1e-6:" << 2.0 * M_PI - 1e-6 << "]\nset samples 2000\n";
  // Inline data blocks, one per series: the damped eigenvalues, and apart
  // those with Re >= 0 (undamped modes, or growth away from equilibrium),
  // which a log axis of -Re cannot hold: drawn on the left edge, marked.
  // A series with no point gets no block and no plot clause (gnuplot warns
  // of an empty one on the terminal).
  std::vector<int> damped(plot.series.size(), 0), on_edge(plot.series.size(), 0);
  const double edge_x = x_lo * std::pow(10.0, 0.12);  // just inside the frame
  for (std::size_t i = 0; i < plot.series.size(); ++i) {
    std::ostringstream d, e;
    d.precision(17);
    e.precision(17);
    for (const auto& l : plot.series[i].eigenvalues) {
      if (-l.real() > 0.0) {
        d << -l.real() << " " << l.imag() << "\n";
        ++damped[i];
      } else {
        e << edge_x << " " << l.imag() << "\n";
        ++on_edge[i];
      }
    }
    if (damped[i] > 0) s << "$s" << i << " << EOD\n" << d.str() << "EOD\n";
    if (on_edge[i] > 0) s << "$e" << i << " << EOD\n" << e.str() << "EOD\n";
  }
  bool any_edge = false;
  for (int c : on_edge) any_edge = any_edge || c > 0;
  if (any_edge)
    s << "set arrow from " << edge_x << "," << -y_hi << " to " << edge_x << "," << y_hi
      << " nohead lw 2 dt 2 lc rgb '#ff7f0e' back\n";
  const char* styles[] = {"pt 7 ps 1.0 lc rgb '#1f77b4'", "pt 9 ps 1.2 lc rgb '#d62728'", "pt 5 ps 0.9 lc rgb '#2ca02c'",
                          "pt 11 ps 1.0 lc rgb '#9467bd'"};
  s << "plot ";
  bool first = true;
  if (h > 0.0) {
    // |1 + h lambda| = 1: lambda = (e^{it} - 1) / h, i.e. -Re = (1 - cos t)/h, Im = sin t / h.
    char label[128];
    std::snprintf(label, sizeof label, "forward Euler stable region, h = %.4g s (-Re < 2/h = %.4g)", h, 2.0 / h);
    s << "(1 - cos(t)) / " << h << ", sin(t) / " << h << " with filledcurves closed fc rgb '#dddddd' fs transparent solid 0.6 title "
      << gnuplot_quote(label) << ", (1 - cos(t)) / " << h << ", sin(t) / " << h << " with lines lw 2 lc rgb '#555555' notitle";
    first = false;
  }
  for (std::size_t i = 0; i < plot.series.size(); ++i) {
    if (damped[i] > 0) {
      s << (first ? "" : ", ") << "$s" << i << " using 1:2 with points " << styles[i % 4] << " title "
        << gnuplot_quote(plot.series[i].label + " (" + std::to_string(damped[i]) + ")");
      first = false;
    }
    if (on_edge[i] > 0) {
      // Open diamonds on the dashed orange line, whatever the series' marker.
      s << (first ? "" : ", ") << "$e" << i << " using 1:2 with points pt 12 ps 2.0 lw 2 lc rgb '#ff7f0e' title "
        << gnuplot_quote(plot.series[i].label + ", Re >= 0 (undamped, or growth away from equilibrium), on the dashed line (" +
                         std::to_string(on_edge[i]) + ")");
      first = false;
    }
  }
  if (first) s << "0, 0 with dots notitle";  // nothing to draw: an empty frame, not a gnuplot error
  s << "\n";
  const int status = run_gnuplot(*gnuplot, s.str());
  if (status != 0) {
    std::cerr << "mbfe modal: --plot: gnuplot " << (status < 0 ? "could not be started" : "failed") << "\n";
    return 1;
  }
  std::cerr << "mbfe modal: wrote " << png_path << "\n";
  return 0;
}

}  // namespace mbfe::tool
