# SPDX-License-Identifier: Apache-2.0
# `lidarfx roofs DSM.asc DTM.asc FOOTPRINTS.geojson` on footprint files the reader must take or refuse by name:
# a UTF-8 byte order mark is accepted; a coordinate of 1e300 is refused naming the file, the feature, its
# building_id and the value (exit code 2, not Boost's "bad numeric conversion" with exit code 1); a 2 MB file
# is refused under --memory 1MiB before it is read and under --memory 3MiB while it is read (its footprints
# would take another 2 MB), and accepted without --memory. No output folder is left by a refusal.
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")
set(grid "ncols 20\nnrows 20\nxllcorner 1000\nyllcorner 2000\ncellsize 1\nNODATA_value -9999\n")
string(REPEAT " 100" 20 row)
string(REPEAT "${row}\n" 20 rows)
file(WRITE "${WORK_DIR}/dsm.asc" "${grid}${rows}")
set(d "${WORK_DIR}/dsm.asc")

set(square "[[1002,2002],[1008,2002],[1008,2008],[1002,2008],[1002,2002]]")
set(collection "{\"type\":\"FeatureCollection\",\"features\":[")
function(feature id ring out)
    set(${out} "{\"type\":\"Feature\",\"properties\":{\"building_id\":${id}},\"geometry\":{\"type\":\"Polygon\",\"coordinates\":[${ring}]}}" PARENT_SCOPE)
endfunction()

# A byte order mark (EF BB BF) before the text, as some GIS tools write: accepted, the footprint used.
feature(5 "${square}" f5)
string(ASCII 239 187 191 bom)
file(WRITE "${WORK_DIR}/bom.geojson" "${bom}${collection}${f5}]}")
execute_process(COMMAND "${LIDARFX}" roofs "${d}" "${d}" --xy-unit m --z-unit m "${WORK_DIR}/bom.geojson" --formats png --out "${WORK_DIR}/out_bom"
                RESULT_VARIABLE rc OUTPUT_VARIABLE said ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
    message(FATAL_ERROR "a footprint file with a byte order mark was refused (${rc}):\n${said}\n${err}")
endif()
file(READ "${WORK_DIR}/out_bom/footprints.csv" report)
string(FIND "${report}" "5,0,used" at)
if(at EQUAL -1)
    message(FATAL_ERROR "footprints.csv of the file with a byte order mark does not say '5,0,used':\n${report}")
endif()
message(STATUS "byte order mark: accepted, footprint 5 used")

# A vertex at 1e300 in the second feature.
feature(12 "[[1e300,2002],[1008,2002],[1008,2008],[1002,2008],[1e300,2002]]" f12)
file(WRITE "${WORK_DIR}/huge.geojson" "${collection}${f5},${f12}]}")

# 40 footprints of 3005 vertices each (2.1 MB of text; kept, about as many bytes again).
string(REPEAT "[1010.25,2005.5]," 3000 many)
set(big "${collection}")
foreach(id RANGE 1 40)
    feature(${id} "[[1000,2000],[1010,2000],${many}[1010,2010],[1000,2010],[1000,2000]]" f)
    if(id GREATER 1)
        string(APPEND big ",")
    endif()
    string(APPEND big "${f}")
endforeach()
file(WRITE "${WORK_DIR}/big.geojson" "${big}]}")
execute_process(COMMAND "${LIDARFX}" roofs "${d}" "${d}" --xy-unit m --z-unit m "${WORK_DIR}/big.geojson" --formats png --out "${WORK_DIR}/out_big"
                RESULT_VARIABLE rc OUTPUT_VARIABLE said ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
    message(FATAL_ERROR "the 2 MB footprint file was refused without --memory (${rc}):\n${said}\n${err}")
endif()

set(out "${WORK_DIR}/refused")
set(cases
    "2|huge.geojson: feature 1 (building_id 12): coordinate x = 1e300 of vertex 0|beyond +-1e9|roofs^${d}^${d}^--xy-unit^m^--z-unit^m^${WORK_DIR}/huge.geojson^--out^${out}"
    "2|big.geojson: reading the footprints needs more than the file's 1.95 MiB|over the memory budget of 1 MiB|roofs^${d}^${d}^--xy-unit^m^--z-unit^m^${WORK_DIR}/big.geojson^--memory^1MiB^--out^${out}"
    "2|big.geojson: reading the footprints needs about|over the memory budget of 3 MiB|roofs^${d}^${d}^--xy-unit^m^--z-unit^m^${WORK_DIR}/big.geojson^--memory^3MiB^--out^${out}")
include("${CMAKE_CURRENT_LIST_DIR}/expect_refusals.cmake")
