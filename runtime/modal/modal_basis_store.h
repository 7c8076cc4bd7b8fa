// Somewhere to keep modal bases between runs. Slicing out the modes a cap
// keeps in a large beam takes seconds per beam (thousands of modes), the
// dense solve of a beam of a thousand DOFs most of a second; they depend only
// on the beam's matrices, the options and the code, so a run, a sweep point
// or another speed can reuse them. The runtime knows no
// files: it describes what the modes depend on (sliced_modes_inputs) and asks
// a store; the API keeps them on disk (api/modal_cache.h).
#pragma once

#include <optional>
#include <string>

#include "runtime/modal/modal_basis.h"

namespace mbfe::runtime {

struct BeamSystem;    // runtime/fem/beam_system.h
struct ModalOptions;  // runtime/modal/modal_analysis.h

class ModalBasisStore {
 public:
  virtual ~ModalBasisStore() = default;
  /// The basis kept under exactly these `inputs`, with `rows` rows (the
  /// beam's DOFs), or nullopt when there is none or what is there fails the
  /// store's checks. Must be safe to call from several threads at once.
  virtual std::optional<ModalBasis> find(const std::string& inputs, int rows) const = 0;
  /// Keeps `basis` under `inputs`. Failing to keep it is not an error (the
  /// next run computes it again); thread-safe as find.
  virtual void keep(const std::string& inputs, const ModalBasis& basis) const = 0;
};

/// Version of the slicing's results: raised whenever the slicing would return
/// other bits for the same matrices (the disk store also keys on the sources
/// of runtime/modal/ and the compiler).
inline constexpr int kSlicedModesVersion = 1;

/// What modal_analysis(beam, options) with options.up_to_omega > 0 depends
/// on, as bytes: kSlicedModesVersion, the options, and M, K and the
/// stiffness factor bit for bit (sizes, sparsity and values). Equal inputs
/// give equal bases. About 12 bytes per stored matrix entry.
std::string sliced_modes_inputs(const BeamSystem& beam, const ModalOptions& options);

/// Version of the dense path's results (modal_dense), as kSlicedModesVersion.
inline constexpr int kDenseModesVersion = 1;

/// What modal_dense(beam.M, beam.K) depends on, as bytes: kDenseModesVersion
/// and M and K bit for bit. Never equal to any sliced_modes_inputs.
std::string dense_modes_inputs(const BeamSystem& beam);

}  // namespace mbfe::runtime
