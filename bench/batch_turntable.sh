#!/usr/bin/env bash
# The batch benchmark of issue 22 (docs/batch.md "Measured"): a turntable of the machined part,
# FRAMES frames (default 360) at SIZE (default 1280x720), rendered
#   1. by one process:               quadrix render --turntable FRAMES
#   2. by MPI ranks:                 mpirun -np 2 quadrix render --turntable FRAMES
#   3. by FRAMES separate processes: quadrix render --az A --el 25, one per frame
#   4. by POV-Ray's animation loop of the exported scene (+KFI0 +KFF(FRAMES-1)), if povray exists
#      (exported with --shadows, as Quadrix's frames have them by default)
# then one big picture (BIG, default 3840x2160, PNG with the picture defaults) by one process and
# by `mpirun -np 2 --sort-first` (pixel bands drawn and shaded by the ranks), checked
# byte-identical, and the Frame dump of both at DUMP (default 960x540, untimed); writes the
# side-by-side table to bench/results/batch_<date>.md (and latest_batch.md). It reports, it never
# fails on time. BIG_ONLY=1 runs only the big picture (batch_big_<date>.md, latest_batch_big.md).
#
#   bench/batch_turntable.sh [QUADRIX_BINARY] [FRAMES] [SIZE]
# SAMPLE=N (environment) renders only the first N frames of the FRAMES-frame orbit in every run
# (runs 1 and 2 with --frame-range 0:N-1): the rates are per frame either way, and the table
# says how many frames were timed. On a loaded machine that keeps the runs comparable in one
# sitting.
set -uo pipefail
cd "$(dirname "$0")/.."
Q=$(realpath "${1:-build/quadrix}")
FRAMES=${2:-360}
SIZE=${3:-1280x720}
W=${SIZE%x*}
H=${SIZE#*x}
SCENE=$(realpath examples/machined_part.uq)
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
now() { date +%s.%N; }
rate() { python3 -c "import sys; f,t=float(sys.argv[1]),float(sys.argv[2]); print(f'{t:.2f} s | {f/t:.3g} frames/s | {1e3*t/f:.1f} ms')" "$1" "$2"; }
SAMPLE=${SAMPLE:-$FRAMES}
# BIG_ONLY=1: only the big picture (one process against --sort-first).
BIG_ONLY=${BIG_ONLY:-0}
RANGE=()
[ "$SAMPLE" -lt "$FRAMES" ] && RANGE=(--frame-range "0:$((SAMPLE - 1))")
rows=()

one_summary="(not run: BIG_ONLY=1)"
mpi_summary="$one_summary"
same="-"
if [ "$BIG_ONLY" != 1 ]; then
mkdir -p "$OUT/one"
t0=$(now)
"$Q" render "$SCENE" -o "$OUT/one/f.png" --size "$SIZE" --turntable "$FRAMES" --el 25 \
    "${RANGE[@]}" 2>"$OUT/one.log"
t1=$(now)
rows+=("| one process (\`render --turntable $FRAMES\`, $SAMPLE frames) | $(rate "$SAMPLE" "$(echo "$t1 - $t0" | bc)") |")
one_summary=$(tail -1 "$OUT/one.log")

if command -v mpirun >/dev/null; then
    mkdir -p "$OUT/mpi"
    t0=$(now)
    mpirun --oversubscribe -np 2 "$Q" render "$SCENE" -o "$OUT/mpi/f.png" --size "$SIZE" \
        --turntable "$FRAMES" --el 25 "${RANGE[@]}" 2>"$OUT/mpi.log"
    t1=$(now)
    rows+=("| \`mpirun -np 2\`, 2 ranks ($SAMPLE frames) | $(rate "$SAMPLE" "$(echo "$t1 - $t0" | bc)") |")
    mpi_summary=$(tail -1 "$OUT/mpi.log")
    same=0
    for f in "$OUT"/mpi/f_*.png; do cmp -s "$f" "$OUT/one/$(basename "$f")" && same=$((same + 1)); done
else
    mpi_summary="(mpirun not found)"
    same="-"
fi

mkdir -p "$OUT/sep"
# The azimuths are computed before the clock starts (a python3 per frame cost ~40 ms of each).
mapfile -t azimuths < <(python3 -c "
for i in range($SAMPLE): print(35 + 360.0 * i / $FRAMES)")
t0=$(now)
for ((i = 0; i < SAMPLE; i++)); do
    az=${azimuths[$i]}
    "$Q" render "$SCENE" -o "$(printf "$OUT/sep/f_%04d.png" "$i")" --size "$SIZE" --az "$az" \
        --el 25 2>/dev/null
done
t1=$(now)
rows+=("| separate \`quadrix render --az\` processes ($SAMPLE of $FRAMES frames timed) | $(rate "$SAMPLE" "$(echo "$t1 - $t0" | bc)") |")

if command -v povray >/dev/null; then
    "$Q" export --to pov "$SCENE" -o "$OUT/part.pov" --size "$SIZE" --shadows 2>/dev/null
    # The exported scene is in device space with a fixed camera: the solids turn with POV-Ray's
    # clock about the vertical line through the image centre instead (the same work per frame,
    # not the same pictures as the orbit).
    python3 - "$OUT/part.pov" "$OUT/anim.pov" "$W" <<'PY'
import sys, re
src = open(sys.argv[1]).read()
cx = float(sys.argv[3]) / 2
# Everything after the camera/light declarations is wrapped in a union turned by the clock.
m = re.search(r'^(union|intersection|difference|object|sphere|box|plane|quadric)\b', src, re.M)
head, body = (src[:m.start()], src[m.start():]) if m else (src, '')
open(sys.argv[2], 'w').write(head + 'union {\n' + body +
                             f'\ntranslate <{-cx},0,0> rotate y*360*clock translate <{cx},0,0>\n}}\n')
PY
    t0=$(now)
    (cd "$OUT" && povray +I"anim.pov" +O"pov_.png" +W"$W" +H"$H" +KFI0 +KFF$((FRAMES - 1)) +SF1 +EF"$SAMPLE" +KC \
        -D +FN -GA >/dev/null 2>"$OUT/pov.log")
    t1=$(now)
    rows+=("| POV-Ray 3.7 \`+KFF$((FRAMES - 1))\` of the exported scene ($SAMPLE frames timed) | $(rate "$SAMPLE" "$(echo "$t1 - $t0" | bc)") |")
fi
fi

BIG=${BIG:-3840x2160}
big_same="-"
dump_same="-"
# The big picture as PNG only (the picture defaults: shadows, anti-aliasing): with --sort-first
# each rank draws and shades its bands and rank 0 only assembles and writes (batch/sort_first.h).
# Each run's wall time and its CPU time (user + system of every process it waited for, the
# ranks included): on a machine with fewer cores than ranks × threads the wall time says little
# about sort-first, the CPU time says what it costs in all (per-rank costs that are not shared).
cpu() { python3 -c "import sys; u,s=open(sys.argv[1]).read().split(); print(f'{float(u)+float(s):.2f}')" "$1"; }
timed() {  # timed OUTVAR COMMAND...: wall seconds into OUTVAR, CPU seconds into OUTVAR_cpu
    local var=$1
    shift
    local t0 t1
    t0=$(now)
    /usr/bin/time -f "%U %S" -o "$OUT/time.txt" "$@" 2>/dev/null
    t1=$(now)
    printf -v "$var" '%s' "$(echo "$t1 - $t0" | bc)"
    printf -v "${var}_cpu" '%s' "$(cpu "$OUT/time.txt")"
}
timed big_one "$Q" render "$SCENE" -o "$OUT/big_one.png" --size "$BIG"
rows+=("| one picture at $BIG, one process (CPU $big_one_cpu s) | $(rate 1 "$big_one") |")
timed big_one1 "$Q" render "$SCENE" -o "$OUT/big_one1.png" --size "$BIG" --threads 1
rows+=("| the same, one process, \`--threads 1\` (CPU $big_one1_cpu s) | $(rate 1 "$big_one1") |")
if command -v mpirun >/dev/null; then
    timed big_mpi mpirun --oversubscribe -np 2 "$Q" render "$SCENE" -o "$OUT/big_mpi.png" \
        --size "$BIG" --sort-first
    rows+=("| one picture at $BIG, \`mpirun -np 2 --sort-first\` ($(python3 -c "print(f'{$big_one / $big_mpi:.2f}')")× one process's speed; CPU $big_mpi_cpu s) | $(rate 1 "$big_mpi") |")
    timed big_mpi1 mpirun --oversubscribe -np 2 "$Q" render "$SCENE" -o "$OUT/big_mpi1.png" \
        --size "$BIG" --sort-first --threads 1
    rows+=("| the same, \`mpirun -np 2 --sort-first --threads 1\` ($(python3 -c "print(f'{$big_one / $big_mpi1:.2f}')")× one process's speed; CPU $big_mpi1_cpu s, $(python3 -c "print(f'{$big_mpi1_cpu / $big_one1_cpu:.2f}')")× one thread's) | $(rate 1 "$big_mpi1") |")
    cmp -s "$OUT/big_one.png" "$OUT/big_mpi.png" && cmp -s "$OUT/big_one.png" "$OUT/big_mpi1.png" \
        && big_same=yes || big_same=no
    # The Frame too (a .qxf text dump, untimed, at a quarter of the size: the dump is ~40 bytes
    # of text a pixel).
    DUMP=${DUMP:-960x540}
    "$Q" render "$SCENE" -o "$OUT/d_one.png" --size "$DUMP" --dump-frame "$OUT/d_one.qxf" 2>/dev/null
    mpirun --oversubscribe -np 2 "$Q" render "$SCENE" -o "$OUT/d_mpi.png" --size "$DUMP" \
        --dump-frame "$OUT/d_mpi.qxf" --sort-first 2>/dev/null
    cmp -s "$OUT/d_one.png" "$OUT/d_mpi.png" && cmp -s "$OUT/d_one.qxf" "$OUT/d_mpi.qxf" \
        && dump_same=yes || dump_same=no
fi

mkdir -p bench/results
stamp=$(date -u +%Y-%m-%d_%H%M%S)
name=batch_  # BIG_ONLY: batch_big_…md and latest_batch_big.md, beside the whole run's files
[ "$BIG_ONLY" = 1 ] && name=batch_big_
{
    echo "# Batch benchmark: turntable of examples/machined_part.uq, $FRAMES frames at $SIZE"
    echo
    echo "$(date -u), $(nproc) hardware threads, load average $(cut -d' ' -f1-3 /proc/loadavg)."
    echo "Whole-run wall-clock time (includes process start, reading, PNG encoding and the"
    echo "atomic write with fsync of every frame)."
    echo
    echo "| run | wall time | frames/s | per frame |"
    echo "|---|---|---|---|"
    printf '%s\n' "${rows[@]}"
    echo
    echo "One process: $one_summary"
    echo
    echo "MPI: $mpi_summary"
    echo
    echo "MPI frames byte-identical to the one-process frames: $same of $SAMPLE."
    echo
    echo "Sort-first picture at $BIG (PNG) byte-identical to the one-process one: $big_same;"
    echo "at ${DUMP:-960x540} with the Frame (PNG and .qxf dump): $dump_same."
} >"bench/results/$name$stamp.md"
cp "bench/results/$name$stamp.md" "bench/results/latest_${name%_}.md"
cat "bench/results/$name$stamp.md"
