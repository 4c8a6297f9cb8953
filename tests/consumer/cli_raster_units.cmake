# SPDX-License-Identifier: Apache-2.0
# A survey in international feet (tests/data/scene_oregon_ft.las, EPSG:2994, x, y and z in feet): `lidarfx
# rasterize` writes max_z in the CRS's units (3.28 ft cells, heights in feet, the CRS in max_z.prj and in
# max_z.tif), and `lidarfx solar` on that max_z.asc and on max_z.tif gives the year's mean irradiation of `lidarfx
# solar` on the LAS file within 0.5 %, as does the same DSM in another format GDAL reads (Erdas Imagine .img,
# made here with GDAL_TRANSLATE). `lidarfx hydroflatten` writes its DEM in feet too. HAVE_GDAL says how lidarfx was
# built.
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")
set(las "${DATA}/scene_oregon_ft.las")
set(place --lat 44.06 --lon -123.07)
if(HAVE_GDAL)
    set(formats asc,tif)
else()
    set(formats asc)
endif()

function(run name)
    execute_process(COMMAND "${LIDARFX}" ${ARGN} --out "${WORK_DIR}/${name}" RESULT_VARIABLE rc OUTPUT_VARIABLE said
                    ERROR_VARIABLE err)
    if(NOT rc EQUAL 0)
        message(FATAL_ERROR "lidarfx ${ARGN} failed (${rc}):\n${said}\n${err}")
    endif()
    set(said "${said}" PARENT_SCOPE)
endfunction()

# The year's mean from a solar run's summary.csv, in Wh/m2 (an integer: CMake's math is integer math).
function(year_mean name var)
    file(STRINGS "${WORK_DIR}/${name}/summary.csv" rows REGEX "^year,")
    if(NOT rows MATCHES "^year,([0-9]+)\\.?([0-9]*),")
        message(FATAL_ERROR "${name}/summary.csv has no year row: ${rows}")
    endif()
    string(SUBSTRING "${CMAKE_MATCH_2}000" 0 3 milli)
    math(EXPR wh "${CMAKE_MATCH_1} * 1000 + 1${milli} - 1000")
    set(${var} "${wh}" PARENT_SCOPE)
endfunction()

run(rasterize rasterize "${las}" --cell 1 --formats ${formats})
file(STRINGS "${WORK_DIR}/rasterize/max_z.asc" header LIMIT_COUNT 6)
if(NOT header MATCHES "cellsize 3\\.28083")
    message(FATAL_ERROR "max_z.asc of a survey in feet does not have 3.28 ft cells: ${header}")
endif()
if(NOT EXISTS "${WORK_DIR}/rasterize/max_z.prj")
    message(FATAL_ERROR "max_z.asc of a survey in EPSG:2994 has no max_z.prj")
endif()
# Heights in feet: the 8 m block on 100 m ground is 354.33 ft high, the ground 328.08 ft.
file(READ "${WORK_DIR}/rasterize/max_z.asc" cells)
if(NOT cells MATCHES " 354\\.33" OR NOT cells MATCHES " 328\\.08")
    message(FATAL_ERROR "max_z.asc does not hold heights in feet (354.33 ft, 328.08 ft)")
endif()

# lidarfx hydroflatten writes its DEM in the same units: feet, 3.28 ft cells, its .prj beside it.
run(hydro hydroflatten "${las}" --cell 1 --force --formats asc,csv)
file(STRINGS "${WORK_DIR}/hydro/dem_hydroflattened.asc" header LIMIT_COUNT 6)
file(READ "${WORK_DIR}/hydro/dem_hydroflattened.asc" cells)
if(NOT header MATCHES "cellsize 3\\.28083" OR NOT EXISTS "${WORK_DIR}/hydro/dem_hydroflattened.prj"
   OR NOT cells MATCHES " 354\\.33" OR NOT cells MATCHES " 328\\.08")
    message(FATAL_ERROR "dem_hydroflattened.asc of a survey in feet is not in feet with its .prj: ${header}")
endif()

run(solar_las solar "${las}" ${place} --formats asc)
year_mean(solar_las from_las)
set(dsms "${WORK_DIR}/rasterize/max_z.asc")
if(HAVE_GDAL)
    list(APPEND dsms "${WORK_DIR}/rasterize/max_z.tif")
    if(GDAL_TRANSLATE)
        execute_process(COMMAND "${GDAL_TRANSLATE}" -q -of HFA "${WORK_DIR}/rasterize/max_z.tif"
                                "${WORK_DIR}/max_z.img" RESULT_VARIABLE rc ERROR_VARIABLE err)
        if(NOT rc EQUAL 0)
            message(FATAL_ERROR "gdal_translate -of HFA failed: ${err}")
        endif()
        list(APPEND dsms "${WORK_DIR}/max_z.img")
    endif()
endif()
set(i 0)
foreach(dsm IN LISTS dsms)
    math(EXPR i "${i} + 1")
    run(solar_dsm${i} solar "${dsm}" ${place} --formats asc)
    string(FIND "${said}" "cells of 1.000 m, EPSG:2994 (foot)" at)
    if(at EQUAL -1)
        message(FATAL_ERROR "lidarfx solar does not read ${dsm} as 1 m cells in EPSG:2994:\n${said}")
    endif()
    year_mean(solar_dsm${i} from_dsm)
    math(EXPR off_ppm "(${from_dsm} - ${from_las}) * 1000000 / ${from_las}")
    if(off_ppm GREATER 5000 OR off_ppm LESS -5000)
        message(FATAL_ERROR "solar on ${dsm}: mean ${from_dsm} Wh/m2, on the LAS file ${from_las} (off by more than 0.5 %)")
    endif()
    message(STATUS "solar on ${dsm}: mean ${from_dsm} Wh/m2, on the LAS file ${from_las}")
endforeach()

# Without its .prj, max_z.asc has no known units: refused (exit code 2, naming the flags, no folder left) unless
# --xy-unit and --z-unit state them; stated as feet it gives the mean again within 0.5 % (without a CRS the sun's
# azimuths are not turned by the meridian convergence, -1.79 degrees here), and flags that disagree with a
# .prj are refused.
file(MAKE_DIRECTORY "${WORK_DIR}/bare")
file(COPY "${WORK_DIR}/rasterize/max_z.asc" DESTINATION "${WORK_DIR}/bare")
set(bare "${WORK_DIR}/bare/max_z.asc")
set(out "${WORK_DIR}/refused")
set(cases
    "2|the units of this raster are unknown|--xy-unit m|solar^${bare}^--lat^44.06^--lon^-123.07^--out^${out}"
    "2|the units of this raster are unknown|--z-unit|solar^${bare}^--lat^44.06^--lon^-123.07^--xy-unit^ft^--out^${out}"
    "2|--xy-unit must be m, ft|(got yard)|solar^${bare}^--lat^44.06^--lon^-123.07^--xy-unit^yard^--z-unit^ft^--out^${out}"
    "2|disagree with its CRS|max_z.prj|solar^${WORK_DIR}/rasterize/max_z.asc^--lat^44.06^--lon^-123.07^--xy-unit^m^--z-unit^m^--out^${out}")
# A GeoTIFF without CRS keys has unknown units too (made from the bare grid, which has no .prj to carry over).
if(HAVE_GDAL AND GDAL_TRANSLATE)
    execute_process(COMMAND "${GDAL_TRANSLATE}" -q -of GTiff "${bare}" "${WORK_DIR}/bare/max_z.tif" RESULT_VARIABLE rc)
    list(APPEND cases
        "2|the units of this raster are unknown|the file states no CRS|solar^${WORK_DIR}/bare/max_z.tif^--lat^44.06^--lon^-123.07^--out^${out}")
endif()
include("${CMAKE_CURRENT_LIST_DIR}/expect_refusals.cmake")
run(solar_bare solar "${bare}" ${place} --xy-unit ft --z-unit ft --formats asc)
year_mean(solar_bare from_bare)
math(EXPR off_ppm "(${from_bare} - ${from_las}) * 1000000 / ${from_las}")
if(off_ppm GREATER 5000 OR off_ppm LESS -5000)
    message(FATAL_ERROR "solar on ${bare} with --xy-unit ft --z-unit ft: mean ${from_bare} Wh/m2, on the LAS ${from_las}")
endif()
message(STATUS "solar on ${bare} with --xy-unit ft --z-unit ft: mean ${from_bare} Wh/m2 (no CRS: no meridian convergence)")
if(HAVE_GDAL AND GDAL_TRANSLATE)
    run(solar_bare_tif solar "${WORK_DIR}/bare/max_z.tif" ${place} --xy-unit ft --z-unit ft --formats asc)
    year_mean(solar_bare_tif from_bare_tif)
    if(NOT from_bare_tif EQUAL from_bare)
        message(FATAL_ERROR "solar on the bare GeoTIFF: mean ${from_bare_tif} Wh/m2, on the bare ESRI ASCII ${from_bare}")
    endif()
endif()
