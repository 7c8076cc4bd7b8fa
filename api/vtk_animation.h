// `mbfe simulate --vtk DIR`: the run as an animation ParaView opens directly
// (docs/animation.md): DIR/<model>.pvd, a collection of VTK XML PolyData
// frames DIR/frames/frame_<k>.vtp, each with
//   - every beam as a polyline of its deformed axis (the Hermite
//     interpolation, 4 segments per element, the deflection times --vtk-scale),
//   - every body as a polyline through its named points (closed from three on),
//   - every contact as a vertex at its point with the force on the body as a
//     vector (N): from the multipliers of a pin or slider_pin, the force of a
//     slider_spring,
// point data `w` (the beam's deflection, unscaled, m) and `contact_force`,
// cell data `part` (the index of the beam, then of the body, then of the contact).
#pragma once

#include <string>
#include <vector>

#include "api/mbfe.h"

namespace mbfe {

/// Frames an animation may have: each is a file (a few kB for a small model,
/// megabytes for a large one); 10,000 frames at 25 per second is nearly 7
/// minutes of film.
constexpr int kMaxVtkFrames = 10000;

class VtkAnimation : public runtime::SimulationObserver {
 public:
  /// @param frames at most this many frames, evenly spaced in time over [0, t_end].
  VtkAnimation(const Model& model, std::string dir, double scale, int frames, double t_end);

  void begin(const runtime::OutputLayout& layout) override;
  void row(const runtime::OutputRow& row) override;
  /// Writes the collection file (also done every few frames, so that a run cut
  /// short leaves a collection of every frame written).
  void finish();
  int frames_written() const { return static_cast<int>(times_.size()); }

 private:
  void write_frame(const runtime::OutputRow& row, const std::string& path) const;

  const Model& model_;
  std::string dir_;
  double scale_;
  double interval_;
  double next_ = 0.0;
  /// The beam's slope w'(s) at s in this row's state (0 off the beam).
  double slope_at(const runtime::OutputRow& row, std::size_t beam, double s) const;

  std::vector<std::vector<int>> force_columns_;  // per contact: its lambda or force columns
  std::vector<double> times_;
  std::vector<std::string> files_;
};

}  // namespace mbfe
