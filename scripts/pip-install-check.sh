#!/usr/bin/env bash
# `pip install .` into a fresh virtualenv, as a Python user installs mbfe
# (docs/python.md, "Installing with pip"): Debian's python3 with its
# site-packages (numpy, the build tools), no package index
# (--no-build-isolation), the module built by the project's CMake in a
# scratch folder. Then, from outside the repository and with a solver cache of
# its own, the installed module compiles a model and its run equals the CLI's
# (build/bin/mbfe, scripts/build.sh) to the last printed digit.
set -euo pipefail
cd "$(dirname "$0")/.."
repo=$PWD
[[ -x build/bin/mbfe ]] || { echo "pip-install-check: build/bin/mbfe missing (run scripts/build.sh first)" >&2; exit 1; }
scratch=$(mktemp -d "${TMPDIR:-/tmp}/mbfe-pip-XXXXXX")
trap 'rm -rf "$scratch"' EXIT

/usr/bin/python3 -m venv --system-site-packages "$scratch/venv"
MBFE_PIP_BUILD_DIR="${MBFE_PIP_BUILD_DIR:-$scratch/cmake}" "$scratch/venv/bin/pip" install --quiet --no-build-isolation "$repo"

export MBFE_CACHE_DIR="$scratch/cache"
model="$repo/models/double_pendulum.yaml"
build/bin/mbfe simulate "$model" --quiet --integrator rk4 --step 1e-3 --t-end 0.5 --every 1 --out "$scratch/cli.csv"
cd "$scratch"
"$scratch/venv/bin/python" - "$model" "$scratch/cli.csv" "$repo" <<'PY'
import sys
import numpy as np
import mbfe

model, cli_csv, repo = sys.argv[1:]
if mbfe.__file__.startswith(repo):
    sys.exit(f"pip-install-check: imported {mbfe.__file__}, not the installed module")
run = mbfe.load(model).simulate(integrator="rk4", step=1e-3, t_end=0.5, every=1)
cli = np.genfromtxt(cli_csv, delimiter=",", names=True)
if run.status != "completed" or len(run.t) != len(cli):
    sys.exit(f"pip-install-check: status {run.status}, {len(run.t)} rows against the CLI's {len(cli)}")
# The CSV prints 17 significant digits: the same doubles read back.
for name in cli.dtype.names:
    got = run[name]
    if not np.array_equal(got, cli[name]):
        sys.exit(f"pip-install-check: column {name} differs from the CLI's by {np.max(np.abs(got - cli[name]))}")
print(f"pip-install-check: {mbfe.__file__} ({mbfe.__version__}) equals the CLI on {len(cli)} rows x {len(cli.dtype.names)} columns")
PY
