// The default width of spectrum slicing, apart from the slicing itself
// (modal_analysis.h) so that the options a caller fills in
// (runtime/damping/beam_analysis_options.h) need no eigensolver.
#pragma once

namespace mbfe::runtime {

/// Modes per Lanczos run of spectrum slicing. Narrow runs cost less per mode
/// found (a run's cost grows with the square of its width): 30 slices a
/// ten-span wire 1.8x faster than 100, and 20 no faster than 30
/// (bench/spectrum_slicing_bench.cpp).
inline constexpr int kDefaultSliceModes = 30;

}  // namespace mbfe::runtime
