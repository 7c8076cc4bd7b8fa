#include "tool/file_checks.h"

#include <sys/stat.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

#include "tool/cli_args.h"

namespace mbfe::tool {

namespace {

namespace fs = std::filesystem;

/// The input among `inputs` that is the same file as `info`, or nullptr.
const std::string* same_file(const struct stat& info, const std::vector<std::string>& inputs) {
  for (const std::string& input : inputs) {
    struct stat other {};
    if (::stat(input.c_str(), &other) == 0 && other.st_dev == info.st_dev && other.st_ino == info.st_ino)
      return &input;
  }
  return nullptr;
}

}  // namespace

void check_input_file(const std::string& path, const std::string& what) {
  struct stat info {};
  if (::stat(path.c_str(), &info) != 0)
    throw UsageError(path + ": cannot read " + what + ": " + std::strerror(errno));
  if (S_ISDIR(info.st_mode)) throw UsageError(path + ": cannot read " + what + ": it is a folder");
  if (!S_ISREG(info.st_mode) && !S_ISFIFO(info.st_mode))
    throw UsageError(path + ": cannot read " + what + ": not a regular file (a device or a socket)");
}

void check_output_file(const std::string& path, const std::string& flag, const std::vector<std::string>& inputs,
                       bool folder_made_later) {
  struct stat info {};
  if (::stat(path.c_str(), &info) == 0) {
    if (const std::string* input = same_file(info, inputs))
      throw UsageError(flag + " " + path + ": that is the input " + *input + "; writing there would destroy it");
    if (S_ISDIR(info.st_mode)) throw UsageError(flag + " " + path + ": cannot write the output: it is a folder");
    return;
  }
  // A file to be created: its folder must exist (the message simulate has
  // always given for it).
  const fs::path parent = fs::path(path).parent_path();
  std::error_code ec;
  if (!folder_made_later && !parent.empty() && !fs::is_directory(parent, ec))
    throw UsageError(path + ": cannot write the output: No such file or directory");
}

void check_output_folder(const std::string& dir, const std::string& flag, const std::vector<std::string>& inputs) {
  struct stat info {};
  if (::stat(dir.c_str(), &info) != 0) return;  // created later, with its parents
  if (const std::string* input = same_file(info, inputs))
    throw UsageError(flag + " " + dir + ": that is the input " + *input + "; writing there would destroy it");
  if (!S_ISDIR(info.st_mode))
    throw UsageError(flag + " " + dir + ": exists and is not a folder (the output goes into a folder)");
}

void check_folder_holds_no_input(const std::string& dir, const std::string& flag,
                                 const std::vector<std::string>& inputs) {
  struct stat folder {};
  if (::stat(dir.c_str(), &folder) != 0) return;
  for (const std::string& input : inputs) {
    std::error_code ec;
    const fs::path real = fs::weakly_canonical(fs::absolute(input, ec), ec);
    if (ec) continue;
    for (fs::path up = real.parent_path(); !up.empty(); up = up.parent_path()) {
      struct stat info {};
      if (::stat(up.c_str(), &info) == 0 && info.st_dev == folder.st_dev && info.st_ino == folder.st_ino)
        throw UsageError(flag + " " + dir + ": that folder holds the input " + input +
                         ", and mbfe writes files of its own naming there; put the input elsewhere");
      if (up == up.root_path()) break;
    }
  }
}

std::vector<std::string> model_inputs(const std::string& model_path, const ir::Model& model) {
  std::vector<std::string> inputs{model_path};
  for (std::string& file : ir::data_files(model)) inputs.push_back(std::move(file));
  return inputs;
}

}  // namespace mbfe::tool
