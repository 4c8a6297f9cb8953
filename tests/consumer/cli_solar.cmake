# SPDX-License-Identifier: Apache-2.0
# `lidarfx solar` on a small generated DSM (flat ground, one 6 m block) with the clear-sky default writes every
# file its usage promises, says that it used the clear-sky model, and summary.csv has 12 month rows and the year.
# Then the refusals: exit code 2, a message naming the way out, no folder left behind.
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")
set(dsm "${WORK_DIR}/dsm.asc")
set(text "ncols 16\nnrows 16\nxllcorner 1000\nyllcorner 2000\ncellsize 1\nNODATA_value -9999\n")
foreach(r RANGE 15)
    set(row "")
    foreach(c RANGE 15)
        if(r GREATER_EQUAL 6 AND r LESS 10 AND c GREATER_EQUAL 6 AND c LESS 10)
            string(APPEND row " 106")
        else()
            string(APPEND row " 100")
        endif()
    endforeach()
    string(APPEND text "${row}\n")
endforeach()
file(WRITE "${dsm}" "${text}")

set(out "${WORK_DIR}/out")
execute_process(COMMAND "${LIDARFX}" solar "${dsm}" --lat 52.5 --lon 13.4 --formats asc,png --out "${out}"
                RESULT_VARIABLE rc OUTPUT_VARIABLE said ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
    message(FATAL_ERROR "lidarfx solar failed (${rc}):\n${said}\n${err}")
endif()
string(FIND "${said}" "no --tmy given, using the clear-sky model" at)
if(at EQUAL -1)
    message(FATAL_ERROR "lidarfx solar without --tmy does not say it uses the clear-sky model:\n${said}")
endif()
set(expected annual_kwh_m2.asc svf.asc annual_kwh_m2.png svf.png summary.csv)
foreach(m 01 02 03 04 05 06 07 08 09 10 11 12)
    list(APPEND expected month_${m}_kwh_m2.asc)
endforeach()
foreach(f IN LISTS expected)
    if(NOT EXISTS "${out}/${f}")
        message(FATAL_ERROR "lidarfx solar did not write ${f}")
    endif()
endforeach()
file(STRINGS "${out}/summary.csv" lines)
list(POP_FRONT lines header)
if(NOT header MATCHES "^month,mean_kwh_m2,min_kwh_m2,max_kwh_m2,ghi_kwh_m2")
    message(FATAL_ERROR "summary.csv header: ${header}")
endif()
set(months 0)
foreach(line IN LISTS lines)
    if(line MATCHES "^(1[0-2]|[1-9]),[0-9.]+,[0-9.]+,[0-9.]+,[0-9.]+$")
        math(EXPR months "${months} + 1")
    elseif(NOT line MATCHES "^\"?year\"?,")
        message(FATAL_ERROR "summary.csv: unexpected row '${line}'")
    endif()
endforeach()
if(NOT months EQUAL 12)
    message(FATAL_ERROR "summary.csv has ${months} month rows, not 12:\n${lines}")
endif()
message(STATUS "lidarfx solar: ${expected} written, 12 month rows")

# The Perez sky option runs too.
execute_process(COMMAND "${LIDARFX}" solar "${dsm}" --lat 52.5 --lon 13.4 --diffuse perez --formats asc
                        --out "${WORK_DIR}/out_perez"
                RESULT_VARIABLE rc OUTPUT_VARIABLE said ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT EXISTS "${WORK_DIR}/out_perez/annual_kwh_m2.asc")
    message(FATAL_ERROR "lidarfx solar --diffuse perez failed (${rc}):\n${said}\n${err}")
endif()

set(cases
    "2|--lat must be given|[-90, 90]|solar^${dsm}^--out^${out}_refused"
    "2|--lon must be given|[-180, 180]|solar^${dsm}^--lat^52^--out^${out}_refused"
    "2|--year-from-tmy needs --tmy|FILE.csv|solar^${dsm}^--lat^52^--lon^13^--year-from-tmy^--out^${out}_refused"
    "2|--year must be in|(got 1066)|solar^${dsm}^--lat^52^--lon^13^--year^1066^--out^${out}_refused"
    "2|--diffuse must be isotropic or perez|(got hay)|solar^${dsm}^--lat^52^--lon^13^--diffuse^hay^--out^${out}_refused")
set(out "${out}_refused")
include("${CMAKE_CURRENT_LIST_DIR}/expect_refusals.cmake")
