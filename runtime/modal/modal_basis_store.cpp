#include "runtime/modal/modal_basis_store.h"

#include <cstring>
#include <type_traits>

#include "runtime/fem/beam_system.h"
#include "runtime/modal/modal_analysis.h"

namespace mbfe::runtime {

namespace {

template <typename T>
void append_raw(std::string& out, const T* data, std::size_t count) {
  static_assert(std::is_trivially_copyable_v<T>);
  out.append(reinterpret_cast<const char*>(data), count * sizeof(T));
}

template <typename T>
void append_value(std::string& out, T value) {
  append_raw(out, &value, 1);
}

// Sizes, then the compressed columns (outer starts, inner indices, values).
void append_matrix(std::string& out, const char* name, Eigen::SparseMatrix<double> A) {
  A.makeCompressed();
  out += name;
  append_value<long long>(out, A.rows());
  append_value<long long>(out, A.cols());
  append_value<long long>(out, A.nonZeros());
  append_raw(out, A.outerIndexPtr(), static_cast<std::size_t>(A.outerSize()) + 1);
  append_raw(out, A.innerIndexPtr(), static_cast<std::size_t>(A.nonZeros()));
  append_raw(out, A.valuePtr(), static_cast<std::size_t>(A.nonZeros()));
}

}  // namespace

std::string sliced_modes_inputs(const BeamSystem& beam, const ModalOptions& options) {
  std::string out = "sliced modes " + std::to_string(kSlicedModesVersion) + "\n";
  append_value(out, options.up_to_omega);
  append_value(out, options.slice_modes);
  append_value(out, options.dense_limit);
  append_value(out, shift_below_lowest(beam));
  append_matrix(out, "M", beam.M);
  append_matrix(out, "K", beam.K);
  append_matrix(out, "S", beam.stiffness_factor);
  return out;
}

std::string dense_modes_inputs(const BeamSystem& beam) {
  std::string out = "dense modes " + std::to_string(kDenseModesVersion) + "\n";
  append_matrix(out, "M", beam.M);
  append_matrix(out, "K", beam.K);
  return out;
}

}  // namespace mbfe::runtime
