#include "runtime/signal/butterworth.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <stdexcept>
#include <string>

namespace mbfe::runtime {

namespace {

using cplx = std::complex<double>;

/// Coefficients of prod (z - r_k), highest power first, real parts (the roots
/// come in conjugate pairs).
std::vector<double> poly(const std::vector<cplx>& roots) {
  std::vector<cplx> c{1.0};
  for (const cplx& r : roots) {
    std::vector<cplx> next(c.size() + 1, 0.0);
    for (std::size_t i = 0; i < c.size(); ++i) {
      next[i] += c[i];
      next[i + 1] -= r * c[i];
    }
    c = std::move(next);
  }
  std::vector<double> out(c.size());
  for (std::size_t i = 0; i < c.size(); ++i) out[i] = c[i].real();
  return out;
}

/// Direct form II transposed, as scipy.signal.lfilter: y[n] = b0 x[n] + z0,
/// z_i = b_{i+1} x[n] - a_{i+1} y[n] + z_{i+1}. `z` is the state (len - 1).
void lfilter(const IirFilter& f, std::vector<double>& x, std::vector<double> z) {
  const std::size_t n = f.a.size();
  for (double& v : x) {
    const double in = v;
    const double out = f.b[0] * in + (n > 1 ? z[0] : 0.0);
    for (std::size_t i = 0; i + 1 < n; ++i)
      z[i] = f.b[i + 1] * in - f.a[i + 1] * out + (i + 2 < n ? z[i + 1] : 0.0);
    v = out;
  }
}

/// The state that a constant input of 1 keeps constant (scipy.signal.lfilter_zi):
/// with y = sum(b) / sum(a), z_i = sum_{k > i} (b_k - a_k y).
std::vector<double> steady_state(const IirFilter& f) {
  double sb = 0.0, sa = 0.0;
  for (double v : f.b) sb += v;
  for (double v : f.a) sa += v;
  const double y = sb / sa;
  std::vector<double> z(f.a.size() - 1, 0.0);
  double acc = 0.0;
  for (std::size_t i = f.a.size() - 1; i >= 1; --i) {
    acc += f.b[i] - f.a[i] * y;
    z[i - 1] = acc;
  }
  return z;
}

}  // namespace

IirFilter butterworth_lowpass(int order, double cutoff_hz, double sample_hz) {
  if (order < 1 || order > 8) throw std::invalid_argument("Butterworth order must be 1..8, got " + std::to_string(order));
  const double nyquist = 0.5 * sample_hz;
  if (!(cutoff_hz > 0.0) || !(cutoff_hz < nyquist)) {
    throw std::invalid_argument("low-pass cutoff " + std::to_string(cutoff_hz) +
                                " Hz must be above 0 and below half the sample rate (" + std::to_string(nyquist) +
                                " Hz)");
  }
  // scipy.signal.butter: the analog prototype's poles on the left half of the
  // unit circle, scaled to the pre-warped cutoff (fs = 2 in normalised units).
  const double wn = cutoff_hz / nyquist;
  const double fs = 2.0;
  const double warped = 2.0 * fs * std::tan(M_PI * wn / fs);
  std::vector<cplx> poles;
  for (int k = -order + 1; k < order; k += 2) poles.push_back(-std::exp(cplx(0.0, M_PI * k / (2.0 * order))));
  double gain = 1.0;
  for (cplx& p : poles) {
    p *= warped;
    gain *= warped;
  }
  // Bilinear transform: z = (2 fs + s) / (2 fs - s); the zeros at infinity go to -1.
  const double fs2 = 2.0 * fs;
  cplx denominator = 1.0;
  for (cplx& p : poles) {
    denominator *= fs2 - p;
    p = (fs2 + p) / (fs2 - p);
  }
  gain *= (1.0 / denominator).real();
  IirFilter f;
  f.b = poly(std::vector<cplx>(static_cast<std::size_t>(order), -1.0));
  for (double& v : f.b) v *= gain;
  f.a = poly(poles);
  return f;
}

std::vector<double> filtfilt(const IirFilter& f, const std::vector<double>& x) {
  const std::size_t pad = 3 * std::max(f.a.size(), f.b.size());
  if (x.size() <= pad) {
    throw std::invalid_argument("the signal has " + std::to_string(x.size()) + " samples; the filter needs more than " +
                                std::to_string(pad));
  }
  // Odd extension: 2 x[0] - x[pad..1], x, 2 x[n-1] - x[n-2..n-1-pad].
  const std::size_t n = x.size();
  std::vector<double> ext;
  ext.reserve(n + 2 * pad);
  for (std::size_t i = pad; i >= 1; --i) ext.push_back(2.0 * x[0] - x[i]);
  ext.insert(ext.end(), x.begin(), x.end());
  for (std::size_t i = 1; i <= pad; ++i) ext.push_back(2.0 * x[n - 1] - x[n - 1 - i]);
  const std::vector<double> zi = steady_state(f);
  auto scaled = [&](double s) {
    std::vector<double> z = zi;
    for (double& v : z) v *= s;
    return z;
  };
  lfilter(f, ext, scaled(ext.front()));
  std::reverse(ext.begin(), ext.end());
  lfilter(f, ext, scaled(ext.front()));
  std::reverse(ext.begin(), ext.end());
  return std::vector<double>(ext.begin() + static_cast<std::ptrdiff_t>(pad), ext.end() - static_cast<std::ptrdiff_t>(pad));
}

}  // namespace mbfe::runtime
