#!/usr/bin/env bash
# Hydro-flattening against waterbody extraction on a survey larger than memory: issue 41's "a 60 M-point tiled
# survey hydro-flattened in less than twice the time of lidarfx water on it". Makes the survey of
# bench/tiled_survey.sh (make_water_survey: 2 SIZE x SIZE metres of LAS files of 250 m, lakes and a river across
# file and tile borders), then runs `lidarfx water` and `lidarfx hydroflatten` on it with the same tiles, cells,
# memory budget and threads, taking turns; prints each one's fastest wall time, its CPU time and peak RSS, and the
# ratio hydroflatten / water (target < 2).
# Usage: bench/hydro_tiled_survey.sh [BUILD_DIR=build/release] [WORK_DIR=/tmp/lidarfx_hydro_bench]
#        environment: SIZE (metres, default 2000: 60 M points at DENSITY 7), DENSITY (pulses/m2, default 7), TILE
#        (metres, default 250), MEMORY (default 512MiB), CELL (default 2), THREADS (default 2), REPEAT (runs per
#        command, default 3), HYDRO_SIZES (hydroflatten's size options, default the ones that keep this survey's
#        ponds and river: "--min-lake-area 2000 --min-river-width 10")
# Needs the programs of the release build: lidarfx and make_water_survey.
set -euo pipefail
build="${1:-build/release}"
work="${2:-/tmp/lidarfx_hydro_bench}"
size="${SIZE:-2000}" density="${DENSITY:-7}" tile="${TILE:-250}" memory="${MEMORY:-512MiB}" cell="${CELL:-2}"
threads="${THREADS:-2}" repeat="${REPEAT:-3}"
read -r -a sizes <<< "${HYDRO_SIZES:---min-lake-area 2000 --min-river-width 10}"
lidarfx="$build/lidarfx" make="$build/make_water_survey"
for program in "$lidarfx" "$make"; do
    [ -x "$program" ] || { echo "hydro_tiled_survey: $program not found; build the release preset first" >&2; exit 1; }
done
rm -rf "$work"
mkdir -p "$work"
"$make" "$work/survey" --size "$size" --density "$density" --file 250 | tee "$work/make.txt"
points=$(awk '{print $2}' "$work/make.txt")
echo "survey: $points points; --cell $cell --tile $tile --memory $memory --threads $threads; CPU: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')"
echo "vector extensions: $(grep -m1 '^flags' /proc/cpuinfo | tr ' ' '\n' | grep -E '^(sse4_2|avx|avx2|fma|avx512f|avx512bw|avx512vl)$' | tr '\n' ' ')"
echo "load: $(uptime | sed 's/.*load average: //')"

stats() {   # file -> "wall cpu rss_kib"
    awk -F': ' '/Elapsed \(wall clock\)/ { n = split($2, t, ":"); w = (n == 3) ? t[1] * 3600 + t[2] * 60 + t[3] : t[1] * 60 + t[2] }
                /User time/ { c += $2 } /System time/ { c += $2 } /Maximum resident set size/ { r = $2 }
                END { print w, c, r }' "$1"
}
declare -A wall cpu rss
once() {   # NAME COMMAND...: keeps NAME's fastest wall (and its CPU) and largest peak RSS
    local name="$1"; shift
    /usr/bin/time -v -o "$work/time_$name.txt" "$@" > "$work/log_$name.txt" 2>&1 ||
        { echo "hydro_tiled_survey: $name failed:" >&2; tail -5 "$work/log_$name.txt" >&2; exit 1; }
    read -r w1 c1 r1 < <(stats "$work/time_$name.txt")
    if [ -z "${wall[$name]:-}" ] || awk -v a="$w1" -v b="${wall[$name]}" 'BEGIN { exit !(a < b) }'; then
        wall[$name]=$w1 cpu[$name]=$c1
    fi
    if [ "$r1" -gt "${rss[$name]:-0}" ]; then rss[$name]=$r1; fi
}
common=(--cell "$cell" --tile "$tile" --memory "$memory" --threads "$threads" --force)
for ((k = 0; k < repeat; k++)); do   # the two take turns: a slow spell of a shared machine falls on both
    once water "$lidarfx" water "$work/survey" "${common[@]}" --out "$work/out_water"
    once hydroflatten "$lidarfx" hydroflatten "$work/survey" "${common[@]}" "${sizes[@]}" --out "$work/out_hydro"
done
for name in water hydroflatten; do
    awk -v n="$name" -v w="${wall[$name]}" -v c="${cpu[$name]}" -v r="${rss[$name]}" -v p="$points" \
        'BEGIN { printf "lidarfx %-13s wall %7.2f s  cpu %7.2f s  peak RSS %7.1f MiB  %6.2f M points/s\n", n, w, c, r / 1024, p / w / 1e6 }'
done
flattened=$(awk -F, 'NR > 1 && $3 == 1' "$work/out_hydro/hydro_bodies.csv" | wc -l)
echo "bodies flattened: $flattened of $(($(wc -l < "$work/out_hydro/hydro_bodies.csv") - 1))"
awk -v a="${wall[hydroflatten]}" -v b="${wall[water]}" 'BEGIN { printf "hydroflatten / water (wall): %.2f (target < 2)\n", a / b }'
