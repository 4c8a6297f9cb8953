# SPDX-License-Identifier: Apache-2.0
# `lidarfx solar` on GeoTIFF DSMs (tests/data/dsm_*.tif, made by make_dsm_tifs.py) and a LAS file in UTM 17N
# (tests/data/test_utm17.las): NoData corners stay holes, feet become metres, degrees and rotated grids are
# refused. With PROJ the place comes from the CRS when --lat/--lon are missing (UTM 13N centred on 40 N, 103 W:
# meridian convergence 1.2859 degrees), and the convergence applies when they are given too; without PROJ their
# absence is refused naming them; without GDAL a .tif is refused.
# HAVE_GDAL and HAVE_PROJ say how lidarfx was built.
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")
set(utm "${DATA}/dsm_utm13n.tif")
set(feet "${DATA}/dsm_oregon_north_ft.tif")

function(run_solar name)
    execute_process(COMMAND "${LIDARFX}" solar ${ARGN} --formats asc --out "${WORK_DIR}/${name}"
                    RESULT_VARIABLE rc OUTPUT_VARIABLE said ERROR_VARIABLE err)
    if(NOT rc EQUAL 0)
        message(FATAL_ERROR "lidarfx solar ${ARGN} failed (${rc}):\n${said}\n${err}")
    endif()
    set(said "${said}" PARENT_SCOPE)
endfunction()

function(expect_said phrase)
    string(FIND "${said}" "${phrase}" at)
    if(at EQUAL -1)
        message(FATAL_ERROR "lidarfx solar does not say '${phrase}':\n${said}")
    endif()
endfunction()

# A LAS survey in UTM 17N (EPSG:32617) without --lat/--lon: its grid's centre (289816.5, 4320979.5) is at
# 39.012608 N, 83.427571 W (gdaltransform), 2.43 degrees west of the central meridian (81 W), so grid north is
# west of true north: atan(tan(-2.427571) sin(39.012608)) = -1.5287 degrees.
if(HAVE_PROJ)
    run_solar(las "${DATA}/test_utm17.las")
    expect_said("latitude 39.012608 from the survey's centre (PROJ), longitude -83.427571 from the survey's centre")
    expect_said("meridian convergence -1.5287 degrees")
endif()

set(out "${WORK_DIR}/refused")
if(NOT HAVE_GDAL)
    set(cases "2|needs GDAL|gdal_translate -of AAIGrid|solar^${utm}^--lat^40^--lon^-103^--out^${out}")
    if(NOT HAVE_PROJ)
        list(APPEND cases "2|--lat must be given|without PROJ|solar^${DATA}/test_utm17.las^--out^${out}")
    endif()
    include("${CMAKE_CURRENT_LIST_DIR}/expect_refusals.cmake")
    return()
endif()

# The UTM DSM with --lat/--lon: read in metres, the NoData corner a hole in the maps.
run_solar(given "${utm}" --lat 40 --lon -103)
expect_said("DSM: ${utm}, 16 x 16 cells of 1.000 m, EPSG:32613 (metre)")
expect_said("latitude 40.000000 from --lat, longitude -103.000000 from --lon")
file(STRINGS "${WORK_DIR}/given/annual_kwh_m2.asc" grid_lines)
list(GET grid_lines 6 first_row)
if(NOT first_row MATCHES "^ *-9999 ")
    message(FATAL_ERROR "the NoData cell (0, 0) of ${utm} is not NoData in annual_kwh_m2.asc: ${first_row}")
endif()
file(READ "${WORK_DIR}/given/manifest.json" manifest)
string(FIND "${manifest}" "latitude 40.000000" at)
if(at EQUAL -1)
    message(FATAL_ERROR "manifest.json does not record the latitude used:\n${manifest}")
endif()

# Feet: 3.28 ft cells and heights in feet are 1 m cells and heights in metres: the year's mean is that of the
# same DSM in metres (an ESRI ASCII grid) within 1 % (the convergence, applied with PROJ, moves shadow edges).
run_solar(feet "${feet}" --lat 45.5 --lon -122)
expect_said("cells of 1.000 m, EPSG:2269 (foot)")
set(text "ncols 16\nnrows 16\nxllcorner 0\nyllcorner 0\ncellsize 1\nNODATA_value -9999\n")
foreach(r RANGE 15)
    set(row "")
    foreach(c RANGE 15)
        if((r EQUAL 0 AND c EQUAL 0) OR (r EQUAL 15 AND c EQUAL 15))
            string(APPEND row " -9999")
        elseif(r GREATER_EQUAL 6 AND r LESS 10 AND c GREATER_EQUAL 6 AND c LESS 10)
            string(APPEND row " 106")
        else()
            string(APPEND row " 100")
        endif()
    endforeach()
    string(APPEND text "${row}\n")
endforeach()
file(WRITE "${WORK_DIR}/metres.asc" "${text}")
run_solar(metres "${WORK_DIR}/metres.asc" --xy-unit m --z-unit m --lat 45.5 --lon -122)
function(year_mean folder var)
    file(STRINGS "${WORK_DIR}/${folder}/summary.csv" year REGEX "^\"?year\"?,")
    if(NOT year MATCHES "^\"?year\"?,([0-9]+)")
        message(FATAL_ERROR "${folder}/summary.csv has no year row")
    endif()
    set(${var} ${CMAKE_MATCH_1} PARENT_SCOPE)
endfunction()
year_mean(feet in_feet)
year_mean(metres in_metres)
math(EXPR gap "${in_feet} - ${in_metres}")
if(gap GREATER 18 OR gap LESS -18)
    message(FATAL_ERROR "the DSM in feet gives a year mean of ${in_feet} kWh/m2, the same in metres ${in_metres}")
endif()
message(STATUS "year mean: ${in_feet} kWh/m2 from feet, ${in_metres} from metres")

if(HAVE_PROJ)
    # No --lat/--lon: the centre of the UTM DSM, and grid north 1.2859 degrees east of true north.
    run_solar(placed "${utm}")
    expect_said("latitude 40.000000 from the survey's centre (PROJ), longitude -103.000000 from the survey's centre")
    expect_said("meridian convergence 1.2859 degrees")
    # Given --lat/--lon win, the convergence still applies.
    run_solar(both "${utm}" --lat 41 --lon -104)
    expect_said("latitude 41.000000 from --lat")
    expect_said("meridian convergence 1.2859 degrees")
    # Oregon North (Lambert, central meridian 120.5 W): 1.5 degrees west of it grid north is west of true north.
    run_solar(feet_placed "${feet}")
    expect_said("latitude 45.500000 from the survey's centre (PROJ), longitude -122.000000")
    expect_said("meridian convergence -1.0")
    set(cases)
else()
    set(cases "2|--lat must be given|without PROJ|solar^${utm}^--out^${out}"
              "2|--lat must be given|without PROJ|solar^${DATA}/test_utm17.las^--out^${out}")
endif()
list(APPEND cases
    "2|longitude and latitude in degrees|gdalwarp -t_srs|solar^${DATA}/dsm_epsg4326.tif^--lat^40^--lon^-103^--out^${out}"
    "1|north-up grids of square cells only|rotated|solar^${DATA}/dsm_rotated.tif^--lat^40^--lon^-103^--out^${out}")
include("${CMAKE_CURRENT_LIST_DIR}/expect_refusals.cmake")
