// mbfe generate MODEL.yaml -o DIR
#include <filesystem>
#include <iostream>

#include "tool/cli_args.h"
#include "tool/commands.h"
#include "tool/file_checks.h"
#include "generator/emit/generate_solver.h"
#include "api/file_util.h"
#include "frontend/parse_model.h"

namespace mbfe::tool {

namespace {
constexpr const char* kHelp = R"(Usage: mbfe generate MODEL.yaml -o DIR [--set PATH=VALUE ...]
       mbfe generate MODEL.yaml --expanded [--set PATH=VALUE ...]

Derives the model's equations of motion in closed form and writes the solver
sources DIR/<model>.h and DIR/<model>.cpp (DIR is created if needed). The
sources compile against runtime/abi/mbfe_model_abi.h; each opens with a banner
naming the model, the SHA-256 of the model file and the operation count of each
kernel. Output is byte-identical from run to run.

Options:
  -o, --output DIR  where the sources go
  --set PATH=VALUE  replace a value of the file first (repeatable; as for
                    mbfe simulate); the banner's SHA-256 then covers them
  --expanded        print the model as the solver is made from it instead,
                    as YAML on stdout: the --set values written in and a
                    train: expanded into its bodies, loads and contacts
                    (docs/trains.md); nothing is written

Examples:
  mbfe generate models/double_pendulum.yaml -o generated/double_pendulum
  mbfe generate models/bridge_hslm_20m.yaml --expanded --set train.hslm=A3
)";
}  // namespace

int cmd_generate(const Args& args) {
  const ParsedArgs parsed(args, {"o", "output", "set"}, {"help", "quiet", "expanded"});
  if (parsed.has("help")) {
    std::cout << kHelp;
    return 0;
  }
  if (parsed.positional().size() != 1) throw UsageError("expected one model file (see --help)");
  const auto out = parsed.value("o") ? parsed.value("o") : parsed.value("output");
  const std::string& model_path = parsed.positional()[0];
  if (parsed.has("expanded")) {
    if (out) throw UsageError("--expanded prints the model on stdout and writes no sources: leave out -o");
    std::string expanded;
    frontend::parse_model_text(frontend::read_model_file(model_path), model_path, {}, model_overrides(parsed),
                               &expanded);
    std::cout << expanded;
    return 0;
  }
  if (!out) throw UsageError("missing -o DIR (see --help)");

  check_output_folder(*out, "-o", {model_path});
  const ir::Model model = frontend::load_model_file(model_path, {}, model_overrides(parsed));
  if (model.bodies.empty())
    throw UsageError("model '" + model.name + "' has no bodies: beams need no generated code (try mbfe modal)");
  const gen::GeneratedSolver solver = gen::generate_solver(model);  // everything in memory first
  for (const auto& file : solver.files)
    check_output_file(*out + "/" + file.name, "-o", model_inputs(model_path, model), true);
  std::filesystem::create_directories(*out);
  for (const auto& file : solver.files) write_file_atomically(*out + "/" + file.name, file.text);
  if (!parsed.has("quiet")) {
    std::cerr << "mbfe: wrote";
    for (const auto& file : solver.files) std::cerr << " " << *out << "/" << file.name;
    std::cerr << " (" << solver.total_emitted() << " operations emitted, " << solver.total_executed()
              << " per call)\n";
  }
  return 0;
}

}  // namespace mbfe::tool
