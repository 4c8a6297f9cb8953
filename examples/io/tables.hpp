// SPDX-License-Identifier: Apache-2.0
// CSV tables and GeoJSON polygon collections for the example program's outputs.
#pragma once

#include <array>
#include <concepts>
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

namespace lidarfx::io {

/// One cell of a table or one GeoJSON property: empty (null), bool, integer, real number or text.
/// Numbers are written in the shortest form that reads back to the same value; a NaN or infinite real
/// is written as an empty CSV field and as JSON null.
class table_value {
public:
    table_value() = default;        ///< null
    table_value(std::nullptr_t) {}  ///< null
    table_value(bool v) : v_(v) {}
    template <std::signed_integral T>
    table_value(T v) : v_(static_cast<std::int64_t>(v))
    {
    }
    template <std::unsigned_integral T>
    requires(!std::same_as<T, bool>) table_value(T v) : v_(static_cast<std::uint64_t>(v)) {}
    template <std::floating_point T>
    table_value(T v) : v_(static_cast<double>(v))
    {
    }
    table_value(std::string v) : v_(std::move(v)) {}
    table_value(const char* v) : v_(std::string(v)) {}
    table_value(std::string_view v) : v_(std::string(v)) {}

    bool is_null() const noexcept { return std::holds_alternative<std::monostate>(v_); }
    bool is_text() const noexcept { return std::holds_alternative<std::string>(v_); }
    /// The value as written in CSV (unquoted) or, for non-text values, in JSON.
    std::string format() const;
    /// The value as a JSON value: text quoted and escaped, non-finite reals and null as null.
    std::string json() const;

    using variant = std::variant<std::monostate, bool, std::int64_t, std::uint64_t, double, std::string>;
    /// The value itself (for writers that keep types, such as GeoPackage fields).
    const variant& value() const noexcept { return v_; }

private:
    variant v_;
};

/// A CSV column: its header name, with the unit in it, and how its real numbers are written. Integers,
/// booleans and text are written as they are in every column; a real number is written in fixed notation with
/// `decimals` decimals (correctly rounded, "-0" written as "0"), or refused when decimals < 0 (a column of ids,
/// counts, flags or text). Build columns with the kind functions below, one rounding rule per kind of quantity.
struct csv_column {
    std::string name;
    int decimals = -1;  ///< decimals of a real number; < 0: the column takes no real numbers
};

/// Ids, counts, 0/1 flags and text (no real numbers). Any name.
csv_column text_column(std::string name);
/// Heights, levels and lengths in metres, to the mm (3 decimals). The name ends in "_m".
csv_column metres_column(std::string name);
/// Areas in m², to 0.1 m² (1 decimal). The name ends in "_m2".
csv_column area_column(std::string name);
/// Coordinates in the unit of the survey's CRS (metres or feet), to 0.001 of that unit (3 decimals). The name
/// ends in "_crs".
csv_column crs_column(std::string name);
/// Angles in degrees, to 0.1° (1 decimal). The name ends in "_deg".
csv_column degrees_column(std::string name);
/// Irradiation in kWh/m² (per year, per month or per day), to 0.001 kWh/m² (3 decimals). The name holds
/// "kwh_m2".
csv_column kwh_m2_column(std::string name);
/// Energy in kWh, to 0.001 kWh (3 decimals). The name ends in "_kwh".
csv_column kwh_column(std::string name);
/// Peak power in kW, to 0.01 kW (2 decimals). The name is "kwp" or ends in "_kwp".
csv_column kwp_column(std::string name);
/// Shares in [0, 1], to 0.01 (2 decimals). The name ends in "_fraction".
csv_column fraction_column(std::string name);
/// Scores and shares in percent, to 0.01 % (2 decimals). The name ends in "_pct".
csv_column percent_column(std::string name);
/// Durations in seconds, to 0.01 s (2 decimals). The name ends in "_s".
csv_column seconds_column(std::string name);
/// Amounts of money in the currency of a tariff, to 0.01 (2 decimals). The name holds "savings".
csv_column money_column(std::string name);
/// LiDAR return intensities (the sensor's unit-free numbers), to 0.1 (1 decimal). The name ends in "intensity".
csv_column intensity_column(std::string name);

/// A CSV field: quoted (with inner quotes doubled) when it holds a comma, a quote, CR, LF or leading or
/// trailing white space, as RFC 4180 describes; otherwise as is.
std::string csv_field(std::string_view text);

/// `value` as written in a CSV field of `column` (unquoted): a real number rounded to the column's decimals.
/// @throws invalid_input naming the column when it takes no real numbers and `value` is one.
std::string csv_text(const table_value& value, const csv_column& column);

/// CSV text: the header line (the column names), then one line per row, fields separated by commas, lines
/// ended by "\n"; each field as csv_text writes it.
/// @throws invalid_input if a row has not as many fields as the header (or the header is empty), or as csv_text.
std::string to_csv(const std::vector<csv_column>& header, const std::vector<std::vector<table_value>>& rows);

/// Writes to_csv(header, rows) to `path`. @throws as to_csv; std::runtime_error naming the file on I/O errors.
void write_csv(const std::string& path, const std::vector<csv_column>& header,
               const std::vector<std::vector<table_value>>& rows);

/// A JSON string literal of `text` (quotes, backslash and control characters escaped; UTF-8 kept).
std::string json_string(std::string_view text);

/// A linear ring of world coordinates (x, y), in the units of the collection's CRS.
using geo_ring = std::vector<std::array<double, 2>>;

/// A polygon feature: `rings[0]` is the outer boundary, the others are holes; plus named properties.
struct geojson_feature {
    std::vector<geo_ring> rings;
    std::vector<std::pair<std::string, table_value>> properties;
};

/// The rings of `feature` (number `f` of its collection, for messages from `fn`) as written: closed (the first
/// position repeated at the end when it is not already) and oriented by the right-hand rule of RFC 7946 (outer
/// ring counter-clockwise, holes clockwise, by the sign of the shoelace area; the first position kept).
/// @throws invalid_input when the feature has no ring, a ring has fewer than 3 distinct positions or a
/// coordinate is not finite.
std::vector<geo_ring> checked_rings(const geojson_feature& feature, std::size_t f, const char* fn);

/// A GeoJSON FeatureCollection of polygons, one feature per line. Rings are closed (the first position
/// repeated at the end when it is not already) and oriented by the right-hand rule of RFC 7946 (outer
/// ring counter-clockwise, holes clockwise, by the sign of the shoelace area). With `epsg` > 0 the
/// collection names its CRS in a "crs" member ("urn:ogc:def:crs:EPSG::<code>", GeoJSON 2008 style, which
/// GDAL/QGIS honour for projected coordinates). O(total positions).
/// @throws invalid_input when a feature has no ring, a ring has fewer than 3 distinct positions, a
/// coordinate is not finite, a property name repeats, or epsg < 0.
std::string to_geojson(const std::vector<geojson_feature>& features, int epsg = 0);

/// Writes to_geojson(features, epsg) to `path`. @throws as to_geojson; std::runtime_error on I/O errors.
void write_geojson(const std::string& path, const std::vector<geojson_feature>& features, int epsg = 0);

}  // namespace lidarfx::io
