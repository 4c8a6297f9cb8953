# SPDX-License-Identifier: Apache-2.0
# `lidarfx roofs` with footprints in the formats OGR reads (made here with ogr2ogr from one GeoJSON): GeoJSON,
# GeoPackage, Shapefile and FlatGeobuf give byte-identical roof_patches.csv and footprints.csv; --id-field picks
# another field; a file without building_id takes its FIDs (with a note); footprints in another CRS (WGS 84, the
# neighbouring UTM zone) are reprojected onto a survey with a CRS and cover the same cells; GeoPackage outputs
# carry the survey's EPSG code; footprints with a CRS on a survey without one are refused (exit code 2).
# DSM and DTM as GeoTIFF give the same patches as ESRI ASCII.
# Needs: LIDARFX, OGR2OGR, OGRINFO, DATA (tests/data), WORK_DIR; GDAL_TRANSLATE (optional).
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")

# DSM and DTM without a CRS (roofs_scene.cmake): a shed roof (building 7) and a flat roof (8) on 50 x 50 cells.
include("${CMAKE_CURRENT_LIST_DIR}/roofs_scene.cmake")
write_roofs_scene("${WORK_DIR}")

# Grids without a .prj may need their units stated (when this lidarfx has --xy-unit).
execute_process(COMMAND "${LIDARFX}" roofs --help OUTPUT_VARIABLE help ERROR_VARIABLE help)
set(units)
if(help MATCHES "--xy-unit")
    set(units --xy-unit m --z-unit m)
endif()

function(footprint_file path features)
    file(WRITE "${path}" "{\"type\":\"FeatureCollection\",\"features\":[${features}]}")
endfunction()
function(feature out id objid ring)
    set(${out} "{\"type\":\"Feature\",\"properties\":{\"building_id\":${id},\"objid\":${objid}},\"geometry\":{\"type\":\"Polygon\",\"coordinates\":[${ring}]}}" PARENT_SCOPE)
endfunction()
feature(shed 7 107 "[[1010,2040],[1030,2040],[1030,2028],[1010,2028],[1010,2040]]")
feature(flat 8 108 "[[1010,2020],[1025,2020],[1025,2008],[1010,2008],[1010,2020]]")
feature(far 9 109 "[[5000,5000],[5010,5000],[5010,5010],[5000,5010],[5000,5000]]")
footprint_file("${WORK_DIR}/fp.geojson" "${shed},${flat},${far}")

function(ogr2ogr)
    execute_process(COMMAND "${OGR2OGR}" ${ARGN} RESULT_VARIABLE rc ERROR_VARIABLE err)
    if(NOT rc EQUAL 0)
        message(FATAL_ERROR "ogr2ogr ${ARGN} failed (${rc}): ${err}")
    endif()
endfunction()
# roofs on `inputs` with the footprints `fp` into WORK_DIR/`name`; its stderr in roofs_err.
function(roofs name fp)
    execute_process(COMMAND "${LIDARFX}" roofs ${inputs} "${fp}" --out "${WORK_DIR}/${name}" ${ARGN}
                    RESULT_VARIABLE rc OUTPUT_VARIABLE said ERROR_VARIABLE err)
    if(NOT rc EQUAL 0)
        message(FATAL_ERROR "lidarfx roofs ... ${fp} ${ARGN} failed (${rc}):\n${said}\n${err}")
    endif()
    set(roofs_err "${err}" PARENT_SCOPE)
endfunction()
function(expect_same a b file)
    file(READ "${WORK_DIR}/${a}/${file}" ta)
    file(READ "${WORK_DIR}/${b}/${file}" tb)
    if(NOT ta STREQUAL tb)
        message(FATAL_ERROR "${b}/${file} differs from ${a}/${file}:\n${ta}\n--\n${tb}")
    endif()
endfunction()

# No CRS anywhere: GeoPackage and FlatGeobuf get GeoPackage's undefined cartesian SRS, the Shapefile no .prj
# (ogr2ogr would give both WGS 84, the CRS RFC 7946 implies for GeoJSON).
set(nocrs "LOCAL_CS[\"Undefined cartesian SRS\",UNIT[\"metre\",1]]")
ogr2ogr(-f GPKG "${WORK_DIR}/fp.gpkg" "${WORK_DIR}/fp.geojson" -a_srs "${nocrs}")
ogr2ogr(-f "ESRI Shapefile" "${WORK_DIR}/fp.shp" "${WORK_DIR}/fp.geojson")
file(REMOVE "${WORK_DIR}/fp.prj")
# (FlatGeobuf's spatial index would put the features in another order, and footprints.csv lists them in file order.)
ogr2ogr(-f FlatGeobuf "${WORK_DIR}/fp.fgb" "${WORK_DIR}/fp.geojson" -a_srs "${nocrs}" -lco SPATIAL_INDEX=NO)
set(inputs "${WORK_DIR}/dsm.asc" "${WORK_DIR}/dtm.asc" ${units})
roofs(out_geojson "${WORK_DIR}/fp.geojson")
file(STRINGS "${WORK_DIR}/out_geojson/roof_patches.csv" rows)
list(LENGTH rows n)
if(n LESS 3)
    message(FATAL_ERROR "roof_patches.csv from GeoJSON footprints should have the shed and the flat roof:\n${rows}")
endif()
foreach(format gpkg shp fgb)
    roofs(out_${format} "${WORK_DIR}/fp.${format}")
    expect_same(out_geojson out_${format} roof_patches.csv)
    expect_same(out_geojson out_${format} footprints.csv)
endforeach()
message(STATUS "GeoJSON, GeoPackage, Shapefile and FlatGeobuf footprints: the same roof_patches.csv (${n} lines)")

# The DSM and DTM as GeoTIFFs (any raster GDAL reads will do) give the same patches as the ESRI ASCII grids.
if(GDAL_TRANSLATE)
    foreach(model dsm dtm)
        execute_process(COMMAND "${GDAL_TRANSLATE}" -q -of GTiff "${WORK_DIR}/${model}.asc" "${WORK_DIR}/${model}.tif"
                        RESULT_VARIABLE rc ERROR_VARIABLE err)
        if(NOT rc EQUAL 0)
            message(FATAL_ERROR "gdal_translate ${model}.asc failed: ${err}")
        endif()
    endforeach()
    set(inputs_asc ${inputs})
    set(inputs "${WORK_DIR}/dsm.tif" "${WORK_DIR}/dtm.tif" ${units})
    roofs(out_tif "${WORK_DIR}/fp.geojson")
    expect_same(out_geojson out_tif roof_patches.csv)
    expect_same(out_geojson out_tif footprints.csv)
    set(inputs ${inputs_asc})
    message(STATUS "GeoTIFF DSM and DTM: the same roof_patches.csv as from ESRI ASCII")
endif()

# The GeoPackage output of a survey without a CRS: GeoPackage's undefined cartesian SRS; its patches as in the CSV.
execute_process(COMMAND "${OGRINFO}" -so "${WORK_DIR}/out_gpkg/roof_patches.gpkg" roof_patches OUTPUT_VARIABLE info)
if(NOT info MATCHES "Undefined Cartesian SRS" OR NOT info MATCHES "building_id: Integer64")
    message(FATAL_ERROR "roof_patches.gpkg of a survey without CRS:\n${info}")
endif()

# --id-field objid: the ids are 107 and 108.
roofs(out_objid "${WORK_DIR}/fp.gpkg" --id-field objid)
file(READ "${WORK_DIR}/out_objid/roof_patches.csv" csv)
if(NOT csv MATCHES "\n107," OR NOT csv MATCHES "\n108," OR csv MATCHES "\n7,")
    message(FATAL_ERROR "--id-field objid should give ids 107 and 108:\n${csv}")
endif()
# Without building_id: the FIDs (GeoPackage counts from 1: the shed is 1, the flat roof 2), with a note.
ogr2ogr(-f GPKG "${WORK_DIR}/noid.gpkg" "${WORK_DIR}/fp.geojson" -select objid -a_srs "${nocrs}")
roofs(out_fid "${WORK_DIR}/noid.gpkg")
if(NOT roofs_err MATCHES "no field \"building_id\": the footprints' ids are their feature ids \\(FID\\)")
    message(FATAL_ERROR "no note on the FIDs used as ids:\n${roofs_err}")
endif()
file(READ "${WORK_DIR}/out_fid/roof_patches.csv" csv)
if(NOT csv MATCHES "\n1," OR NOT csv MATCHES "\n2," OR csv MATCHES "\n7,")
    message(FATAL_ERROR "the FIDs should be the ids (1 and 2):\n${csv}")
endif()
message(STATUS "--id-field objid gives 107 and 108; without building_id the FIDs 1 and 2, with a note")

# A survey with a CRS: test_utm17.las (EPSG:32617, 5 x 3 cells of 1 m from x 289814, y 4320978). A footprint
# over x 289815..289818, y 4320979..4320981 covers 6 cell centres; the same in WGS 84 (GeoPackage) and in the
# neighbouring zone 18 (a Shapefile with its .prj, a GeoJSON with a crs member) is reprojected back and covers the
# same 6 cells.
footprint_file("${WORK_DIR}/utm17.geojson" "{\"type\":\"Feature\",\"properties\":{\"building_id\":5},\"geometry\":{\"type\":\"Polygon\",\"coordinates\":[[[289815,4320979],[289818,4320979],[289818,4320981],[289815,4320981],[289815,4320979]]]}}")
ogr2ogr(-f GPKG "${WORK_DIR}/wgs84.gpkg" "${WORK_DIR}/utm17.geojson" -s_srs EPSG:32617 -t_srs EPSG:4326)
ogr2ogr(-f "ESRI Shapefile" "${WORK_DIR}/utm18.shp" "${WORK_DIR}/utm17.geojson" -s_srs EPSG:32617 -t_srs EPSG:32618)
# GeoJSON in a projected CRS: ogr2ogr names it in a crs member, which lidarfx's GeoJSON reader keeps.
ogr2ogr(-f GeoJSON "${WORK_DIR}/utm18.geojson" "${WORK_DIR}/utm17.geojson" -s_srs EPSG:32617 -t_srs EPSG:32618)
set(inputs "${DATA}/test_utm17.las")
roofs(las_utm17 "${WORK_DIR}/utm17.geojson")
if(NOT roofs_err MATCHES "states no CRS; its footprints are taken to be in the survey's CRS")
    message(FATAL_ERROR "no note on the footprints without CRS:\n${roofs_err}")
endif()
file(READ "${WORK_DIR}/las_utm17/footprints.csv" report)
if(NOT report MATCHES "\n5,0,used,6,")
    message(FATAL_ERROR "the UTM footprint should cover 6 cells:\n${report}")
endif()
foreach(case "las_wgs84|wgs84.gpkg|EPSG:4326" "las_utm18|utm18.shp|EPSG:32618" "las_json18|utm18.geojson|EPSG:32618")
    string(REPLACE "|" ";" case "${case}")
    list(GET case 0 name)
    list(GET case 1 fp)
    list(GET case 2 crs)
    roofs(${name} "${WORK_DIR}/${fp}")
    if(NOT roofs_err MATCHES "footprints reprojected from ${crs} to the survey's CRS")
        message(FATAL_ERROR "${fp}: no note on the reprojection from ${crs}:\n${roofs_err}")
    endif()
    expect_same(las_utm17 ${name} footprints.csv)
    expect_same(las_utm17 ${name} roof_patches.csv)
endforeach()
execute_process(COMMAND "${OGRINFO}" -so "${WORK_DIR}/las_wgs84/roof_patches.gpkg" roof_patches OUTPUT_VARIABLE info)
string(REGEX MATCHALL "ID\\[\"EPSG\",[0-9]+\\]" ids "${info}")
list(GET ids -1 root)
if(NOT root STREQUAL "ID[\"EPSG\",32617]")
    message(FATAL_ERROR "roof_patches.gpkg should be in the survey's EPSG:32617:\n${info}")
endif()
file(READ "${WORK_DIR}/las_wgs84/roof_patches.geojson" geojson)
if(NOT geojson MATCHES "urn:ogc:def:crs:EPSG::32617")
    message(FATAL_ERROR "roof_patches.geojson should name EPSG:32617: ${geojson}")
endif()
# A GeoJSON in WGS 84 without a crs member (RFC 7946 style) is taken to be in the survey's CRS: off the grid, said.
ogr2ogr(-f GeoJSON "${WORK_DIR}/rfc7946.geojson" "${WORK_DIR}/wgs84.gpkg" -lco RFC7946=YES)
roofs(las_rfc7946 "${WORK_DIR}/rfc7946.geojson")
file(READ "${WORK_DIR}/las_rfc7946/footprints.csv" report)
if(NOT report MATCHES "\n5,0,outside the grid" OR NOT roofs_err MATCHES "every footprint lies outside the grid")
    message(FATAL_ERROR "an RFC 7946 GeoJSON on a UTM survey should be reported off the grid:\n${report}\n${roofs_err}")
endif()
message(STATUS "footprints in EPSG:4326 and EPSG:32618 (Shapefile, GeoJSON) reprojected onto the EPSG:32617 survey: the same 6 cells")

# Refused, exit code 2, nothing written: footprints with a CRS on a survey without one, before any cell is read
# (a DTM whose cells are cut off is never reached); an --id-field the file does not have.
file(READ "${WORK_DIR}/dtm.asc" dtm_text)
string(FIND "${dtm_text}" "NODATA_value" header_end)
math(EXPR cut "${header_end} + 40")
string(SUBSTRING "${dtm_text}" 0 ${cut} dtm_cut)
file(WRITE "${WORK_DIR}/dtm_cut.asc" "${dtm_cut}")
list(JOIN units "^" unit_args)
set(out "${WORK_DIR}/refused")
set(no_crs "the footprints are in EPSG:4326 but the survey states no CRS")
set(cases
    "2|${no_crs}|give the survey its CRS|roofs^${WORK_DIR}/dsm.asc^${WORK_DIR}/dtm.asc^${unit_args}^${WORK_DIR}/wgs84.gpkg^--out^${out}"
    "2|${no_crs}|give the survey its CRS|roofs^${WORK_DIR}/dsm.asc^${WORK_DIR}/dtm_cut.asc^${unit_args}^${WORK_DIR}/wgs84.gpkg^--out^${out}"
    "2|no field \"parcel\"|fp.gpkg|roofs^${WORK_DIR}/dsm.asc^${WORK_DIR}/dtm.asc^${unit_args}^${WORK_DIR}/fp.gpkg^--id-field^parcel^--out^${out}")
include("${CMAKE_CURRENT_LIST_DIR}/expect_refusals.cmake")
message(STATUS "refused: footprints with a CRS on a survey without one; an --id-field the file does not have")
