// Published spectra of vertical track irregularity and a random profile drawn
// from one by a seeded sum of harmonics (docs/profiles.md gives the formulas,
// their parameters and their sources).
//
// Convention: S(Omega) is one-sided in the angular spatial frequency
// Omega = 2 pi / wavelength (rad/m), in m^2 / (rad/m), so that the variance of
// the profile over a band is the integral of S over Omega in that band.
#pragma once

#include <cstdint>
#include <vector>

#include "ir/model.h"

namespace mbfe::runtime {

/// One-sided PSD S(Omega) of `spectrum` (m^2/(rad/m)) at Omega (rad/m, > 0).
/// `track_class`: FRA 1..6; German 0 (low disturbance) or 1 (high).
/// @throws std::invalid_argument on a class the spectrum does not have.
double track_psd(ir::TrackSpectrum spectrum, int track_class, double omega);

/// A profile r(s) = sum_k amplitude[k] cos(omega[k] s + phase[k]) (m).
struct HarmonicProfile {
  std::vector<double> omega;      // rad/m
  std::vector<double> amplitude;  // m
  std::vector<double> phase;      // rad
  /// r(s), r'(s), r''(s) at s (m): the sum, evaluated directly.
  void evaluate(double s, double& r, double& dr, double& ddr) const;
};

/// The profile of `spectrum` over the wavelengths [wavelength_min,
/// wavelength_max] (m): the band of Omega is cut into n equal cells, n chosen
/// so that a cell is at most 2 pi / (4 length) wide (the profile does not
/// repeat over `length`, m) and n >= 200; harmonic k sits at a point drawn
/// uniformly in its cell, with amplitude sqrt(2 S(Omega_k) dOmega) (its
/// variance is S dOmega) and a phase drawn uniformly in [0, 2 pi). The draws
/// come from a 64-bit Mersenne twister seeded with `seed`, turned into
/// doubles by hand so that a seed gives the same profile on every platform.
/// @throws std::invalid_argument unless 0 < wavelength_min < wavelength_max
/// and length > 0, or on a bad class.
HarmonicProfile spectrum_profile(ir::TrackSpectrum spectrum, int track_class, double wavelength_min,
                                 double wavelength_max, double length, std::uint64_t seed);

}  // namespace mbfe::runtime
