#!/usr/bin/env bash
# Page faults and start-up, side by side in one run (docs/performance.md, "Page faults and
# start-up"): the same quadrix binary with its heap in huge pages (the default) and with
# QUADRIX_HEAP_PAGES=small, alternating, on the machined part (picture defaults), the synthetic
# helicopters (bench/make_helicopter.py) and 100,000 spheres minus a cylinder, all at 1280x720;
# then start-up: `quadrix --version` and a 64x64 render against empty programs linked with the
# same shared libraries as quadrix, and with only the core ones, and the commands that load a
# module (an .exr output, a PDF drawing) next to one that does not (an SVG drawing). Prints a Markdown table of the
# minimum wall time, CPU time and page faults of REPS runs and the ratios, and writes it to
# bench/results/pages_startup_<date>.md.
#
#   bench/pages_startup.sh [QUADRIX=build/quadrix] [REPS=5]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
quadrix=$(realpath "${1:-$here/../build/quadrix}")
reps=${2:-5}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cd "$tmp"
python3 "$here/make_helicopter.py" heli.asc > /dev/null
python3 "$here/make_helicopter.py" heli130.asc --rows 130 > /dev/null
python3 - <<'PY'
import random
n = 100000
random.seed(12345)
r = (0.6 * 8000.0 / (n * 4.18879)) ** (1 / 3)
with open("spheres100k.uq", "w") as f:
    for i in range(n):
        c = [random.uniform(-10, 10) for _ in range(3)]
        k = sum(x * x for x in c) - r * r
        f.write("quadric q%d <1 1 1 0 0 0 %.9g %.9g %.9g %.9g>;\nbody s%d (q%d);\n"
                % (i, -c[0], -c[1], -c[2], k, i, i))
    f.write("quadric cyl <0.0384615 1 0.961538 0.192308 0 0 0 0 0 -16>;\n"
            "plane cl <-1 0 0 -13>;\nplane cr <1 0 0 -13>;\nbody drill (cyl cl cr);\n")
    f.write("csg balls ((" + " | ".join("s%d" % i for i in range(n)) + ") - drill) =c .9 .75 .55;\n")
    f.write("light fill .25;\nlight key .8 .5 .9 -1;\nview v dop .4 .5 -1;\n")
PY
# best ENV CMD...: "wall cpu faults", each the minimum over REPS runs (wall in milliseconds from
# posix_spawn to exit; CPU and minor faults from the child's rusage).
cat > best.py <<'PY'
import os, sys, time
reps, env = int(sys.argv[1]), sys.argv[2]
cmd = sys.argv[3:]
e = dict(os.environ)
k, _, v = env.partition("=")
e[k] = v
best = None
for _ in range(reps):
    actions = [(os.POSIX_SPAWN_OPEN, 1, os.devnull, os.O_WRONLY, 0),
               (os.POSIX_SPAWN_OPEN, 2, os.devnull, os.O_WRONLY, 0)]
    t0 = time.perf_counter()
    pid = os.posix_spawn(cmd[0], cmd, e, file_actions=actions)
    _, status, ru = os.wait4(pid, 0)
    wall = time.perf_counter() - t0
    if os.waitstatus_to_exitcode(status) != 0:
        sys.exit("failed: " + " ".join(cmd))
    r = (wall * 1e3, (ru.ru_utime + ru.ru_stime) * 1e3, ru.ru_minflt)
    best = r if best is None else tuple(min(a, b) for a, b in zip(best, r))
print("%.1f %.1f %d" % best)
PY
best() {
    python3 best.py "$reps" "$@"
}
out="| case | wall small → huge (ms) | ratio | CPU small → huge (ms) | page faults small → huge |
|---|---|---|---|---|"
row() {
    local name=$1
    shift
    read -r ws cs fs <<< "$(best QUADRIX_HEAP_PAGES=small "$@")"
    read -r wh ch fh <<< "$(best QUADRIX_HEAP_PAGES=huge "$@")"
    out+=$'\n'"| $name | $ws → $wh | $(awk -v a="$ws" -v b="$wh" 'BEGIN{printf "%.2f×", a/b}') | $cs → $ch | $fs → $fh |"
}
ex=$here/../examples
row "machined part, picture defaults" "$quadrix" render "$ex/machined_part.uq" --size 1280x720 -o o.png
row "machined part, --aa off --no-shadows" "$quadrix" render "$ex/machined_part.uq" --size 1280x720 --aa off --no-shadows -o o.png
row "helicopter, 2,211 bodies" "$quadrix" render heli.asc --top all.g --size 1280x720 -o o.png
row "helicopter, 10,131 bodies" "$quadrix" render heli130.asc --top all.g --size 1280x720 -o o.png
row "100,000 spheres − cylinder" "$quadrix" render spheres100k.uq --size 1280x720 -o o.png
# Start-up: empty programs linked like quadrix, and with the core libraries only.
echo 'int main() { return 0; }' > empty.cpp
mapfile -t libs < <(ldd "$quadrix" | awk '$3 ~ /^\// {print $3}')
g++ -O2 empty.cpp -o empty_like_quadrix -Wl,--no-as-needed "${libs[@]}"
g++ -O2 empty.cpp -o empty_core -Wl,--no-as-needed -ltbb -lfmt -lz -ldeflate -lpng16
startup="| program | shared libraries | wall (ms) | CPU (ms) | page faults |
|---|---|---|---|---|"
srow() {
    local name=$1 bin=$2
    shift 2
    read -r w c f <<< "$(best X=1 "$@")"
    startup+=$'\n'"| $name | $(ldd "$bin" | wc -l) | $w | $c | $f |"
}
srow "empty, core libraries" ./empty_core ./empty_core
srow "empty, linked like quadrix" ./empty_like_quadrix ./empty_like_quadrix
srow "quadrix --version" "$quadrix" "$quadrix" --version
srow "quadrix render, machined part 64×64" "$quadrix" "$quadrix" render "$ex/machined_part.uq" --size 64x64 -o o.png
# The commands that load a module on demand (src/quadrix/util/module_loader.h).
srow "quadrix render 64×64 to .exr (+ quadrix-exr.so)" "$quadrix" "$quadrix" render "$ex/machined_part.uq" --size 64x64 -o o.exr
srow "quadrix draw to .pdf (+ quadrix-cairo.so)" "$quadrix" "$quadrix" draw "$ex/machined_part.uq" -o o.pdf
srow "quadrix draw to .svg (no module)" "$quadrix" "$quadrix" draw "$ex/machined_part.uq" -o o.svg
cpu=$(lscpu | sed -n 's/^Model name: *//p' | head -1)
report="# Page faults and start-up, $(date -u '+%Y-%m-%d %H:%M') UTC

$cpu, $(nproc) CPUs, load average at the start: $(cut -d' ' -f1-3 /proc/loadavg); minimum of $reps runs.

$out

$startup"
echo "$report"
mkdir -p "$here/results"
echo "$report" > "$here/results/pages_startup_$(date -u '+%Y-%m-%d_%H%M%S').md"
