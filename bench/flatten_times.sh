#!/usr/bin/env bash
# Flatten and render times of big CAD models, before and after a change (issue 20 item 5,
# docs/performance.md "Flattening big CAD models"). Runs two quadrix binaries alternately on the
# synthetic helicopter (bench/make_helicopter.py, 2,211 and 10,131 bodies) and on every shared
# BRL-CAD sample, in the default (auto-fitted) view and in --az 35 --el 25, and prints the minimum
# over REPS runs of the wall-clock `flatten` and `render` phases of `quadrix render --stats`
# (SIZE, default 512x512, --threads THREADS), with the machine load at the start and the end.
#
#   bench/flatten_times.sh BEFORE_BINARY AFTER_BINARY [REPS=3] [THREADS=1] [SIZE=512x512]
set -euo pipefail
before=$1
after=$2
reps=${3:-3}
threads=${4:-1}
size=${5:-512x512}
here=$(cd "$(dirname "$0")" && pwd)
# The shared samples sit beside the checkout (../shared from the main checkout).
samples=${QUADRIX_BRLCAD_SAMPLES:-$here/../../shared/data/brlcad}
if [ ! -d "$samples" ]; then
    echo "no BRL-CAD samples in $samples (set QUADRIX_BRLCAD_SAMPLES)" >&2
    exit 1
fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
python3 "$here/make_helicopter.py" "$tmp/heli.asc" > /dev/null
python3 "$here/make_helicopter.py" "$tmp/heli130.asc" --rows 130 > /dev/null

# min_phase BINARY PHASE ARGS...: the smallest "PHASE X s" of REPS runs.
min_phase() {
    local bin=$1 phase=$2
    shift 2
    local best=""
    for _ in $(seq "$reps"); do
        local v
        v=$("$bin" render "$@" --threads "$threads" --size "$size" --stats -o "$tmp/out.png" 2>&1 >/dev/null |
            sed -n "s/.*$phase \([0-9.]*\) s.*/\1/p" | head -1)
        best=$(awk -v a="$best" -v b="$v" 'BEGIN { print (a == "" || b + 0 < a + 0) ? b : a }')
    done
    echo "$best"
}

echo "size $size, threads $threads, load at start: $(uptime | sed 's/.*load average: //')"
echo "| model | view | flatten before | flatten after | ratio | render after |"
echo "|---|---|---|---|---|---|"
row() {
    local name=$1 view=$2
    shift 2
    local extra=()
    [ "$view" = "az35/el25" ] && extra=(--az 35 --el 25)
    local fb fa ra
    fb=$(min_phase "$before" flatten "$@" "${extra[@]}")
    fa=$(min_phase "$after" flatten "$@" "${extra[@]}")
    ra=$(min_phase "$after" render "$@" "${extra[@]}")
    echo "| $name | $view | $fb | $fa | $(awk -v a="$fb" -v b="$fa" 'BEGIN { printf (b > 0 ? (a / b >= 10 ? "%.0f×" : "%.1f×") : "—"), a / b }') | $ra |"
}
for view in default az35/el25; do
    row "helicopter (2,211 bodies)" "$view" "$tmp/heli.asc" --top all.g
    row "helicopter (10,131 bodies)" "$view" "$tmp/heli130.asc" --top all.g
done
for f in "$samples"/*.asc; do
    for view in default az35/el25; do
        row "$(basename "$f" .asc)" "$view" "$f" --allow-missing
    done
done
echo "load at end: $(uptime | sed 's/.*load average: //')"
