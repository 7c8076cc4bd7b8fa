// The explicit step of a coupled run in the partitioned formulation (nodal or
// in split coordinates) allocates nothing on the heap once the run has
// started: every scratch vector lives in the run's workspace (CoupledData, the
// steppers' stages), sized at the first evaluation, but for a column of
// M_c^-1 the first time a constraint contact touches a DOF (coupled_dynamics.h).
// The augmented formulation's saddle-point solve keeps its matrix and factors
// in the workspace too.
//
// The oracle is the C library's own count: this file interposes malloc and
// its relatives for the test binary (glibc's __libc_* entry points do the
// work), counting calls while a flag is set. Eigen's temporaries go through
// malloc, not operator new, so counting operator new alone would miss them.
// Under AddressSanitizer, which interposes malloc itself, the test is skipped.
#include <gtest/gtest.h>

#include <atomic>
#include <cstddef>
#include <string>

#include "api/mbfe.h"
#include "api/simulator.h"

#if defined(__SANITIZE_ADDRESS__) || defined(MBFE_SANITIZED_BUILD)
#define MBFE_COUNT_MALLOC 0
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define MBFE_COUNT_MALLOC 0
#endif
#endif
#if !defined(MBFE_COUNT_MALLOC) && defined(__GLIBC__)
#define MBFE_COUNT_MALLOC 1
#endif

#if MBFE_COUNT_MALLOC
namespace {
std::atomic<bool> g_counting{false};
std::atomic<long> g_allocations{0};
inline void count() {
  if (g_counting.load(std::memory_order_relaxed)) g_allocations.fetch_add(1, std::memory_order_relaxed);
}
}  // namespace

extern "C" {
void* __libc_malloc(std::size_t);
void* __libc_calloc(std::size_t, std::size_t);
void* __libc_realloc(void*, std::size_t);
void* __libc_memalign(std::size_t, std::size_t);
void __libc_free(void*);

void* malloc(std::size_t n) {
  count();
  return __libc_malloc(n);
}
void* calloc(std::size_t k, std::size_t n) {
  count();
  return __libc_calloc(k, n);
}
void* realloc(void* p, std::size_t n) {
  count();
  return __libc_realloc(p, n);
}
void* memalign(std::size_t a, std::size_t n) {
  count();
  return __libc_memalign(a, n);
}
void* aligned_alloc(std::size_t a, std::size_t n) {
  count();
  return __libc_memalign(a, n);
}
int posix_memalign(void** p, std::size_t a, std::size_t n) {
  count();
  *p = __libc_memalign(a, n);
  return *p != nullptr ? 0 : 12;  // ENOMEM
}
void free(void* p) { __libc_free(p); }
}
#endif

namespace {

constexpr int kWarmUpSteps = 5;    // the workspace is sized by the first evaluations
constexpr int kCountedSteps = 20;

long allocations_in_steps(const std::string& model_file, const std::string& integrator,
                          const mbfe::ir::ModelOverrides& overrides = {},
                          mbfe::runtime::CoupledFormulation formulation = mbfe::runtime::CoupledFormulation::kPartitioned) {
  mbfe::LoadOptions options;
  options.overrides = overrides;
  const mbfe::Model model = mbfe::Model::load(std::string(MBFE_SOURCE_DIR) + "/" + model_file, options);
  mbfe::runtime::SimulationRequest request = model.request();
  request.integrator = mbfe::runtime::parse_integrator(integrator);
  request.formulation = formulation;
  mbfe::Simulator sim(model, request);
  sim.advance_steps(kWarmUpSteps);
#if MBFE_COUNT_MALLOC
  g_allocations = 0;
  g_counting = true;
  sim.advance_steps(kCountedSteps);
  g_counting = false;
#else
  sim.advance_steps(kCountedSteps);
#endif
  EXPECT_EQ(sim.steps(), kWarmUpSteps + kCountedSteps) << sim.report().message;
#if MBFE_COUNT_MALLOC
  return g_allocations;
#else
  return 0;
#endif
}

class StepAllocations : public ::testing::TestWithParam<std::pair<const char*, const char*>> {};

TEST_P(StepAllocations, NoneAfterTheFirstSteps) {
#if !MBFE_COUNT_MALLOC
  GTEST_SKIP() << "malloc is not countable here (AddressSanitizer, or not glibc)";
#else
  const auto [model, integrator] = GetParam();
  EXPECT_EQ(allocations_in_steps(model, integrator), 0) << model << " with " << integrator;
#endif
}

// The two-span catenary with its wires truncated: the state leaves their
// zeros out, and the row passes keep their scratch in each wire's workspace.
TEST(StepAllocationsTruncated, NoneAfterTheFirstSteps) {
#if !MBFE_COUNT_MALLOC
  GTEST_SKIP() << "malloc is not countable here (AddressSanitizer, or not glibc)";
#else
  const mbfe::ir::ModelOverrides truncate = {{"beams.messenger.adjustment.policy", "truncate"},
                                             {"beams.contact_wire.adjustment.policy", "truncate"}};
  EXPECT_EQ(allocations_in_steps("models/pantograph_catenary_2span.yaml", "rk4", truncate), 0);
#endif
}

// The paper's platform in the augmented formulation: the saddle-point system
// of its pin and slider constraints is formed and solved at every evaluation.
TEST(StepAllocationsAugmented, NoneAfterTheFirstSteps) {
#if !MBFE_COUNT_MALLOC
  GTEST_SKIP() << "malloc is not countable here (AddressSanitizer, or not glibc)";
#else
  EXPECT_EQ(allocations_in_steps("models/paper_platform.yaml", "rk4", {},
                                 mbfe::runtime::CoupledFormulation::kAugmented),
            0);
#endif
}

// A moving mass on an adjusted bridge (a slider spring, a driven joint), the
// paper's platform (pin and slider constraints, partitioned), the two-span
// catenary (wires in split coordinates, droppers as links).
INSTANTIATE_TEST_SUITE_P(CoupledModels, StepAllocations,
                         ::testing::Values(std::make_pair("models/bridge_moving_mass.yaml", "rk4"),
                                           std::make_pair("models/paper_platform.yaml", "rk4"),
                                           std::make_pair("models/pantograph_catenary_2span.yaml", "rk4")));

}  // namespace
