# SPDX-License-Identifier: Apache-2.0
# check_structure.py must catch what it is for: on tests/layering/structure_fixture it reports exactly the
# pipeline's uses of a kernel area's detail:: names, qualified and unqualified from inside its own namespace
# detail (not the uses of core's or its own area's), exactly the
# 154-line function (not the short one), exactly the diary lines of the user doc (not docs/history/), and exactly
# the std:: names used without their standard header (once per name, not in comments) or missing from its table.
# Usage: cmake -DPYTHON=<python3> -DCHECK=<check_structure.py> -DFIXTURE=<structure_fixture> -P structure_self_test.cmake
function(expect_report mode args expected_count)
    execute_process(COMMAND ${PYTHON} ${CHECK} ${mode} ${args} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
    if(rc EQUAL 0)
        message(FATAL_ERROR "check_structure.py ${mode} passed a fixture that breaks its rule:\n${out}${err}")
    endif()
    foreach(expected IN LISTS ARGN)
        string(FIND "${out}" "${expected}" at)
        if(at EQUAL -1)
            message(FATAL_ERROR "check_structure.py ${mode} did not report '${expected}':\n${out}${err}")
        endif()
    endforeach()
    if(NOT out MATCHES "\n${expected_count} violation\\(s\\)")
        message(FATAL_ERROR "check_structure.py ${mode}: expected ${expected_count} violation(s):\n${out}${err}")
    endif()
endfunction()
expect_report(detail "${FIXTURE}/include" 2
    "lidarfx/pipelines/water/flood.hpp:6: detail::smooth_rows belongs to kernels/filter, not pipelines/water"
    "lidarfx/pipelines/water/flood.hpp:168: smooth_rows is internal to kernels/filter, not pipelines/water")
expect_report(length "${FIXTURE}/include;150" 1 "flood.hpp:5: function body of 154 lines")
expect_report(diary "${FIXTURE}/docs" 4 "page.md:4: a work-log date" "page.md:4: a numbered run"
    "page.md:5: a file outside the repository" "page.md:6: a tracker issue number")
expect_report(std_includes "${FIXTURE}/include" 3 "sizes.hpp:4: std::vector is used but <vector> is not included"
    "sizes.hpp:6: std::pair is used but <utility> is not included"
    "sizes.hpp:8: std::some_new_name is not in check_structure.py's table")
message(STATUS "check_structure.py reports the fixture's cross-area detail use, long function, diary lines and "
               "missing standard includes, and only them")
