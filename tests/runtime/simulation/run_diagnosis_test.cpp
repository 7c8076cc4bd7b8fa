// The one sentence for a run that did not complete (run_diagnosis.h), branch
// by branch, on hand-made results.
#include "runtime/simulation/run_diagnosis.h"

#include <gtest/gtest.h>

#include "runtime/integrators/integrator.h"

namespace mbfe::runtime {
namespace {

SimulationResult result(SimulationStatus status, double t, double step) {
  SimulationResult r;
  r.status = status;
  r.t = t;
  r.step = step;
  r.integrator = "forward_euler";
  r.norm = 2e3;
  r.bound = 1e3;
  r.message = "contact 'c': the slider left beam 'b'";
  return r;
}

StepLimit finite(double h, std::complex<double> critical) {
  StepLimit l;
  l.kind = StepLimit::Kind::kFinite;
  l.h = h;
  l.critical = critical;
  return l;
}

TEST(RunDiagnosis, CompletedRunHasNoMessage) {
  EXPECT_EQ(diagnose_run(result(SimulationStatus::kCompleted, 1.0, 1e-3), std::nullopt), "");
}

TEST(RunDiagnosis, DivergenceBeyondTheLimitNamesItAndTheFastestEigenvalue) {
  const std::string m =
      diagnose_run(result(SimulationStatus::kDiverged, 0.004080, 1.5e-5), finite(1.4597e-5, {-1.37021e5, 0.0}));
  EXPECT_EQ(m, "diverged at t = 0.004095 s: step 1.5e-05 exceeds forward_euler's stable limit 1.4597e-05 "
               "(fastest eigenvalue -1.3702e5): |y| = 2000 exceeded the bound 1000");
}

TEST(RunDiagnosis, NoStableStepAndUnknownLimit) {
  StepLimit none;
  none.kind = StepLimit::Kind::kNone;
  none.critical = {0.0, 7.3542e1};
  EXPECT_NE(diagnose_run(result(SimulationStatus::kDiverged, 1.0, 1e-3), none)
                .find("forward_euler has no stable step for this model (eigenvalue 0.0000e0 + 7.3542e1i)"),
            std::string::npos);
  EXPECT_EQ(diagnose_run(result(SimulationStatus::kDiverged, 1.0, 0.5), std::nullopt),
            "diverged at t = 1.5 s: step 0.5 with forward_euler: |y| = 2000 exceeded the bound 1000");
}

// A fault of the model at a stable step is the model's; beyond the limit it is
// the growing state's.
TEST(RunDiagnosis, ContactFaultBlamedOnTheStepOnlyBeyondTheLimit) {
  const SimulationResult failed = result(SimulationStatus::kFailed, 0.25, 1e-5);
  EXPECT_EQ(diagnose_run(failed, finite(2e-5, {-1e5, 0.0})),
            "failed at t = 0.25 s: contact 'c': the slider left beam 'b'");
  const std::string beyond = diagnose_run(failed, finite(5e-6, {-1e5, 0.0}));
  EXPECT_NE(beyond.find("exceeds forward_euler's stable limit 5e-06"), std::string::npos) << beyond;
  EXPECT_NE(beyond.find("the growing state broke a contact: contact 'c'"), std::string::npos) << beyond;
  EXPECT_EQ(diagnose_run(result(SimulationStatus::kCompleted, 1.0, 1e-5), std::nullopt, "row fault"),
            "failed at t = 1 s: row fault");
}

TEST(RunDiagnosis, InterruptedAndEigenvalueText) {
  EXPECT_EQ(diagnose_run(result(SimulationStatus::kInterrupted, 0.5, 1e-3), std::nullopt), "interrupted at t = 0.5 s");
  EXPECT_EQ(eigenvalue_text({-3.6817, 73.5417}), "-3.6817e0 + 7.3542e1i");
  EXPECT_EQ(eigenvalue_text({-1.3702e5, 0.0}), "-1.3702e5");
}

}  // namespace
}  // namespace mbfe::runtime
