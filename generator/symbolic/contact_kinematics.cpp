#include "generator/symbolic/contact_kinematics.h"

#include <cmath>

namespace mbfe::gen {

namespace {

using GiNaC::ex;

// Ground-frame position of a body-frame point as one expression in q (no
// intermediates), so that it can be differentiated: absolute angle = sum of
// the revolute coordinates on the path; origins by the joint conventions.
void point_expression(const ir::Model& model, const std::vector<GiNaC::symbol>& q, int body,
                      const ir::Vec2& local, ex& x, ex& y) {
  std::vector<int> path;
  for (int b = body; b >= 0; b = model.bodies[b].parent) path.insert(path.begin(), b);
  ex ox = 0, oy = 0, angle = 0;
  for (int b : path) {
    const ir::Joint& joint = model.bodies[b].joint;
    ex ax = exact(joint.at[0]), ay = exact(joint.at[1]);
    if (joint.type == ir::JointType::kPrismatic) {
      ax += q[b] * exact(joint.axis[0]);
      ay += q[b] * exact(joint.axis[1]);
    }
    const ex c = GiNaC::cos(angle), s = GiNaC::sin(angle);
    ox += c * ax - s * ay;
    oy += s * ax + c * ay;
    if (joint.type == ir::JointType::kRevolute) angle += q[b];
  }
  const ex c = GiNaC::cos(angle), s = GiNaC::sin(angle);
  x = ox + c * exact(local[0]) - s * exact(local[1]);
  y = oy + s * exact(local[0]) + c * exact(local[1]);
}

// The Hermite cubics on an element of length le at xi in [0, 1].
std::vector<ex> hermite(const ex& xi, const ex& le) {
  const ex xi2 = xi * xi, xi3 = xi2 * xi;
  return {1 - 3 * xi2 + 2 * xi3, le * (xi - 2 * xi2 + xi3), 3 * xi2 - 2 * xi3, le * (xi3 - xi2)};
}

// Sum over a kernel's inputs of d(expr)/d(input) * rate.
ex time_derivative(const ex& expr, const ContactSymbols& sym) {
  ex result = 0;
  for (std::size_t k = 0; k < sym.q.size(); ++k) result += expr.diff(sym.q[k]) * sym.qd[k];
  for (std::size_t l = 0; l < sym.qe.size(); ++l) result += expr.diff(sym.qe[l]) * sym.qed[l];
  return result;
}

std::string index(const std::string& array, std::size_t i) { return array + "[" + std::to_string(i) + "]"; }

}  // namespace

std::vector<ContactKernels> derive_contacts(const ir::Model& model, const ContactSymbols& sym,
                                            CodeList& code) {
  std::vector<ContactKernels> out;
  const std::size_t nq = sym.q.size();
  for (std::size_t c = 0; c < model.contacts.size(); ++c) {
    const ir::Contact& contact = model.contacts[c];
    const ir::Beam& beam = model.beams[contact.beam];
    const ir::Body& body = model.bodies[contact.body];
    ex px, py;
    point_expression(model, sym.q, contact.body, body.points[contact.point].position, px, py);
    // Beam frame: the axis direction (ca, sa) is a constant of the model.
    const ex ca = exact(std::cos(beam.angle)), sa = exact(std::sin(beam.angle));
    const ex dx = px - exact(beam.origin[0]), dy = py - exact(beam.origin[1]);
    const ex x_p = ca * dx + sa * dy;
    const ex y_p = -sa * dx + ca * dy;

    const bool slider = contact.type != ir::ContactType::kPin;
    const ex s = slider ? x_p : ex(exact(contact.at));
    const std::vector<ex> n = hermite((s - sym.s0) / sym.le, sym.le);
    ex w = 0;
    for (int l = 0; l < 4; ++l) w += n[l] * sym.qe[l];
    std::vector<ex> phi = slider ? std::vector<ex>{w - y_p} : std::vector<ex>{exact(contact.at) - x_p, w - y_p};

    ContactKernels k;
    k.name = contact.name;
    k.type = static_cast<int>(contact.type);  // the ABI's numbering: pin 0, slider_pin 1, slider_spring 2
    k.beam = contact.beam;
    k.at = contact.at;
    k.rows = static_cast<int>(phi.size());
    const std::string prefix = "contact_" + std::to_string(c) + "_";
    k.position = {prefix + "position", "const double* q, double* s",
                  "Contact '" + contact.name + "': position along the beam (m).", {}, {{"s[0]", code.define(s)}}};
    k.phi = {prefix + "phi", "const double* q, const double* qe, double s0, double le, double* Phi",
             "Contact '" + contact.name + "': constraint values Phi (m).", {}, {}};
    k.jacobians = {prefix + "jacobians",
                   "const double* q, const double* qe, double s0, double le, double* Jb, double* Je",
                   "Contact '" + contact.name + "': Jb = dPhi/dq (rows x nq), Je = dPhi/dqe (rows x 4).", {}, {}};
    k.gamma = {prefix + "gamma",
               "const double* q, const double* qd, const double* qe, const double* qed, double s0, double le, "
               "double* gamma",
               "Contact '" + contact.name + "': gamma = -(dJ/dt) [q'; qe'] (m/s^2).", {}, {}};
    for (std::size_t r = 0; r < phi.size(); ++r) {
      k.phi.outputs.push_back({index("Phi", r), code.define(phi[r])});
      ex rate = 0;  // Phi' = J [q'; qe']
      for (std::size_t j = 0; j < nq; ++j) {
        const ex jb = phi[r].diff(sym.q[j]);
        k.jacobians.outputs.push_back({index("Jb", r * nq + j), code.define(jb)});
        rate += jb * sym.qd[j];
      }
      for (std::size_t l = 0; l < 4; ++l) {
        const ex je = phi[r].diff(sym.qe[l]);
        k.jacobians.outputs.push_back({index("Je", r * 4 + l), code.define(je)});
        rate += je * sym.qed[l];
      }
      // Phi'' = J [q''; qe''] + d(Phi')/d[q; qe] . [q'; qe'] with the rates held fixed.
      k.gamma.outputs.push_back({index("gamma", r), code.define(-time_derivative(rate, sym))});
    }
    for (Kernel* kernel : {&k.position, &k.phi, &k.jacobians, &k.gamma})
      kernel->statements = code.closure(kernel->outputs);
    out.push_back(std::move(k));
  }
  return out;
}

}  // namespace mbfe::gen
