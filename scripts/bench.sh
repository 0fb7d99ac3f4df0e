#!/usr/bin/env bash
# Runs every native benchmark (bench/*.cpp, Google Benchmark) and prints its table: medians over
# 5 repetitions, with the machine's core count, since these machines are shared and noisy.
#   scripts/bench.sh [FILTER-REGEX]
set -euo pipefail
cd "$(dirname "$0")/.."
filter="${1:-.}"
echo "machine: $(nproc) cores, $(uname -m), $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ *//')"
for exe in build/native-release/bench/bench_*; do
  [ -x "$exe" ] || continue
  echo
  echo "== $(basename "$exe") =="
  "$exe" --benchmark_filter="$filter" --benchmark_repetitions=5 --benchmark_report_aggregates_only=true \
    --benchmark_display_aggregates_only=true 2>&1 | grep -v -E '_(mean|stddev|cv) ' 
done
