#include "runtime/coupled/coupled_model.h"

#include <sstream>
#include <stdexcept>

#include "runtime/coupled/beam_load_force.h"
#include "runtime/coupled/discrete_damping_force.h"

namespace mbfe::runtime {

namespace {

std::vector<BeamMesh> meshes_of(const std::vector<CoupledBeam>& beams) {
  std::vector<BeamMesh> out;
  for (const CoupledBeam& b : beams) out.push_back(b.mesh);
  return out;
}

}  // namespace

CoupledModel::CoupledModel(const mbfe_model_v1& kernels, CoupledBeams beams, std::vector<BodyInertia> bodies,
                           const std::vector<ir::Link>& links, const std::vector<double>& link_rests,
                           const std::vector<ir::Contact>& contacts)
    : kernels_(kernels),
      beams_(std::move(beams.beams)),
      structures_(std::move(beams.structures)),
      bodies_(std::move(bodies)),
      constraints_(kernels, meshes_of(beams_)),
      driven_(kernels),
      nb_(kernels.num_coordinates),
      nc_(constraints_.num_beam_dofs()) {
  if (kernels.abi_version != MBFE_MODEL_ABI_VERSION) {
    throw std::invalid_argument("model '" + std::string(kernels.model_name) +
                                "' has another ABI version; regenerate it");
  }
  loads_.setZero(nc_);
  for (std::size_t k = 0; k < beams_.size(); ++k) {
    const CoupledBeam& b = beams_[k];
    const int n = b.mesh.num_free;
    const bool own = b.structure < 0;
    std::ostringstream problem;
    if (b.M.rows() != n || b.M.cols() != n || b.P.size() != n)
      problem << "M is " << b.M.rows() << " x " << b.M.cols() << " and P has " << b.P.size() << " entries";
    else if (own && n > 0 && (b.C.rows() != n || b.K.rows() != n))
      problem << "it has no C and K of its own (" << b.C.rows() << " and " << b.K.rows() << " rows)";
    else if (b.offset != constraints_.beam_offset(static_cast<int>(k)))
      problem << "its offset is " << b.offset << ", its place in q_c " << constraints_.beam_offset(static_cast<int>(k));
    else if (b.structure >= static_cast<int>(structures_.size()))
      problem << "it names structure " << b.structure << " of " << structures_.size();
    if (!problem.str().empty())
      throw std::invalid_argument("beam '" + b.mesh.name + "': " + problem.str() + "; expected " + std::to_string(n) +
                                  " free DOFs");
    // A beam that is an adjusted structure of its own on its M (base M, one
    // range, the same matrix) shares that structure's factorisation of it.
    std::shared_ptr<const Factor> shared;
    if (!own) {
      const LowRankStructure& st = *structures_[static_cast<std::size_t>(b.structure)];
      if (st.base() == LowRankStructure::Base::kMass && st.ranges().size() == 1 &&
          st.M().nonZeros() == b.M.nonZeros() && (st.M() - b.M).norm() == 0.0)
        shared = st.shared_base_factor();
    }
    if (shared) {
      mass_factors_.push_back(std::move(shared));
    } else {
      auto factor = std::make_shared<Factor>(b.M);
      if (factor->info() != Eigen::Success || (n > 0 && !(factor->vectorD().minCoeff() > 0.0))) {
        throw std::runtime_error("beam '" + b.mesh.name +
                                 "': mass matrix is not positive definite (a lumped mass "
                                 "matrix without rotary inertia cannot carry a contact)");
      }
      mass_factors_.push_back(std::move(factor));
    }
    loads_.segment(b.offset, n) = b.P;
  }
  // Each structure covers beams that name it, whole.
  for (std::size_t s = 0; s < structures_.size(); ++s) {
    for (const LowRankStructure::Range& r : structures_[s]->ranges()) {
      bool whole = false;
      for (const CoupledBeam& b : beams_)
        whole = whole || (b.offset == r.offset && b.mesh.num_free == r.size && b.structure == static_cast<int>(s));
      if (!whole)
        throw std::invalid_argument("adjusted structure '" + structures_[s]->name() + "': its range at " +
                                    std::to_string(r.offset) + " (" + std::to_string(r.size) +
                                    " DOFs) is not a beam that names it");
    }
  }
  if (!driven_.empty() && constraints_.num_rows() > 0) {
    throw std::invalid_argument("model '" + std::string(kernels.model_name) +
                                "': driven joints with pin or slider_pin contacts are not supported; "
                                "use slider_spring contacts with driven joints");
  }
  // The force elements, in the order their forces are summed: slider springs,
  // links, each beam's time loads, then the damping of adjusted beams'
  // discrete parts.
  const std::vector<BeamMesh> meshes = meshes_of(beams_);
  for (int c = 0; c < kernels.num_contacts; ++c) {
    if (kernels.contacts[c].type != 2) continue;
    const int beam = kernels.contacts[c].beam;
    SpringLaw law;
    if (c < static_cast<int>(contacts.size()) && contacts[c].law == ir::ContactLaw::kHertz)
      law = {true, contacts[c].coefficient};
    auto spring = std::make_unique<SliderSpringForce>(kernels, c, meshes[beam], constraints_.beam_offset(beam), law);
    springs_.push_back(spring.get());
    spring_elements_.push_back(static_cast<int>(forces_.size()));
    forces_.push_back(std::move(spring));
  }
  if (!link_rests.empty() && link_rests.size() != links.size())
    throw std::invalid_argument(std::to_string(link_rests.size()) + " link rest offsets for " +
                                std::to_string(links.size()) + " links");
  for (std::size_t l = 0; l < links.size(); ++l) {
    const ir::Link& link = links[l];
    // Inside a joined structure when both its beams are in the same one.
    const int sa = beams_[link.a.beam].structure, sb = beams_[link.b.beam].structure;
    const bool inside = sa >= 0 && sa == sb && structures_[sa]->ranges().size() > 1;
    auto force = std::make_unique<LinkForce>(link, link_rests.empty() ? link.rest : link_rests[l],
                                             link_gradient(link, meshes, constraints_.beam_offsets()), inside, nb_);
    links_.push_back(force.get());
    link_elements_.push_back(static_cast<int>(forces_.size()));
    forces_.push_back(std::move(force));
  }
  for (const CoupledBeam& b : beams_)
    if (b.time_loads) forces_.push_back(std::make_unique<BeamLoadForce>(b.time_loads, b.offset));
  for (const CoupledBeam& b : beams_)
    if (!b.damping_remainder.empty())
      forces_.push_back(std::make_unique<DiscreteDampingForce>(b.mesh.name, b.damping_remainder, b.offset, nb_));
  // Split coordinates take the single beams in the low-rank form; a joined
  // structure or a constraint contact rules them out.
  bool any = false, joined = false;
  for (const auto& s : structures_) {
    joined = joined || s->ranges().size() > 1;
    any = any || (s->ranges().size() == 1 && !s->every_mode());
  }
  splittable_ = constraints_.num_rows() == 0 && !joined && any;
}

std::vector<std::string> CoupledModel::coordinate_names() const {
  std::vector<std::string> out;
  for (int i = 0; i < kernels_.num_coordinates; ++i) {
    out.push_back(kernels_.coordinate_names && kernels_.coordinate_names[i] ? kernels_.coordinate_names[i]
                                                                           : "q" + std::to_string(i));
  }
  for (const CoupledBeam& b : beams_) {
    std::vector<std::string> names(b.mesh.num_free);
    for (std::size_t full = 0; full < b.mesh.full_to_free.size(); ++full) {
      const int f = b.mesh.full_to_free[full];
      if (f < 0) continue;
      names[f] = b.mesh.name + (full % 2 == 0 ? "_w" : "_dw") + std::to_string(full / 2);
    }
    out.insert(out.end(), names.begin(), names.end());
  }
  return out;
}

}  // namespace mbfe::runtime
