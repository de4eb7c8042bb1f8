#!/usr/bin/env bash
# Builds the importer and pipeline libFuzzer targets with clang (ASan + UBSan) and fuzzes each for
# a bounded time (README.md):
#
#   tests/fuzz_importers/run.sh [SECONDS_PER_TARGET] [TARGET...]   (default 30 s each, all six)
#
# Seeds: seeds/<target>/ (hand-written inputs and this issue's regressions), the freeform models of
# src/quadrix/import/freeform/testdata, and the sample files of $QUADRIX_SAMPLE_DIR (default
# /work/shared/data: BRL-CAD v4/v5 databases and the COMGEOM deck) when that directory exists.
# The freeform and pipeline targets read their first byte as a selector (format, engine), so their
# seeds get one prepended. Findings go to tests/fuzz_importers/findings/<target>/.
set -euo pipefail
seconds="${1:-30}"
shift || true
targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then targets=(v4 v5 comgeom openscad freeform pipeline); fi
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
build="${FUZZ_IMPORTERS_BUILD_DIR:-$root/build-fuzz-importers}"
samples="${QUADRIX_SAMPLE_DIR:-/work/shared/data}"
launcher=()
if command -v ccache >/dev/null; then launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi
CC=clang CXX=clang++ cmake -S "$here" -B "$build" -G Ninja "${launcher[@]}" >/dev/null
ninja -C "$build" -j "${JOBS:-2}" $(printf 'fuzz_%s ' "${targets[@]}")

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

for t in "${targets[@]}"; do
    c="$work/corpus-$t"
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
        exit 1
    fi
done
