#!/usr/bin/env bash
# Checks that every #include points down the layers (docs/architecture.md):
#
#   ir        <- frontend, generator, runtime      (the model IR: std + Eigen only)
#   frontend  <- api, tool                         (YAML -> IR)
#   generator <- api, tool                         (IR -> C++, GiNaC)
#   runtime   <- api, tool                         (numerics: Eigen, Spectra)
#   api       <- tool, python, examples            (the public C++ API)
#   tool      <- nobody                            (the command line)
#
# inside the runtime, folder by folder (each is a library of its own; see
# runtime_allowed_for below, lowest first), and that the libraries of one layer
# stay out of the headers of another (yaml-cpp only in frontend/, GiNaC only
# in generator/, OpenSSL only in frontend/). Prints every violation as
# file:line: what is wrong, and exits 1 if there is one. Run by CTest (test
# `architecture_layers`) and by hand.
set -euo pipefail
cd "$(dirname "$0")/.."

# Layer of a path -> the project folders it may include from.
allowed_for() {
  case "$1" in
    ir) echo "ir" ;;
    frontend) echo "ir frontend" ;;
    generator) echo "ir generator" ;;
    runtime) echo "ir runtime" ;;
    api) echo "ir frontend generator runtime api" ;;
    tool) echo "ir frontend generator runtime api tool" ;;
    python) echo "ir frontend generator runtime api python" ;;
    examples) echo "ir frontend generator runtime api examples" ;;
    bench) echo "ir frontend generator runtime api tests bench" ;;
    tests) echo "ir frontend generator runtime api tests" ;;
  esac
}
# Runtime folder -> the runtime folders its files may include (itself first).
runtime_allowed_for() {
  case "$1" in
    errors) echo "errors" ;;
    abi) echo "abi" ;;
    platform) echo "platform errors" ;;
    linalg) echo "linalg errors" ;;
    fem) echo "fem errors" ;;
    integrators) echo "integrators errors" ;;
    signal) echo "signal errors" ;;
    modal) echo "modal fem errors" ;;
    stability) echo "stability integrators modal errors" ;;
    damping) echo "damping modal fem integrators platform errors" ;;
    structure) echo "structure damping modal fem integrators linalg platform errors" ;;
    multibody) echo "multibody abi integrators linalg errors" ;;
    coupled) echo "coupled multibody structure damping modal fem integrators linalg stability abi platform errors" ;;
    simulation) echo "simulation coupled multibody structure damping modal fem integrators linalg stability signal abi platform errors" ;;
    advisor) echo "advisor simulation coupled multibody structure damping modal fem integrators linalg stability abi platform errors" ;;
    *) echo "" ;;
  esac
}
# Third-party headers (<prefix/...>) a layer must not include.
forbidden_system_for() {
  case "$1" in
    ir) echo "yaml-cpp ginac cln openssl Spectra nlohmann" ;;
    frontend) echo "ginac cln Spectra" ;;
    generator) echo "yaml-cpp openssl Spectra" ;;
    runtime) echo "yaml-cpp ginac cln openssl nlohmann" ;;
    api) echo "yaml-cpp ginac cln openssl" ;;
  esac
}
project_folders="ir frontend generator runtime api tool python examples bench tests"

violations=0
while IFS= read -r file; do
  layer=${file%%/*}
  allowed=$(allowed_for "$layer")
  forbidden=$(forbidden_system_for "$layer")
  # Tests of the command line's own pieces may reach into tool/.
  [[ $file == tests/tool/* ]] && allowed="$allowed tool"
  while IFS= read -r hit; do
    line=${hit%%:*}
    text=${hit#*:}
    if [[ $text =~ \#include[[:space:]]*\"([^\"/]+)/ ]]; then
      target=${BASH_REMATCH[1]}
      [[ " $project_folders " == *" $target "* ]] || continue
      if [[ " $allowed " != *" $target "* ]]; then
        echo "$file:$line: $layer/ must not include $target/ ($text)"
        violations=$((violations + 1))
      elif [[ $layer == runtime && $target == runtime && $text =~ \"runtime/([^\"/]+)/ ]]; then
        from=${file#runtime/}
        from=${from%%/*}
        to=${BASH_REMATCH[1]}
        if [[ " $(runtime_allowed_for "$from") " != *" $to "* ]]; then
          echo "$file:$line: runtime/$from/ must not include runtime/$to/ ($text)"
          violations=$((violations + 1))
        fi
      fi
    elif [[ $text =~ \#include[[:space:]]*\<([^/\>]+)/ ]]; then
      target=${BASH_REMATCH[1]}
      if [[ " $forbidden " == *" $target "* ]]; then
        echo "$file:$line: $layer/ must not include <$target/...> ($text)"
        violations=$((violations + 1))
      fi
    fi
  done < <(grep -n '^[[:space:]]*#include' "$file" || true)
done < <(git ls-files --cached --others --exclude-standard -- $(for f in $project_folders; do echo "$f/*.h" "$f/*.cpp" "$f/*.cc"; done) 2>/dev/null)

# The public C++ API (api/mbfe.h and the headers it names) reaches, through
# its project #includes, only the runtime's value types: requests, rows,
# reports, spectra, step limits, errors, the solver ABI and the modal store a
# caller may give. The runtime's classes stay behind it (docs/api.md).
public_headers="api/mbfe.h api/simulator.h api/results_output.h api/run_record.h api/vtk_animation.h"
public_runtime="runtime/abi/mbfe_model_abi.h runtime/advisor/model_spectrum.h
  runtime/damping/beam_analysis_options.h runtime/errors/invalid_input.h runtime/errors/multibody_errors.h
  runtime/integrators/integrator_spec.h runtime/integrators/simulation_result.h runtime/modal/modal_basis.h
  runtime/modal/modal_basis_store.h runtime/modal/slicing_defaults.h runtime/modal/state_spectrum.h
  runtime/simulation/model_kind.h runtime/simulation/simulation_types.h runtime/stability/step_limits.h"
declare -A reached=()
pending=($public_headers)
while ((${#pending[@]})); do
  header=${pending[0]}
  pending=("${pending[@]:1}")
  [[ -n ${reached[$header]:-} ]] && continue
  reached[$header]=1
  while IFS= read -r hit; do
    line=${hit%%:*}
    if [[ ${hit#*:} =~ \#include[[:space:]]*\"([^\"]+)\" && -f ${BASH_REMATCH[1]} ]]; then
      target=${BASH_REMATCH[1]}
      if [[ $target == runtime/* && " $(echo $public_runtime) " != *" $target "* ]]; then
        echo "$header:$line: the public API reaches the runtime's internal $target"
        violations=$((violations + 1))
      else
        pending+=("$target")
      fi
    fi
  done < <(grep -n '^[[:space:]]*#include' "$header" || true)
done

if ((violations > 0)); then
  echo "check-layers: $violations include(s) against the layering (see the comment at the top of $0)"
  exit 1
fi
echo "check-layers: every include follows the layering"
