// How far the modal analysis of a model's beams goes: what a caller chooses
// when it loads a model (api/mbfe.h LoadOptions), apart from the analysis.
#pragma once

#include <memory>

#include "runtime/modal/modal_basis_store.h"
#include "runtime/modal/slicing_defaults.h"

namespace mbfe::runtime {

/// How far the modal analysis of a beam goes.
struct BeamAnalysisOptions {
  /// Beams up to this many DOFs get every mode (dense path).
  int dense_limit = 2000;
  /// Beams above dense_limit: 0 = refused (time integration and the stability
  /// advisor use every mode); k > 0 = the lowest k modes by sparse Lanczos,
  /// a partial spectrum (what `mbfe modal` shows of a large beam).
  int sparse_modes = 0;
  /// Beams above dense_limit whose adjustment is a per-beam cap: every mode
  /// the cap keeps (omega <= omega_limit) and the first it changes, by
  /// spectrum slicing, instead of sparse_modes: what the low-rank adjusted
  /// operators need (a coupled model's time integration).
  bool modes_kept_by_cap = false;
  /// Modes per Lanczos run of that slicing (SlicedModalOptions::slice_modes).
  int slice_modes = kDefaultSliceModes;
  /// For a coupled model whose runs all use the original beams (--adjust
  /// off): its large beams skip the modes their cap keeps (the slicing, the
  /// expensive part of the set-up), and adjusted runs of it are refused.
  bool original_only = false;
  /// Where the sliced modes are looked up before slicing and kept after
  /// (modal_basis_store.h); null = always slice. The API gives its disk cache.
  std::shared_ptr<const ModalBasisStore> modes_store;
  /// Dense beams of at least this many DOFs look their modes up in
  /// modes_store too: the dense solve grows as n^3 (about 0.6 s for a wire of
  /// 960 DOFs, a third of the two-span catenary's whole run), while a few
  /// hundred DOFs take milliseconds, less than reading a file would save.
  int dense_store_from = 400;
};

}  // namespace mbfe::runtime
