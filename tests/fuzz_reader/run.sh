#!/usr/bin/env bash
# Builds the reader's libFuzzer target with clang (ASan + UBSan) and fuzzes for a bounded time:
#
#   tests/fuzz_reader/run.sh [SECONDS]      (default 60; CI runs it with 60)
#
# FUZZ_BUILD_ONLY=1 builds and stops; FUZZ_NO_BUILD=1 fuzzes what was built (tests/fuzz_importers/
# run.sh does both when its targets include `reader`, to fuzz it alongside the importers).
# The corpus starts from corpus/ (the examples and hand-written seeds) and regressions/ (every
# input that once broke the reader). Findings are written to tests/fuzz_reader/findings/; each one
# becomes a file of regressions/ once fixed (tests/fuzz_reader_test.cpp replays them all).
set -euo pipefail
seconds="${1:-60}"
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
build="${FUZZ_BUILD_DIR:-$root/build-fuzz}"
launcher=()
if command -v ccache >/dev/null; then launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi
if [ "${FUZZ_NO_BUILD:-0}" != 1 ]; then
    CC=clang CXX=clang++ cmake -S "$here" -B "$build" -G Ninja "${launcher[@]}" >/dev/null
    ninja -C "$build" -j "${JOBS:-2}" reader_fuzzer
fi
if [ "${FUZZ_BUILD_ONLY:-0}" = 1 ]; then exit 0; fi

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/corpus" "$here/findings"
cp "$here"/corpus/* "$here"/regressions/* "$work/corpus/"
# Files that fuzzed `read` statements may reach (relative reads resolve in the working directory).
printf 'plane from_part <1 0 0 0>; body (from_part);\n' > "$work/part"
printf 'read loop;\n' > "$work/loop"
cd "$work"
"$build/reader_fuzzer" corpus -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
  -max_len=4096 -dict="$here/uq.dict" -artifact_prefix="$here/findings/" -print_final_stats=1 \
  < /dev/null
