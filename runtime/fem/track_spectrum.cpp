#include "runtime/fem/track_spectrum.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>
#include <string>

namespace mbfe::runtime {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr int kMinHarmonics = 200;

// FRA vertical profile (docs/profiles.md): S = A_v Omega_c^2 / (Omega^2 (Omega^2 + Omega_c^2)),
// A_v in cm^2 rad/m per class 1..6, Omega_c = 0.8245 rad/m.
constexpr double kFraAv[6] = {1.2107, 1.0181, 0.6816, 0.5376, 0.2095, 0.0339};
constexpr double kFraOmegaC = 0.8245;
constexpr double kCm2 = 1e-4;  // m^2 per cm^2

// German high-speed track spectra: S = A_v Omega_c^2 / ((Omega^2 + Omega_r^2) (Omega^2 + Omega_c^2)),
// A_v in m^2 rad/m: low disturbance 4.032e-7, high disturbance 1.080e-6.
constexpr double kGermanAv[2] = {4.032e-7, 1.080e-6};
constexpr double kGermanOmegaC = 0.8246;
constexpr double kGermanOmegaR = 0.0206;

/// A double uniform in [0, 1) from the top 53 bits of one draw.
double unit_draw(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

}  // namespace

double track_psd(ir::TrackSpectrum spectrum, int track_class, double omega) {
  const double o2 = omega * omega;
  if (spectrum == ir::TrackSpectrum::kFra) {
    if (track_class < 1 || track_class > 6)
      throw std::invalid_argument("FRA track class " + std::to_string(track_class) + ": expected 1 to 6");
    const double c2 = kFraOmegaC * kFraOmegaC;
    return kCm2 * kFraAv[track_class - 1] * c2 / (o2 * (o2 + c2));
  }
  if (track_class < 0 || track_class > 1)
    throw std::invalid_argument("German track spectrum class " + std::to_string(track_class) +
                                ": expected 0 (low disturbance) or 1 (high)");
  const double c2 = kGermanOmegaC * kGermanOmegaC;
  return kGermanAv[track_class] * c2 / ((o2 + kGermanOmegaR * kGermanOmegaR) * (o2 + c2));
}

void HarmonicProfile::evaluate(double s, double& r, double& dr, double& ddr) const {
  r = dr = ddr = 0.0;
  for (std::size_t k = 0; k < omega.size(); ++k) {
    const double x = omega[k] * s + phase[k];
    const double a = amplitude[k];
    const double c = std::cos(x), sn = std::sin(x);
    r += a * c;
    dr -= a * omega[k] * sn;
    ddr -= a * omega[k] * omega[k] * c;
  }
}

HarmonicProfile spectrum_profile(ir::TrackSpectrum spectrum, int track_class, double wavelength_min,
                                 double wavelength_max, double length, std::uint64_t seed) {
  if (!(wavelength_min > 0.0 && wavelength_max > wavelength_min && std::isfinite(wavelength_max)))
    throw std::invalid_argument("track spectrum: wavelengths [" + std::to_string(wavelength_min) + ", " +
                                std::to_string(wavelength_max) + "] m; expected 0 < min < max");
  if (!(length > 0.0)) throw std::invalid_argument("track spectrum: the length must be > 0");
  track_psd(spectrum, track_class, 1.0);  // refuses a bad class
  const double lo = 2.0 * kPi / wavelength_max, hi = 2.0 * kPi / wavelength_min;
  const double widest = 2.0 * kPi / (4.0 * length);
  const int n = std::max(kMinHarmonics, static_cast<int>(std::ceil((hi - lo) / widest)));
  const double cell = (hi - lo) / n;
  std::mt19937_64 rng(seed);
  HarmonicProfile out;
  out.omega.resize(n);
  out.amplitude.resize(n);
  out.phase.resize(n);
  for (int k = 0; k < n; ++k) {
    out.omega[k] = lo + (k + unit_draw(rng)) * cell;
    out.phase[k] = 2.0 * kPi * unit_draw(rng);
    out.amplitude[k] = std::sqrt(2.0 * track_psd(spectrum, track_class, out.omega[k]) * cell);
  }
  return out;
}

}  // namespace mbfe::runtime
