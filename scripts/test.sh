#!/usr/bin/env bash
# Builds and runs the whole test suite twice: a Release build with warnings as errors, then an
# AddressSanitizer + UndefinedBehaviorSanitizer build. Fails if anything fails.
set -euo pipefail
cd "$(dirname "$0")/.."
JOBS="${JOBS:-$(nproc)}"
phase() { echo "== $* (at ${SECONDS} s)"; }

phase "Formatting (.clang-format; scripts/check-format.sh)"
bash scripts/check-format.sh

phase "Release build (-Werror)"
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DQUADRIX_WERROR=ON
cmake --build build -j "$JOBS"
phase "Release tests"
ctest --test-dir build --output-on-failure -j "$JOBS"

phase "ASan+UBSan build"
cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=Debug -DQUADRIX_WERROR=ON \
      -DQUADRIX_SANITIZE=ON -DQUADRIX_BUILD_BENCH=OFF
cmake --build build-asan -j "$JOBS"
phase "ASan+UBSan tests"
ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  LSAN_OPTIONS=suppressions="$PWD/tests/lsan.supp" ctest --test-dir build-asan --output-on-failure -j "$JOBS"
# Fuzzing (libFuzzer; tests/fuzz_reader/README.md, tests/fuzz_importers/README.md): the language
# reader and the importers' five targets, 60 s each, two at a time (the machine has nothing else to
# do here), about 3 minutes. The pipeline target, which needs the whole library built with clang,
# is for long runs (FUZZ_TARGETS="reader v4 v5 comgeom openscad freeform pipeline").
read -r -a fuzz_targets <<< "${FUZZ_TARGETS:-reader v4 v5 comgeom openscad freeform}"
fuzz_seconds="${FUZZ_SECONDS:-60}"
phase "Fuzzing (libFuzzer, ${fuzz_targets[*]}: $fuzz_seconds s each, ${FUZZ_JOBS:-2} at a time)"
FUZZ_JOBS="${FUZZ_JOBS:-2}" bash tests/fuzz_importers/run.sh "$fuzz_seconds" "${fuzz_targets[@]}"
phase "all tests passed"
