#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# The portable-speed table of docs/performance.md: every kernel target and the waterbody pipeline's, on the
# native build (-march=native) and the AVX2-only build (-march=x86-64-v3), each with its peer in the same run.
#
#   bash bench/portable_speed.sh [OUT_DIR]        (default OUT_DIR: ./portable-speed)
#
# Builds the `bench` and `bench-v3` presets (only the programs used), then per build writes OUT_DIR/<preset>.log
# with: the CPU model and vector extensions (every Google Benchmark program prints them as context),
# peer_filter_stats.py (angular_filter and slope_aspect against NumPy, ks_one_sided against SciPy),
# peer_morphology_label.py (morphology and connected_components against OpenCV), ks_one_sided against a
# sort-and-sweep baseline, the 4096^2 kernels on 1 and 2 threads (into and returning forms),
# extract_waterbodies (rasters -> labels) and the memory bandwidth (STREAM-like copy, first touch).
# Needs the peers' packages: bash scripts/install-deps.sh --peers. Run it on an otherwise idle machine: the
# builds' runs alternate, so a slow spell hits both, but wall times on a shared machine measure the scheduler.
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-portable-speed}
mkdir -p "$out"
python=/usr/bin/python3  # Debian's, which has numpy, scipy and cv2
programs=(bench_filter bench_stats bench_water bench_label bench_morphology bench_bandwidth)
for preset in bench bench-v3; do
    cmake --preset "$preset" > /dev/null
    cmake --build --preset "$preset" -j2 --target "${programs[@]}" > /dev/null
done
for preset in bench bench-v3; do
    dir=build/$preset/bench
    log=$out/$preset.log
    {
        echo "### $preset: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2-), $(nproc) cores"
        echo "### build flags: $(grep -m1 '^CMAKE_CXX_FLAGS:' "build/$preset/CMakeCache.txt" | cut -d= -f2-)"
        echo "### peer_filter_stats.py"
        # The peer scripts exit 1 when a target is missed; the table shows which, and the run goes on.
        LIDARFX_BENCH_BUILD=$dir "$python" bench/peers/peer_filter_stats.py || echo "(a target above was missed)"
        echo "### peer_morphology_label.py"
        LIDARFX_BENCH_BUILD=$dir "$python" bench/peers/peer_morphology_label.py || echo "(a target above was missed)"
        echo "### ks_one_sided against sort-and-sweep"
        "$dir/bench_stats" --benchmark_filter=vs_sort
        echo "### kernels at 4096^2, 1 and 2 threads"
        "$dir/bench_filter" --benchmark_filter='4096' --benchmark_min_time=1
        "$dir/bench_morphology" --benchmark_filter='4096/5/' --benchmark_min_time=1
        "$dir/bench_label" --benchmark_min_time=1
        echo "### extract_waterbodies, rasters -> labels"
        "$dir/bench_water" --benchmark_filter='extract_waterbodies_4096' --benchmark_min_time=3
        echo "### bandwidth"
        "$dir/bench_bandwidth"
    } 2>&1 | tee "$log"
done
echo "logs in $out/"
