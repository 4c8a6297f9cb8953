// SPDX-License-Identifier: Apache-2.0
#include "io/vectors_z.hpp"
#include "io/vectors.hpp"

#include <stdexcept>

#ifdef LIDARFX_HAVE_GDAL
#include <algorithm>
#include <cctype>
#include <cmath>
#include <memory>
#include <set>

#include <lidarfx/core/error.hpp>

#include "io/ogr_util.hpp"
#endif

namespace lidarfx::io {

#ifdef LIDARFX_HAVE_GDAL

namespace {

using parts_z = std::vector<std::vector<xyz>>;

// The rings of a polygon feature closed and oriented by checked_rings (on x, y), each vertex with its own z.
parts_z checked_rings_z(const feature_z& feature, std::size_t f, const std::string& fn)
{
    geojson_feature flat;
    for (const auto& part : feature.parts) {
        geo_ring& ring = flat.rings.emplace_back();
        for (const xyz& p : part) ring.push_back({p[0], p[1]});
    }
    const std::vector<geo_ring> rings = checked_rings(flat, f, fn.c_str());
    parts_z out(rings.size());
    for (std::size_t k = 0; k < rings.size(); ++k) {
        // checked_rings keeps the first vertex of the open ring (n vertices) and keeps or reverses the others; the
        // two orders can only look alike in x, y when the ring has no area, and then nothing was reversed.
        const std::size_t n = rings[k].size() - 1;
        const bool kept =
            std::equal(rings[k].begin(), rings[k].begin() + static_cast<std::ptrdiff_t>(n), flat.rings[k].begin());
        for (std::size_t i = 0; i <= n; ++i) {
            const std::size_t from = i == n ? 0 : kept ? i : (n - i) % n;
            out[k].push_back({rings[k][i][0], rings[k][i][1], feature.parts[k][from][2]});
        }
    }
    return out;
}

// The parts of a line feature, checked: at least one, each of at least 2 distinct vertices.
parts_z checked_lines(const feature_z& feature, std::size_t f, const std::string& fn)
{
    if (feature.parts.empty()) throw invalid_input(detail::concat(fn, ": feature ", f, " has no line"));
    for (std::size_t k = 0; k < feature.parts.size(); ++k) {
        const auto& line = feature.parts[k];
        if (std::find_if(line.begin(), line.end(), [&](const xyz& p) { return p != line.front(); }) == line.end())
            throw invalid_input(detail::concat(fn, ": feature ", f, " line ", k,
                                               " must have at least 2 distinct "
                                               "positions (got ",
                                               line.size(), " vertices)"));
    }
    return feature.parts;
}

std::unique_ptr<OGRGeometry> geometry_of(const parts_z& parts, geometry_z kind)
{
    const auto fill = [](OGRSimpleCurve& curve, const std::vector<xyz>& vertices) {
        curve.setNumPoints(static_cast<int>(vertices.size()), FALSE);
        for (std::size_t i = 0; i < vertices.size(); ++i) {
            const xyz& p = vertices[i];
            curve.setPoint(static_cast<int>(i), p[0], p[1], p[2]);
        }
    };
    if (kind == geometry_z::line) {
        auto lines = std::make_unique<OGRMultiLineString>();
        for (const auto& part : parts) {
            auto line = std::make_unique<OGRLineString>();
            fill(*line, part);
            lines->addGeometryDirectly(line.release());
        }
        return lines;
    }
    auto poly = std::make_unique<OGRPolygon>();
    for (const auto& part : parts) {
        auto ring = std::make_unique<OGRLinearRing>();
        fill(*ring, part);
        poly->addRingDirectly(ring.release());
    }
    return poly;
}

// Throws unless `props` has the names of `first`, in its order.
void require_same_names(const property_list& first, const property_list& props, std::size_t f, const std::string& fn)
{
    const auto names = [](const property_list& p) {
        std::string s;
        for (const auto& [name, value] : p) s += (s.empty() ? "" : ", ") + name;
        return "(" + s + ")";
    };
    const auto same = [](const auto& a, const auto& b) { return a.first == b.first; };
    if (!std::equal(first.begin(), first.end(), props.begin(), props.end(), same)) {
        throw invalid_input(detail::concat(fn, ": feature ", f, " has the properties ", names(props), ", feature 0 ",
                                           names(first), "; every feature of a layer needs the same names in order"));
    }
}

}  // namespace

void write_geopackage_z(const std::string& path, const std::vector<layer_z>& layers, const std::string& crs_wkt,
                        int epsg)
{
    constexpr const char* fn = "write_geopackage_z";
    detail::require(epsg >= 0, fn, "epsg", ">= 0", epsg);
    std::set<std::string> table_names;  // SQLite compares table names ignoring ASCII case
    for (const layer_z& layer : layers) {
        std::string lower = layer.name;
        for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
        if (lower.empty() || !table_names.insert(lower).second)
            throw invalid_input(detail::concat(fn, ": layer name '", layer.name, "' is empty or used twice"));
    }

    std::vector<std::vector<parts_z>> parts(layers.size());  // checked before the file exists
    std::vector<geopackage_layer_source> sources;
    for (std::size_t l = 0; l < layers.size(); ++l) {
        const layer_z& layer = layers[l];
        const std::string at = detail::concat(fn, ": layer '", layer.name, "'");
        for (std::size_t f = 0; f < layer.features.size(); ++f) {
            const feature_z& feature = layer.features[f];
            for (std::size_t k = 0; k < feature.parts.size(); ++k) {
                for (const xyz& p : feature.parts[k]) {
                    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) {
                        throw invalid_input(detail::concat(at, ": feature ", f, " part ", k,
                                                           " has a non-finite coordinate (", p[0], ", ", p[1], ", ",
                                                           p[2], ")"));
                    }
                }
            }
            require_same_names(layer.features.front().properties, feature.properties, f, at);
            parts[l].push_back(layer.geometry == geometry_z::line ? checked_lines(feature, f, at)
                                                                  : checked_rings_z(feature, f, at));
        }
        geopackage_layer_source& source = sources.emplace_back();
        source.name = layer.name;
        source.type = layer.geometry == geometry_z::line ? wkbMultiLineString25D : wkbPolygon25D;
        for (const feature_z& feature : layer.features) source.properties.push_back(&feature.properties);
        source.geometry = [&checked = parts[l], kind = layer.geometry](std::size_t f) {
            return geometry_of(checked[f], kind);
        };
    }
    write_geopackage_layers(path, sources, crs_wkt, epsg, fn);
}

#else  // without GDAL

void write_geopackage_z(const std::string& path, const std::vector<layer_z>&, const std::string&, int)
{
    throw std::runtime_error(path + ": GeoPackage output needs OGR; " + vectors_rebuild_hint);
}

#endif

}  // namespace lidarfx::io
