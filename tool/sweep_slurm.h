// `mbfe sweep --slurm`: the sweep as a Slurm job array, one task per point
// (each `mbfe sweep SWEEP --out DIR --point $SLURM_ARRAY_TASK_ID`), and a
// collect job that depends on it and writes the summary (docs/sweeps.md).
#pragma once

#include <string>
#include <vector>

namespace mbfe::tool {

struct SlurmOptions {
  std::string partition;  // empty: the cluster's default
  std::string time;       // per task, Slurm's format ("10:00"); empty: the default
  long array_limit = 0;   // at most this many tasks at once; 0: no limit
  bool dry_run = false;   // write the scripts, do not submit
  std::vector<std::string> model_sets;  // each task's `--set PATH=VALUE`s: "PATH=VALUE"
};

struct SlurmSubmission {
  std::string points_script, collect_script;  // paths written
  std::string array_job, collect_job;         // job ids (empty on a dry run)
};

/// `s` as one word for bash (single-quoted), as the scripts quote paths.
std::string shell_word(const std::string& s);

/// Refuses (UsageError, exit status 2) what a Slurm script cannot carry: a
/// control character (a newline would end a line of the script and start
/// another) in any argument, a backslash in `out_dir` (it would stop Slurm
/// from expanding %a in the log names), a partition or time other than
/// letters, digits and _ . , : - . Every path in the scripts is quoted.
void check_slurm_arguments(const std::string& mbfe, const std::string& sweep_file, const std::string& out_dir,
                           const SlurmOptions& options);

/// Writes DIR/slurm/points.sbatch and DIR/slurm/collect.sbatch for `points`
/// tasks and, unless a dry run, submits them with sbatch (the collect job
/// --dependency=afterany on the array). `mbfe` and the sweep file are given
/// as absolute paths; DIR must be on a filesystem the nodes share, and the
/// solver cache is DIR/cache. @throws std::runtime_error when sbatch fails,
/// with its message.
SlurmSubmission submit_slurm_sweep(const std::string& mbfe, const std::string& sweep_file, const std::string& out_dir,
                                   const std::string& sweep_name, long points, const SlurmOptions& options);

}  // namespace mbfe::tool
