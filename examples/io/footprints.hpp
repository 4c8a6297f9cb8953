// SPDX-License-Identifier: Apache-2.0
// Building footprints from a GeoJSON FeatureCollection (Polygon / MultiPolygon features with an integer
// `building_id` property) or, with GDAL, from any vector source OGR opens (io/vectors.hpp), checked so that no
// footprint is lost without a word.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <lidarfx/kernels/vector/polygonize.hpp>

namespace lidarfx::io {

/// The largest |x| or |y| a footprint vertex may have, in the units of the file's CRS: 1e9 is 25 times the
/// Earth's circumference in metres (no projected CRS comes near it), a double still resolves 1e-7 there, and
/// the validity checks (Boost.Geometry) stay far from their integer overflow near 1e19.
inline constexpr double footprint_max_abs_coordinate = 1e9;

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
    std::uint64_t peak_bytes = 0;  ///< the read's memory estimate at its peak (text, kept footprints, one feature)
    /// The CRS the file states, as written: a GeoJSON `crs` member's name ("urn:ogc:def:crs:EPSG::32613"),
    /// an OGR layer's WKT; "" when the file states none.
    std::string crs;
    std::vector<std::string> notes;  ///< what the read assumed, one sentence each (e.g. ids taken from the FIDs)
};

/// How a footprint file is read.
struct footprint_read_options {
    /// Memory budget of the read, bytes; 0 = half the physical memory (as --memory). The estimate counted
    /// against it: the file's text; per kept footprint 16 bytes a vertex, 48 a ring and a part, and about 150
    /// (its entry in the list and its id); and 48 bytes a vertex of the feature being read (its coordinates,
    /// its rings and the validity check's copy).
    std::uint64_t memory_budget_bytes = 0;
    /// The property (field) holding each footprint's id; "" = building_id (with the FID fallback of
    /// read_footprints_ogr when the source has no such field).
    std::string id_field{};
};

/// The memory budget `opt` gives a read: its memory_budget_bytes, or half the physical memory when that is 0.
std::uint64_t footprint_memory_budget(const footprint_read_options& opt);

/// Why the footprint cannot be used as drawn ("" when it can): a ring crossing itself, zero area, or another
/// reason of Boost.Geometry's is_valid. @throws what Boost.Geometry throws (e.g. a numeric cast).
std::string footprint_geometry_problem(const footprint& fp);

/// A byte count as the readers' memory messages print it: "1.5 GiB" from 1 GiB up, else "12.3 MiB".
std::string footprint_size_text(double bytes);

/// Orients every part as lidarfx::polygon documents: outer ring counter-clockwise, holes clockwise.
void orient_footprint(footprint& fp);

/// Files a footprint just read: into out.problems with its reason when footprint_geometry_problem finds one, else
/// oriented (orient_footprint) into out.footprints. Adds what it keeps to the read's memory estimate: per vertex
/// 16 bytes, per ring and part 48 (a vector and its allocation), per footprint or problem its entry in a list
/// that grows by doubling and its id in the reader's id table (64), a problem's text.
/// @throws invalid_input naming `at` when the polygon checks themselves fail (Boost.Geometry's own exceptions).
void keep_footprint(footprint&& fp, const std::string& at, footprint_collection& out, double& kept_bytes,
                    std::size_t& kept_vertices);

/// Parses GeoJSON text in one pass that keeps only the footprints (one feature's coordinates at a time, no
/// document tree), so memory follows the vertices kept: about the text plus 16 bytes per vertex. A UTF-8
/// byte order mark at the start is skipped. Structural errors throw invalid_input naming `source`, the
/// feature index (and building_id once read) and what to fix: not JSON (with byte and line) or not a
/// FeatureCollection, a feature without a Polygon/MultiPolygon geometry (null geometries included), a
/// missing or non-integer `building_id` (the property opt.id_field names, when given; or one outside 1 .. 2^31 - 1, the
/// value as written), an id used by two features, a coordinate that is not a number or whose magnitude is beyond
/// footprint_max_abs_coordinate or a double's range (the value as written, its axis and vertex), a ring with fewer than
/// 4 positions; and a read whose estimate exceeds the budget (naming the budget and the feature reached). Geometric
/// faults are reported per building in `problems` and the footprint is left out: zero area, a self-intersecting or
/// otherwise invalid polygon (Boost.Geometry's is_valid, with its reason). Ring order and orientation are
/// normalised (outer counter-clockwise, holes clockwise, closed). A top-level `crs` member (GeoJSON 2008,
/// as GDAL writes for a projected CRS) gives `crs` its name; without one, `crs` stays "" (lidarfx takes such
/// a file to be in the survey's CRS, not RFC 7946's WGS 84).
footprint_collection parse_footprints_geojson(const std::string& text, const std::string& source,
                                              const footprint_read_options& opt = {});

/// parse_footprints_geojson on the contents of `path`, read into one buffer of the file's size (refused
/// before reading when the file alone exceeds the budget). @throws std::runtime_error naming the file when
/// it cannot be read.
footprint_collection read_footprints_geojson(const std::string& path, const footprint_read_options& opt = {});

/// True when read_footprints reads `path` with the GeoJSON reader above (names ending .geojson or .json, any
/// case); other files go through OGR.
bool is_geojson_name(const std::string& path);

/// Footprints from `path`: read_footprints_geojson for GeoJSON names, read_footprints_ogr (io/vectors.hpp)
/// for any other. @throws as those; std::runtime_error saying how to get OGR formats (rebuild with GDAL) for a
/// file that is not GeoJSON in a build without GDAL.
footprint_collection read_footprints(const std::string& path, const footprint_read_options& opt = {});

}  // namespace lidarfx::io
