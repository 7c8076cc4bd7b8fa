// The modes cache (api/modal_cache.h): what it keeps comes back bit for bit,
// and a damaged, truncated, extended or foreign entry, or one in a folder
// others may write, is refused and computed again, never trusted. End to end:
// the two-span catenary's wires sliced (dense limit below their size), loaded
// once computing and once from the cache, give the same bits.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <Eigen/Dense>
#include <atomic>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>

#include "api/mbfe.h"
#include "api/modal_cache.h"
#include "runtime/simulation/assembled_model.h"
#include "tests/support/process.h"
#include "tests/support/two_span_catenary.h"

namespace mbfe {
namespace {

namespace fs = std::filesystem;
using test::TempDir;

constexpr int kRows = 30;
constexpr int kCols = 7;

runtime::ModalBasis random_basis(unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> n(0.0, 1.0);
  runtime::ModalBasis basis;
  basis.omega.resize(kCols);
  for (int j = 0; j < kCols; ++j) basis.omega[j] = 10.0 * (j + 1) + n(rng);
  basis.phi = Eigen::MatrixXd::NullaryExpr(kRows, kCols, [&]() { return n(rng); });
  basis.complete = false;
  return basis;
}

bool same_bits(const runtime::ModalBasis& a, const runtime::ModalBasis& b) {
  return a.complete == b.complete && a.omega.size() == b.omega.size() && a.phi.rows() == b.phi.rows() &&
         a.phi.cols() == b.phi.cols() &&
         std::memcmp(a.omega.data(), b.omega.data(), sizeof(double) * a.omega.size()) == 0 &&
         std::memcmp(a.phi.data(), b.phi.data(), sizeof(double) * a.phi.size()) == 0;
}

class ModalCache : public ::testing::Test {
 protected:
  fs::path cache() const { return tmp_ / "cache"; }
  DiskModalStore store() const { return DiskModalStore(cache().string(), true); }
  std::string kept(const std::string& inputs, const runtime::ModalBasis& basis) const {
    store().keep(inputs, basis);
    const std::string path = store().entry_path(inputs);
    EXPECT_TRUE(fs::is_regular_file(path));
    return path;
  }
  TempDir tmp_;
};

TEST_F(ModalCache, KeptBasisComesBackBitForBit) {
  const runtime::ModalBasis basis = random_basis(1);
  const std::string path = kept("inputs A", basis);
  const std::optional<runtime::ModalBasis> found = store().find("inputs A", kRows);
  ASSERT_TRUE(found);
  EXPECT_TRUE(same_bits(*found, basis));
  // Private: the folder 0700, the entry 0600.
  EXPECT_EQ(fs::status(cache() / "modes").permissions() & fs::perms::all, fs::perms::owner_all);
  EXPECT_EQ(fs::status(path).permissions() & fs::perms::all, fs::perms::owner_read | fs::perms::owner_write);
  // Other inputs, another entry: nothing found.
  EXPECT_NE(store().entry_path("inputs B"), path);
  EXPECT_FALSE(store().find("inputs B", kRows));
  // The caller's rows are checked against the file's.
  EXPECT_FALSE(store().find("inputs A", kRows + 1));
}

TEST_F(ModalCache, TruncatedOrExtendedEntryIsRefused) {
  const std::string path = kept("inputs", random_basis(2));
  const auto size = fs::file_size(path);
  fs::resize_file(path, size - 8);
  EXPECT_FALSE(store().find("inputs", kRows));
  fs::resize_file(path, size + 8);
  EXPECT_FALSE(store().find("inputs", kRows));
  fs::resize_file(path, 40);  // inside the header
  EXPECT_FALSE(store().find("inputs", kRows));
  // Kept again, it is found again.
  kept("inputs", random_basis(2));
  EXPECT_TRUE(store().find("inputs", kRows));
}

TEST_F(ModalCache, FlippedDataByteIsRefused) {
  const std::string path = kept("inputs", random_basis(3));
  const auto size = fs::file_size(path);
  std::fstream file(path, std::ios::in | std::ios::out | std::ios::binary);
  file.seekg(static_cast<std::streamoff>(size - 100));
  char c = 0;
  file.read(&c, 1);
  file.seekp(static_cast<std::streamoff>(size - 100));
  c = static_cast<char>(c ^ 0x01);
  file.write(&c, 1);
  file.close();
  EXPECT_EQ(fs::file_size(path), size);
  EXPECT_FALSE(store().find("inputs", kRows));
}

TEST_F(ModalCache, EntryOfOtherInputsUnderThisNameIsRefused) {
  // A whole, self-consistent entry of other inputs renamed to this key.
  const std::string here = kept("inputs", random_basis(4));
  const std::string other = kept("other inputs", random_basis(5));
  fs::rename(other, here);
  EXPECT_FALSE(store().find("inputs", kRows));
}

TEST_F(ModalCache, EntryOthersMayWriteIsNotTrusted) {
  const std::string path = kept("inputs", random_basis(6));
  fs::permissions(path, fs::perms::group_write, fs::perm_options::add);
  EXPECT_FALSE(store().find("inputs", kRows));
  fs::permissions(path, fs::perms::group_write, fs::perm_options::remove);
  EXPECT_TRUE(store().find("inputs", kRows));
  fs::permissions(cache() / "modes", fs::perms::others_write, fs::perm_options::add);
  EXPECT_FALSE(store().find("inputs", kRows));
}

// Counts what the disk store finds, to see the second load use the cache.
class CountingStore : public runtime::ModalBasisStore {
 public:
  explicit CountingStore(std::string dir) : disk_(std::move(dir), true) {}
  std::optional<runtime::ModalBasis> find(const std::string& inputs, int rows) const override {
    std::optional<runtime::ModalBasis> found = disk_.find(inputs, rows);
    ++(found ? hits : misses);
    last_path = disk_.entry_path(inputs);
    return found;
  }
  void keep(const std::string& inputs, const runtime::ModalBasis& basis) const override { disk_.keep(inputs, basis); }
  mutable std::atomic<int> hits{0}, misses{0};
  mutable std::string last_path;

 private:
  DiskModalStore disk_;
};

constexpr int kBelowTheWires = 40;  // DOF; each wire has about 80: sliced

Model load(const std::shared_ptr<CountingStore>& store, const std::string& cap = "{omega_limit: 800.0, margin: 0.1}") {
  LoadOptions options;
  options.beams.dense_limit = kBelowTheWires;
  options.beams.slice_modes = 10;
  options.beams.modes_store = store;
  return Model::parse(test::with_wire_adjustment(cap), "modal_cache.yaml", options);
}

// Accelerations of the adjusted model at a seeded random state.
Eigen::VectorXd accelerations(const Model& model) {
  auto dynamics = model.assembled().make_dynamics(true);
  Eigen::VectorXd q, qd, a, lambda;
  model.assembled().initial_coordinates(q, qd);
  std::mt19937 rng(20261124);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int i = dynamics->nb(); i < q.size(); ++i) {
    q[i] = 1e-3 * u(rng);
    qd[i] = 1e-2 * u(rng);
  }
  dynamics->evaluate(0.0, q, qd);
  dynamics->solve_augmented(0.0, a, lambda);
  return a;
}

TEST_F(ModalCache, SecondLoadUsesTheCacheAndGivesTheSameBits) {
  auto store = std::make_shared<CountingStore>(cache().string());
  const Model first = load(store);
  first.assembled();  // the modes are computed with the assembled model, on first use
  EXPECT_EQ(store->misses, 2);  // both wires computed
  const Model second = load(store);
  second.assembled();
  EXPECT_EQ(store->hits, 2);  // and found
  for (std::size_t k = 0; k < 2; ++k) {
    const runtime::BeamPart& a = first.assembled().beams().beams[k];
    const runtime::BeamPart& b = second.assembled().beams().beams[k];
    EXPECT_FALSE(a.dense);
    EXPECT_TRUE(same_bits(a.basis, b.basis)) << "beam " << k;
  }
  const Eigen::VectorXd a1 = accelerations(first), a2 = accelerations(second);
  ASSERT_EQ(a1.size(), a2.size());
  EXPECT_EQ(std::memcmp(a1.data(), a2.data(), sizeof(double) * a1.size()), 0);

  // A damaged entry is computed again, to the same bits.
  fs::resize_file(store->last_path, fs::file_size(store->last_path) - 1);
  const Model third = load(store);
  third.assembled();
  EXPECT_EQ(store->misses, 3);
  EXPECT_TRUE(same_bits(third.assembled().beams().beams[1].basis, first.assembled().beams().beams[1].basis));

  // Another cap slices other modes: other inputs, nothing found.
  const int hits = store->hits;
  const Model other = load(store, "{omega_limit: 600.0, margin: 0.1}");
  other.assembled();
  EXPECT_EQ(store->hits, hits);
  EXPECT_LT(other.assembled().beams().beams[1].basis.omega.size(), first.assembled().beams().beams[1].basis.omega.size());
}

TEST_F(ModalCache, DenseBeamsKeepEveryModeAndGetTheSameBits) {
  auto store = std::make_shared<CountingStore>(cache().string());
  const auto load_dense = [&]() {
    LoadOptions options;
    options.beams.dense_store_from = kBelowTheWires;  // the wires are dense (default limit) and kept
    options.beams.modes_store = store;
    return Model::parse(test::with_wire_adjustment("{omega_limit: 800.0, margin: 0.1}"), "modal_cache.yaml",
                        options);
  };
  const Model first = load_dense();
  first.assembled();
  EXPECT_EQ(store->misses, 2);
  const Model second = load_dense();
  second.assembled();
  EXPECT_EQ(store->hits, 2);
  for (std::size_t k = 0; k < 2; ++k) {
    const runtime::BeamPart& a = first.assembled().beams().beams[k];
    const runtime::BeamPart& b = second.assembled().beams().beams[k];
    EXPECT_TRUE(a.dense);
    EXPECT_TRUE(b.basis.complete);
    EXPECT_EQ(b.basis.phi.cols(), b.basis.phi.rows());
    EXPECT_TRUE(same_bits(a.basis, b.basis)) << "beam " << k;
  }
  const Eigen::VectorXd a1 = accelerations(first), a2 = accelerations(second);
  ASSERT_EQ(a1.size(), a2.size());
  EXPECT_EQ(std::memcmp(a1.data(), a2.data(), sizeof(double) * a1.size()), 0);

  // Beams below the threshold never ask the store.
  const int asked = store->hits + store->misses;
  LoadOptions small;
  small.beams.modes_store = store;
  Model::parse(test::with_wire_adjustment("{omega_limit: 800.0, margin: 0.1}"), "modal_cache.yaml", small).assembled();
  EXPECT_EQ(store->hits + store->misses, asked);
}

// Accelerations of the original model at a seeded random state.
Eigen::VectorXd original_accelerations(const runtime::AssembledModel& assembled) {
  auto dynamics = assembled.make_dynamics(false);
  Eigen::VectorXd q, qd, a, lambda;
  assembled.initial_coordinates(q, qd);
  std::mt19937 rng(20261125);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int i = dynamics->nb(); i < q.size(); ++i) {
    q[i] = 1e-3 * u(rng);
    qd[i] = 1e-2 * u(rng);
  }
  dynamics->evaluate(0.0, q, qd);
  dynamics->solve_augmented(0.0, a, lambda);
  return a;
}

TEST_F(ModalCache, OriginalRunsDoNotComputeTheKeptModes) {
  auto store = std::make_shared<CountingStore>(cache().string());
  const Model model = load(store);
  const runtime::AssembledModel& original = model.assembled_for(false);
  EXPECT_EQ(store->hits + store->misses, 0) << "an original run asked for the kept modes";
  EXPECT_THROW(original.make_dynamics(true), runtime::InvalidInput);
  // The same original model as the whole assembly's, to the bit.
  const Eigen::VectorXd lazy = original_accelerations(original);
  const runtime::AssembledModel& whole = model.assembled_for(true);
  EXPECT_EQ(store->misses, 2);
  const Eigen::VectorXd eager = original_accelerations(whole);
  ASSERT_EQ(lazy.size(), eager.size());
  EXPECT_EQ(std::memcmp(lazy.data(), eager.data(), sizeof(double) * lazy.size()), 0);
  // Once the whole assembly exists, original runs use it too.
  EXPECT_EQ(&model.assembled_for(false), &whole);
}

}  // namespace
}  // namespace mbfe
