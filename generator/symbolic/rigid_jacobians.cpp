#include "generator/symbolic/rigid_jacobians.h"

#include <string>

#include "generator/symbolic/forward_derivatives.h"

namespace mbfe::gen {

using GiNaC::ex;

namespace {

/// The value of output `target` of `kernel` (0 if it has none).
ex output_value(const Kernel& kernel, const std::string& target) {
  for (const KernelOutput& o : kernel.outputs)
    if (o.target == target) return o.value;
  return 0;
}

}  // namespace

Kernel derive_dynamics_jacobians(const ir::Model& model, RigidDerivation& d, const std::vector<GiNaC::symbol>& qdd) {
  const int n = static_cast<int>(model.bodies.size());
  CodeList& code = d.code;
  const AncestorPairAssembly& assembly = *d.mass_matrix.assembly;
  // (M a)_j = sum over k of M_jk a_k, with M_jk = S_j . U_k when j is k or an
  // ancestor of k, S_k . U_j when k is an ancestor of j, and 0 otherwise.
  auto entry = [&](int j, int k) {
    ex sum = 0;
    for (int c = 0; c < assembly.width; ++c) {
      const std::string jc = "[" + std::to_string(j) + "][" + std::to_string(c) + "]";
      const std::string kc = "[" + std::to_string(k) + "][" + std::to_string(c) + "]";
      sum += output_value(d.mass_matrix, assembly.left + jc) * output_value(d.mass_matrix, assembly.right + kc);
    }
    return sum;
  };
  auto is_ancestor_or_self = [&](int j, int k) {
    for (int b = k; b >= 0; b = assembly.parent[b])
      if (b == j) return true;
    return false;
  };
  std::vector<ex> tau(n);
  for (int j = 0; j < n; ++j) {
    ex ma = 0;
    for (int k = 0; k < n; ++k) {
      if (is_ancestor_or_self(j, k)) ma += entry(j, k) * qdd[k];
      else if (is_ancestor_or_self(k, j)) ma += entry(k, j) * qdd[k];
    }
    const ex f = output_value(d.inertial_forces, "F[" + std::to_string(j) + "]");
    const ex q = output_value(d.generalized_forces, "Q[" + std::to_string(j) + "]");
    tau[j] = code.define(ma + f - q);
  }
  Kernel k{"dynamics_jacobians", "const double* q, const double* qd, const double* qdd, double t, double* K, double* C",
           "Tangents of tau = M(q) qdd + F - Q: K = d tau / dq, C = d tau / dqd, row-major nq x nq.",
           {}, {}};
  std::vector<GiNaC::symbol> variables(d.q.begin(), d.q.end());
  variables.insert(variables.end(), d.qd.begin(), d.qd.end());
  ForwardDerivatives derivatives(code, variables);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      k.outputs.push_back({"K[" + std::to_string(i * n + j) + "]", derivatives.derivative(tau[i], j)});
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      k.outputs.push_back({"C[" + std::to_string(i * n + j) + "]", derivatives.derivative(tau[i], n + j)});
  k.statements = code.closure(k.outputs);
  return k;
}

}  // namespace mbfe::gen
