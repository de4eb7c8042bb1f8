#!/usr/bin/env bash
# Builds the importer and pipeline libFuzzer targets with clang (ASan + UBSan) and fuzzes each for
# a bounded time (README.md):
#
#   tests/fuzz_importers/run.sh [SECONDS_PER_TARGET] [TARGET...]   (default 30 s each, all six)
#
# TARGET is one of v4 v5 comgeom openscad freeform pipeline, or `reader`: the language reader's
# target (tests/fuzz_reader/run.sh, built here first), so that one run can schedule them all.
# FUZZ_JOBS=N fuzzes N targets at once (default 1; scripts/test.sh runs 2 on its 2 cores): every
# target is built first, then each runs in its own process with its own corpus copy and log, the
# log printed when the target ends. The run fails when any target leaves a finding.
#
# Seeds: seeds/<target>/ (hand-written inputs and this issue's regressions), the freeform models of
# src/quadrix/import/freeform/testdata, and the sample files of $QUADRIX_SAMPLE_DIR (default
# /work/shared/data: BRL-CAD v4/v5 databases and the COMGEOM deck) when that directory exists.
# The freeform and pipeline targets read their first byte as a selector (format, engine), so their
# seeds get one prepended. Findings go to tests/fuzz_importers/findings/<target>/ (the reader's to
# tests/fuzz_reader/findings/).
set -euo pipefail
seconds="${1:-30}"
shift || true
targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then targets=(v4 v5 comgeom openscad freeform pipeline); fi
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
build="${FUZZ_IMPORTERS_BUILD_DIR:-$root/build-fuzz-importers}"
samples="${QUADRIX_SAMPLE_DIR:-/work/shared/data}"
# FUZZ_PREBUILT=1: $build is the main tree's sanitizer build configured with -DQUADRIX_FUZZ=ON
# (cmake/QuadrixFuzz.cmake; scripts/test.sh), which holds every target, the reader's included:
# nothing is configured here, the targets are only brought up to date.
prebuilt="${FUZZ_PREBUILT:-0}"
launcher=()
if command -v ccache >/dev/null; then launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi
if [ "$prebuilt" != 1 ]; then
    CC=clang CXX=clang++ cmake -S "$here" -B "$build" -G Ninja "${launcher[@]}" >/dev/null
fi
jobs="${FUZZ_JOBS:-1}"
reader=0
built=()
for t in "${targets[@]}"; do
    case "$t" in
        reader) reader=1 ;;
        v4|v5|comgeom|openscad|freeform|pipeline) built+=("fuzz_$t") ;;
        *) echo "run.sh: unknown target '$t' (v4 v5 comgeom openscad freeform pipeline reader)" >&2
           exit 2 ;;
    esac
done
if [ "$prebuilt" = 1 ] && [ "$reader" = 1 ]; then built+=(reader_fuzzer); fi
if [ ${#built[@]} -gt 0 ]; then ninja -C "$build" -j "${JOBS:-2}" "${built[@]}"; fi
if [ "$reader" = 1 ] && [ "$prebuilt" != 1 ]; then FUZZ_BUILD_ONLY=1 bash "$root/tests/fuzz_reader/run.sh"; fi
reader_env=()
if [ "$prebuilt" = 1 ]; then reader_env=(FUZZ_BUILD_DIR="$build"); fi

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
freeform="$root/src/quadrix/import/freeform/testdata"

# seed FILE DIR [SELECTOR...]: copies FILE (its first 8 KiB) into DIR, once per selector byte.
seed() {
    local file="$1" dir="$2" base
    shift 2
    base="$(basename "$file")"
    if [ $# -eq 0 ]; then head -c 8192 "$file" > "$dir/$base"; return; fi
    for s in "$@"; do
        { printf "\\$(printf '%03o' "$s")"; head -c 8191 "$file"; } > "$dir/$s.$base"
    done
}

# fuzz_one TARGET: prepares the target's corpus and fuzzes it; its output goes to $work/log-TARGET.
# Exits non-zero when the target left a finding.
fuzz_one() {
    local t="$1" c="$work/corpus-$1" f
    if [ "$t" = reader ]; then
        local rc=0
        echo "== reader (tests/fuzz_reader/run.sh), $seconds s"
        env "${reader_env[@]}" FUZZ_NO_BUILD=1 bash "$root/tests/fuzz_reader/run.sh" "$seconds" > "$work/raw-reader" 2>&1 || rc=$?
        grep -E "^(#[0-9]+ *DONE|stat::number_of_executed_units|INFO: seed)|ERROR|SUMMARY|violated|artifact" \
            "$work/raw-reader" || true
        if [ "$rc" != 0 ]; then tail -40 "$work/raw-reader"; echo "reader: findings in $root/tests/fuzz_reader/findings" >&2; fi
        return "$rc"
    fi
    mkdir -p "$c" "$here/findings/$t"
    case "$t" in
        v4|v5|comgeom|openscad) for f in "$here/seeds/$t"/*; do [ -f "$f" ] && seed "$f" "$c"; done ;;
    esac
    case "$t" in
        v4) for f in "$samples"/brlcad/*.asc; do
                [ -f "$f" ] && head -1 "$f" | grep -q '^I ' && seed "$f" "$c"; done ;;
        v5) for f in "$samples"/brlcad/*.asc; do
                [ -f "$f" ] && ! head -1 "$f" | grep -q '^I ' && seed "$f" "$c"; done ;;
        comgeom) for f in "$samples"/brlcad/comgeom/*.comgeom; do [ -f "$f" ] && seed "$f" "$c"; done ;;
        freeform)  # selector % 4: 0 Newell, 1 bpt, 2 Geomview, 3 OBJ
            for f in "$freeform"/newell/*; do seed "$f" "$c" 0; done
            for f in "$freeform"/bpt/*; do seed "$f" "$c" 1; done
            for f in "$freeform"/geomview/*; do seed "$f" "$c" 2; done
            for f in "$freeform"/obj/*; do seed "$f" "$c" 3; done ;;
        pipeline)  # selector % 5: .uq .asc .scad .obj .bpt; (selector / 5) % 4: the engine
            for f in "$root"/examples/*.uq "$root"/tests/fuzz_reader/corpus/*.uq; do
                seed "$f" "$c" 0 5 10 15; done
            for f in "$here"/seeds/v5/* "$samples"/brlcad/cornell.asc "$samples"/brlcad/operators.asc; do
                [ -f "$f" ] && seed "$f" "$c" 1 6; done
            for f in "$here"/seeds/openscad/*; do seed "$f" "$c" 2 7 12; done
            seed "$freeform/obj/sphere_nurbs.obj" "$c" 3
            seed "$freeform/bpt/teacup.bpt" "$c" 4 ;;
    esac
    echo "== fuzz_$t: $(ls "$c" | wc -l) seeds, $seconds s"
    mkdir -p "$work/run-$t"
    (cd "$work/run-$t" && "$build/fuzz_$t" "$c" -max_total_time="$seconds" -timeout=10 \
        -rss_limit_mb=2048 -max_len=8192 -artifact_prefix="$here/findings/$t/" \
        -print_final_stats=1 < /dev/null 2>&1 | grep -E "^(==|#[0-9]+ *DONE|stat::number_of_executed_units|INFO: seed)|ERROR|SUMMARY|violated" || true)
    # A finding leaves a crash-/timeout-/oom- file: fail.
    if compgen -G "$here/findings/$t/crash-*" >/dev/null || compgen -G "$here/findings/$t/timeout-*" >/dev/null ||
       compgen -G "$here/findings/$t/oom-*" >/dev/null || compgen -G "$here/findings/$t/leak-*" >/dev/null; then
        echo "fuzz_$t: findings in $here/findings/$t" >&2
        return 1
    fi
}

# At most $jobs targets at once; each log is printed when its target ends.
declare -A pids=()
failed=()
finish() {  # waits for any one target, prints its log, records a failure
    local done_pid rc=0 t
    wait -n -p done_pid "${!pids[@]}" || rc=$?
    t="${pids[$done_pid]}"
    unset "pids[$done_pid]"
    cat "$work/log-$t"
    if [ "$rc" != 0 ]; then failed+=("$t"); fi
}
for t in "${targets[@]}"; do
    while [ ${#pids[@]} -ge "$jobs" ]; do finish; done
    fuzz_one "$t" > "$work/log-$t" 2>&1 &
    pids[$!]="$t"
done
while [ ${#pids[@]} -gt 0 ]; do finish; done
if [ ${#failed[@]} -gt 0 ]; then
    echo "fuzzing: findings (or a failed run) in ${failed[*]}" >&2
    exit 1
fi
