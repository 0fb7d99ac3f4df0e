#!/usr/bin/env bash
# Fuzzes the readers, mesh building and a short filter run with libFuzzer (clang, AddressSanitizer,
# UndefinedBehaviorSanitizer, every report fatal):
#   npm run fuzz [-- SECONDS [HARNESS...]]   (default 60 seconds per harness, every harness)
# The harnesses (fuzz/) are built in build/native-asan (CMake preset native-asan, shared with the
# sanitizer run of the native tests in scripts/test.sh, which calls this script for its smoke run):
#   gltf glb obj off ply stl   fuzz/read_mesh.cpp: readDocument, then buildMesh of every part
#   las tif                    fuzz/read_terrain.cpp: readTerrain (LAS + Delaunay, GeoTIFF + grid)
#   ply_points                 fuzz/read_ply_points.cpp: readPlyPoints
#   soup                       fuzz/build_soup.cpp: buildMesh / withTwins of arbitrary soups
#   filter                     fuzz/filter_soup.cpp: a short mean shift and denoise of such a mesh
# Each is seeded from fuzz/seeds/NAME (the mesh readers also from tests/data/damaged) with
# fuzz/dict/NAME.dict when there is one. The growing corpus
# stays in build/native-asan/fuzz/corpus/NAME; GEOSHIFT_FUZZ_SEED fixes libFuzzer's seed (random
# otherwise). Inputs that crash go to
# build/native-asan/fuzz/artifacts/NAME/ and make the script fail. Prints the executions each reached.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-60}"
shift || true
all=(gltf glb obj off ply stl las tif ply_points soup filter)
harnesses=("$@")
[ "${#harnesses[@]}" -gt 0 ] || harnesses=("${all[@]}")
jobs="${GEOSHIFT_BUILD_JOBS:-2}"
log() { printf '[fuzz] %s\n' "$*"; }

# clang and its runtime libraries (libFuzzer, sanitizers): Debian's clang and libclang-rt-dev
# (scripts/bootstrap.sh installs them too; this is for `npm run fuzz` on a machine without them).
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

build=build/native-asan
[ -f "$build/CMakeCache.txt" ] || cmake --preset native-asan >/dev/null
cmake --build "$build" -j "$jobs" --target "${harnesses[@]/#/fuzz_}" >/dev/null

export ASAN_OPTIONS="detect_leaks=1:allocator_may_return_null=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
failed=0
summary=()
for f in "${harnesses[@]}"; do
  out="$build/fuzz"
  corpus="$out/corpus/$f" artifacts="$out/artifacts/$f/"
  mkdir -p "$corpus" "$artifacts"
  logf="$out/fuzz_$f.log"
  seeds="fuzz/seeds/$f" dict="fuzz/dict/$f.dict"
  case "$f" in
    glb) dict=fuzz/dict/gltf.dict ;;  # the JSON chunk's words
    ply_points) dict=fuzz/dict/ply.dict seeds=fuzz/seeds/ply ;;
    filter) seeds=fuzz/seeds/soup ;;
  esac
  # The damaged catalogue (tests/data/damaged, one file per way a file can be wrong) seeds the mesh
  # readers too: copied into the corpus, which libFuzzer then minimises like any other input.
  case "$f" in
    gltf|glb|obj|off|ply|stl) cp tests/data/damaged/*."$f" "$corpus"/ 2>/dev/null || true ;;
  esac
  args=("$corpus")
  [ -d "$seeds" ] && args+=("$seeds")
  [ -f "$dict" ] && args+=("-dict=$dict")
  [ -n "${GEOSHIFT_FUZZ_SEED:-}" ] && args+=("-seed=$GEOSHIFT_FUZZ_SEED")
  log "fuzz_$f for ${seconds} s (log: $logf)"
  status=0
  "$build/fuzz/fuzz_$f" "${args[@]}" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
    -max_len=65536 -print_final_stats=1 -artifact_prefix="$artifacts" >"$logf" 2>&1 || status=$?
  runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$logf" | grep -o '[0-9]*$' || echo '?')
  if [ "$status" != 0 ]; then
    failed=1
    summary+=("fuzz_$f: FAILED after $runs executions (exit $status); input in $artifacts, see $logf")
    # The report itself, for a log that is all one has (CI).
    grep -m1 -A25 -E '^==[0-9]+==ERROR|runtime error|^ALARM|deadly signal' "$logf" | sed 's/^/[fuzz]   /' || true
  else
    summary+=("fuzz_$f: $runs executions in ${seconds} s, no crash")
  fi
done
for s in "${summary[@]}"; do log "$s"; done
exit "$failed"
