# SPDX-License-Identifier: Apache-2.0
# The layering check must catch what it is for: run it on tests/layering/fixture, a small tree with one upward
# include (core/bad.hpp -> pipelines) and one sideways include (kernels/label -> kernels/filter) beside
# allowed ones, and require that it fails naming exactly those two lines.
execute_process(COMMAND ${CMAKE_COMMAND} -DINCLUDE_DIR=${FIXTURE} -P ${CHECK}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
string(APPEND out "${err}")
string(REGEX REPLACE "[ \t\r\n]+" " " flat "${out}")  # CMake wraps long messages
if(rc EQUAL 0)
    message(FATAL_ERROR "the layering check passed a tree with wrong includes:\n${out}")
endif()
foreach(expected
        "lidarfx/core/bad.hpp:3: #include \"lidarfx/pipelines/water/flood.hpp\" (upwards"
        "lidarfx/kernels/label/regions.hpp:3: #include \"lidarfx/kernels/filter/smooth.hpp\" (sideways")
    string(FIND "${flat}" "${expected}" at)
    if(at EQUAL -1)
        message(FATAL_ERROR "the layering check did not report '${expected}':\n${out}")
    endif()
endforeach()
foreach(allowed "base.hpp:" "smooth.hpp:" "flood.hpp:" "regions.hpp:2:")
    string(FIND "${flat}" "${allowed}" at)
    if(NOT at EQUAL -1)
        message(FATAL_ERROR "the layering check reported an allowed include ('${allowed}'):\n${out}")
    endif()
endforeach()
message(STATUS "the layering check fails on the fixture's two wrong includes and only on them")
