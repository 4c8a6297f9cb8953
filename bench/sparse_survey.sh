#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Issue 10's sparse-survey target: `lidarfx rasterize` on 1,000 points spread over 5 km x 5 km at 1 m cells
# must refuse at once naming a cell that suits the data, and with --force finish in under 10 s and 1 GB.
# Prints wall time and peak memory (GNU time) of both runs, and the CPU's vector extensions.
# Usage: bash bench/sparse_survey.sh   (after `cmake --preset bench && cmake --build --preset bench`)
set -euo pipefail
cd "$(dirname "$0")/.."
build="${BUILD:-build/bench}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
"$build/bench/make_sparse_las" "$work/sparse.las" 1000 5000
echo "CPU: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs); vector extensions:" \
     "$(grep -m1 -o -w -E 'avx512f|avx2|sse4_2' /proc/cpuinfo | sort -u | xargs)"
run() {
    local label="$1"; shift
    local rc=0
    /usr/bin/time -f "%e %M" -o "$work/time" "$build/lidarfx" rasterize "$work/sparse.las" --cell 1 "$@" \
        --out "$work/out_$label" >"$work/log_$label" 2>&1 || rc=$?
    read -r seconds kib < <(tail -n 1 "$work/time")  # GNU time puts "Command exited..." first on failure
    awk -v l="$label" -v rc="$rc" -v s="$seconds" -v k="$kib" \
        'BEGIN { printf "%-8s exit %d  %6.2f s  %7.1f MB peak\n", l, rc, s, k / 1024 }'
    grep -m1 -E "Use --cell|error" "$work/log_$label" || true
}
run refused
run forced --force --threads 0
