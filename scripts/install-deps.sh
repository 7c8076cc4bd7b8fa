#!/usr/bin/env bash
# Installs the Debian 12 packages mbfe needs, if any are missing.
# Safe to run repeatedly; does nothing when everything is present.
set -euo pipefail

PACKAGES=(
  build-essential cmake pkg-config git        # toolchain
  ccache                                      # compile cache: pip's build reuses this build's objects
  libginac-dev libcln-dev ginac-tools         # symbolic derivation (generator)
  libeigen3-dev libspectra-dev                # dense/sparse linear algebra, Lanczos
  libyaml-cpp-dev                             # model files
  libssl-dev                                  # SHA-256 for banners and the solver cache
  nlohmann-json3-dev                          # JSON output
  libgtest-dev libgmock-dev libbenchmark-dev  # tests and benchmarks
  gnuplot-nox                                 # pictures (mbfe plot, mbfe modal --plot)
  python3-dev pybind11-dev python3-numpy      # the Python module (docs/python.md)
  python3-venv python3-setuptools python3-wheel  # pip install . into a virtualenv (docs/python.md)
  python3-matplotlib                          # its example's picture (examples/python/)
  python3-vtk9 xvfb xauth                     # reading and rendering the animation in tests (docs/animation.md)
  python3-sympy                               # the SymPy oracle of the spatial kernels (tests/generator/)
)
# Optional extras, heavy or only for some jobs:
if [[ "${MBFE_WITH_SUNDIALS:-0}" == 1 ]]; then
  PACKAGES+=(libsundials-dev)                 # CVODE baseline of docs/accuracy-vs-cost.md (pulls MPI, PETSc)
fi
if [[ "${MBFE_WITH_SLURM:-0}" == 1 ]]; then
  PACKAGES+=(slurm-wlm munge)                 # the one-node Slurm of scripts/slurm-local.sh
fi
if [[ "${MBFE_WITH_BASELINES:-0}" == 1 ]]; then
  PACKAGES+=(libmujoco-dev)                   # MuJoCo beside the spatial kernels (docs/performance.md)
fi
if [[ "${MBFE_WITH_FUZZ:-0}" == 1 ]]; then
  PACKAGES+=(clang libclang-rt-14-dev)        # libFuzzer + sanitizer runtimes
fi

missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]} == 0)); then
  echo "install-deps: all ${#PACKAGES[@]} packages present"
  exit 0
fi
echo "install-deps: missing: ${missing[*]}"
if [[ $(id -u) -ne 0 ]]; then
  echo "install-deps: not root; run as root, or: sudo apt-get install -y ${missing[*]}" >&2
  exit 1
fi
export DEBIAN_FRONTEND=noninteractive
apt-get update -qq
apt-get install -y -qq --no-install-recommends "${missing[@]}"
echo "install-deps: installed ${#missing[@]} packages"
