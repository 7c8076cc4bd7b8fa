#!/usr/bin/env bash
# Regenerates the tables of docs/accuracy-vs-cost-coupled.md between its
# "adjustment-errors" markers: adjusted runs against a converged reference of
# the original model, for every study of bench/adjustment_error_studies.yaml.
#
#   scripts/adjustment_error_study.sh            # every study (about 20 minutes on 2 cores)
#   scripts/adjustment_error_study.sh --only Vehicle   # the studies whose title has the text
#
# Configures the study build folder build-study (Release, no tests), builds the
# program bench/adjustment_error_study.cpp and runs it. With --only the tables
# are printed, not written into the document.
set -euo pipefail
cd "$(dirname "$0")/.."
doc=docs/accuracy-vs-cost-coupled.md

cmake -S . -B build-study -DCMAKE_BUILD_TYPE=Release -DMBFE_BUILD_TESTS=OFF >/dev/null
cmake --build build-study -j"${MBFE_JOBS:-2}" --target adjustment_error_study

if [[ $# -gt 0 ]]; then
  exec build-study/bin/adjustment_error_study bench/adjustment_error_studies.yaml "$@"
fi

out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
build-study/bin/adjustment_error_study bench/adjustment_error_studies.yaml --markdown "$out/tables.md"

cpu=$(lscpu | sed -n 's/^Model name:[[:space:]]*//p' | head -1)
{
  echo "Machine: ${cpu}, $(nproc) cores; $(g++ --version | head -1); load average at the end of the run: $(cut -d' ' -f1-3 /proc/loadavg); $(date -u +%Y-%m-%d)."
  echo
  cat "$out/tables.md"
} > "$out/block.md"

python3 - "$doc" "$out/block.md" <<'PY'
import sys
doc, block = sys.argv[1], open(sys.argv[2]).read()
text = open(doc).read()
begin, end = "<!-- adjustment-errors:begin (scripts/adjustment_error_study.sh) -->", "<!-- adjustment-errors:end -->"
i, j = text.index(begin) + len(begin), text.index(end)
open(doc, "w").write(text[:i] + "\n" + block + text[j:])
PY
echo "adjustment_error_study: wrote the tables of ${doc}"
