#!/usr/bin/env bash
# Builds the libFuzzer target over parse + validate + generate
# (tests/fuzz/model_fuzz.cpp, body in tests/fuzz/fuzz_entry.h) with
# clang++ -fsanitize=fuzzer,address,undefined into build-fuzz/ and runs it for a
# bounded time from the committed seed corpus. Fails on any crash, sanitizer
# report, leak, time-out (10 s per input) or memory blow-up (2 GiB): the input
# that did it is left in build-fuzz/artifacts/; copy it into
# tests/fuzz/regressions/ so that the normal test suite replays it for ever.
#
# Needs clang and libclang-rt-14-dev (MBFE_WITH_FUZZ=1 scripts/install-deps.sh).
# Environment:
#   MBFE_FUZZ_SECONDS  total fuzzing time (default 120)
#   MBFE_FUZZ_MAX_LEN  longest input in bytes (default 131072)
#   MBFE_FUZZ_BUILD_DIR  build folder (default build-fuzz)
#   MBFE_JOBS          parallel compile jobs (default: nproc)
set -euo pipefail
cd "$(dirname "$0")/.."

if [[ "${MBFE_WITH_FUZZ:-0}" == 1 ]]; then
  scripts/install-deps.sh
fi
seconds="${MBFE_FUZZ_SECONDS:-120}"
# Inputs up to 128 KiB: a sum of 60,000 terms (120 KB) once crashed the
# generator, so the fuzzer must be able to write inputs that long; the seeds
# hold long chains for it to grow (tests/fuzz/corpus/v_long_*.yaml).
max_len="${MBFE_FUZZ_MAX_LEN:-131072}"
build_dir="${MBFE_FUZZ_BUILD_DIR:-build-fuzz}"
jobs="${MBFE_JOBS:-$(nproc 2>/dev/null || echo 2)}"
cxx="${MBFE_FUZZ_CXX:-clang++}"
command -v "$cxx" >/dev/null || { echo "fuzz: $cxx not found (MBFE_WITH_FUZZ=1 scripts/install-deps.sh)" >&2; exit 1; }

version=$(sed -n 's/^project(mbfe VERSION \([0-9.]*\).*/\1/p' CMakeLists.txt)
flags=(-std=c++17 -O1 -g -fno-omit-frame-pointer
       -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=undefined
       -DMBFE_GENERATOR_VERSION="\"${version}\"" -I.)
read -r -a ginac_cflags <<<"$(pkg-config --cflags ginac)"
read -r -a ginac_libs <<<"$(pkg-config --libs ginac)"
read -r -a eigen_cflags <<<"$(pkg-config --cflags eigen3)"
flags+=("${ginac_cflags[@]}" "${eigen_cflags[@]}")

sources=(ir/*.cpp frontend/*.cpp generator/symbolic/*.cpp generator/emit/*.cpp tests/fuzz/model_fuzz.cpp)
mkdir -p "$build_dir/obj" "$build_dir/corpus" "$build_dir/artifacts"

# Incremental: an object is rebuilt when its source, any header of ir/, frontend/, generator/
# or tests/fuzz/, or the flags changed.
stamp="$build_dir/obj/flags"
flag_text="$cxx ${flags[*]}"
[[ -f "$stamp" && "$(cat "$stamp")" == "$flag_text" ]] || rm -f "$build_dir"/obj/*.o
newest_header=$(ls -t ir/*.h frontend/*.h generator/*/*.h tests/fuzz/*.h | head -n1)
to_build=()
objects=()
for src in "${sources[@]}"; do
  obj="$build_dir/obj/$(echo "$src" | tr / _).o"
  objects+=("$obj")
  if [[ ! -f "$obj" || "$src" -nt "$obj" || "$newest_header" -nt "$obj" ]]; then to_build+=("$src"); fi
done
if ((${#to_build[@]})); then
  echo "fuzz: compiling ${#to_build[@]} sources with $cxx"
  printf '%s\n' "${to_build[@]}" |
    xargs -P "$jobs" -I{} sh -c 'obj="$1/obj/$(echo "$2" | tr / _).o"; shift 2; exec "$@" -c "$0" -o "$obj"' \
      {} "$build_dir" {} "$cxx" "${flags[@]}"
fi
printf '%s' "$flag_text" >"$stamp"
"$cxx" "${flags[@]}" "${objects[@]}" -o "$build_dir/model_fuzz" -lyaml-cpp "${ginac_libs[@]}" -lcln -lcrypto

# Seeds (read-only): the committed corpus, every regression, and the malformed
# corpus of the parser tests. New inputs go to the working corpus only.
seeds=(tests/fuzz/corpus tests/fuzz/regressions)
[[ -d tests/malformed ]] && seeds+=(tests/malformed)
echo "fuzz: running model_fuzz for ${seconds} s"
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"
export LSAN_OPTIONS="${LSAN_OPTIONS:-suppressions=$PWD/tests/support/lsan.supp:print_suppressions=0}"
set +e
"$build_dir/model_fuzz" "$build_dir/corpus" "${seeds[@]}" \
  -dict=tests/fuzz/model.dict -max_len="$max_len" -rss_limit_mb=2048 -timeout=10 \
  -max_total_time="$seconds" -print_final_stats=1 -artifact_prefix="$build_dir/artifacts/" \
  >"$build_dir/fuzz.log" 2>&1
status=$?
set -e
grep -E '^INFO: seed corpus' "$build_dir/fuzz.log" | head -n1 || true
grep -E '^(stat::|Done [0-9]+ runs)' "$build_dir/fuzz.log" | tail -n6 || true
if ((status != 0)); then
  tail -n 60 "$build_dir/fuzz.log"
  echo "fuzz: FAILED (status $status); the input is in $build_dir/artifacts/:" >&2
  ls -l "$build_dir/artifacts/" >&2
  echo "fuzz: copy it into tests/fuzz/regressions/ (fuzz_regressions_test replays it) and fix the bug" >&2
  exit 1
fi
execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$build_dir/fuzz.log" | tail -n1)
echo "fuzz: ok: ${execs:-?} inputs in ${seconds} s, no crash"
