// The subcommands of `mbfe`. Each lives in its own cmd_<name>.cpp, takes the
// arguments after the subcommand name and returns the process exit status:
// 0 success, 1 internal failure, 2 bad input (model file or flags),
// 3 a simulation that diverged or failed part-way (output so far kept).
#pragma once

#include <string>
#include <vector>

namespace mbfe::tool {

using Args = std::vector<std::string>;

int cmd_generate(const Args& args);
int cmd_eval(const Args& args);
int cmd_simulate(const Args& args);
int cmd_modal(const Args& args);
int cmd_stability(const Args& args);
int cmd_advise(const Args& args);
int cmd_plot(const Args& args);
int cmd_sweep(const Args& args);
int cmd_stats(const Args& args);

}  // namespace mbfe::tool
