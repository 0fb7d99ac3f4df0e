#!/usr/bin/env bash
# Fuzzes every mesh reader with libFuzzer (clang, AddressSanitizer, UndefinedBehaviorSanitizer):
#   npm run fuzz [-- SECONDS]      (default 60 seconds per harness)
# Harnesses: fuzz/read_mesh.cpp built once per format (gltf glb obj off ply stl) and
# fuzz/read_ply_points.cpp (terrain point sets) in build/fuzz, seeded from fuzz/seeds/FORMAT, with
# fuzz/dict/FORMAT.dict. The growing corpus stays in
# build/fuzz/corpus/FORMAT; inputs that crash go to build/fuzz/artifacts/FORMAT/ and make the
# script fail. Prints the executions each harness reached.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-60}"
jobs="${GEOSHIFT_BUILD_JOBS:-2}"
log() { printf '[fuzz] %s\n' "$*"; }

# clang and its runtime libraries (libFuzzer, sanitizers): Debian's clang and libclang-rt-dev.
missing=()
for p in clang libclang-rt-dev cmake; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' || missing+=("$p")
done
if [ "${#missing[@]}" -gt 0 ]; then
  log "installing Debian packages: ${missing[*]}"
  sudo=""
  [ "$(id -u)" != 0 ] && sudo="sudo"
  export DEBIAN_FRONTEND=noninteractive
  $sudo apt-get update -qq
  $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

build=build/fuzz
formats=(gltf glb obj off ply stl ply_points)
CC=clang CXX=clang++ cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DGEOSHIFT_FUZZ=ON >/dev/null
cmake --build "$build" -j "$jobs" --target "${formats[@]/#/fuzz_}" >/dev/null

export ASAN_OPTIONS="detect_leaks=1:allocator_may_return_null=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
failed=0
summary=()
for f in "${formats[@]}"; do
  corpus="$build/corpus/$f" artifacts="$build/artifacts/$f/"
  mkdir -p "$corpus" "$artifacts"
  logf="$build/fuzz_$f.log"
  dict="fuzz/dict/$f.dict" seeds="fuzz/seeds/$f"
  [ "$f" = glb ] && dict=fuzz/dict/gltf.dict  # the JSON chunk's words
  [ "$f" = ply_points ] && dict=fuzz/dict/ply.dict seeds=fuzz/seeds/ply
  log "fuzz_$f for ${seconds} s (log: $logf)"
  status=0
  "$build/fuzz/fuzz_$f" "$corpus" "$seeds" -dict="$dict" -max_total_time="$seconds" \
    -timeout=10 -rss_limit_mb=2048 -max_len=65536 -print_final_stats=1 -artifact_prefix="$artifacts" \
    >"$logf" 2>&1 || status=$?
  runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$logf" | grep -o '[0-9]*$' || echo '?')
  if [ "$status" != 0 ]; then
    failed=1
    summary+=("fuzz_$f: FAILED after $runs executions (exit $status); input in $artifacts, see $logf")
  else
    summary+=("fuzz_$f: $runs executions in ${seconds} s, no crash")
  fi
done
for s in "${summary[@]}"; do log "$s"; done
exit "$failed"
