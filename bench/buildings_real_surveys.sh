#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# The real-city table of docs/buildings.md: extract_buildings as `lidarfx solar --facades` runs it on LAS input
# (trees by their split pulses, the terrain from the vendor's class 2, or without classes from the morphological
# ground filter; each building's rim decided by the share of its points raised above that terrain) and the mask
# route (every cell with a split pulse as a tree and rough parts dropped, the
# terrain found from the DSM), scored by
# bench/buildings_real_survey.cpp against the vendor's building class (6) and, where given, footprint polygons.
# The surveys are not in the repository (sizes and licenses keep them out; one Montpellier tile is a test
# fixture): put them in a folder and name it in LIDARFX_REAL_SURVEYS; a survey that is not there is skipped with
# a message.
# Usage: LIDARFX_REAL_SURVEYS=DIR bash bench/buildings_real_surveys.sh
#        (after `cmake --preset bench && cmake --build --preset bench --target buildings_real_survey`)
set -euo pipefail
cd "$(dirname "$0")/.."
build="${BUILD:-build/bench}"
folder="${LIDARFX_REAL_SURVEYS:-}"
# name | files (space-separated) | cell, metres | where they come from | footprint polygons beside them (optional)
# | more options of the scorer (optional)
surveys=(
    "Delft 1|ahn3_cropped_1.laz|1|tudelft3d/3dfier, example_data/ahn3/ahn3_cropped_1.laz (AHN3, Dutch open data; repository GPL-3) and example_data/bgt/bgt_pand.sqlite (BGT building polygons)|bgt_pand.sqlite"
    "Delft 2|ahn3_cropped_2.laz|1|tudelft3d/3dfier, example_data/ahn3/ahn3_cropped_2.laz (AHN3, Dutch open data; repository GPL-3) and example_data/bgt/bgt_pand.sqlite (BGT building polygons)|bgt_pand.sqlite"
    "Montpellier|lidarhd_montpellier_77050_627755.laz lidarhd_montpellier_77050_627760.laz lidarhd_montpellier_77055_627755.laz lidarhd_montpellier_77055_627760.laz lidarhd_montpellier_77060_627755.laz lidarhd_montpellier_77060_627760.laz|1|IGNF/ign-pdal-tools, test/data/classified_laz/test_data_77050_627755_LA93_IGN69.laz and test/data/test_data_770{50,55,60}_62775{5,60}_LA93_IGN69.laz (IGN LiDAR HD, Etalab 2.0; repository MIT)|"
    "Louhans|lidarhd_louhans_870000_6618000.laz|1|IGNF/lidar-prod, tests/files/870000_6618000.subset.postValidation.laz and .postIA.shp (IGN LiDAR HD and BD UNI; repository BSD-3)|lidarhd_louhans_bd_uni.shp"
    "Le Grau-du-Roi|lidar_legrauduroi_left.laz lidar_legrauduroi_right.laz|1|IGNF/pacasam, tests/data/laz/792000_6272000-50mx100m-{left,right}.laz (IGN; repository BSD-3)|"
    "Zurich|lastools_zurich.laz|1|LAStools/LAStools, data/zurich.laz (no licence stated for the data)||--truth-ignore 12"
    "Adelaide|lastools_fusa_adelaide.laz|1|LAStools/LAStools, data/fusa.laz (no licence stated for the data; classes probably made by LAStools)|"
)
for entry in "${surveys[@]}"; do
    IFS='|' read -r name files cell source polygons more <<<"$entry"
    paths=()
    for f in $files; do
        if [[ -z "$folder" || ! -f "$folder/$f" ]]; then
            echo "skip $name: $f is not in LIDARFX_REAL_SURVEYS (${folder:-unset}); it comes from $source"
            continue 2
        fi
        paths+=("$folder/$f")
    done
    truth=()
    [[ -n "$polygons" && -f "$folder/$polygons" ]] && truth=(--footprints "$folder/$polygons")
    read -r -a extra <<<"${more:-}"
    truth+=("${extra[@]}")
    echo "== $name, $cell m cells"
    echo "-- the program's route (split pulses, class 2):"
    "$build/bench/buildings_real_survey" "${paths[@]}" --cell "$cell" --ground class2 "${truth[@]}" | tail -n +2
    echo "-- the program's route with the rim left to the DSM (no second pass over the points):"
    "$build/bench/buildings_real_survey" "${paths[@]}" --cell "$cell" --ground class2 --rim dsm "${truth[@]}" |
        tail -n +2
    echo "-- without the classes (split pulses, morphological ground filter):"
    "$build/bench/buildings_real_survey" "${paths[@]}" --cell "$cell" --ground filter "${truth[@]}" | tail -n +2
    echo "-- the mask route (any split pulse a tree, rough parts dropped, terrain from the DSM):"
    "$build/bench/buildings_real_survey" "${paths[@]}" --cell "$cell" --ground model --vegetation any "${truth[@]}" |
        tail -n +2
done
