#include "ir/model.h"

#include <algorithm>

namespace mbfe::ir {

int position_count(JointType type) {
  switch (type) {
    case JointType::kSpherical: return 4;
    case JointType::kFree: return 7;
    default: return 1;
  }
}

int velocity_count(JointType type) {
  switch (type) {
    case JointType::kSpherical: return 3;
    case JointType::kFree: return 6;
    default: return 1;
  }
}

int loop_rows(LoopType type, int dimension) {
  if (dimension != 3) return 2;  // the plane: a point, or a slide and an angle
  return type == LoopType::kPoint ? 3 : 5;
}

std::vector<std::string> data_files(const Model& model) {
  std::vector<std::string> files;
  for (const Beam& beam : model.beams) {
    const std::string& path = beam.profile.table_path;
    if (beam.profile.kind == ProfileKind::kTable && !path.empty() &&
        std::find(files.begin(), files.end(), path) == files.end())
      files.push_back(path);
  }
  return files;
}

}  // namespace mbfe::ir
