#include "tool/sweep_slurm.h"

#include <cctype>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <utility>

#include "frontend/text_guard.h"
#include "tool/cli_args.h"

namespace mbfe::tool {

namespace fs = std::filesystem;

namespace {

/// A word for bash: single-quoted.
std::string quote(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

/// A value on an #SBATCH line: double-quoted, \ and " escaped (sbatch groups
/// quoted text and takes \ as an escape when it reads the line).
std::string sbatch_quote(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
}

/// A path put into a filename pattern of --output, where % starts a
/// replacement (%a: the task): % doubled, taken literally.
std::string pattern_literal(const std::string& s) {
  std::string out;
  for (char c : s) out += c == '%' ? std::string("%%") : std::string(1, c);
  return out;
}

/// The first control character (newline, tab, ...) of `s`, or -1.
int control_character(const std::string& s) {
  for (char c : s)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7F) return static_cast<unsigned char>(c);
  return -1;
}

std::string hex(int c) {
  char buf[8];
  std::snprintf(buf, sizeof buf, "\\x%02X", c);
  return buf;
}

/// `s` for a message: control characters as \xNN, at most 80 bytes.
std::string shown(const std::string& s) {
  std::string out;
  for (char c : frontend::utf8_prefix(s, 80))
    out += static_cast<unsigned char>(c) < 0x20 || c == 0x7F ? hex(static_cast<unsigned char>(c)) : std::string(1, c);
  return out + (s.size() > 80 ? "..." : "");
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

/// `log_folder`/`log_pattern`: the folder taken literally, the file name a
/// pattern of Slurm's (point-%a.out).
std::string header(const std::string& name, const fs::path& log_folder, const std::string& log_pattern,
                   const SlurmOptions& o) {
  std::string h = "#!/bin/bash\n# Written by mbfe sweep --slurm (docs/sweeps.md).\n#SBATCH --job-name=" + name +
                  "\n#SBATCH --output=" + sbatch_quote(pattern_literal(log_folder.string()) + "/" + log_pattern) +
                  "\n#SBATCH --ntasks=1\n#SBATCH --cpus-per-task=1\n";
  if (!o.partition.empty()) h += "#SBATCH --partition=" + o.partition + "\n";
  if (!o.time.empty()) h += "#SBATCH --time=" + o.time + "\n";
  return h;
}

}  // namespace

std::string shell_word(const std::string& s) { return quote(s); }

void check_slurm_arguments(const std::string& mbfe, const std::string& sweep_file, const std::string& out_dir,
                           const SlurmOptions& options) {
  const std::pair<const char*, const std::string*> words[] = {
      {"--out", &out_dir}, {"the sweep file", &sweep_file}, {"the mbfe executable", &mbfe},
      {"--partition", &options.partition}, {"--time", &options.time}};
  std::vector<std::pair<const char*, const std::string*>> checked(std::begin(words), std::end(words));
  for (const std::string& set : options.model_sets) checked.emplace_back("--set", &set);
  for (const auto& [what, value] : checked) {
    if (const int c = control_character(*value); c >= 0)
      throw UsageError(std::string(what) + ": '" + shown(*value) + "' holds the control character " +
                       hex(c) + ", which a Slurm script cannot carry (one would end its line)");
  }
  if (out_dir.find('\\') != std::string::npos)
    throw UsageError("--out: '" + shown(out_dir) + "' holds a backslash, which stops Slurm from expanding %a in the task "
                     "logs' names (DIR/slurm/point-%a.out)");
  for (const auto& [what, value] : {std::pair<const char*, const std::string*>{"--partition", &options.partition},
                                    {"--time", &options.time}}) {
    for (char c : *value)
      if (!std::isalnum(static_cast<unsigned char>(c)) && std::string("_.,:-").find(c) == std::string::npos)
        throw UsageError(std::string(what) + ": '" + shown(*value) + "' holds '" + std::string(1, c) +
                         "'; expected letters, digits and _ . , : - (a Slurm partition or time)");
  }
}

SlurmSubmission submit_slurm_sweep(const std::string& mbfe, const std::string& sweep_file, const std::string& out_dir,
                                   const std::string& sweep_name, long points, const SlurmOptions& options) {
  const fs::path dir = fs::absolute(out_dir);
  const fs::path slurm = dir / "slurm";
  fs::create_directories(slurm);
  const std::string env = "export MBFE_CACHE_DIR=" + quote((dir / "cache").string()) + "\n";
  std::string base = quote(fs::absolute(mbfe).string()) + " sweep " + quote(fs::absolute(sweep_file).string()) +
                     " --out " + quote(dir.string());
  for (const std::string& set : options.model_sets) base += " --set " + quote(set);
  SlurmSubmission s;
  s.points_script = (slurm / "points.sbatch").string();
  s.collect_script = (slurm / "collect.sbatch").string();
  std::string array = "#SBATCH --array=0-" + std::to_string(points - 1);
  if (options.array_limit > 0) array += "%" + std::to_string(options.array_limit);
  write_script(s.points_script, header("mbfe-" + sweep_name, slurm, "point-%a.out", options) + array + "\n" + env +
                                    "exec " + base + " --point \"$SLURM_ARRAY_TASK_ID\" --quiet\n");
  write_script(s.collect_script, header("mbfe-" + sweep_name + "-collect", slurm, "collect.out", options) + env +
                                     "exec " + base + " --collect --quiet\n");
  if (options.dry_run) return s;
  s.array_job = run("sbatch --parsable " + quote(s.points_script));
  s.array_job = s.array_job.substr(0, s.array_job.find(';'));  // "id;cluster" on federated clusters
  s.collect_job = run("sbatch --parsable --dependency=afterany:" + s.array_job + " " + quote(s.collect_script));
  s.collect_job = s.collect_job.substr(0, s.collect_job.find(';'));
  return s;
}

}  // namespace mbfe::tool
