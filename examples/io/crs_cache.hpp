// SPDX-License-Identifier: Apache-2.0
// crs_of with its answers kept on disk: a survey's thousands of tiles, and every later run, skip GDAL's search.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "io/crs.hpp"
#include "io/las.hpp"

namespace lidarfx::io {

/// Where remembered CRS answers live: $LIDARFX_CACHE_DIR/crs when that variable is set and not empty, else
/// $XDG_CACHE_HOME/lidarfx/crs, else $HOME/.cache/lidarfx/crs. Nothing (no cache) when LIDARFX_CACHE_DIR is set
/// to the empty string or no home is known.
std::optional<std::filesystem::path> crs_cache_folder();

/// The same answer as crs_of(h) (with GDAL), remembered in `folder` (default crs_cache_folder()) under a key made
/// of h's CRS records (GeoKeys, their parameters, the WKT record, the WKT flag), the versions of GDAL and PROJ
/// (whose EPSG database ships with it) and the text of the code that interprets them. Interpreting a CRS given
/// by parameters costs about 0.1 s of GDAL's time (its search for a matching EPSG code, mostly); a remembered
/// answer costs a file read. Each answer is one small file, written under a temporary name and renamed into
/// place, so that concurrent runs never read half an answer; a file that cannot be read back exactly is
/// ignored and written again. Only files of this form in that folder are ever written; none are deleted. When
/// the folder cannot be created or written, the answer is computed as crs_of does and nothing is kept.
/// Without GDAL, crs_of itself (cheap) is returned. Never throws for bad CRS data, like crs_of.
survey_crs crs_of_remembered(const las_header& h,
                             const std::optional<std::filesystem::path>& folder = crs_cache_folder());

}  // namespace lidarfx::io
