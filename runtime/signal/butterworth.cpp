#include "runtime/signal/butterworth.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <sstream>
#include <stdexcept>

namespace mbfe::runtime {

namespace {

using cplx = std::complex<double>;

bool is_real(cplx v) { return v.imag() == 0.0; }

/// Index of the pole closest to the unit circle, the first on a tie (numpy's argmin).
std::size_t worst(const std::vector<cplx>& p, const std::vector<std::size_t>& among) {
  std::size_t best = among.front();
  for (std::size_t i : among)
    if (std::abs(1.0 - std::abs(p[i])) < std::abs(1.0 - std::abs(p[best]))) best = i;
  return best;
}

std::vector<std::size_t> all_of(const std::vector<cplx>& v) {
  std::vector<std::size_t> out(v.size());
  for (std::size_t i = 0; i < v.size(); ++i) out[i] = i;
  return out;
}

enum class Which { kAny, kReal, kComplex };

/// The entry of `from` nearest to `to` of the kind asked (scipy's
/// _nearest_real_complex_idx: a stable sort by distance, the first that fits).
std::size_t nearest(const std::vector<cplx>& from, cplx to, Which which) {
  std::vector<std::size_t> order = all_of(from);
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return std::abs(from[a] - to) < std::abs(from[b] - to); });
  for (std::size_t i : order)
    if (which == Which::kAny || (which == Which::kReal) == is_real(from[i])) return i;
  throw std::logic_error("Butterworth design: no zero of the kind asked is left");
}

cplx take(std::vector<cplx>& v, std::size_t i) {
  const cplx out = v[i];
  v.erase(v.begin() + static_cast<std::ptrdiff_t>(i));
  return out;
}

/// The section with zeros z1, z2 and poles p1, p2 (a complex root stands for
/// its conjugate pair too): b = poly(zeros), a = poly(poles).
Biquad section(cplx z1, cplx z2, cplx p1, cplx p2) {
  auto poly = [](cplx r1, cplx r2, double* out) {
    out[0] = 1.0;
    if (!is_real(r1) && r2 == std::conj(r1)) {
      out[1] = -2.0 * r1.real();
      out[2] = r1.real() * r1.real() + r1.imag() * r1.imag();
    } else {
      out[1] = -(r1.real() + r2.real());
      out[2] = r1.real() * r2.real();
    }
  };
  Biquad s{};
  poly(z1, z2, s.data());
  poly(p1, p2, s.data() + 3);
  return s;
}

/// scipy.signal.zpk2sos with pairing 'nearest' for a digital filter whose
/// zeros are real (as many as poles) and whose complex poles are given once
/// (upper half plane):
/// the poles closest to the unit circle go into the last section.
SosFilter pair_into_sections(std::vector<cplx> z, std::vector<cplx> p, double k) {
  const std::size_t order = z.size();  // as many zeros as poles, counting both of a pair
  const std::size_t n_sections = (order + 1) / 2;
  if (order % 2 == 1) {
    p.push_back(0.0);
    z.push_back(0.0);
  }
  // Conjugate pairs first (by real part, then |imag|), then the real poles in
  // ascending order: numpy's order after _cplxreal.
  auto by_real_then_imag = [](cplx a, cplx b) {
    return a.real() != b.real() ? a.real() < b.real() : std::abs(a.imag()) < std::abs(b.imag());
  };
  std::vector<cplx> pc, pr;
  for (cplx v : p) (is_real(v) ? pr : pc).push_back(v);
  std::sort(pc.begin(), pc.end(), by_real_then_imag);
  std::sort(pr.begin(), pr.end(), by_real_then_imag);
  p = pc;
  p.insert(p.end(), pr.begin(), pr.end());
  std::sort(z.begin(), z.end(), by_real_then_imag);

  SosFilter f;
  f.sections.resize(n_sections);
  for (std::size_t si = n_sections; si-- > 0;) {
    const cplx p1 = take(p, worst(p, all_of(p)));
    std::vector<std::size_t> real_poles;
    for (std::size_t i = 0; i < p.size(); ++i)
      if (is_real(p[i])) real_poles.push_back(i);
    std::size_t real_zeros = 0;
    for (cplx v : z) real_zeros += is_real(v) ? 1 : 0;
    if (is_real(p1) && real_poles.empty()) {
      // The last real pole: with the nearest real zero and a pole and zero at 0.
      const cplx z1 = take(z, nearest(z, p1, Which::kReal));
      f.sections[si] = section(z1, 0.0, p1, 0.0);
    } else if (p.size() + 1 == z.size() && !is_real(p1) && real_poles.size() == 1 && real_zeros == 1) {
      const cplx z1 = take(z, nearest(z, p1, Which::kComplex));
      f.sections[si] = section(z1, std::conj(z1), p1, std::conj(p1));
    } else {
      const cplx p2 = is_real(p1) ? take(p, worst(p, real_poles)) : std::conj(p1);
      const cplx z1 = take(z, nearest(z, p1, Which::kAny));
      if (!is_real(z1)) {
        f.sections[si] = section(z1, std::conj(z1), p1, p2);
      } else {
        const cplx z2 = take(z, nearest(z, p1, Which::kReal));
        f.sections[si] = section(z1, z2, p1, p2);
      }
    }
  }
  for (int i = 0; i < 3; ++i) f.sections.front()[static_cast<std::size_t>(i)] *= k;
  return f;
}

/// The state of one section that a constant input of 1 keeps constant
/// (scipy.signal.lfilter_zi): (I - A^T) z = b[1:] - a[1:] b0, solved.
std::array<double, 2> steady_state(const Biquad& s) {
  const double r0 = s[1] - s[4] * s[0];
  const double r1 = s[2] - s[5] * s[0];
  const double z0 = (r0 + r1) / (1.0 + s[4] + s[5]);
  return {z0, r1 - s[5] * z0};
}

/// The cascade over x in place, from the states `z` (2 per section):
/// direct form II transposed, as scipy.signal.sosfilt.
void sosfilt(const SosFilter& f, std::vector<double>& x, std::vector<std::array<double, 2>> z) {
  for (double& v : x) {
    double in = v;
    for (std::size_t s = 0; s < f.sections.size(); ++s) {
      const Biquad& c = f.sections[s];
      const double out = c[0] * in + z[s][0];
      z[s][0] = c[1] * in - c[4] * out + z[s][1];
      z[s][1] = c[2] * in - c[5] * out;
      in = out;
    }
    v = in;
  }
}

}  // namespace

SosFilter butterworth_lowpass(int order, double cutoff_hz, double sample_hz) {
  if (order < 1 || order > 8) throw std::invalid_argument("Butterworth order must be 1..8, got " + std::to_string(order));
  const double nyquist = 0.5 * sample_hz;
  if (!(cutoff_hz >= kMinCutoffFraction * sample_hz) || !(cutoff_hz < nyquist)) {
    std::ostringstream os;
    os << "low-pass cut-off " << cutoff_hz << " Hz must be at least " << kMinCutoffFraction
       << " of the sample rate and below half of it (" << kMinCutoffFraction * sample_hz << " to " << nyquist
       << " Hz for samples at " << sample_hz << " Hz)";
    throw std::invalid_argument(os.str());
  }
  // scipy.signal.buttap: the analog prototype's poles on the left half of the
  // unit circle; lp2lp_zpk: scaled to the pre-warped cut-off (fs = 2 in
  // normalised units), the gain by warped^order.
  const double wn = cutoff_hz / nyquist;
  const double fs = 2.0;
  const double warped = 2.0 * fs * std::tan(M_PI * wn / fs);
  std::vector<cplx> analog;
  for (int m = -order + 1; m < order; m += 2) analog.push_back(-std::exp(cplx(0.0, M_PI * m / (2.0 * order))));
  for (cplx& p : analog) p *= warped;
  double gain = std::pow(warped, order);
  // bilinear_zpk: z = (2 fs + s) / (2 fs - s); the zeros at infinity go to -1.
  const double fs2 = 2.0 * fs;
  cplx denominator = 1.0;
  std::vector<cplx> poles;
  for (const cplx& p : analog) {
    denominator *= fs2 - p;
    const cplx digital = (fs2 + p) / (fs2 - p);
    if (digital.imag() >= 0.0) poles.push_back(digital);  // one of each conjugate pair, and the real pole
  }
  gain *= (1.0 / denominator).real();
  return pair_into_sections(std::vector<cplx>(static_cast<std::size_t>(order), -1.0), poles, gain);
}

std::size_t sosfiltfilt_padding(const SosFilter& f) {
  std::size_t b2_zero = 0, a2_zero = 0;
  for (const Biquad& s : f.sections) {
    b2_zero += s[2] == 0.0 ? 1 : 0;
    a2_zero += s[5] == 0.0 ? 1 : 0;
  }
  return 3 * (2 * f.sections.size() + 1 - std::min(b2_zero, a2_zero));
}

std::vector<double> sosfiltfilt(const SosFilter& f, const std::vector<double>& x) {
  const std::size_t pad = sosfiltfilt_padding(f);
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
  // scipy.signal.sosfilt_zi: each section's steady state times the gain at
  // 0 Hz of the sections before it.
  std::vector<std::array<double, 2>> zi;
  double scale = 1.0;
  for (const Biquad& s : f.sections) {
    const std::array<double, 2> z = steady_state(s);
    zi.push_back({scale * z[0], scale * z[1]});
    scale *= (s[0] + s[1] + s[2]) / (s[3] + s[4] + s[5]);
  }
  auto scaled = [&](double v) {
    std::vector<std::array<double, 2>> z = zi;
    for (auto& s : z) s = {s[0] * v, s[1] * v};
    return z;
  };
  sosfilt(f, ext, scaled(ext.front()));
  std::reverse(ext.begin(), ext.end());
  sosfilt(f, ext, scaled(ext.front()));
  std::reverse(ext.begin(), ext.end());
  return std::vector<double>(ext.begin() + static_cast<std::ptrdiff_t>(pad), ext.end() - static_cast<std::ptrdiff_t>(pad));
}

}  // namespace mbfe::runtime
