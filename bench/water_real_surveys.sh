#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# The real-survey table of docs/waterbodies.md: `lidarfx water` (its default, and --dropout-seeds-only, the
# library's defaults) on public surveys whose vendor classification marks water or that come with independent
# water polygons, scored by bench/water_real_survey.cpp. The surveys are not in the repository (their licenses or sizes keep them out):
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
# file | cell, metres | where it comes from | truth: polygon file beside it (empty: class 9) | bridge-deck class
surveys=(
    "Topography.laz|2|r-lidar/lidR, inst/extdata/Topography.laz (GPL-3)||17"
    "ahn3_cropped_1.laz|1|tudelft3d/3dfier, example_data/ahn3/ahn3_cropped_1.laz and example_data/bgt/bgt_waterdeel.sqlite (AHN3 and BGT, Dutch open data; repository GPL-3)|bgt_waterdeel.sqlite|26"
    "ahn3_cropped_2.laz|1|tudelft3d/3dfier, example_data/ahn3/ahn3_cropped_2.laz and example_data/bgt/bgt_waterdeel.sqlite (AHN3 and BGT, Dutch open data; repository GPL-3)|bgt_waterdeel.sqlite|26"
    "lake.laz|2|LAStools/LAStools, data/lake.laz (no licence stated for the data)||17"
)
for entry in "${surveys[@]}"; do
    IFS='|' read -r file cell source polygons deck <<<"$entry"
    if [[ -z "$folder" || ! -f "$folder/$file" ]]; then
        echo "skip $file: not in LIDARFX_REAL_SURVEYS (${folder:-unset}); it comes from $source"
        continue
    fi
    truth=(--deck-class "$deck")
    if [[ -n "$polygons" ]]; then
        if [[ ! -f "$folder/$polygons" ]]; then
            echo "skip $file: its water polygons $polygons are not in LIDARFX_REAL_SURVEYS (same source)"
            continue
        fi
        truth+=(--polygons "$folder/$polygons")
    fi
    for method in default dropout-seeds-only; do
        extra=()
        [[ "$method" == default ]] || extra=(--dropout-seeds-only)
        out="$work/$file.$method"
        "$build/lidarfx" water "$folder/$file" --cell "$cell" --formats asc --out "$out" "${extra[@]}" >"$work/log" 2>&1 ||
            { echo "lidarfx water failed on $file:"; cat "$work/log"; exit 1; }
        echo "$file, $cell m cells, $method:"
        "$build/bench/water_real_survey" "$folder/$file" "$out/water.asc" "${truth[@]}"
    done
done
