#include "api/vtk_animation.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "runtime/fem/hermite_shape.h"
#include "runtime/multibody/spatial_poses.h"
#include "runtime/simulation/assembled_model.h"

namespace mbfe {

namespace fs = std::filesystem;

namespace {

constexpr int kSegmentsPerElement = 4;  // enough for a cubic to look smooth
constexpr int kCollectionEvery = 20;    // frames between rewrites of the .pvd

struct Geometry {
  std::vector<std::array<double, 3>> points;
  std::vector<double> w;                             // per point
  std::vector<std::array<double, 3>> force;          // per point
  std::vector<std::vector<int>> lines, verts;        // point indices
  std::vector<int> line_part, vert_part;
  std::vector<int> line_axis;  // per line: the axis (0 x, 1 y, 2 z) of a body's triad, -1 otherwise
};

// A spatial model's triads are this fraction of its largest body point distance long.
constexpr double kTriadShare = 0.25;
constexpr double kTriadDefault = 0.1;  // m, when no body has a point off its origin

template <class T>
void write_array(std::ostream& out, const char* type, const char* name, int components, const std::vector<T>& v) {
  out << "        <DataArray type=\"" << type << "\" Name=\"" << name << "\"";
  if (components > 1) out << " NumberOfComponents=\"" << components << "\"";
  out << " format=\"ascii\">\n         ";
  for (const T& x : v) out << ' ' << x;
  out << "\n        </DataArray>\n";
}

void write_cells(std::ostream& out, const char* tag, const std::vector<std::vector<int>>& cells) {
  std::vector<int> connectivity, offsets;
  for (const auto& c : cells) {
    connectivity.insert(connectivity.end(), c.begin(), c.end());
    offsets.push_back(static_cast<int>(connectivity.size()));
  }
  out << "      <" << tag << ">\n";
  write_array(out, "Int32", "connectivity", 1, connectivity);
  write_array(out, "Int32", "offsets", 1, offsets);
  out << "      </" << tag << ">\n";
}

}  // namespace

VtkAnimation::VtkAnimation(const Model& model, std::string dir, double scale, int frames, double t_end)
    : model_(model), dir_(std::move(dir)), scale_(scale), interval_(frames > 1 ? t_end / (frames - 1) : t_end) {
  fs::create_directories(fs::path(dir_) / "frames");
}

void VtkAnimation::begin(const runtime::OutputLayout& layout) {
  auto column = [&](const std::string& name) {
    for (std::size_t k = 0; k < layout.columns.size(); ++k)
      if (layout.columns[k] == name) return static_cast<int>(k);
    return -1;
  };
  for (const ir::Contact& c : model_.ir().contacts) {
    switch (c.type) {
      case ir::ContactType::kPin:
        force_columns_.push_back({column("lambda_" + c.name + "_1"), column("lambda_" + c.name + "_2")});
        break;
      case ir::ContactType::kSliderPin: force_columns_.push_back({column("lambda_" + c.name)}); break;
      case ir::ContactType::kSliderSpring: force_columns_.push_back({column("force_" + c.name)}); break;
    }
  }
}

double VtkAnimation::slope_at(const runtime::OutputRow& row, std::size_t beam, double s) const {
  const ir::Model& ir = model_.ir();
  // Geometry only: the beams' systems, the same in either assembly (Model::assembled_for).
  const runtime::BeamPart& bp = model_.assembled_for(false).beams().beams[beam];
  const double le = bp.system.element_length;
  if (!(s >= 0.0 && s <= bp.system.length)) return 0.0;  // off the beam: no force to tilt
  const int e = std::min(static_cast<int>(s / le), ir.beams[beam].elements - 1);
  Eigen::Vector4d qe;
  for (int a = 0; a < 4; ++a) {
    const int f = bp.system.full_to_free[2 * e + a];
    qe[a] = f >= 0 ? row.q[static_cast<Eigen::Index>(ir.bodies.size()) + bp.offset + f] : 0.0;
  }
  return runtime::hermite::dN_ds((s - e * le) / le, le) * qe;
}

void VtkAnimation::row(const runtime::OutputRow& row) {
  if (row.t + 1e-9 * interval_ < next_) return;
  // The next frame at the next multiple of the interval, not one interval
  // after this row: rows that do not fall on the multiples would otherwise
  // push every later frame a little further, and the last one short of t_end.
  next_ = (std::floor(row.t / interval_ + 1e-9) + 1.0) * interval_;
  char name[32];
  std::snprintf(name, sizeof name, "frame_%06d.vtp", frames_written());
  const std::string file = (fs::path("frames") / name).string();
  write_frame(row, (fs::path(dir_) / file).string());
  times_.push_back(row.t);
  files_.push_back(file);
  if (frames_written() % kCollectionEvery == 0) finish();
}

void VtkAnimation::finish() {
  std::ostringstream out;
  out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
      << "  <Collection>\n";
  out.precision(17);
  for (std::size_t k = 0; k < times_.size(); ++k)
    out << "    <DataSet timestep=\"" << times_[k] << "\" group=\"\" part=\"0\" file=\"" << files_[k] << "\"/>\n";
  out << "  </Collection>\n</VTKFile>\n";
  const fs::path path = fs::path(dir_) / (model_.ir().name + ".pvd");
  const fs::path tmp = path.string() + ".tmp";
  std::ofstream(tmp) << out.str();
  fs::rename(tmp, path);
}

void VtkAnimation::write_frame(const runtime::OutputRow& row, const std::string& path) const {
  const ir::Model& ir = model_.ir();
  const int nb = static_cast<int>(ir.bodies.size());
  Geometry g;
  int part = 0;
  // Beams: the deformed axis.
  if (!ir.beams.empty()) {
    const runtime::BeamModel& beams = model_.assembled_for(false).beams();
    for (std::size_t b = 0; b < ir.beams.size(); ++b) {
      const ir::Beam& beam = ir.beams[b];
      const runtime::BeamPart& bp = beams.beams[b];
      const double le = bp.system.element_length;
      const double ca = std::cos(beam.angle), sa = std::sin(beam.angle);
      std::vector<int> line;
      for (int e = 0; e < beam.elements; ++e) {
        Eigen::Vector4d qe;
        for (int a = 0; a < 4; ++a) {
          const int f = bp.system.full_to_free[2 * e + a];
          qe[a] = f >= 0 ? row.q[nb + bp.offset + f] : 0.0;
        }
        for (int k = (e == 0 ? 0 : 1); k <= kSegmentsPerElement; ++k) {
          const double xi = static_cast<double>(k) / kSegmentsPerElement;
          const double s = (e + xi) * le;
          const double w = runtime::hermite::N(xi, le) * qe;
          line.push_back(static_cast<int>(g.points.size()));
          g.points.push_back({beam.origin[0] + s * ca - scale_ * w * sa, beam.origin[1] + s * sa + scale_ * w * ca, 0.0});
          g.w.push_back(w);
          g.force.push_back({0.0, 0.0, 0.0});
        }
      }
      g.lines.push_back(line);
      g.line_part.push_back(part++);
      g.line_axis.push_back(-1);
    }
  }
  // Bodies: through their named points, in the ground frame.
  const mbfe_model_v1* solver = model_.solver();
  if (ir.dimension == 3 && solver) {
    // A spatial body: a polyline from its frame's origin through its points,
    // and its frame as a triad of three lines (cell data `axis`).
    const std::vector<runtime::BodyPose> poses = runtime::spatial_poses(ir, row.q.data());
    double reach = 0.0;
    for (const ir::Body& body : ir.bodies)
      for (const ir::NamedPoint& point : body.points)
        reach = std::max(reach, Eigen::Vector3d(point.position3[0], point.position3[1], point.position3[2]).norm());
    const double triad = reach > 0.0 ? kTriadShare * reach : kTriadDefault;
    auto add_point = [&](const Eigen::Vector3d& x) {
      g.points.push_back({x[0], x[1], x[2]});
      g.w.push_back(0.0);
      g.force.push_back({0.0, 0.0, 0.0});
      return static_cast<int>(g.points.size()) - 1;
    };
    for (int b = 0; b < nb; ++b) {
      const runtime::BodyPose& pose = poses[static_cast<std::size_t>(b)];
      std::vector<int> line{add_point(pose.origin)};
      for (const ir::NamedPoint& point : ir.bodies[b].points) {
        double xyz[3];
        solver->point_position3(row.q.data(), b, static_cast<int>(&point - ir.bodies[b].points.data()), xyz);
        line.push_back(add_point(Eigen::Vector3d(xyz[0], xyz[1], xyz[2])));
      }
      if (line.size() >= 2) {
        g.lines.push_back(line);
        g.line_part.push_back(part);
        g.line_axis.push_back(-1);
      } else {
        g.verts.push_back(line);
        g.vert_part.push_back(part);
      }
      ++part;
    }
    for (int b = 0; b < nb; ++b) {
      const runtime::BodyPose& pose = poses[static_cast<std::size_t>(b)];
      for (int axis = 0; axis < 3; ++axis) {
        g.lines.push_back({add_point(pose.origin), add_point(pose.origin + triad * pose.rotation.col(axis))});
        g.line_part.push_back(part);
        g.line_axis.push_back(axis);
      }
      ++part;
    }
  }
  for (int b = 0; b < nb && solver && ir.dimension != 3; ++b) {
    const auto& points = ir.bodies[b].points;
    if (!points.empty()) {
      std::vector<int> line;
      for (std::size_t p = 0; p < points.size(); ++p) {
        double xy[2];
        solver->point_position(row.q.data(), b, static_cast<int>(p), xy);
        line.push_back(static_cast<int>(g.points.size()));
        g.points.push_back({xy[0], xy[1], 0.0});
        g.w.push_back(0.0);
        g.force.push_back({0.0, 0.0, 0.0});
      }
      if (line.size() >= 3) line.push_back(line.front());
      if (line.size() >= 2) {
        g.lines.push_back(line);
        g.line_part.push_back(part);
        g.line_axis.push_back(-1);
      } else {
        g.verts.push_back(line);
        g.vert_part.push_back(part);
      }
    }
    ++part;
  }
  // Contacts: the force on the body at its point, f_P = -(dPhi/dr_P)^T lambda
  // (docs/contacts.md): a pin a lambda_1 + n lambda_2; a slider_pin
  // lambda (n - w'(s) a); a slider_spring N (n - w'(s) a), N its force.
  for (std::size_t c = 0; c < ir.contacts.size(); ++c) {
    const ir::Contact& contact = ir.contacts[c];
    const std::vector<int>& columns = force_columns_[c];
    if (!solver || columns.empty() || columns.front() < 0) continue;
    double xy[2];
    solver->point_position(row.q.data(), contact.body, contact.point, xy);
    const ir::Beam& beam = ir.beams[static_cast<std::size_t>(contact.beam)];
    const double ax = std::cos(beam.angle), ay = std::sin(beam.angle), nx = -ay, ny = ax;
    auto value = [&](int k) { return row.values[static_cast<std::size_t>(columns[static_cast<std::size_t>(k)])]; };
    double fx = 0.0, fy = 0.0;
    if (contact.type == ir::ContactType::kPin) {
      fx = ax * value(0) + nx * value(1);
      fy = ay * value(0) + ny * value(1);
    } else {
      const double s = (xy[0] - beam.origin[0]) * ax + (xy[1] - beam.origin[1]) * ay;
      const double slope = slope_at(row, static_cast<std::size_t>(contact.beam), s);
      fx = value(0) * (nx - slope * ax);
      fy = value(0) * (ny - slope * ay);
    }
    g.verts.push_back({static_cast<int>(g.points.size())});
    g.vert_part.push_back(part++);
    g.points.push_back({xy[0], xy[1], 0.0});
    g.w.push_back(0.0);
    g.force.push_back({fx, fy, 0.0});
  }

  std::ostringstream out;
  out.precision(17);
  out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"LittleEndian\">\n"
      << "  <PolyData>\n    <FieldData>\n"
      << "      <DataArray type=\"Float64\" Name=\"TIME\" NumberOfTuples=\"1\" format=\"ascii\"> " << row.t
      << " </DataArray>\n    </FieldData>\n"
      << "    <Piece NumberOfPoints=\"" << g.points.size() << "\" NumberOfVerts=\"" << g.verts.size()
      << "\" NumberOfLines=\"" << g.lines.size() << "\" NumberOfStrips=\"0\" NumberOfPolys=\"0\">\n"
      << "      <PointData Scalars=\"w\" Vectors=\"contact_force\">\n";
  std::vector<double> flat_force, flat_points;
  for (const auto& f : g.force) flat_force.insert(flat_force.end(), f.begin(), f.end());
  for (const auto& p : g.points) flat_points.insert(flat_points.end(), p.begin(), p.end());
  write_array(out, "Float64", "w", 1, g.w);
  write_array(out, "Float64", "contact_force", 3, flat_force);
  out << "      </PointData>\n      <CellData Scalars=\"part\">\n";
  std::vector<int> parts = g.vert_part;
  parts.insert(parts.end(), g.line_part.begin(), g.line_part.end());  // VTK orders cells: verts, then lines
  write_array(out, "Int32", "part", 1, parts);
  if (ir.dimension == 3) {
    std::vector<int> axes(g.verts.size(), -1);
    axes.insert(axes.end(), g.line_axis.begin(), g.line_axis.end());
    write_array(out, "Int32", "axis", 1, axes);
  }
  out << "      </CellData>\n      <Points>\n";
  write_array(out, "Float64", "position", 3, flat_points);
  out << "      </Points>\n";
  write_cells(out, "Verts", g.verts);
  write_cells(out, "Lines", g.lines);
  out << "    </Piece>\n  </PolyData>\n</VTKFile>\n";
  std::ofstream file(path);
  file << out.str();
  if (!file) throw std::runtime_error(path + ": cannot write");
}

}  // namespace mbfe
