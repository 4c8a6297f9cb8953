// SPDX-License-Identifier: Apache-2.0
// Building footprints from a GeoJSON FeatureCollection (Polygon / MultiPolygon features with an integer
// `building_id` property), checked so that no footprint is lost without a word.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <lidarfx/kernels/vector/polygonize.hpp>

namespace lidarfx::io {

/// One building footprint: its id and parts (each an exterior ring and holes, closed, in file coordinates).
struct footprint {
    std::int32_t building_id = 0;
    std::vector<polygon> parts;
    std::size_t feature = 0;  ///< index of its feature in the file (0-based)
};

/// A footprint that cannot be used as drawn, with the reason ("self-intersecting ring", "empty (zero area)").
struct footprint_problem {
    std::int32_t building_id = 0;
    std::size_t feature = 0;
    std::string problem;
};

/// The usable footprints and the problems of the others (each footprint is in exactly one of the two).
struct footprint_collection {
    std::vector<footprint> footprints;
    std::vector<footprint_problem> problems;
};

/// Parses GeoJSON text. Structural errors throw invalid_input naming `source`, the feature index and what to
/// fix: not JSON or not a FeatureCollection, a feature without a Polygon/MultiPolygon geometry (null
/// geometries included), a missing or non-integer `building_id` (or one outside 1 .. 2^31 - 1), an id used
/// by two features, a non-finite or non-numeric coordinate, a ring with fewer than 4 positions. Geometric
/// faults are reported per building in `problems` and the footprint is left out: zero area, a
/// self-intersecting or otherwise invalid polygon (Boost.Geometry's is_valid, with its reason). Ring order and
/// orientation are normalised (outer counter-clockwise, holes clockwise, closed).
footprint_collection parse_footprints_geojson(const std::string& text, const std::string& source);

/// parse_footprints_geojson on the contents of `path`. @throws std::runtime_error naming the file when it
/// cannot be read.
footprint_collection read_footprints_geojson(const std::string& path);

}  // namespace lidarfx::io
