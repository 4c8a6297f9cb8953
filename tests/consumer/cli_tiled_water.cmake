cmake_minimum_required(VERSION 3.25)
# lidarfx water --tile gives the untiled run's files byte for byte on a synthetic survey of 18 LAS files
# (lakes and a river across file and tile borders): tile edges 120 m (60 cells), 200 m and 310 m (not a
# divisor of the survey), 1 and 2 threads. The tile folder is gone after each complete run.
# -DLIDARFX=<lidarfx> -DMAKE_SURVEY=<make_water_survey> -DWORK_DIR=<scratch folder>
include("${CMAKE_CURRENT_LIST_DIR}/make_water_survey.cmake")
include("${CMAKE_CURRENT_LIST_DIR}/same_files.cmake")
file(GLOB las_files "${WORK_DIR}/survey/*.las")
list(LENGTH las_files file_count)
if(file_count LESS 9)
    message(FATAL_ERROR "the synthetic survey has ${file_count} files, fewer than 9")
endif()

function(run_water out_dir)
    execute_process(COMMAND "${LIDARFX}" water "${WORK_DIR}/survey" --cell 2 ${ARGN} --out "${out_dir}"
                    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
    if(NOT rc EQUAL 0)
        message(FATAL_ERROR "lidarfx water ${ARGN} failed (${rc}):\n${out}\n${err}")
    endif()
endfunction()

run_water("${WORK_DIR}/untiled" --threads 2)
file(GLOB outputs RELATIVE "${WORK_DIR}/untiled" "${WORK_DIR}/untiled/*")
list(REMOVE_ITEM outputs manifest.json .lidarfx.lock)   # the manifest records the command line
foreach(required water.asc waterbody_labels.asc waterbodies.csv waterbodies.geojson)
    if(NOT required IN_LIST outputs)
        message(FATAL_ERROR "the untiled run wrote no ${required} (it wrote ${outputs})")
    endif()
endforeach()
file(STRINGS "${WORK_DIR}/untiled/waterbodies.csv" rows)
list(LENGTH rows row_count)
if(row_count LESS 4)   # a header line and the lake, the pond and the river at least
    message(FATAL_ERROR "the untiled run found too few waterbodies to compare:\n${rows}")
endif()

foreach(tile 120 200 310)
    foreach(threads 1 2)
        set(dir "${WORK_DIR}/tile_${tile}_threads_${threads}")
        run_water("${dir}" --tile ${tile} --threads ${threads})
        expect_same_files("${WORK_DIR}/untiled" "${dir}" "--tile ${tile} --threads ${threads}")
        message(STATUS "--tile ${tile} --threads ${threads}: the untiled run's files, byte for byte")
    endforeach()
endforeach()

# The default is flat_seed_water_method(); --dropout-seeds-only runs the library's defaults, and the two
# flags together are a usage error (exit code 2) that writes nothing.
run_water("${WORK_DIR}/dropout_seeds_only" --dropout-seeds-only)
if(NOT EXISTS "${WORK_DIR}/dropout_seeds_only/water.asc")
    message(FATAL_ERROR "--dropout-seeds-only wrote no water.asc")
endif()
execute_process(COMMAND "${LIDARFX}" water "${WORK_DIR}/survey" --cell 2 --flat-seeds --dropout-seeds-only
                        --out "${WORK_DIR}/both"
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 2 OR NOT err MATCHES "exclude each other" OR EXISTS "${WORK_DIR}/both/water.asc")
    message(FATAL_ERROR "--flat-seeds with --dropout-seeds-only: exit ${rc}, expected 2 and no map:\n${err}")
endif()
