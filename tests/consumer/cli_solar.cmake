# SPDX-License-Identifier: Apache-2.0
# `lidarfx solar` on a small generated DSM (flat ground, one 6 m block) with the clear-sky default writes every
# file its usage promises, says that it used the clear-sky model, and summary.csv has 12 month rows and the year.
# Then the refusals: exit code 2, a message naming the way out, no folder left behind.
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")
set(dsm "${WORK_DIR}/dsm.asc")
include("${CMAKE_CURRENT_LIST_DIR}/block_dsm.cmake")
write_block_dsm("${dsm}" 16 6 10 6 10 106)

set(out "${WORK_DIR}/out")
execute_process(COMMAND "${LIDARFX}" solar "${dsm}" --xy-unit m --z-unit m --lat 52.5 --lon 13.4 --formats asc,png --out "${out}"
                RESULT_VARIABLE rc OUTPUT_VARIABLE said ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
    message(FATAL_ERROR "lidarfx solar failed (${rc}):\n${said}\n${err}")
endif()
string(FIND "${said}" "no --tmy given, using the clear-sky model" at)
if(at EQUAL -1)
    message(FATAL_ERROR "lidarfx solar without --tmy does not say it uses the clear-sky model:\n${said}")
endif()
if(NOT said MATCHES "DSM outliers: 0 spikes and 0 pits")
    message(FATAL_ERROR "the block's corners are not outliers:\n${said}")
endif()
set(expected annual_kwh_m2.asc svf.asc annual_kwh_m2.png svf.png summary.csv dsm_outliers.csv)
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
execute_process(COMMAND "${LIDARFX}" solar "${dsm}" --xy-unit m --z-unit m --lat 52.5 --lon 13.4 --diffuse perez --formats asc
                        --out "${WORK_DIR}/out_perez"
                RESULT_VARIABLE rc OUTPUT_VARIABLE said ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT EXISTS "${WORK_DIR}/out_perez/annual_kwh_m2.asc")
    message(FATAL_ERROR "lidarfx solar --diffuse perez failed (${rc}):\n${said}\n${err}")
endif()

# --svf: each definition is said in the log; share (the dissertation's) writes another svf.asc than the
# default cosine (the SVF of GRASS and SAGA). --surface terrain tilts each cell by its own slope: another map.
foreach(run "cosine;--svf;cosine" "share;--svf;share" "directions;--svf-directions;36" "terrain;--surface;terrain")
    list(GET run 0 name)
    list(SUBLIST run 1 2 option)
    execute_process(COMMAND "${LIDARFX}" solar "${dsm}" --xy-unit m --z-unit m --lat 52.5 --lon 13.4 ${option}
                            --formats asc --out "${WORK_DIR}/out_svf_${name}"
                    RESULT_VARIABLE rc OUTPUT_VARIABLE said ERROR_VARIABLE err)
    if(NOT rc EQUAL 0)
        message(FATAL_ERROR "lidarfx solar ${option} failed (${rc}):\n${said}\n${err}")
    endif()
    set(said_${name} "${said}")
    file(READ "${WORK_DIR}/out_svf_${name}/svf.asc" svf_${name})
    file(READ "${WORK_DIR}/out_svf_${name}/annual_kwh_m2.asc" annual_${name})
endforeach()
if(NOT said_cosine MATCHES "sky view factor: cosine-weighted, 72 azimuths" OR NOT said_share MATCHES
   "sky view factor: share of point sources, 72 azimuths" OR NOT said_directions MATCHES "cosine-weighted, 36 azimuths"
   OR NOT said_terrain MATCHES "surfaces: each cell's own slope and aspect")
    message(FATAL_ERROR "the log does not say which SVF and surfaces were used:\n${said_cosine}\n${said_share}")
endif()
if(svf_share STREQUAL svf_cosine OR svf_directions STREQUAL svf_cosine)
    message(FATAL_ERROR "--svf share or --svf-directions 36 wrote the same svf.asc as the default")
endif()
if(annual_terrain STREQUAL annual_cosine)
    message(FATAL_ERROR "--surface terrain wrote the same annual map as horizontal surfaces")
endif()

# A bird 150 m above the ground in one cell: the log names the cell, dsm_outliers.csv lists it with its height
# before and after, and the shadow it would cast is gone (the cells north of it get what open ground gets);
# --keep-outliers keeps it.
write_block_dsm("${WORK_DIR}/bird.asc" 16 3 4 12 13 250)
foreach(name filtered kept)
    set(option "")
    if(name STREQUAL "kept")
        set(option --keep-outliers)
    endif()
    execute_process(COMMAND "${LIDARFX}" solar "${WORK_DIR}/bird.asc" --xy-unit m --z-unit m --lat 52.5 --lon 13.4
                            ${option} --formats asc --out "${WORK_DIR}/out_bird_${name}"
                    RESULT_VARIABLE rc OUTPUT_VARIABLE said_${name} ERROR_VARIABLE err)
    if(NOT rc EQUAL 0)
        message(FATAL_ERROR "lidarfx solar on the bird DSM (${name}) failed (${rc}):\n${said_${name}}\n${err}")
    endif()
    file(STRINGS "${WORK_DIR}/out_bird_${name}/dsm_outliers.csv" outliers_${name})
endforeach()
if(NOT said_filtered MATCHES "1 spikes and 0 pits" OR NOT said_filtered MATCHES "spike at row 3, col 12 \\(x 1012.50, y 2012.50\\): 250.00 m -> 100.00 m")
    message(FATAL_ERROR "lidarfx solar does not name the bird it filtered:\n${said_filtered}")
endif()
if(NOT outliers_filtered STREQUAL "kind,row,col,x_crs,y_crs,z_m,replaced_by_m;spike,3,12,1012.500,2012.500,250.000,100.000")
    message(FATAL_ERROR "dsm_outliers.csv of the bird:\n${outliers_filtered}")
endif()
if(NOT said_kept MATCHES "DSM outliers: kept" OR NOT outliers_kept STREQUAL "kind,row,col,x_crs,y_crs,z_m,replaced_by_m")
    message(FATAL_ERROR "--keep-outliers:\n${said_kept}\n${outliers_kept}")
endif()
file(READ "${WORK_DIR}/out_bird_filtered/annual_kwh_m2.asc" annual_filtered)
file(READ "${WORK_DIR}/out_bird_kept/annual_kwh_m2.asc" annual_kept)
if(annual_filtered STREQUAL annual_kept)
    message(FATAL_ERROR "the bird's shadow is in both maps")
endif()

# --facades on a 40 x 40 DSM with one 12 x 10 m block 10 m tall: the buildings, facade, table and bill files, one
# building found, the Table 1 header and rows, and the south facade above the north one at 52.5 N.
write_block_dsm("${WORK_DIR}/box.asc" 40 14 24 14 26 110)
set(fac "${WORK_DIR}/out_facades")
execute_process(COMMAND "${LIDARFX}" solar "${WORK_DIR}/box.asc" --xy-unit m --z-unit m --lat 52.5 --lon 13.4 --facades --formats asc,png
                        --out "${fac}"
                RESULT_VARIABLE rc OUTPUT_VARIABLE said ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
    message(FATAL_ERROR "lidarfx solar --facades failed (${rc}):\n${said}\n${err}")
endif()
foreach(f buildings.geojson facade_patches.csv surface_table.csv bill_savings.csv buildings_energy.png)
    if(NOT EXISTS "${fac}/${f}")
        message(FATAL_ERROR "lidarfx solar --facades did not write ${f}")
    endif()
endforeach()
file(READ "${fac}/buildings.geojson" geojson)
string(REGEX MATCHALL "\"building_id\":[0-9]+" ids "${geojson}")
if(NOT ids STREQUAL "\"building_id\":1")
    message(FATAL_ERROR "buildings.geojson should hold exactly building 1, holds: ${ids}")
endif()
file(STRINGS "${fac}/facade_patches.csv" patch_lines LIMIT_COUNT 1)
if(NOT patch_lines STREQUAL "building_id,patch_id,level,facing_azimuth_deg,height_m,area_m2,annual_kwh_m2,q1_kwh_m2_day,q2_kwh_m2_day,q3_kwh_m2_day,q4_kwh_m2_day")
    message(FATAL_ERROR "facade_patches.csv header: ${patch_lines}")
endif()
file(STRINGS "${fac}/surface_table.csv" table)
list(LENGTH table rows)
if(NOT rows EQUAL 6)
    message(FATAL_ERROR "surface_table.csv should have a header and 5 rows:\n${table}")
endif()
foreach(line IN LISTS table)
    if(line MATCHES "^\"?(north|south) facade\"?,[^,]*,[^,]*,[^,]*,[^,]*,([0-9.]+),")
        set(annual_${CMAKE_MATCH_1} "${CMAKE_MATCH_2}")
    endif()
endforeach()
if(NOT DEFINED annual_south OR NOT DEFINED annual_north OR NOT annual_south GREATER annual_north)
    message(FATAL_ERROR "the south facade should get more than the north one:\n${table}")
endif()
message(STATUS "lidarfx solar --facades: south facade ${annual_south}, north ${annual_north} kWh/m2/yr")

set(cases
    "2|--lat must be given|[-90, 90]|solar^${dsm}^--xy-unit^m^--z-unit^m^--out^${out}_refused"
    "2|--lon must be given|[-180, 180]|solar^${dsm}^--xy-unit^m^--z-unit^m^--lat^52^--out^${out}_refused"
    "2|--year-from-tmy needs --tmy|FILE.csv|solar^${dsm}^--xy-unit^m^--z-unit^m^--lat^52^--lon^13^--year-from-tmy^--out^${out}_refused"
    "2|--year must be in|(got 1066)|solar^${dsm}^--xy-unit^m^--z-unit^m^--lat^52^--lon^13^--year^1066^--out^${out}_refused"
    "2|--diffuse must be isotropic or perez|(got hay)|solar^${dsm}^--xy-unit^m^--z-unit^m^--lat^52^--lon^13^--diffuse^hay^--out^${out}_refused"
    "2|--svf must be cosine or share|(got grass)|solar^${dsm}^--xy-unit^m^--z-unit^m^--lat^52^--lon^13^--svf^grass^--out^${out}_refused"
    "2|--svf-directions must be in|(got 2)|solar^${dsm}^--xy-unit^m^--z-unit^m^--lat^52^--lon^13^--svf-directions^2^--out^${out}_refused"
    "2|--surface must be horizontal or terrain|(got roof)|solar^${dsm}^--xy-unit^m^--z-unit^m^--lat^52^--lon^13^--surface^roof^--out^${out}_refused")
set(out "${out}_refused")
include("${CMAKE_CURRENT_LIST_DIR}/expect_refusals.cmake")
