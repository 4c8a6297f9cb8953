# `lidarfx water` on a survey without intensity and too sparse for 2 m cells must say why, write no map,
# and exit with code 3.
file(REMOVE_RECURSE "${WORK_DIR}")
execute_process(COMMAND "${LIDARFX}" water "${DATA}" --cell 2 --out "${WORK_DIR}"
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 3)
    message(FATAL_ERROR "expected exit code 3, got ${rc}\n${out}\n${err}")
endif()
foreach(reason "intensity is the same" "points per 2.0 m cell" "use a cell of at least")
    string(FIND "${out}" "${reason}" at)
    if(at EQUAL -1)
        message(FATAL_ERROR "the output does not say '${reason}':\n${out}")
    endif()
endforeach()
if(EXISTS "${WORK_DIR}/water.asc" OR EXISTS "${WORK_DIR}/waterbody_labels.asc")
    message(FATAL_ERROR "a map was written for data that cannot support it")
endif()
message(STATUS "refused with the reasons, no map written")
