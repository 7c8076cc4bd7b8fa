#!/usr/bin/env bash
# Regenerates the committed solver sources generated/<model>/ of every shipped
# model that has bodies (beam-only models have no generated part).
set -euo pipefail
cd "$(dirname "$0")/.."
[[ -x build/bin/mbfe ]] || scripts/build.sh
for model in models/*.yaml; do
  grep -q '^bodies:' "$model" || continue
  name=$(sed -n 's/^model:[[:space:]]*\([A-Za-z_][A-Za-z0-9_]*\).*/\1/p' "$model")
  build/bin/mbfe generate "$model" -o "generated/$name"
done
