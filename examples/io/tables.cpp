// SPDX-License-Identifier: Apache-2.0
#include "io/tables.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <set>

#include <lidarfx/core/error.hpp>

#include "io/file_output.hpp"

namespace lidarfx::io {

namespace {

template <class T>
std::string shortest(T v)
{
    char buf[64];
    const auto res = std::to_chars(buf, buf + sizeof buf, v);
    return std::string(buf, res.ptr);
}

/// A column of `decimals` decimals whose name must `end` with (or, when !at_end, hold) `unit`: the unit is in
/// the header, so a reader never guesses it.
csv_column unit_column(std::string name, int decimals, std::string_view unit, bool at_end = true)
{
    const std::string_view n = name;
    const bool named = at_end ? n.size() >= unit.size() && n.substr(n.size() - unit.size()) == unit
                              : n.find(unit) != std::string_view::npos;
    if (!named) {
        throw invalid_input(
            detail::concat("csv column '", name, "' must ", at_end ? "end in '" : "hold '", unit, "' (its unit)"));
    }
    return {std::move(name), decimals};
}

/// Signed area of a ring by the shoelace formula (positive = counter-clockwise with y up).
double signed_area(const geo_ring& ring)
{
    double twice = 0;
    for (std::size_t i = 0, n = ring.size(); i < n; ++i) {
        const auto& a = ring[i];
        const auto& b = ring[(i + 1) % n];
        twice += a[0] * b[1] - b[0] * a[1];
    }
    return twice / 2;
}

}  // namespace

std::string table_value::format() const
{
    return std::visit(
        [](const auto& v) -> std::string {
            using V = std::decay_t<decltype(v)>;
            if constexpr (std::is_same_v<V, std::monostate>)
                return "";
            else if constexpr (std::is_same_v<V, bool>)
                return v ? "true" : "false";
            else if constexpr (std::is_same_v<V, double>)
                return std::isfinite(v) ? shortest(v) : "";
            else if constexpr (std::is_same_v<V, std::string>)
                return v;
            else
                return shortest(v);
        },
        v_);
}

std::string table_value::json() const
{
    if (is_text()) return json_string(std::get<std::string>(v_));
    const std::string s = format();
    return s.empty() ? "null" : s;
}

csv_column text_column(std::string name)
{
    return {std::move(name), -1};
}
csv_column metres_column(std::string name)
{
    return unit_column(std::move(name), 3, "_m");
}
csv_column area_column(std::string name)
{
    return unit_column(std::move(name), 1, "_m2");
}
csv_column crs_column(std::string name)
{
    return unit_column(std::move(name), 3, "_crs");
}
csv_column degrees_column(std::string name)
{
    return unit_column(std::move(name), 1, "_deg");
}
csv_column kwh_m2_column(std::string name)
{
    return unit_column(std::move(name), 3, "kwh_m2", false);
}
csv_column kwh_column(std::string name)
{
    return unit_column(std::move(name), 3, "_kwh");
}
csv_column kwp_column(std::string name)
{
    if (name == "kwp") return {std::move(name), 2};
    return unit_column(std::move(name), 2, "_kwp");
}
csv_column fraction_column(std::string name)
{
    return unit_column(std::move(name), 2, "_fraction");
}
csv_column percent_column(std::string name)
{
    return unit_column(std::move(name), 2, "_pct");
}
csv_column seconds_column(std::string name)
{
    return unit_column(std::move(name), 2, "_s");
}
csv_column money_column(std::string name)
{
    return unit_column(std::move(name), 2, "savings", false);
}
csv_column intensity_column(std::string name)
{
    return unit_column(std::move(name), 1, "intensity");
}

std::string csv_text(const table_value& value, const csv_column& column)
{
    const auto* real = std::get_if<double>(&value.value());
    if (!real) return value.format();
    if (column.decimals < 0) {
        throw invalid_input(detail::concat("to_csv: column '", column.name, "' takes no real numbers (got ", *real,
                                           "); give it a kind with decimals"));
    }
    if (!std::isfinite(*real)) return "";
    char buf[400];  // DBL_MAX in fixed notation has 309 digits before the point
    const auto res = std::to_chars(buf, buf + sizeof buf, *real, std::chars_format::fixed, column.decimals);
    std::string text(buf, res.ptr);
    // A negative number rounded to zero reads as zero.
    if (text.front() == '-' && text.find_first_not_of("-0.") == std::string::npos) text.erase(0, 1);
    return text;
}

std::string csv_field(std::string_view text)
{
    const bool quote = text.find_first_of(",\"\r\n") != std::string_view::npos ||
                       (!text.empty() && (std::isspace(static_cast<unsigned char>(text.front())) ||
                                          std::isspace(static_cast<unsigned char>(text.back()))));
    if (!quote) return std::string(text);
    std::string out = "\"";
    for (const char ch : text) {
        if (ch == '"') out += '"';
        out += ch;
    }
    out += '"';
    return out;
}

std::string to_csv(const std::vector<csv_column>& header, const std::vector<std::vector<table_value>>& rows)
{
    detail::require(!header.empty(), "to_csv", "header must not be empty");
    std::string out;
    for (std::size_t i = 0; i < header.size(); ++i) {
        if (i) out += ',';
        out += csv_field(header[i].name);
    }
    out += '\n';
    for (std::size_t r = 0; r < rows.size(); ++r) {
        if (rows[r].size() != header.size()) {
            throw invalid_input(
                detail::concat("to_csv: row ", r, " has ", rows[r].size(), " fields, the header ", header.size()));
        }
        for (std::size_t i = 0; i < header.size(); ++i) {
            if (i) out += ',';
            out += csv_field(csv_text(rows[r][i], header[i]));
        }
        out += '\n';
    }
    return out;
}

void write_csv(const std::string& path, const std::vector<csv_column>& header,
               const std::vector<std::vector<table_value>>& rows)
{
    write_file(path, to_csv(header, rows));
}

std::string json_string(std::string_view text)
{
    std::string out = "\"";
    for (const char ch : text) {
        const auto u = static_cast<unsigned char>(ch);
        switch (ch) {
            case '"':
                out += "\\\"";
                break;
            case '\\':
                out += "\\\\";
                break;
            case '\n':
                out += "\\n";
                break;
            case '\r':
                out += "\\r";
                break;
            case '\t':
                out += "\\t";
                break;
            case '\b':
                out += "\\b";
                break;
            case '\f':
                out += "\\f";
                break;
            default:
                if (u < 0x20) {
                    static constexpr char hex[] = "0123456789abcdef";
                    out += "\\u00";
                    out += hex[u >> 4];
                    out += hex[u & 15];
                } else {
                    out += ch;
                }
        }
    }
    out += '"';
    return out;
}

std::vector<geo_ring> checked_rings(const geojson_feature& feature, std::size_t f, const char* fn)
{
    if (feature.rings.empty()) throw invalid_input(detail::concat(fn, ": feature ", f, " has no ring"));
    std::vector<geo_ring> rings;
    for (std::size_t k = 0; k < feature.rings.size(); ++k) {
        geo_ring ring = feature.rings[k];
        for (const auto& pt : ring) {
            if (!std::isfinite(pt[0]) || !std::isfinite(pt[1])) {
                throw invalid_input(detail::concat(fn, ": feature ", f, " ring ", k, " has a non-finite coordinate (",
                                                   pt[0], ", ", pt[1], ")"));
            }
        }
        if (!ring.empty() && ring.front() == ring.back()) ring.pop_back();  // work on the open ring
        geo_ring distinct = ring;
        std::sort(distinct.begin(), distinct.end());
        if (std::unique(distinct.begin(), distinct.end()) - distinct.begin() < 3) {
            throw invalid_input(
                detail::concat(fn, ": feature ", f, " ring ", k, " must have at least 3 distinct positions"));
        }
        const bool outer = k == 0;
        const double area = signed_area(ring);
        if ((outer && area < 0) || (!outer && area > 0)) std::reverse(ring.begin() + 1, ring.end());  // same start
        ring.push_back(ring.front());
        rings.push_back(std::move(ring));
    }
    return rings;
}

std::string to_geojson(const std::vector<geojson_feature>& features, int epsg)
{
    constexpr const char* fn = "to_geojson";
    detail::require(epsg >= 0, fn, "epsg", ">= 0", epsg);
    std::string out = "{\"type\":\"FeatureCollection\",";
    if (epsg > 0) {
        out += "\"crs\":{\"type\":\"name\",\"properties\":{\"name\":\"urn:ogc:def:crs:EPSG::" + std::to_string(epsg) +
               "\"}},";
    }
    out += "\"features\":[";
    for (std::size_t f = 0; f < features.size(); ++f) {
        const geojson_feature& feature = features[f];
        if (feature.rings.empty()) throw invalid_input(detail::concat(fn, ": feature ", f, " has no ring"));
        out += f ? ",\n" : "\n";
        out += "{\"type\":\"Feature\",\"properties\":{";
        std::set<std::string> names;
        for (std::size_t p = 0; p < feature.properties.size(); ++p) {
            const auto& [name, value] = feature.properties[p];
            if (!names.insert(name).second) {
                throw invalid_input(detail::concat(fn, ": feature ", f, " has property '", name, "' twice"));
            }
            if (p) out += ',';
            out += json_string(name) + ":" + value.json();
        }
        out += "},\"geometry\":{\"type\":\"Polygon\",\"coordinates\":[";
        const std::vector<geo_ring> rings = checked_rings(feature, f, fn);
        for (std::size_t k = 0; k < rings.size(); ++k) {
            const geo_ring& ring = rings[k];
            out += k ? ",[" : "[";
            for (std::size_t i = 0; i < ring.size(); ++i) {
                out += i ? ",[" : "[";
                out += shortest(ring[i][0]) + "," + shortest(ring[i][1]) + "]";
            }
            out += "]";
        }
        out += "]}}";
    }
    out += "\n]}\n";
    return out;
}

void write_geojson(const std::string& path, const std::vector<geojson_feature>& features, int epsg)
{
    write_file(path, to_geojson(features, epsg));
}

}  // namespace lidarfx::io
