#!/usr/bin/env bash
# Installs whatever is missing for building and testing geoshift on Debian 12, then builds.
# Idempotent: when nothing is missing it only checks, and the builds are incremental.
#   scripts/bootstrap.sh [--no-build] [--no-wasm] [--no-browser] [--no-python]
set -euo pipefail
cd "$(dirname "$0")/.."

build=1 wasm=1 browser=1 python=1
for a in "$@"; do
  case "$a" in
    --no-build) build=0 ;;
    --no-wasm) wasm=0 ;;
    --no-browser) browser=0 ;;
    --no-python) python=0 ;;
    *) echo "bootstrap: unknown option $a" >&2; exit 2 ;;
  esac
done

log() { printf '[bootstrap] %s\n' "$*"; }

# --- system packages -------------------------------------------------------------------------
pkgs=(cmake g++ make pkg-config libeigen3-dev libtinygltf-dev nlohmann-json3-dev catch2
      libtinyobjloader-dev libcli11-dev libbenchmark-dev libtiff-dev
      clang libclang-rt-dev)  # clang: the sanitizer build and the libFuzzer harnesses (native-asan)
[ "$wasm" = 1 ] && pkgs+=(emscripten)
[ "$browser" = 1 ] && pkgs+=(chromium)
# The Python package (python/, `pip install .` into build/venv) and its tests: Debian's Python only.
[ "$python" = 1 ] && pkgs+=(python3-dev python3-venv python3-pip python3-setuptools pybind11-dev python3-pybind11
                            python3-numpy python3-dask python3-distributed python3-psutil python3-pytest)
missing=()
for p in "${pkgs[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' || missing+=("$p")
done
if [ "${#missing[@]}" -gt 0 ]; then
  log "installing Debian packages: ${missing[*]}"
  sudo=""
  if [ "$(id -u)" != 0 ]; then
    command -v sudo >/dev/null || { echo "bootstrap: need root or sudo to install ${missing[*]}" >&2; exit 1; }
    sudo="sudo"
  fi
  export DEBIAN_FRONTEND=noninteractive
  $sudo apt-get update -qq
  $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
else
  log "Debian packages present"
fi

# --- npm packages ----------------------------------------------------------------------------
stamp=node_modules/.geoshift-lock
if [ ! -f "$stamp" ] || ! cmp -s package-lock.json "$stamp"; then
  log "npm ci"
  npm ci --no-audit --no-fund --loglevel=error
  cp package-lock.json "$stamp"
else
  log "npm packages present"
fi

[ "$build" = 1 ] || exit 0

jobs=$(nproc 2>/dev/null || echo 2)

# --- native build ----------------------------------------------------------------------------
log "native build (build/native-release)"
# With the Python package the native build also compiles the module, from the same core objects
# (position-independent, GEOSHIFT_PYTHON): pip then only copies it instead of compiling the core
# again in build/python. A build dir configured before keeps its settings (setup.py then falls back).
native=()
[ "$python" = 1 ] && native=(-DGEOSHIFT_PYTHON=ON -DPython_EXECUTABLE=/usr/bin/python3)
[ -f build/native-release/CMakeCache.txt ] || cmake --preset native-release "${native[@]}" >/dev/null
cmake --build build/native-release -j "$jobs"

# --- wasm build ------------------------------------------------------------------------------
if [ "$wasm" = 1 ]; then
  # Debian's emscripten runs its JS tools with the system node, which needs Debian's modules.
  export NODE_PATH=/usr/share/nodejs
  log "wasm build (build/wasm-release)"
  [ -f build/wasm-release/CMakeCache.txt ] || emcmake cmake --preset wasm-release >/dev/null
  cmake --build build/wasm-release -j "$jobs"
  # The npm package (package/): its TypeScript and the two web flavours, which the app imports as
  # `geoshift` (an npm workspace, docs/architecture.md#the-npm-package).
  log "npm package (package/dist)"
  node package/scripts/build.mjs
fi
# --- Python package --------------------------------------------------------------------------
# Debian's interpreter (a python3 earlier on PATH may not see Debian's packages); the venv sees
# them (--system-site-packages) and gets the package by pip, offline.
if [ "$python" = 1 ]; then
  stamp=build/venv/.geoshift-installed
  [ -x build/venv/bin/python ] || /usr/bin/python3 -m venv --system-site-packages build/venv
  if [ ! -f "$stamp" ] || [ -n "$(find python core CMakeLists.txt setup.py pyproject.toml -newer "$stamp" -type f 2>/dev/null | head -1)" ]; then
    log "Python package (the native build's module, or build/python; pip install into build/venv)"
    GEOSHIFT_PYTHON_BUILD_DIR="$PWD/build/native-release" GEOSHIFT_BUILD_JOBS="$jobs" \
      build/venv/bin/pip install --no-build-isolation --no-deps --quiet .
    touch "$stamp"
  else
    log "Python package up to date"
  fi
fi
log "ready"
