# SPDX-License-Identifier: Apache-2.0
# Every raster `lidarfx rasterize` and `lidarfx solar` write on a LAS survey in UTM 17N (tests/data/test_utm17.las,
# EPSG:32617), read back by GDAL (gdalsrsinfo): each .asc through the .prj written beside it, each .tif through its
# own keys, names the survey's CRS; every .tif is a Cloud-Optimized GeoTIFF (gdalinfo: LAYOUT=COG, DEFLATE).
# GDALSRSINFO and GDALINFO are GDAL's programs.
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")

function(run name)
    execute_process(COMMAND "${LIDARFX}" ${ARGN} --formats asc,tif --out "${WORK_DIR}/${name}"
                    RESULT_VARIABLE rc OUTPUT_VARIABLE said ERROR_VARIABLE err)
    if(NOT rc EQUAL 0)
        message(FATAL_ERROR "lidarfx ${ARGN} failed (${rc}):\n${said}\n${err}")
    endif()
endfunction()

# Each .asc has its .prj, and GDAL identifies EPSG:32617 in every .asc and .tif of the folder.
function(expect_crs name)
    file(GLOB grids "${WORK_DIR}/${name}/*.asc" "${WORK_DIR}/${name}/*.tif")
    list(LENGTH grids n)
    if(n LESS 2)
        message(FATAL_ERROR "lidarfx ${name} wrote fewer than 2 rasters: ${grids}")
    endif()
    foreach(grid IN LISTS grids)
        if(grid MATCHES "\\.asc$")
            string(REGEX REPLACE "\\.asc$" ".prj" prj "${grid}")
            if(NOT EXISTS "${prj}")
                message(FATAL_ERROR "${grid} has no .prj beside it")
            endif()
        endif()
        execute_process(COMMAND "${GDALSRSINFO}" -e -o epsg "${grid}" RESULT_VARIABLE rc OUTPUT_VARIABLE srs
                        ERROR_VARIABLE err)
        if(NOT rc EQUAL 0 OR NOT srs MATCHES "EPSG:32617")
            message(FATAL_ERROR "GDAL does not read EPSG:32617 from ${grid} (${rc}):\n${srs}\n${err}")
        endif()
        if(grid MATCHES "\\.tif$")
            execute_process(COMMAND "${GDALINFO}" "${grid}" RESULT_VARIABLE rc OUTPUT_VARIABLE info ERROR_VARIABLE err)
            if(NOT rc EQUAL 0 OR NOT info MATCHES "LAYOUT=COG" OR NOT info MATCHES "COMPRESSION=DEFLATE")
                message(FATAL_ERROR "${grid} is not a DEFLATE Cloud-Optimized GeoTIFF (${rc}):\n${info}\n${err}")
            endif()
        endif()
    endforeach()
    message(STATUS "${name}: ${n} rasters, each in EPSG:32617, the .tif files COG")
endfunction()

run(rasterize rasterize "${DATA}/test_utm17.las" --cell 1)
expect_crs(rasterize)
run(solar solar "${DATA}/test_utm17.las" --lat 39 --lon -83.4)
expect_crs(solar)
