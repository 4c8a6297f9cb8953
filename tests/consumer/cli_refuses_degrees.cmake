# SPDX-License-Identifier: Apache-2.0
# A survey in degrees (EPSG:4326) is refused by the distance-based subcommands with exit code 2, a message that
# says why and how to reproject, and no output folder left behind.
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")
set(out "${WORK_DIR}/out")
set(cases
    "2|longitude and latitude in degrees|EPSG:4326|rasterize^${DATA}^--cell^2^--out^${out}"
    "2|Reproject|filters.reprojection|rasterize^${DATA}^--cell^2^--out^${out}"
    "2|longitude and latitude in degrees|EPSG:4326|water^${DATA}^--cell^2^--out^${out}"
    "2|Reproject|filters.reprojection|water^${DATA}^--cell^2^--out^${out}")
include("${CMAKE_CURRENT_LIST_DIR}/expect_refusals.cmake")
