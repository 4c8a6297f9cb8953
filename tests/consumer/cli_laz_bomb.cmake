# SPDX-License-Identifier: Apache-2.0
# A LAZ chunk bomb is refused at once within --memory: tests/io/laz.cpp writes simple.laz with its one chunk
# claiming 10 M points (340 MB decoded) in 18 KB of zeroed bytes, runs `lidarfx rasterize` and `lidarfx water`
# on it with --memory 256MiB on 1 and 2 threads, and checks exit code 2, a message naming the chunk, the budget
# and --memory, under 5 s and a peak resident memory (ru_maxrss of the program) under half the budget; then
# the report's 1e9-point claim, refused when the file is opened.   Usage: -DLIDARFX=... -DTESTS_IO=...
execute_process(
    COMMAND ${CMAKE_COMMAND} -E env "LIDARFX_CLI=${LIDARFX}"
            "${TESTS_IO}" "--test-case=io/laz: the program refuses a LAZ chunk bomb*" --success=false
    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message(STATUS "${out}${err}")
if(NOT rc EQUAL 0)
    message(FATAL_ERROR "the LAZ chunk bomb case failed (exit code ${rc})")
endif()
if(NOT out MATCHES "test cases: +1 \\| +1 passed")
    message(FATAL_ERROR "the LAZ chunk bomb case did not run (is tests/io/laz.cpp built into ${TESTS_IO}?)")
endif()
