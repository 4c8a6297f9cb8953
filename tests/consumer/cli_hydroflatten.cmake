cmake_minimum_required(VERSION 3.25)
# lidarfx hydroflatten on a synthetic survey of 18 LAS files (lakes and a river across file and tile borders):
# every output is written, every check of hydro_qa.csv passes, --tile gives the untiled run's files byte for
# byte (tile edges 200 m and 310 m, 1 and 2 threads), --formats asc writes the DEM as an ASCII grid with its .prj,
# and bad values of its own flags are usage errors (exit code 2) that write nothing. With ogrinfo, the breaklines
# are 3D polygons and 3D lines in the survey's CRS.
# -DLIDARFX=<lidarfx> -DMAKE_SURVEY=<make_water_survey> -DWORK_DIR=<scratch folder> [-DOGRINFO=<ogrinfo>]
include("${CMAKE_CURRENT_LIST_DIR}/make_water_survey.cmake")
include("${CMAKE_CURRENT_LIST_DIR}/same_files.cmake")

# The survey's river is about 28 m wide and its pond 4,000 m²: under the specification's minimums, so both are
# lowered to flatten everything the survey holds.
set(sizes --min-river-width 10 --min-lake-area 2000)

function(run_hydro out_dir)
    execute_process(COMMAND "${LIDARFX}" hydroflatten "${WORK_DIR}/survey" --cell 2 ${sizes} ${ARGN} --out "${out_dir}"
                    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
    if(NOT rc EQUAL 0)
        message(FATAL_ERROR "lidarfx hydroflatten ${ARGN} failed (${rc}):\n${out}\n${err}")
    endif()
endfunction()

run_hydro("${WORK_DIR}/untiled" --threads 2)
file(GLOB outputs RELATIVE "${WORK_DIR}/untiled" "${WORK_DIR}/untiled/*")
list(REMOVE_ITEM outputs manifest.json .lidarfx.lock)
foreach(required dem_hydroflattened.tif hydro_bodies.csv hydro_qa.csv breaklines.gpkg)
    if(NOT required IN_LIST outputs)
        message(FATAL_ERROR "the run wrote no ${required} (it wrote ${outputs})")
    endif()
endforeach()
if("dem_hydroflattened.asc" IN_LIST outputs)
    message(FATAL_ERROR "an ASCII grid was written although --formats did not ask for one")
endif()
file(STRINGS "${WORK_DIR}/untiled/hydro_bodies.csv" bodies)
list(FILTER bodies INCLUDE REGEX ",river,1,")
list(LENGTH bodies rivers)
if(rivers LESS 1)
    message(FATAL_ERROR "no river was flattened")
endif()
file(STRINGS "${WORK_DIR}/untiled/hydro_qa.csv" checks)
list(REMOVE_AT checks 0)
list(LENGTH checks check_count)
if(check_count LESS 3)
    message(FATAL_ERROR "hydro_qa.csv holds only ${check_count} bodies")
endif()
foreach(row IN LISTS checks)
    string(REPLACE "," ";" fields "${row}")
    list(GET fields 2 pass)
    if(NOT pass STREQUAL "1")
        message(FATAL_ERROR "a check fails: ${row}")
    endif()
endforeach()

foreach(tile 200 310)
    foreach(threads 1 2)
        set(dir "${WORK_DIR}/tile_${tile}_threads_${threads}")
        run_hydro("${dir}" --tile ${tile} --threads ${threads})
        expect_same_files("${WORK_DIR}/untiled" "${dir}" "--tile ${tile} --threads ${threads}")
    endforeach()
endforeach()

run_hydro("${WORK_DIR}/ascii" --formats asc,csv)
foreach(f dem_hydroflattened.asc dem_hydroflattened.prj hydro_bodies.csv)
    if(NOT EXISTS "${WORK_DIR}/ascii/${f}")
        message(FATAL_ERROR "--formats asc,csv wrote no ${f}")
    endif()
endforeach()

foreach(bad "--shoreline;sideways" "--min-lake-area;-1" "--min-river-width;nan" "--min-island-area;-5")
    execute_process(COMMAND "${LIDARFX}" hydroflatten "${WORK_DIR}/survey" --cell 2 ${bad} --out "${WORK_DIR}/refused"
                    RESULT_VARIABLE rc OUTPUT_QUIET ERROR_VARIABLE err)
    if(NOT rc EQUAL 2 OR EXISTS "${WORK_DIR}/refused/hydro_qa.csv")
        message(FATAL_ERROR "${bad}: expected a usage error (2) writing nothing, got ${rc}:\n${err}")
    endif()
endforeach()

if(OGRINFO)
    execute_process(COMMAND "${OGRINFO}" -so "${WORK_DIR}/untiled/breaklines.gpkg" water_bodies OUTPUT_VARIABLE polygons)
    execute_process(COMMAND "${OGRINFO}" -so "${WORK_DIR}/untiled/breaklines.gpkg" river_centrelines OUTPUT_VARIABLE lines)
    if(NOT polygons MATCHES "Geometry: 3D Polygon" OR NOT polygons MATCHES "UTM zone 33N")
        message(FATAL_ERROR "water_bodies is not a 3D polygon layer in the survey's CRS:\n${polygons}")
    endif()
    if(NOT lines MATCHES "Geometry: 3D Multi Line String")
        message(FATAL_ERROR "river_centrelines is not a 3D line layer:\n${lines}")
    endif()
endif()
