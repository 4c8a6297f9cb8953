# SPDX-License-Identifier: Apache-2.0
# lidarfx solar --facades and lidarfx roofs on a classified survey (the IGN LiDAR HD tile over Montpellier,
# tests/data/README.md): by default the terrain under the buildings is the vendor's class 2, --ground model
# finds it from the DSM, --ground filter by a morphological filter of the lowest points, and both apartment blocks
# of the tile are found with class 2, with the filter and with --buildings class6 (the vendor's buildings); the
# rims are decided by the raised points; the --ground and --buildings refusals.
# Inputs: LIDARFX (the program), DATA (tests/data), WORK_DIR.
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")
set(survey "${DATA}/lidarhd_montpellier_77055_627755.laz")

# Runs solar --facades with the extra arguments ${ARGN} into ${WORK_DIR}/${name}; sets said_${name} and
# buildings_${name} (the building ids of buildings.geojson).
function(facades name)
    execute_process(COMMAND "${LIDARFX}" solar "${survey}" --lat 43.59 --lon 3.87 --facades --formats asc,csv,geojson
                            --out "${WORK_DIR}/${name}" ${ARGN}
                    RESULT_VARIABLE rc OUTPUT_VARIABLE said ERROR_VARIABLE err)
    if(NOT rc EQUAL 0)
        message(FATAL_ERROR "lidarfx solar --facades ${ARGN} failed (${rc}):\n${said}\n${err}")
    endif()
    file(READ "${WORK_DIR}/${name}/buildings.geojson" geojson)
    string(REGEX MATCHALL "\"building_id\":[0-9]+" ids "${geojson}")
    list(REMOVE_DUPLICATES ids)
    set(said_${name} "${said}" PARENT_SCOPE)
    set(buildings_${name} "${ids}" PARENT_SCOPE)
endfunction()

facades(auto)
string(FIND "${said_auto}" "terrain under buildings: class 2 (ground)" at)
if(at EQUAL -1)
    message(FATAL_ERROR "the default should take the survey's class 2 as the terrain:\n${said_auto}")
endif()
list(LENGTH buildings_auto found)
if(found LESS 2)
    message(FATAL_ERROR "both blocks of the tile should be found, buildings.geojson holds: ${buildings_auto}")
endif()

facades(filter --ground filter)
string(FIND "${said_filter}" "terrain under buildings: ground filter" at)
list(LENGTH buildings_filter found_filter)
if(at EQUAL -1 OR found_filter LESS 2)
    message(FATAL_ERROR "--ground filter should say so and find both blocks (${buildings_filter}):\n${said_filter}")
endif()

facades(model --ground model)
string(FIND "${said_model}" "terrain under buildings: found from the DSM" at)
if(at EQUAL -1)
    message(FATAL_ERROR "--ground model should find the terrain from the DSM:\n${said_model}")
endif()
message(STATUS "solar --facades: ${found} buildings with class 2, ${buildings_model} with --ground model")

# Each building's rim by its raised points: the second pass over the file is said in the log.
string(FIND "${said_auto}" "building edges: by the share of each cell's points" at)
if(at EQUAL -1)
    message(FATAL_ERROR "with the class-2 terrain the raised points should decide the edges:\n${said_auto}")
endif()
# The lowest raised points reach extract_buildings: the tile's trees over roofs give roof cells under crowns, said
# with their count (18 at this release; any positive count passes).
string(REGEX MATCH "roof under overhanging crowns: ([0-9]+) cells" under_crowns "${said_auto}")
if(NOT under_crowns OR CMAKE_MATCH_1 EQUAL 0)
    message(FATAL_ERROR "the roof under the tile's overhanging crowns should be found and said:\n${said_auto}")
endif()

# --buildings class6: the vendor's buildings, both blocks, said in the log.
facades(class6 --buildings class6)
string(FIND "${said_class6}" "buildings: class 6 (building)" at)
list(LENGTH buildings_class6 found_class6)
if(at EQUAL -1 OR found_class6 LESS 2)
    message(FATAL_ERROR "--buildings class6 should say so and give both blocks (${buildings_class6}):\n${said_class6}")
endif()

set(out "${WORK_DIR}/refused")
set(cases
    "2|--ground must be auto, class2, filter or model|(got dtm)|solar^${survey}^--lat^43.6^--lon^3.9^--facades^--ground^dtm^--out^${out}"
    "2|--ground needs --facades|--ground|solar^${survey}^--lat^43.6^--lon^3.9^--ground^class2^--out^${out}"
    "2|--ground must be auto, class2, filter or model|(got dtm)|roofs^${survey}^${WORK_DIR}/none.geojson^--ground^dtm^--out^${out}"
    "2|--buildings must be points or class6|(got 'class5')|solar^${survey}^--lat^43.6^--lon^3.9^--facades^--buildings^class5^--out^${out}"
    "2|--buildings needs --facades|--buildings|solar^${survey}^--lat^43.6^--lon^3.9^--buildings^class6^--out^${out}"
    "2|--buildings class6 with --ground model|wrong heights|solar^${survey}^--lat^43.6^--lon^3.9^--facades^--buildings^class6^--ground^model^--out^${out}"
    "2|is of class 6 (building)|inside --crop|solar^${survey}^--lat^43.6^--lon^3.9^--facades^--buildings^class6^--crop^770550,6277548,770552,6277550^--out^${out}")
include("${CMAKE_CURRENT_LIST_DIR}/expect_refusals.cmake")
