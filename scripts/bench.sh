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
  # The filter benchmarks run whole filters of minutes each: one repetition (their counters are
  # per-vertex figures over thousands of vertices already).
  reps=5
  case "$(basename "$exe")" in bench_mean_shift | bench_hybrid) reps=1 ;; esac
  "$exe" --benchmark_filter="$filter" --benchmark_repetitions="$reps" --benchmark_report_aggregates_only=true \
    --benchmark_display_aggregates_only=true 2>&1 | grep -v -E '_(mean|stddev|cv) ' 
done

# The same denoise job natively, in Node wasm (one thread) and in Chromium wasm (threads), with the
# wasm/native speed ratio (issue 7). It reports rows it cannot run (no Chromium) and goes on.
echo
echo "== wasm vs native: denoise (bench/wasm/denoise.mjs) =="
node bench/wasm/denoise.mjs || echo "bench/wasm/denoise.mjs failed"

# Live preview latency per mesh size (issue 21): preview() on coarse levels in Chromium (threads)
# and Node (one thread); 30k to 1M vertices, a few minutes on 2 cores.
echo
echo "== live preview latency (bench/wasm/preview.mjs) =="
node bench/wasm/preview.mjs || echo "bench/wasm/preview.mjs failed"

# Tiled filtering on Dask (issue 20): terrain-bms on the autzen LiDAR and a 4M-vertex procedural
# terrain with 1 and 2 workers (about 15 minutes on 2 cores).
echo
echo "== tiles on Dask (bench/python/tiles_bench.py) =="
if [ -x build/venv/bin/python ]; then
  build/venv/bin/python bench/python/tiles_bench.py || echo "bench/python/tiles_bench.py failed"
else
  echo "build/venv missing: run scripts/bootstrap.sh"
fi
