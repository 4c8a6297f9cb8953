# SPDX-License-Identifier: Apache-2.0
# `lidarfx roofs DSM.asc DTM.asc FOOTPRINTS.geojson` on a generated scene: a shed roof rising to the north (tilt
# atan(0.5) = 26.57 deg, facing south) and a flat roof, plus a footprint off the grid and a self-intersecting one.
# Every promised file is written; roof_patches.csv has the promised columns and the shed's plane; footprints.csv
# reports the two bad footprints; both modes run. Then the refusals: exit code 2, no folder left behind.
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")
include("${CMAKE_CURRENT_LIST_DIR}/roofs_scene.cmake")
write_roofs_scene("${WORK_DIR}")
# Grid: x 1000..1050, y 2000..2050, row r spans y 2050 - r - 1 .. 2050 - r.
set(shed "[[1010,2040],[1030,2040],[1030,2028],[1010,2028],[1010,2040]]")
set(flat "[[1010,2020],[1025,2020],[1025,2008],[1010,2008],[1010,2020]]")
set(far "[[5000,5000],[5010,5000],[5010,5010],[5000,5010],[5000,5000]]")
set(bowtie "[[1001,2001],[1006,2006],[1006,2001],[1001,2006],[1001,2001]]")
set(features "")
foreach(f "7|${shed}" "8|${flat}" "9|${far}" "10|${bowtie}")
    string(REPLACE "|" ";" parts "${f}")
    list(GET parts 0 id)
    list(GET parts 1 ring)
    if(features)
        string(APPEND features ",")
    endif()
    string(APPEND features "{\"type\":\"Feature\",\"properties\":{\"building_id\":${id}},\"geometry\":{\"type\":\"Polygon\",\"coordinates\":[${ring}]}}")
endforeach()
file(WRITE "${WORK_DIR}/footprints.geojson" "{\"type\":\"FeatureCollection\",\"features\":[${features}]}")

foreach(mode planes paper)
    set(out "${WORK_DIR}/out_${mode}")
    execute_process(COMMAND "${LIDARFX}" roofs "${WORK_DIR}/dsm.asc" "${WORK_DIR}/dtm.asc" --xy-unit m --z-unit m "${WORK_DIR}/footprints.geojson"
                            --mode ${mode} --out "${out}"
                    RESULT_VARIABLE rc OUTPUT_VARIABLE said ERROR_VARIABLE err)
    if(NOT rc EQUAL 0)
        message(FATAL_ERROR "lidarfx roofs --mode ${mode} failed (${rc}):\n${said}\n${err}")
    endif()
    foreach(f roof_patches.csv roof_patches.geojson roof_patches.png footprints.csv manifest.json)
        if(NOT EXISTS "${out}/${f}")
            message(FATAL_ERROR "lidarfx roofs --mode ${mode} did not write ${f}")
        endif()
    endforeach()
    file(STRINGS "${out}/roof_patches.csv" rows)
    list(POP_FRONT rows head)
    if(NOT head MATCHES "^building_id,patch_id,tilt_deg,azimuth_deg,area_m2,sloped_area_m2,kwp,suitable,centroid_x_crs,centroid_y_crs,flat,reason$")
        message(FATAL_ERROR "roof_patches.csv header: ${head}")
    endif()
    set(shed_found FALSE)
    set(flat_found FALSE)
    foreach(line IN LISTS rows)
        string(REPLACE "," ";" v "${line}")
        list(GET v 0 id)
        list(GET v 2 tilt)
        list(GET v 3 azimuth)
        list(GET v 7 suitable)
        if(id EQUAL 7 AND tilt GREATER 25.5 AND tilt LESS 27.5 AND azimuth GREATER 175 AND azimuth LESS 185
           AND suitable EQUAL 1)
            set(shed_found TRUE)
        endif()
        if(id EQUAL 8 AND tilt LESS 1)
            set(flat_found TRUE)
        endif()
    endforeach()
    if(NOT shed_found OR NOT flat_found)
        message(FATAL_ERROR "--mode ${mode}: the shed (26.6 deg, facing 180, suitable) or the flat roof is missing:\n${rows}")
    endif()
    file(READ "${out}/footprints.csv" report)
    foreach(phrase "9,2,outside the grid" "10,3,invalid polygon")
        string(FIND "${report}" "${phrase}" at)
        if(at EQUAL -1)
            message(FATAL_ERROR "footprints.csv does not report '${phrase}':\n${report}")
        endif()
    endforeach()
    message(STATUS "lidarfx roofs --mode ${mode}: shed and flat roof found, bad footprints reported")
endforeach()

# With a place (clear-sky year) the patches carry their yield: the south-facing shed gets more per m2 than the
# flat roof at 40 N.
execute_process(COMMAND "${LIDARFX}" roofs "${WORK_DIR}/dsm.asc" "${WORK_DIR}/dtm.asc" --xy-unit m --z-unit m "${WORK_DIR}/footprints.geojson"
                        --lat 40 --lon -105 --formats png --out "${WORK_DIR}/out_yield"
                RESULT_VARIABLE rc OUTPUT_VARIABLE said ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
    message(FATAL_ERROR "lidarfx roofs --lat --lon failed (${rc}):\n${said}\n${err}")
endif()
file(STRINGS "${WORK_DIR}/out_yield/roof_patches.csv" rows)
list(POP_FRONT rows head)
if(NOT head MATCHES ",annual_kwh_m2,annual_kwh$")
    message(FATAL_ERROR "roof_patches.csv with --lat/--lon has no yield columns: ${head}")
endif()
foreach(line IN LISTS rows)
    string(REPLACE "," ";" v "${line}")
    list(GET v 0 id)
    list(GET v 12 kwh_m2)
    set(yield_${id} "${kwh_m2}")
endforeach()
if(NOT yield_7 GREATER yield_8)
    message(FATAL_ERROR "the south-facing shed (${yield_7}) should get more than the flat roof (${yield_8}) per m2")
endif()
message(STATUS "lidarfx roofs --lat 40: shed ${yield_7}, flat ${yield_8} kWh/m2")

file(WRITE "${WORK_DIR}/dup.geojson" "{\"type\":\"FeatureCollection\",\"features\":[{\"type\":\"Feature\",\"properties\":{\"building_id\":3},\"geometry\":{\"type\":\"Polygon\",\"coordinates\":[${shed}]}},{\"type\":\"Feature\",\"properties\":{\"building_id\":3},\"geometry\":{\"type\":\"Polygon\",\"coordinates\":[${flat}]}}]}")
file(WRITE "${WORK_DIR}/noid.geojson" "{\"type\":\"FeatureCollection\",\"features\":[{\"type\":\"Feature\",\"properties\":{\"name\":\"x\"},\"geometry\":{\"type\":\"Polygon\",\"coordinates\":[${shed}]}}]}")
set(out "${WORK_DIR}/refused")
set(d "${WORK_DIR}/dsm.asc")
set(t "${WORK_DIR}/dtm.asc")
set(cases
    "2|building_id 3 is used by feature 0|unique|roofs^${d}^${t}^--xy-unit^m^--z-unit^m^${WORK_DIR}/dup.geojson^--out^${out}"
    "2|no integer \"building_id\"|every footprint|roofs^${d}^${t}^--xy-unit^m^--z-unit^m^${WORK_DIR}/noid.geojson^--out^${out}"
    "2|--mode must be planes or paper|(got best)|roofs^${d}^${t}^--xy-unit^m^--z-unit^m^${WORK_DIR}/footprints.geojson^--mode^best^--out^${out}"
    "2|the last input must be the footprints|.geojson|roofs^${d}^${t}^--xy-unit^m^--z-unit^m^--out^${out}"
    "2|--lat and --lon|go together|roofs^${d}^${t}^--xy-unit^m^--z-unit^m^${WORK_DIR}/footprints.geojson^--lat^40^--out^${out}")
include("${CMAKE_CURRENT_LIST_DIR}/expect_refusals.cmake")
