#include "runtime/structure/beam_links.h"

#include <algorithm>
#include <cmath>

#include "runtime/fem/hermite_shape.h"

namespace mbfe::runtime {

namespace {

/// Adds sign N(s) on the element holding s to g (its free DOFs only).
void add_point(const BeamMesh& mesh, int offset, double s, double sign, BeamLinks::Gradient& g) {
  const int element = std::clamp(static_cast<int>(std::floor(s / mesh.element_length)), 0, mesh.num_elements - 1);
  const double xi = (s - element * mesh.element_length) / mesh.element_length;
  const hermite::Row4 n = hermite::N(xi, mesh.element_length);
  for (int j = 0; j < 4; ++j) {
    const int f = mesh.full_to_free[2 * element + j];
    if (f < 0 || n[j] == 0.0) continue;
    g.cols[g.size] = offset + f;
    g.values[g.size] = sign * n[j];
    ++g.size;
  }
}

}  // namespace

BeamLinks::Gradient link_gradient(const ir::Link& link, const std::vector<BeamMesh>& meshes,
                                  const std::vector<int>& offsets) {
  BeamLinks::Gradient g;
  add_point(meshes[link.a.beam], offsets[link.a.beam], link.a.at, -1.0, g);
  add_point(meshes[link.b.beam], offsets[link.b.beam], link.b.at, +1.0, g);
  return g;
}

BeamLinks::BeamLinks(const std::vector<ir::Link>& links, const std::vector<BeamMesh>& meshes,
                     const std::vector<int>& offsets) {
  for (const ir::Link& l : links) {
    End e;
    e.name = l.name;
    e.k = l.stiffness;
    e.c = l.damping;
    e.rest = l.rest;
    e.slack = l.slack;
    e.g = link_gradient(l, meshes, offsets);
    ends_.push_back(e);
  }
  states_.resize(ends_.size());
}

void BeamLinks::apply(const double* qc, const double* qcd, Eigen::Ref<Eigen::VectorXd> beam_force) {
  for (std::size_t k = 0; k < ends_.size(); ++k) {
    const End& e = ends_[k];
    LinkState& st = states_[k];
    double ext = -e.rest, rate = 0.0;
    for (int i = 0; i < e.g.size; ++i) {
      ext += e.g.values[i] * qc[e.g.cols[i]];
      rate += e.g.values[i] * qcd[e.g.cols[i]];
    }
    double t = e.k * ext + e.c * rate;
    st.extension = ext;
    st.rate = rate;
    st.slack = e.slack && t <= 0.0;
    if (st.slack) t = 0.0;
    st.tension = t;
    // Inside a joined structure, the force less the structure's part (see the header).
    const double f = e.inside ? t - e.k * (ext + e.rest) : t;
    if (f == 0.0) continue;
    for (int i = 0; i < e.g.size; ++i) beam_force[e.g.cols[i]] -= f * e.g.values[i];
  }
}

}  // namespace mbfe::runtime
