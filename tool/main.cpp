// build/bin/mbfe: the command-line front door.
#include <cstdio>
#include <cstring>
#include <exception>
#include <iostream>
#include <map>
#include <string>

#include "tool/cli_args.h"
#include "tool/commands.h"
#include "ir/model_error.h"
#include "runtime/errors/invalid_input.h"

namespace {

constexpr const char* kUsage = R"(mbfe: symbolic multibody + finite-element beam modeler

Usage: mbfe <command> MODEL.yaml [options]     (mbfe <command> --help for details)

Commands:
  generate   write the generated C++ solver sources of a model into a folder
  eval       evaluate M, F, Q (and contact constraints) at a state, as JSON
  simulate   integrate a model in time and write a CSV
  modal      modal analysis and state-space eigenvalues (the paper's Table 1)
  stability  largest stable step of each integrator, original and adjusted
  advise     the lowest omega_limit for an accuracy tolerance, its steps and wall time
  plot       plot a results CSV to a PNG (needs gnuplot)
  sweep      a parameter study: many runs of one model, locally or on Slurm
  stats      contact-force statistics of a results column (EN 50318: filtered, windowed);
             the peak deck acceleration and its EN 1990 check

Example:
  mbfe simulate models/double_pendulum.yaml --t-end 2 --out pendulum.csv
  mbfe modal models/paper_beam.yaml

Exit status: 0 ok, 1 internal error, 2 bad input, 3 simulation failed part-way.
)";

}  // namespace

int main(int argc, char** argv) {
  using namespace mbfe::tool;
  if (argc < 2 || !std::strcmp(argv[1], "--help") || !std::strcmp(argv[1], "-h") ||
      !std::strcmp(argv[1], "help")) {
    std::cout << kUsage;
    return argc < 2 ? 2 : 0;
  }
  if (!std::strcmp(argv[1], "--version")) {
    std::cout << "mbfe " << MBFE_GENERATOR_VERSION << "\n";
    return 0;
  }
  const std::map<std::string, int (*)(const Args&)> commands = {
      {"generate", cmd_generate}, {"eval", cmd_eval},           {"simulate", cmd_simulate},
      {"modal", cmd_modal},       {"stability", cmd_stability}, {"plot", cmd_plot},
      {"sweep", cmd_sweep},       {"stats", cmd_stats},         {"advise", cmd_advise}};
  const std::string name = argv[1];
  const auto it = commands.find(name);
  if (it == commands.end()) {
    std::cerr << "mbfe: unknown command '" << name << "'\n\n" << kUsage;
    return 2;
  }
  const Args args(argv + 2, argv + argc);
  try {
    return it->second(args);
  } catch (const mbfe::ir::ModelError& e) {
    std::cerr << e.what() << "\n";
    return 2;
  } catch (const mbfe::runtime::InvalidRequest& e) {
    // The runtime names the request's field; the command line says its flag.
    std::cerr << "mbfe " << name << ": " << request_flag(e.field()) << " " << e.detail() << "\n";
    return 2;
  } catch (const mbfe::runtime::InvalidInput& e) {
    std::cerr << "mbfe " << name << ": " << e.what() << "\n";
    return 2;
  } catch (const UsageError& e) {
    std::cerr << "mbfe " << name << ": " << e.what() << "\n";
    return 2;
  } catch (const std::bad_alloc&) {
    std::cerr << "mbfe " << name << ": out of memory\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "mbfe " << name << ": error: " << e.what() << "\n";
    return 1;
  }
}
