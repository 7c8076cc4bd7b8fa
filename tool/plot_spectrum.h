// `mbfe modal --plot`: eigenvalues in the complex plane with forward Euler's
// stability region for a step H: the picture that explains the method.
#pragma once

#include <complex>
#include <string>
#include <vector>

namespace mbfe::tool {

struct SpectrumPlot {
  struct Series {
    std::string label;
    std::vector<std::complex<double>> eigenvalues;
  };
  std::string title;
  std::vector<Series> series;
  double step = 0.0;  // s: forward Euler's region |1 + h lambda| <= 1 is drawn for it
};

/// Draws -Re(lambda) on a log axis against Im(lambda) (linear), every series
/// in its own colour, and the boundary of forward Euler's stability disk for
/// `step`. Prints its own messages. @return 0, 2 (gnuplot missing) or 1.
int draw_spectrum_plot(const SpectrumPlot& plot, const std::string& png_path);

}  // namespace mbfe::tool
