#!/usr/bin/env bash
# The denoising evaluation table (issue 5): builds the native release preset if needed and runs
# eval/denoise_eval, which prints Markdown tables (RMS ×10², mean normal error, time per method).
#   scripts/eval.sh [--set tuning|validation|broad|holdout|all] [--mesh SUBSTRING] [--quick] [--markdown FILE] [--results FILE] [--data DIR]
#   scripts/eval.sh --compare BEFORE AFTER   (two --results files; docs/denoising.md#comparing-two-runs)
#   (denoise_eval --help lists the rest.)
set -euo pipefail
cd "$(dirname "$0")/.."
if [ ! -f build/native-release/CMakeCache.txt ]; then
  cmake --preset native-release >/dev/null
fi
cmake --build build/native-release -j"$(nproc)" --target denoise_eval >/dev/null
echo "machine: $(nproc) cores, $(uname -m), $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ *//')" >&2
# The broad and holdout sets' meshes are fetched from Debian's libcgal-demo the first time they are asked for.
for a in "$@"; do
  if [ "$a" = broad ] || [ "$a" = holdout ]; then bash scripts/eval-data.sh; break; fi
done
exec build/native-release/eval/denoise_eval "$@"
