#!/usr/bin/env bash
# Installs what Quadrix needs to build and test, from Debian packages only (docs/dependencies.md).
# Idempotent: packages already present are skipped; apt-get runs only when something is missing.
set -euo pipefail

PACKAGES=(
  cmake ninja-build g++ pkg-config   # build
  libfmt-dev                         # formatting of messages and numbers
  libcli11-dev                       # command-line parsing
  nlohmann-json3-dev                 # JSON output (--stats --json)
  libpng-dev                         # PNG output
  libtbb-dev                         # oneTBB: parallel tiles
  libgtest-dev                       # GoogleTest
  libedit-dev                        # line editing at the uq> prompt (BSD license)
  libcairo2-dev                      # PDF/EPS output of `quadrix draw` (vector drawings)
  povray                             # the independent exact renderer the tests compare against
  clang libclang-rt-14-dev           # libFuzzer: the reader's fuzz target (tests/fuzz_reader)
  clang-format                       # scripts/check-format.sh: the checked-in .clang-format
  dpkg-dev file                      # cpack -G DEB (dpkg-shlibdeps) and its test
  libsdl2-dev xvfb xauth             # quadrix view: the window (SDL2); its tests run under Xvfb
  pybind11-dev python3-dev           # the Python module (import quadrix)
  python3-numpy python3-pytest       # its arrays and its tests
  libopenexr-dev                     # float images with depth/normal/id layers (.exr)
  libopenmpi-dev openmpi-bin         # distributed batch and tiled rendering (mpirun)
  libdeflate-dev                     # fast DEFLATE for PNG output
  libxsimd-dev                       # portable SIMD where auto-vectorisation fails
  openscad                           # .scad files with variables/modules, and the PNG comparison
)

missing=()
for p in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#PACKAGES[@]} packages present"
  exit 0
fi

SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
echo "install-deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
if ! $SUDO apt-get install -y --no-install-recommends "${missing[@]}"; then
  $SUDO apt-get update
  $SUDO apt-get install -y --no-install-recommends "${missing[@]}"
fi
