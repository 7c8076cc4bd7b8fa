#include "tool/sweep_slurm.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace mbfe::tool {

namespace fs = std::filesystem;

namespace {

std::string quote(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

void write_script(const fs::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
  if (!out) throw std::runtime_error(path.string() + ": cannot write");
  fs::permissions(path, fs::perms::owner_exec | fs::perms::group_exec | fs::perms::others_exec, fs::perm_options::add);
}

/// Runs a command, returns its standard output; throws with it on failure.
std::string run(const std::string& command) {
  std::FILE* pipe = ::popen((command + " 2>&1").c_str(), "r");
  if (!pipe) throw std::runtime_error("cannot run: " + command);
  std::string out;
  char buf[512];
  while (std::fgets(buf, sizeof buf, pipe)) out += buf;
  const int status = ::pclose(pipe);
  if (status != 0) throw std::runtime_error(command + " failed: " + out);
  while (!out.empty() && (out.back() == '\n' || out.back() == '\r')) out.pop_back();
  return out;
}

std::string header(const std::string& name, const fs::path& log, const SlurmOptions& o) {
  std::string h = "#!/bin/bash\n# Written by mbfe sweep --slurm (docs/sweeps.md).\n#SBATCH --job-name=" + name +
                  "\n#SBATCH --output=" + log.string() + "\n#SBATCH --ntasks=1\n#SBATCH --cpus-per-task=1\n";
  if (!o.partition.empty()) h += "#SBATCH --partition=" + o.partition + "\n";
  if (!o.time.empty()) h += "#SBATCH --time=" + o.time + "\n";
  return h;
}

}  // namespace

SlurmSubmission submit_slurm_sweep(const std::string& mbfe, const std::string& sweep_file, const std::string& out_dir,
                                   const std::string& sweep_name, long points, const SlurmOptions& options) {
  const fs::path dir = fs::absolute(out_dir);
  const fs::path slurm = dir / "slurm";
  fs::create_directories(slurm);
  const std::string env = "export MBFE_CACHE_DIR=" + quote((dir / "cache").string()) + "\n";
  const std::string base = quote(fs::absolute(mbfe).string()) + " sweep " + quote(fs::absolute(sweep_file).string()) +
                           " --out " + quote(dir.string());
  SlurmSubmission s;
  s.points_script = (slurm / "points.sbatch").string();
  s.collect_script = (slurm / "collect.sbatch").string();
  std::string array = "#SBATCH --array=0-" + std::to_string(points - 1);
  if (options.array_limit > 0) array += "%" + std::to_string(options.array_limit);
  write_script(s.points_script, header("mbfe-" + sweep_name, slurm / "point-%a.out", options) + array + "\n" + env +
                                    "exec " + base + " --point \"$SLURM_ARRAY_TASK_ID\" --quiet\n");
  write_script(s.collect_script, header("mbfe-" + sweep_name + "-collect", slurm / "collect.out", options) + env +
                                     "exec " + base + " --collect --quiet\n");
  if (options.dry_run) return s;
  s.array_job = run("sbatch --parsable " + quote(s.points_script));
  s.array_job = s.array_job.substr(0, s.array_job.find(';'));  // "id;cluster" on federated clusters
  s.collect_job = run("sbatch --parsable --dependency=afterany:" + s.array_job + " " + quote(s.collect_script));
  s.collect_job = s.collect_job.substr(0, s.collect_job.find(';'));
  return s;
}

}  // namespace mbfe::tool
