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

echo
if [ "${#failed[@]}" -gt 0 ]; then
  echo "FAILED suites: ${failed[*]}"
  exit 1
fi
echo "all suites passed"
