# Sourced by scripts/build.sh and scripts/sanitize.sh: sets `launcher` to the
# CMake arguments that compile through ccache when it is installed
# (install-deps.sh installs it), so that a later build of the same sources in
# the same folder (the next CI run, pip's own build folder) compiles only what
# changed. The test files' precompiled header is cacheable only with these
# sloppiness settings (ccache's manual, "Precompiled headers"); nothing of
# ours reads __DATE__ or __TIME__.
launcher=()
if command -v ccache >/dev/null; then
  launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
  export CCACHE_SLOPPINESS="${CCACHE_SLOPPINESS:-pch_defines,time_macros,include_file_mtime,include_file_ctime}"
fi
