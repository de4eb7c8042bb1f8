#!/usr/bin/env bash
# Runs the benchmark suite (docs/performance.md): builds Release, then measures every engine and
# POV-Ray side by side. Extra arguments go to quadrix_bench (e.g. --quick, --only spheres).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release
cmake --build build -j "$(nproc)" --target quadrix quadrix_bench
mkdir -p bench/results
./build/bench/quadrix_bench --out bench/results --quadrix build/quadrix --source . "$@"
