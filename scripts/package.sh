#!/usr/bin/env bash
# Builds the npm package (package/, docs/architecture.md#the-npm-package) and packs it:
# build/package/geoshift-VERSION.tgz, the file `npm install` takes. Needs the wasm build
# (npm run package runs scripts/bootstrap.sh first).
set -euo pipefail
cd "$(dirname "$0")/.."
node package/scripts/build.mjs
mkdir -p build/package
rm -f build/package/geoshift-*.tgz
tarball=$(cd package && npm pack --pack-destination ../build/package --loglevel=error | tail -n 1)
echo "build/package/$tarball"
