# SPDX-License-Identifier: Apache-2.0
# Every CSV the program writes against the column tables of the docs (cli_csv_docs.py): `lidarfx demo` (scores,
# roof scores, waterbodies and roof patches of the synthetic scenes), `lidarfx roofs --lat --lon` on the shed and
# flat roof (roof patches with yields, footprints) and `lidarfx solar --facades` on a block (summary, facade
# patches, surface table, bill savings). Every column written is documented with its unit, every documented
# column is written, names carry the documented unit and every number has the documented decimals.
# -DLIDARFX=<lidarfx> -DPYTHON=<python3> -DMAKE_SURVEY=<make_water_survey> -DDOCS=<docs folder>
# -DWORK_DIR=<scratch folder>
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")

function(run name)
    execute_process(COMMAND "${LIDARFX}" ${ARGN} --out "${WORK_DIR}/${name}" RESULT_VARIABLE rc OUTPUT_VARIABLE said
                    ERROR_VARIABLE err)
    if(NOT rc EQUAL 0)
        message(FATAL_ERROR "lidarfx ${ARGN} failed (${rc}):\n${said}\n${err}")
    endif()
endfunction()

run(demo demo --size 300 --seed 3 --threads 1)

include("${CMAKE_CURRENT_LIST_DIR}/roofs_scene.cmake")
write_roofs_scene("${WORK_DIR}")
set(features "")
foreach(f "7|[[1010,2040],[1030,2040],[1030,2028],[1010,2028],[1010,2040]]"
          "8|[[1010,2020],[1025,2020],[1025,2008],[1010,2008],[1010,2020]]"
          "9|[[5000,5000],[5010,5000],[5010,5010],[5000,5010],[5000,5000]]")
    string(REPLACE "|" ";" parts "${f}")
    list(GET parts 0 id)
    list(GET parts 1 ring)
    if(features)
        string(APPEND features ",")
    endif()
    string(APPEND features "{\"type\":\"Feature\",\"properties\":{\"building_id\":${id}},\"geometry\":{\"type\":\"Polygon\",\"coordinates\":[${ring}]}}")
endforeach()
file(WRITE "${WORK_DIR}/footprints.geojson" "{\"type\":\"FeatureCollection\",\"features\":[${features}]}")
run(roofs roofs "${WORK_DIR}/dsm.asc" "${WORK_DIR}/dtm.asc" --xy-unit m --z-unit m "${WORK_DIR}/footprints.geojson"
    --lat 40 --lon -105 --formats csv)

include("${CMAKE_CURRENT_LIST_DIR}/block_dsm.cmake")
write_block_dsm("${WORK_DIR}/box.asc" 40 14 24 14 26 110)
run(solar solar "${WORK_DIR}/box.asc" --xy-unit m --z-unit m --lat 52.5 --lon 13.4 --facades --formats asc,csv)

# Hydro-flattening on the synthetic water survey (its river and pond are under the specification's minimums).
execute_process(COMMAND "${MAKE_SURVEY}" "${WORK_DIR}/survey" RESULT_VARIABLE rc OUTPUT_QUIET ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
    message(FATAL_ERROR "make_water_survey failed (${rc}):\n${err}")
endif()
run(hydro hydroflatten "${WORK_DIR}/survey" --cell 2 --min-river-width 10 --min-lake-area 2000 --shoreline flag
    --formats csv)

execute_process(COMMAND "${PYTHON}" "${CMAKE_CURRENT_LIST_DIR}/cli_csv_docs.py" "${WORK_DIR}" "${DOCS}"
                RESULT_VARIABLE rc OUTPUT_VARIABLE said ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
    message(FATAL_ERROR "the CSVs and their docs disagree:\n${said}${err}")
endif()
message(STATUS "${said}")
