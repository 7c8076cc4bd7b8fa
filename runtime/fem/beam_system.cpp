// Sparse assembly of one beam: element matrices -> M, K, C, P with the
// support-fixed DOFs removed (contract order: nodes s = 0 .. L, [w, w']).
#include "runtime/fem/beam_system.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "ir/beam_nodes.h"
#include "runtime/errors/invalid_input.h"
#include "runtime/fem/beam_element.h"
#include "runtime/fem/hermite_shape.h"
#include "runtime/fem/running_surface.h"

namespace mbfe::runtime {

namespace {

std::string beam_error(const ir::Beam& beam, const std::string& message) {
  return "beam '" + beam.name + "': " + message;
}

}  // namespace

int node_at(const ir::Beam& beam, double s, const char* what) {
  const double L = beam.length;
  const double slack = ir::kNodeTolerance * L;
  if (!(s >= -slack && s <= L + slack)) {
    std::ostringstream os;
    os.precision(17);
    os << what << " at " << s << " m is outside the beam [0, " << L << "]";
    throw std::invalid_argument(beam_error(beam, os.str()));
  }
  const ir::NodeOnBeam node = ir::node_on_beam(L, beam.elements, s);
  if (!node.on_node) {
    std::ostringstream os;
    os.precision(17);
    os << what << " at " << s << " m is not at a node (nodes every " << node.spacing << " m; nearest "
       << node.nearest * node.spacing << " m)";
    throw std::invalid_argument(beam_error(beam, os.str()));
  }
  return static_cast<int>(node.nearest);
}

BeamSystem assemble_beam(const ir::Beam& beam, const ir::Vec2& gravity) {
  const std::unique_ptr<BeamElement> element = make_beam_element(beam);
  const int ne = beam.elements;
  const int nd = element->node_dofs();
  const int nn = ne + 1;
  const int n_full = nd * nn;

  BeamSystem sys;
  sys.name = beam.name;
  sys.num_nodes = nn;
  sys.length = beam.length;
  sys.element_length = beam.length / ne;
  sys.rayleigh_alpha = beam.rayleigh_alpha;
  sys.rayleigh_beta = beam.rayleigh_beta;

  // Supports: pinned fixes w, clamped fixes w and w'.
  std::vector<char> fixed(n_full, 0);
  for (const ir::Support& sup : beam.supports) {
    const int node = sup.node >= 0 ? sup.node : node_at(beam, sup.at, "support");
    if (node < 0 || node >= nn) {
      throw std::invalid_argument(beam_error(beam, "support node " + std::to_string(node) +
                                                       " is outside 0.." + std::to_string(ne)));
    }
    if (sup.type == ir::SupportType::kSpring) continue;  // elastic: added to K, C, M below
    fixed[nd * node] = 1;
    if (sup.type == ir::SupportType::kClamped) fixed[nd * node + 1] = 1;
  }
  sys.full_to_free.assign(n_full, -1);
  for (int i = 0; i < n_full; ++i) {
    if (!fixed[i]) {
      sys.full_to_free[i] = static_cast<int>(sys.free_dof.size());
      sys.free_dof.push_back(i);
    }
  }
  const int n = static_cast<int>(sys.free_dof.size());
  if (n == 0)
    throw InvalidInput("beam '" + beam.name + "': its supports hold every node (" + std::to_string(n_full) +
                       " degrees of freedom, none free), so it cannot move; give it more elements or fewer supports");

  // Full-length load vector first; restricted to the free DOFs below.
  Eigen::VectorXd p_full = Eigen::VectorXd::Zero(n_full);
  const double nx = -std::sin(beam.angle);
  const double ny = std::cos(beam.angle);
  const double q_weight = beam.density * beam.area * (gravity[0] * nx + gravity[1] * ny);

  // Uniform beam: one element matrix serves every element.
  const Eigen::MatrixXd ke = element->stiffness();
  const Eigen::MatrixXd me = element->mass();
  const Eigen::VectorXd pe = element->uniform_load(q_weight);
  const int ed = 2 * nd;

  std::vector<Eigen::Triplet<double>> tk, tm;
  tk.reserve(static_cast<size_t>(ne) * ed * ed);
  tm.reserve(static_cast<size_t>(ne) * ed * ed);
  for (int e = 0; e < ne; ++e) {
    const int base = nd * e;
    for (int a = 0; a < ed; ++a) {
      p_full[base + a] += pe[a];
      const int ra = sys.full_to_free[base + a];
      if (ra < 0) continue;
      for (int b = 0; b < ed; ++b) {
        const int cb = sys.full_to_free[base + b];
        if (cb < 0) continue;
        if (ke(a, b) != 0.0) tk.emplace_back(ra, cb, ke(a, b));
        if (me(a, b) != 0.0) tm.emplace_back(ra, cb, me(a, b));
      }
    }
  }
  std::vector<TimedNodalLoad> timed_full;  // free_index holds the full DOF until the supports are known
  for (const ir::BeamPointLoad& load : beam.loads) {
    const int node = load.node >= 0 ? load.node : node_at(beam, load.at, "point load");
    if (node < 0 || node >= nn) {
      throw std::invalid_argument(beam_error(beam, "point load node " + std::to_string(node) +
                                                       " is outside 0.." + std::to_string(ne)));
    }
    if (load.value.is_constant() && load.window.always()) {
      p_full[nd * node] += load.value.evaluate(0.0);
    } else {
      timed_full.push_back({nd * node, load.value, load.window});
    }
  }
  sys.moving_loads = beam.moving_loads;

  sys.K.resize(n, n);
  sys.M.resize(n, n);
  sys.K.setFromTriplets(tk.begin(), tk.end());
  sys.M.setFromTriplets(tm.begin(), tm.end());
  // Rayleigh damping is the beam's own (its elements, tension included); the
  // discrete parts below (spring supports, their dampers and masses, point
  // masses) add to K, C and M as they are.
  sys.C = beam.rayleigh_alpha * sys.M + beam.rayleigh_beta * sys.K;
  std::vector<Eigen::Triplet<double>> dk, dc, dm;
  std::vector<Eigen::Triplet<double>> spring_rows;  // sqrt(k) on w: rows of the stiffness factor
  // The weight of a lumped mass on w: m (g . n), n the beam's normal.
  const double g_normal = gravity[0] * nx + gravity[1] * ny;
  for (const ir::Support& sup : beam.supports) {
    if (sup.type != ir::SupportType::kSpring) continue;
    const int support_node = sup.node >= 0 ? sup.node : node_at(beam, sup.at, "support");
    p_full[nd * support_node] += sup.mass * g_normal;
    const int w = sys.full_to_free[nd * support_node];
    if (w < 0) continue;
    if (sup.stiffness != 0.0) dk.emplace_back(w, w, sup.stiffness);
    if (sup.damping != 0.0) dc.emplace_back(w, w, sup.damping);
    if (sup.mass != 0.0) dm.emplace_back(w, w, sup.mass);
    if (sup.stiffness > 0.0) spring_rows.emplace_back(static_cast<int>(spring_rows.size()), w, std::sqrt(sup.stiffness));
  }
  for (const ir::BeamPointMass& pm : beam.masses) {
    const int node = pm.node >= 0 ? pm.node : node_at(beam, pm.at, "point mass");
    if (node < 0 || node >= nn) {
      throw std::invalid_argument(beam_error(beam, "point mass node " + std::to_string(node) +
                                                       " is outside 0.." + std::to_string(ne)));
    }
    p_full[nd * node] += pm.mass * g_normal;
    const int w = sys.full_to_free[nd * node];
    if (w >= 0) dm.emplace_back(w, w, pm.mass);  // else: the support carries it
  }
  auto add = [n](Eigen::SparseMatrix<double>& A, const std::vector<Eigen::Triplet<double>>& t) {
    if (t.empty()) return;
    Eigen::SparseMatrix<double> D(n, n);
    D.setFromTriplets(t.begin(), t.end());
    A += D;
  };
  add(sys.K, dk);
  add(sys.C, dc);
  add(sys.M, dm);
  {
    std::map<int, double> remainder;
    for (const auto& t : dc) remainder[t.row()] += t.value();
    for (const auto& t : dm) remainder[t.row()] -= beam.rayleigh_alpha * t.value();
    for (const auto& t : dk) remainder[t.row()] -= beam.rayleigh_beta * t.value();
    for (const auto& [dof, value] : remainder)
      if (value != 0.0) sys.damping_remainder.emplace_back(dof, value);
  }
  sys.K.makeCompressed();
  sys.M.makeCompressed();
  sys.C.makeCompressed();
  // The stiffness factor, element rows stacked (free columns only).
  const Eigen::MatrixXd fe = element->stiffness_factor();
  if (fe.size() > 0) {
    const int fr = static_cast<int>(fe.rows());
    std::vector<Eigen::Triplet<double>> tf;
    tf.reserve(static_cast<size_t>(ne) * fr * ed);
    for (int e = 0; e < ne; ++e) {
      for (int r = 0; r < fr; ++r) {
        for (int b = 0; b < ed; ++b) {
          const int cb = sys.full_to_free[nd * e + b];
          if (cb >= 0 && fe(r, b) != 0.0) tf.emplace_back(fr * e + r, cb, fe(r, b));
        }
      }
    }
    // Spring supports: one row sqrt(k) on their w each, after the elements'.
    for (const Eigen::Triplet<double>& r : spring_rows) tf.emplace_back(fr * ne + r.row(), r.col(), r.value());
    sys.stiffness_factor.resize(static_cast<Eigen::Index>(fr) * ne + static_cast<Eigen::Index>(spring_rows.size()), n);
    sys.stiffness_factor.setFromTriplets(tf.begin(), tf.end());
    sys.stiffness_factor.makeCompressed();
  }
  sys.P.resize(n);
  for (int k = 0; k < n; ++k) sys.P[k] = p_full[sys.free_dof[k]];
  for (TimedNodalLoad& load : timed_full) {
    load.free_index = sys.full_to_free[load.free_index];
    if (load.free_index >= 0) sys.timed_loads.push_back(std::move(load));  // else: the support carries it
  }
  if (std::optional<RunningSurface> surface = running_surface(beam, gravity))
    sys.surface = std::make_shared<const RunningSurface>(std::move(*surface));
  return sys;
}

BeamPoint locate_on_beam(const BeamSystem& beam, double s) {
  const double L = beam.length;
  if (!(s >= -1e-12 * L && s <= L * (1.0 + 1e-12))) {
    std::ostringstream os;
    os.precision(17);
    os << "beam '" << beam.name << "': position " << s << " m is outside [0, " << L << "]";
    throw std::invalid_argument(os.str());
  }
  const int ne = beam.num_nodes - 1;
  const double le = beam.element_length;
  BeamPoint p;
  p.element = std::clamp(static_cast<int>(std::floor(s / le)), 0, ne - 1);
  p.xi = std::clamp((s - p.element * le) / le, 0.0, 1.0);
  return p;
}

BeamPointWeights point_weights(const BeamSystem& beam, double s) {
  const BeamPoint p = locate_on_beam(beam, s);
  const double le = beam.element_length;
  BeamPointWeights out;
  out.w = hermite::N(p.xi, le).transpose();
  out.dw_ds = hermite::dN_ds(p.xi, le).transpose();
  out.d2w_ds2 = hermite::d2N_ds2(p.xi, le).transpose();
  for (int a = 0; a < 4; ++a) out.free_index[a] = beam.full_to_free[2 * p.element + a];
  return out;
}

double deflection_at(const BeamSystem& beam, const Eigen::VectorXd& q, double s) {
  if (q.size() != static_cast<Eigen::Index>(beam.free_dof.size())) {
    throw std::invalid_argument("beam '" + beam.name + "': q has " + std::to_string(q.size()) +
                                " entries, expected " + std::to_string(beam.free_dof.size()) +
                                " (free DOFs in contract order)");
  }
  const BeamPointWeights wts = point_weights(beam, s);
  double w = 0.0;
  for (int a = 0; a < 4; ++a) {
    if (wts.free_index[a] >= 0) w += wts.w[a] * q[wts.free_index[a]];
  }
  return w;
}

}  // namespace mbfe::runtime
