#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Issue 12's solar peers: GRASS GIS `r.sunmask` against lidarfx's raylines_shadow (one sun position) and
# `r.horizon` (one direction) against lidarfx's horizon_map, on the same DSM in the same run. The DSM is the
# box town of bench/bench_shadow.cpp (1 m cells, buildings 8..30 m on a side, 3..25 m tall over noisy, tilted
# ground), written raw by bench/solar_peer and imported into a temporary GRASS location (r.in.bin) in UTM 33N
# (EPSG:32633) centred on the zone's central meridian, so that cells are metres and grid north is true north
# (r.horizon turns directions by the meridian convergence; r.horizon refuses an XY location).
#
# Prints the CPU's vector extensions, the wall and CPU (user + system) time of each side, the ratio
# GRASS / lidarfx (> 1: lidarfx is faster), and how the results agree: the share of cells where r.sunmask's
# shadow (1, else NULL) matches raylines_shadow's (0 = shadow), and the largest and mean absolute difference
# of the horizon angle between r.horizon -d (clipped at 0: lidarfx's horizon is never below the horizontal)
# and horizon_map, with the share of cells within 1 degree. Only the kernels are timed: lidarfx's times are
# the kernel alone (best of $REPEAT, bench/solar_peer), GRASS's the module's whole run (best of $REPEAT for
# r.horizon; r.sunmask once, as it takes minutes), its import and export not counted. GRASS 8.2's modules
# run on one thread; lidarfx is timed on one thread and on all cores.
#
# Skips with a message when grass is absent (apt-get install --no-install-recommends grass-core).
#
# Usage: bash bench/peers/grass_solar.sh [N ...]   (after `cmake --preset bench &&
#        cmake --build --preset bench --target solar_peer`)
#   N         side of the square DSM in cells (default: 1024); several sizes run one after another
# Environment: BUILD (default build/bench), AZIMUTH (sun azimuth and horizon direction, degrees clockwise
#   from north; default 135), ELEVATION (sun elevation, degrees; default 30), REPEAT (default 3),
#   SUNMASK_MAX_N (largest N given to r.sunmask, default 1024: r.sunmask marches every cell towards the sun
#   and needs about 34 s for 256² here, ~9 min for 1024²), PYTHON (default /usr/bin/python3, with numpy).
set -euo pipefail
cd "$(dirname "$0")/../.."
build="${BUILD:-build/bench}"
repeat="${REPEAT:-3}"
azimuth="${AZIMUTH:-135}"
elevation="${ELEVATION:-30}"
sunmask_max_n="${SUNMASK_MAX_N:-1024}"
python="${PYTHON:-/usr/bin/python3}"
sizes=("$@")
[[ ${#sizes[@]} -gt 0 ]] || sizes=(1024)

grass="$(command -v grass || true)"
if [[ -z "$grass" ]]; then
    echo "grass_solar: skipped: no grass program on PATH (apt-get install --no-install-recommends grass-core)"
    exit 0
fi
if ! "$python" -c 'import numpy' 2>/dev/null; then
    echo "grass_solar: skipped: $python lacks numpy (apt-get install python3-numpy)"
    exit 0
fi
solar_peer="$(realpath -m "$build/bench/solar_peer")"
[[ -x "$solar_peer" ]] || { echo "$solar_peer not found: build with cmake --preset bench &&" \
                                 "cmake --build --preset bench --target solar_peer" >&2; exit 2; }

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
# r.horizon's direction: degrees counterclockwise from east.
direction="$(awk -v a="$azimuth" 'BEGIN { d = 90 - a; while (d < 0) d += 360; while (d >= 360) d -= 360; print d }')"

echo "CPU: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs), $(nproc) cores; vector extensions:" \
     "$(grep -o -w -E 'avx512f|avx2|sse4_2' /proc/cpuinfo | sort -u | xargs)"
echo "$("$grass" --version 2>&1 | head -n 1); sun azimuth $azimuth°, elevation $elevation°;" \
     "horizon towards azimuth $azimuth° (r.horizon direction=$direction)"

# Runs inside the GRASS session: imports town.f32, runs each module ($repeat times, or once for r.sunmask),
# appends "name wall cpu" lines to times.txt (best wall, best CPU) and exports the results raw.
cat >"$work/inside.sh" <<'EOF'
set -euo pipefail
cd "$WORK"
half=$((N / 2))
r.in.bin -f input=town.f32 output=dsm rows="$N" cols="$N" bytes=4 --quiet \
    north=$((5000000 + half)) south=$((5000000 - N + half)) east=$((500000 + N - half)) west=$((500000 - half))
g.region raster=dsm
timed() {  # name runs command...: best wall and CPU seconds over runs
    local name="$1" runs="$2"; shift 2
    for _ in $(seq "$runs"); do
        /usr/bin/time -f "%e %U %S" -o time.txt "$@" --overwrite --quiet >log.txt 2>&1 || { cat log.txt >&2; exit 1; }
        tail -n 1 time.txt
    done | awk -v n="$name" '{ w = $1; c = $2 + $3; if (NR == 1 || w < bw) bw = w; if (NR == 1 || c < bc) bc = c }
                             END { print n, bw, bc }' >>times.txt
}
timed r.horizon "$REPEAT" r.horizon -d elevation=dsm direction="$DIRECTION" output=hor
r.out.bin -f input="$(g.list raster pattern='hor_*' | head -n 1)" output=grass_horizon.f32 null=-9999 --quiet
if [[ "$SUNMASK" == 1 ]]; then
    timed r.sunmask 1 r.sunmask elevation=dsm output=sunmask altitude="$ELEVATION" azimuth="$AZIMUTH"
    r.out.bin input=sunmask output=grass_shadow.u8 bytes=1 null=0 --quiet
fi
EOF

for n in "${sizes[@]}"; do
    echo
    echo "== ${n}² cells, 1 m =="
    rm -f "$work"/*.f32 "$work"/*.u8 "$work/times.txt"
    "$solar_peer" town "$n" "$work/town.f32"
    for threads in 1 0; do
        s="$("$solar_peer" shadow "$work/town.f32" "$n" "$azimuth" "$elevation" "$threads" "$repeat" "$work/lidarfx_shadow.u8")"
        echo "raylines_shadow/$threads $(echo "$s" | awk '/^seconds/ { print $2, $2 }')" >>"$work/times.txt"
        s="$("$solar_peer" horizon "$work/town.f32" "$n" "$azimuth" "$threads" "$repeat" "$work/lidarfx_horizon.f32")"
        echo "horizon_map/$threads $(echo "$s" | awk '/^seconds/ { print $2, $2 }')" >>"$work/times.txt"
    done
    sunmask=1
    if (( n > sunmask_max_n )); then
        sunmask=0
        echo "r.sunmask skipped at ${n}² (> SUNMASK_MAX_N=$sunmask_max_n: it would take hours)"
    fi
    WORK="$work" N="$n" REPEAT="$repeat" DIRECTION="$direction" AZIMUTH="$azimuth" ELEVATION="$elevation" \
    SUNMASK="$sunmask" "$grass" --tmp-location EPSG:32633 --exec bash "$work/inside.sh" >"$work/grass.log" 2>&1 \
        || { cat "$work/grass.log" >&2; exit 1; }
    "$python" - "$work" "$n" "$(nproc)" <<'EOF'
import os, sys
import numpy as np
work, n, cores = sys.argv[1], int(sys.argv[2]), sys.argv[3]
times = {}
for line in open(os.path.join(work, "times.txt")):
    name, wall, cpu = line.split()
    times[name] = (float(wall), float(cpu))
cells = n * n
print(f"{'':28} {'wall s':>10} {'M cells/s':>10}")
for name, (wall, cpu) in times.items():
    label = name.replace("/1", ", 1 thread").replace("/0", f", {cores} threads")
    print(f"{label:28} {wall:10.4f} {cells / wall / 1e6:10.2f}" + (f"   (CPU {cpu:.2f} s)" if name.startswith("r.") else ""))
for peer, ours in (("r.sunmask", "raylines_shadow"), ("r.horizon", "horizon_map")):
    if peer in times:
        w = times[peer][0]
        print(f"ratio {peer} / {ours}: {w / times[ours + '/1'][0]:.0f}x (1 thread), "
              f"{w / times[ours + '/0'][0]:.0f}x ({cores} threads)  (> 1: lidarfx is faster)")
if os.path.exists(os.path.join(work, "grass_shadow.u8")):
    grass_shadow = np.fromfile(os.path.join(work, "grass_shadow.u8"), np.uint8).reshape(n, n) == 1
    ours_shadow = np.fromfile(os.path.join(work, "lidarfx_shadow.u8"), np.uint8).reshape(n, n) == 0
    agree = np.mean(grass_shadow == ours_shadow)
    print(f"shadow: cells agreeing {100 * agree:.2f} %; shadow share r.sunmask {100 * grass_shadow.mean():.2f} %, "
          f"raylines_shadow {100 * ours_shadow.mean():.2f} %; only r.sunmask {100 * np.mean(grass_shadow & ~ours_shadow):.2f} %, "
          f"only lidarfx {100 * np.mean(ours_shadow & ~grass_shadow):.2f} %")
grass_h = np.fromfile(os.path.join(work, "grass_horizon.f32"), np.float32).reshape(n, n).astype(np.float64)
ours_h = np.fromfile(os.path.join(work, "lidarfx_horizon.f32"), np.float32).reshape(n, n).astype(np.float64)
valid = grass_h != -9999
d = np.abs(np.maximum(grass_h, 0.0) - ours_h)[valid]
# Cells more than 100 m from the raster's edges, where neither side's profile is cut short by the border.
inner = np.zeros((n, n), bool)
inner[100:n - 100, 100:n - 100] = True
di = np.abs(np.maximum(grass_h, 0.0) - ours_h)[valid & inner]
inner_text = (f"cells > 100 m from the edge: max {di.max():.3f}, within 1 degree {100 * np.mean(di <= 1.0):.2f} %; "
              if di.size else "")
print(f"horizon (r.horizon clipped at 0 vs horizon_map, degrees): max |diff| {d.max():.3f}, mean {d.mean():.4f}, "
      f"within 1 degree {100 * np.mean(d <= 1.0):.2f} %, within 0.1 degree {100 * np.mean(d <= 0.1):.2f} %; "
      + inner_text +
      f"r.horizon below 0 on {100 * np.mean(grass_h[valid] < 0):.2f} % of cells")
EOF
done
