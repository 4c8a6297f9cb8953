cmake_minimum_required(VERSION 3.25)
# mpirun -np 2 lidarfx-mpi water --tile writes the untiled lidarfx water run's files byte for byte on the
# synthetic survey of 18 LAS files (lakes and a river across file and tile borders).
# -DLIDARFX=<lidarfx> -DLIDARFX_MPI=<lidarfx-mpi> -DMPIEXEC=<mpirun> -DMAKE_SURVEY=<make_water_survey> -DWORK_DIR=<dir>
include("${CMAKE_CURRENT_LIST_DIR}/make_water_survey.cmake")
execute_process(COMMAND "${LIDARFX}" water "${WORK_DIR}/survey" --cell 2 --out "${WORK_DIR}/untiled"
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
    message(FATAL_ERROR "untiled lidarfx water failed (${rc}):\n${out}\n${err}")
endif()
execute_process(COMMAND "${MPIEXEC}" --allow-run-as-root --oversubscribe -np 2 "${LIDARFX_MPI}" water "${WORK_DIR}/survey"
                        --cell 2 --tile 120 --threads 1 --out "${WORK_DIR}/mpi"
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
    message(FATAL_ERROR "mpirun -np 2 lidarfx-mpi water failed (${rc}):\n${out}\n${err}")
endif()
file(GLOB outputs RELATIVE "${WORK_DIR}/untiled" "${WORK_DIR}/untiled/*")
list(REMOVE_ITEM outputs manifest.json .lidarfx.lock)   # the manifest records the command line
list(LENGTH outputs count)
if(count LESS 5)
    message(FATAL_ERROR "the untiled run wrote only ${count} files: ${outputs}")
endif()
foreach(f IN LISTS outputs)
    file(SHA256 "${WORK_DIR}/untiled/${f}" want)
    file(SHA256 "${WORK_DIR}/mpi/${f}" got)
    if(NOT want STREQUAL got)
        message(FATAL_ERROR "2 MPI ranks: ${f} differs from the untiled run's")
    endif()
endforeach()
message(STATUS "2 MPI ranks: ${count} files as the untiled run's, byte for byte")
