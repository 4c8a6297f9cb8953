# SPDX-License-Identifier: Apache-2.0
# The weather rules on the command line: `lidarfx solar` and `lidarfx roofs` with --tmy print the year's coverage as
# one line on stderr, take a generated TMY3 year lacking its last hour (8759 rows), and refuse (exit code 2, the
# file, the line and the hour or value named) the year given twice and a DNI of 5000 W/m^2.
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")
include("${CMAKE_CURRENT_LIST_DIR}/block_dsm.cmake")
write_block_dsm("${WORK_DIR}/dsm.asc" 20 6 14 6 14 106)
write_block_dsm("${WORK_DIR}/dtm.asc" 20 0 0 0 0 100)
file(WRITE "${WORK_DIR}/footprints.geojson"
     "{\"type\":\"FeatureCollection\",\"features\":[{\"type\":\"Feature\",\"properties\":{\"building_id\":1},"
     "\"geometry\":{\"type\":\"Polygon\",\"coordinates\":[[[1006,2014],[1014,2014],[1014,2006],[1006,2006],"
     "[1006,2014]]]}}]}")

# A TMY3 year in 2001 (hour-ending stamps 01:00 .. 24:00): GHI 500, DNI 600, DHI 100 W/m^2 from 08:00 to 17:00.
set(station "723170,\"GREENSBORO PIEDMONT TRIAD INT\",NC,-5.0,36.100,-79.950,273\n")
set(header "Date (MM/DD/YYYY),Time (HH:MM),ETR (W/m^2),ETRN (W/m^2),GHI (W/m^2),GHI source,GHI uncert (%),")
string(APPEND header "DNI (W/m^2),DNI source,DNI uncert (%),DHI (W/m^2),DHI source,DHI uncert (%)\n")
set(rows "")
set(month 0)
foreach(days 31 28 31 30 31 30 31 31 30 31 30 31)
    math(EXPR month "${month} + 1")
    string(LENGTH "${month}" n)
    set(mm "${month}")
    if(n EQUAL 1)
        set(mm "0${month}")
    endif()
    foreach(day RANGE 1 ${days})
        set(dd "${day}")
        if(day LESS 10)
            set(dd "0${day}")
        endif()
        foreach(hh 01 02 03 04 05 06 07)
            string(APPEND rows "${mm}/${dd}/2001,${hh}:00,0,0,0,1,0,0,1,0,0,1,0\n")
        endforeach()
        foreach(hh 08 09 10 11 12 13 14 15 16 17)
            string(APPEND rows "${mm}/${dd}/2001,${hh}:00,0,0,500,1,0,600,1,0,100,1,0\n")
        endforeach()
        foreach(hh 18 19 20 21 22 23)
            string(APPEND rows "${mm}/${dd}/2001,${hh}:00,0,0,0,1,0,0,1,0,0,1,0\n")
        endforeach()
        if(NOT (month EQUAL 12 AND day EQUAL 31))  # the year's last hour is left out: 8759 rows
            string(APPEND rows "${mm}/${dd}/2001,24:00,0,0,0,1,0,0,1,0,0,1,0\n")
        endif()
    endforeach()
endforeach()
file(WRITE "${WORK_DIR}/short.csv" "${station}${header}${rows}")
file(WRITE "${WORK_DIR}/twice.csv" "${station}${header}${rows}12/31/2001,24:00,0,0,0,1,0,0,1,0,0,1,0\n${rows}")
string(REPLACE "06/21/2001,13:00,0,0,500,1,0,600," "06/21/2001,13:00,0,0,500,1,0,5000," dni_rows "${rows}")
file(WRITE "${WORK_DIR}/dni.csv" "${station}${header}${dni_rows}")

set(coverage "covers 8759 of 8760 hours of the year (1 missing, the first 12/31 24:00: they add nothing; at most 88")
set(solar solar "${WORK_DIR}/dsm.asc" --xy-unit m --z-unit m --formats asc)
set(roofs roofs "${WORK_DIR}/dsm.asc" "${WORK_DIR}/dtm.asc" "${WORK_DIR}/footprints.geojson" --xy-unit m --z-unit m --formats asc)
foreach(command solar roofs)
    execute_process(COMMAND "${LIDARFX}" ${${command}} --tmy "${WORK_DIR}/short.csv" --out "${WORK_DIR}/${command}"
                    RESULT_VARIABLE rc OUTPUT_VARIABLE said ERROR_VARIABLE err)
    if(NOT rc EQUAL 0)
        message(FATAL_ERROR "lidarfx ${command} --tmy short.csv (8759 rows) failed (${rc}):\n${said}\n${err}")
    endif()
    string(FIND "${err}" "weather: ${WORK_DIR}/short.csv ${coverage}" at)
    if(at EQUAL -1)
        message(FATAL_ERROR "lidarfx ${command} does not report the coverage on stderr:\n${err}")
    endif()
    # line 2 + 8759 rows + the 12/31 24:00 row, then the first hour again
    foreach(refusal "twice.csv|line 8763: the hour 01/01 01:00 ('01/01/2001,01:00') is already on line 3"
                    "dni.csv|line 4119: DNI 5000 W/m^2 is above 1415 W/m^2")
        string(REPLACE "|" ";" parts "${refusal}")
        list(GET parts 0 file)
        list(GET parts 1 message)
        execute_process(COMMAND "${LIDARFX}" ${${command}} --tmy "${WORK_DIR}/${file}" --out "${WORK_DIR}/${command}_no"
                        RESULT_VARIABLE rc OUTPUT_VARIABLE said ERROR_VARIABLE err)
        string(FIND "${err}" "${WORK_DIR}/${file}: ${message}" at)
        if(NOT rc EQUAL 2 OR at EQUAL -1)
            message(FATAL_ERROR "lidarfx ${command} --tmy ${file}: expected exit code 2 and '${message}', got ${rc}:\n"
                                "${said}\n${err}")
        endif()
        if(EXISTS "${WORK_DIR}/${command}_no")
            message(FATAL_ERROR "lidarfx ${command} --tmy ${file} left ${WORK_DIR}/${command}_no behind")
        endif()
    endforeach()
endforeach()
message(STATUS "lidarfx solar and roofs: coverage reported (8759 of 8760), a doubled year and DNI 5000 refused")
