#!/usr/bin/env bash
# Runs every suite after scripts/bootstrap.sh has built everything: native Catch2 through ctest,
# the wasm module under Node, and the browser end-to-end tests in headless Chromium. Every suite runs
# even when an earlier one fails; the exit code is non-zero if any failed.
set -uo pipefail
cd "$(dirname "$0")/.."

failed=()
section() { printf '\n===== %s =====\n' "$*"; }

section "native (ctest)"
ctest --test-dir build/native-release --output-on-failure -j "$(nproc 2>/dev/null || echo 2)" || failed+=(native)

# The same native tests under AddressSanitizer + UndefinedBehaviorSanitizer (clang RelWithDebInfo,
# every report fatal), in the build the libFuzzer harnesses share (preset native-asan); then each
# harness fuzzes for a short while (scripts/fuzz.sh; GEOSHIFT_FUZZ_SECONDS, default 15 s each).
section "native under ASan + UBSan (build/native-asan)"
asan_start=$SECONDS
asan_targets=(geoshift geoshift_fuzzers denoise_eval)  # denoise_eval: its ctest smoke tests (eval/CMakeLists.txt)
for f in tests/native/test_*.cpp; do asan_targets+=("$(basename "$f" .cpp)"); done
asan_jobs="${GEOSHIFT_BUILD_JOBS:-$(nproc 2>/dev/null || echo 2)}"
mkdir -p build/native-asan
if { [ -f build/native-asan/CMakeCache.txt ] || cmake --preset native-asan >/dev/null; } &&
   cmake --build build/native-asan -j "$asan_jobs" --target "${asan_targets[@]}" >build/native-asan/build.log 2>&1; then
  echo "built in $((SECONDS - asan_start)) s (log: build/native-asan/build.log)"
  test_start=$SECONDS
  # Reports go to files as well, so that one in a CLI run by a test that expects the CLI to fail
  # (exit code != 0) still fails the suite.
  reports="$PWD/build/native-asan/sanitizer-reports"
  rm -rf "$reports" && mkdir -p "$reports"
  ASAN_OPTIONS="halt_on_error=1:detect_leaks=1:log_path=$reports/asan" \
  UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1:log_path=$reports/ubsan" \
    ctest --test-dir build/native-asan --output-on-failure -j "$asan_jobs" || failed+=(native-asan)
  if [ -n "$(ls -A "$reports")" ]; then
    for r in "$reports"/*; do echo "--- $r"; head -n 40 "$r"; done
    failed+=(native-asan-reports)
  fi
  echo "sanitizer tests ran in $((SECONDS - test_start)) s"
  section "fuzz smoke (libFuzzer, ${GEOSHIFT_FUZZ_SECONDS:-15} s per harness)"
  # A fixed seed: every CI run starts from the same inputs, so the smoke guards against regressions
  # and a run does not fail on a defect a lucky random seed happens to find (the long runs of
  # `npm run fuzz` use random seeds to find new ones).
  GEOSHIFT_FUZZ_SEED="${GEOSHIFT_FUZZ_SEED:-1}" bash scripts/fuzz.sh "${GEOSHIFT_FUZZ_SECONDS:-15}" || failed+=(fuzz)
else
  tail -n 40 build/native-asan/build.log
  failed+=(native-asan-build)
fi
echo "sanitizers and fuzz smoke: $((SECONDS - asan_start)) s"

section "wasm (node --test)"
node --test tests/wasm/ || failed+=(wasm)

section "python (pytest; Dask LocalCluster of 2 workers)"
if [ -x build/venv/bin/python ]; then
  build/venv/bin/python -m pytest -q tests/python || failed+=(python)
else
  echo "build/venv missing: run scripts/bootstrap.sh"; failed+=(python)
fi

section "web type check (tsc)"
npx --no-install tsc -p web/tsconfig.json --noEmit && echo "tsc: no type errors" || failed+=(typecheck)

section "browser end-to-end (playwright-core + chromium)"
node --test --test-concurrency=1 tests/e2e/ || failed+=(e2e)

# The npm package as its users get it: packed, installed offline into a temporary project,
# type-checked, run under Node and bundled by Vite into a page in Chromium; and docs/api up to date.
section "npm package (pack, install, tsc, Node, Vite + chromium)"
node --test --test-concurrency=1 tests/package/ || failed+=(package)

echo
if [ "${#failed[@]}" -gt 0 ]; then
  echo "FAILED suites: ${failed[*]}"
  exit 1
fi
echo "all suites passed"
