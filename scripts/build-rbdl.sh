#!/usr/bin/env bash
# Builds RBDL (Rigid Body Dynamics Library, https://github.com/rbdl/rbdl) from
# its public source in a scratch folder and installs it there, for the
# comparison of the spatial kernels with it (cmake/MbfeSpatialBaselines.cmake,
# docs/performance.md "Spatial models against RBDL and MuJoCo"). Debian does
# not package RBDL; nothing of it enters the repository.
#
#   scripts/build-rbdl.sh [SCRATCH]        # default SCRATCH: build/rbdl
#   cmake -S . -B build -DMBFE_RBDL_DIR=SCRATCH/install ...
#
# RBDL_SOURCE=DIR uses an unpacked source tree instead of downloading the
# release tarball (for machines without network access).
set -euo pipefail

VERSION=3.3.1
scratch=$(realpath -m "${1:-build/rbdl}")
mkdir -p "$scratch"
if [[ -n "${RBDL_SOURCE:-}" ]]; then
  source_dir=$(realpath "$RBDL_SOURCE")
else
  source_dir="$scratch/rbdl-$VERSION"
  if [[ ! -f "$source_dir/CMakeLists.txt" ]]; then
    url="https://github.com/rbdl/rbdl/archive/refs/tags/v$VERSION.tar.gz"
    echo "build-rbdl: downloading $url"
    curl -fsSL "$url" | tar -xz -C "$scratch"
  fi
fi
grep -q "RBDL_VERSION_MINOR" "$source_dir/CMakeLists.txt" ||
  { echo "build-rbdl: $source_dir is not an RBDL source tree" >&2; exit 2; }

# The library alone: no addons, no Lua, no Python, no tests.
cmake -S "$source_dir" -B "$scratch/build" -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_INSTALL_PREFIX="$scratch/install" -DRBDL_BUILD_TESTS=OFF -DRBDL_BUILD_PYTHON_WRAPPER=OFF \
  -DRBDL_BUILD_ADDON_LUAMODEL=OFF -DRBDL_BUILD_ADDON_URDFREADER=OFF -DRBDL_BUILD_EXECUTABLES=OFF >/dev/null
cmake --build "$scratch/build" -j"$(nproc)" >/dev/null
cmake --install "$scratch/build" >/dev/null
echo "build-rbdl: RBDL $VERSION installed in $scratch/install; configure mbfe with -DMBFE_RBDL_DIR=$scratch/install"
