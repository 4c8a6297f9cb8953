# SPDX-License-Identifier: Apache-2.0
# A survey in degrees (EPSG:4326) is refused by the distance-based subcommands with exit code 2, a message that
# says why and how to reproject, and no output folder left behind.
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")
set(out "${WORK_DIR}/out")
foreach(command IN ITEMS rasterize water)
    execute_process(COMMAND "${LIDARFX}" ${command} "${DATA}" --cell 2 --out "${out}"
        RESULT_VARIABLE rc OUTPUT_VARIABLE stdout ERROR_VARIABLE stderr)
    string(REGEX REPLACE "[ \t\r\n]+" " " said "${stdout}${stderr}")
    if(NOT rc EQUAL 2)
        message(FATAL_ERROR "lidarfx ${command} on degrees: expected exit code 2, got ${rc}\n${said}")
    endif()
    foreach(p IN ITEMS "longitude and latitude in degrees" "EPSG:4326" "Reproject" "filters.reprojection")
        string(FIND "${said}" "${p}" at)
        if(at EQUAL -1)
            message(FATAL_ERROR "lidarfx ${command} on degrees: the message does not say '${p}':\n${said}")
        endif()
    endforeach()
    if(EXISTS "${out}")
        message(FATAL_ERROR "lidarfx ${command} on degrees: the refused run left ${out} behind")
    endif()
    message(STATUS "${command} refused degrees (${rc})")
endforeach()
