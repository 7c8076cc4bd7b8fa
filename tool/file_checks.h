// The files a command reads and writes, checked before it starts, so that bad
// paths are bad input (UsageError, exit status 2) found before any work, and
// an output can never overwrite an input: a results file written over the
// model it came from, a picture over its CSV.
#pragma once

#include <string>
#include <vector>

#include "ir/model.h"

namespace mbfe::tool {

/// Refuses a file that cannot be read as a stream of bytes: one that does not
/// exist, a folder, a device (/dev/zero would be read without end) or a
/// socket. Regular files and pipes pass. `what` names it in the message
/// ("the results file").
/// @throws UsageError "<path>: cannot read <what>: ..." .
void check_input_file(const std::string& path, const std::string& what);

/// Refuses the output file `path` (given by `flag`) before anything is
/// written: the same file as any of `inputs` (same device and inode, whatever
/// the names), an existing folder, or a path in a folder that does not exist
/// (unless `folder_made_later`: the command creates it). A device
/// (--out /dev/null) passes.
/// @throws UsageError "<flag> <path>: ..." .
void check_output_file(const std::string& path, const std::string& flag, const std::vector<std::string>& inputs,
                       bool folder_made_later = false);

/// Refuses the output folder `dir` (given by `flag`): an existing path that is
/// not a folder, or one of `inputs`. A folder that does not exist yet passes
/// (it is created).
/// @throws UsageError "<flag> <dir>: ..." .
void check_output_folder(const std::string& dir, const std::string& flag, const std::vector<std::string>& inputs);

/// Refuses when one of `inputs` lies inside the folder `dir` (at any depth,
/// symbolic links followed): a folder the command fills with files of its
/// own naming (the --vtk frames, a sweep's points), which could replace it.
/// A folder that does not exist yet holds nothing.
/// @throws UsageError "<flag> <dir>: ..." .
void check_folder_holds_no_input(const std::string& dir, const std::string& flag,
                                 const std::vector<std::string>& inputs);

/// The model file `model_path` and the files reading it read besides (its
/// profile tables, ir::data_files): what no output of a run may overwrite.
std::vector<std::string> model_inputs(const std::string& model_path, const ir::Model& model);

}  // namespace mbfe::tool
