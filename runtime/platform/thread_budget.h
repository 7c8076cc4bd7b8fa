// How many threads one run may use: the cores this process may run on (its
// CPU affinity: a Slurm task's CPUs, a `taskset`), not the machine's, and at
// most MBFE_THREADS when that is a positive whole number (`mbfe sweep` sets
// it for the points it runs side by side, so that two points on two cores
// do not start four threads). Threads are an optimisation everywhere they
// are used: the bits of a result do not depend on the budget.
#pragma once

namespace mbfe::runtime {

/// At least 1; read once per process.
unsigned thread_budget();

/// The budget of a process that may run on `cores` cores with MBFE_THREADS
/// set to `limit` (null: unset). A value that is not a positive whole number
/// does not limit: it must neither make runs slower silently nor fail them.
unsigned thread_budget(unsigned cores, const char* limit);

}  // namespace mbfe::runtime
