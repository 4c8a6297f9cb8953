#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# The real-survey table of docs/waterbodies.md: `lidarfx water` (its default, and --dropout-seeds-only, the
# library's defaults) on public surveys whose vendor classification marks water, scored by
# bench/water_real_survey.cpp. The surveys are not in the repository (their licenses or sizes keep them out):
# put them in a folder and name it in LIDARFX_REAL_SURVEYS; a survey that is not there is skipped with a
# message.
# Usage: LIDARFX_REAL_SURVEYS=DIR bash bench/water_real_surveys.sh
#        (after `cmake --preset bench && cmake --build --preset bench`)
set -euo pipefail
cd "$(dirname "$0")/.."
build="${BUILD:-build/bench}"
folder="${LIDARFX_REAL_SURVEYS:-}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
# file | cell, metres | where it comes from
surveys=(
    "Topography.laz|2|r-lidar/lidR, inst/extdata/Topography.laz (GPL-3)"
)
for entry in "${surveys[@]}"; do
    IFS='|' read -r file cell source <<<"$entry"
    if [[ -z "$folder" || ! -f "$folder/$file" ]]; then
        echo "skip $file: not in LIDARFX_REAL_SURVEYS (${folder:-unset}); it comes from $source"
        continue
    fi
    for method in default dropout-seeds-only; do
        extra=()
        [[ "$method" == default ]] || extra=(--dropout-seeds-only)
        out="$work/$file.$method"
        "$build/lidarfx" water "$folder/$file" --cell "$cell" --formats asc --out "$out" "${extra[@]}" >"$work/log" 2>&1 ||
            { echo "lidarfx water failed on $file:"; cat "$work/log"; exit 1; }
        echo -n "$file, $cell m cells, $method: "
        "$build/bench/water_real_survey" "$folder/$file" "$out/water.asc"
    done
done
