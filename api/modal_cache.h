// The modes a cap keeps in a large beam, and every mode of a dense beam of
// some hundreds of DOFs, kept on disk in the solver cache's folder
// (api/cache_folder.h) so that the slicing or the dense solve is paid once per
// beam: reused by later runs, sweep points and speeds of the same beam.
//
// Layout, in the cache folder:
//   modes/                 mode 0700
//     <key>.modes          one basis (0600): a text header line, then the
//                          omega (cols doubles) and Phi (rows x cols doubles,
//                          column-major) in this machine's byte order;
//     .tmp-*               a basis being written.
// The key is the SHA-256 of the runtime's description of what the modes
// depend on (runtime::sliced_modes_inputs or dense_modes_inputs: the beam's
// matrices bit for bit, the options), the sources of runtime/modal/, the compiler, its flags and the
// Eigen version. A file is written under a temporary name, flushed and renamed
// into place in one step, so a reader sees a whole file or none.
//
// Nothing is used unless the folder and the file belong to the user and no
// one else may write them, the header names this key, the rows the caller
// expects and 1 <= cols <= rows, the file's size is exactly the header's plus
// 8 (cols + rows cols) bytes, and the SHA-256 of the data is the header's.
// An entry that fails a check is not trusted: the modes are computed again
// and the entry replaced.
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "runtime/modal/modal_basis_store.h"

namespace mbfe {

class DiskModalStore : public runtime::ModalBasisStore {
 public:
  /// @param cache_dir the cache folder (solver_cache_dir()); created (0700)
  ///        on first use. @param quiet no line on stderr when an entry is
  ///        refused.
  DiskModalStore(std::string cache_dir, bool quiet) : cache_dir_(std::move(cache_dir)), quiet_(quiet) {}

  std::optional<runtime::ModalBasis> find(const std::string& inputs, int rows) const override;
  void keep(const std::string& inputs, const runtime::ModalBasis& basis) const override;

  /// The file a basis with these inputs is kept in.
  std::string entry_path(const std::string& inputs) const;

 private:
  std::string cache_dir_;
  bool quiet_;
};

/// A DiskModalStore in solver_cache_dir(), or null when there is no cache
/// folder setting (nothing is then kept).
std::shared_ptr<const runtime::ModalBasisStore> disk_modal_store(bool quiet);

}  // namespace mbfe
