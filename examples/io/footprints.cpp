// SPDX-License-Identifier: Apache-2.0
#include "io/footprints.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string_view>
#include <variant>

#include <boost/geometry.hpp>
#include <boost/geometry/geometries/point_xy.hpp>
#include <boost/geometry/geometries/polygon.hpp>

#include <lidarfx/core/error.hpp>

namespace lidarfx::io {
namespace {

// A small JSON document model: enough for GeoJSON (RFC 8259 values; numbers as double).
struct json;
using json_object = std::vector<std::pair<std::string, json>>;
using json_array = std::vector<json>;
struct json {
    std::variant<std::nullptr_t, bool, double, std::string, std::shared_ptr<json_array>, std::shared_ptr<json_object>> v;
    const json* member(std::string_view name) const
    {
        if (const auto* o = std::get_if<std::shared_ptr<json_object>>(&v)) {
            for (const auto& [k, value] : **o)
                if (k == name) return &value;
        }
        return nullptr;
    }
    const json_array* array() const
    {
        const auto* a = std::get_if<std::shared_ptr<json_array>>(&v);
        return a ? a->get() : nullptr;
    }
    const std::string* string() const { return std::get_if<std::string>(&v); }
    const double* number() const { return std::get_if<double>(&v); }
};

class json_parser {
public:
    json_parser(std::string_view text, const std::string& source) : s_(text), source_(source) {}

    json document()
    {
        json value = parse(0);
        skip_space();
        if (i_ != s_.size()) fail("unexpected text after the JSON value");
        return value;
    }

private:
    [[noreturn]] void fail(const std::string& what) const
    {
        throw invalid_input(detail::concat(source_, ": not valid JSON at byte ", i_, ": ", what));
    }
    void skip_space()
    {
        while (i_ < s_.size() && (s_[i_] == ' ' || s_[i_] == '\t' || s_[i_] == '\n' || s_[i_] == '\r')) ++i_;
    }
    bool take(char c)
    {
        skip_space();
        if (i_ < s_.size() && s_[i_] == c) {
            ++i_;
            return true;
        }
        return false;
    }
    void expect(char c)
    {
        if (!take(c)) fail(std::string("expected '") + c + "'");
    }
    json parse(int depth)
    {
        if (depth > 64) fail("nesting deeper than 64 levels");
        skip_space();
        if (i_ >= s_.size()) fail("unexpected end");
        const char c = s_[i_];
        if (c == '{') {
            ++i_;
            auto o = std::make_shared<json_object>();
            if (!take('}')) {
                do {
                    skip_space();
                    std::string key = string();
                    expect(':');
                    o->emplace_back(std::move(key), parse(depth + 1));
                } while (take(','));
                expect('}');
            }
            return {o};
        }
        if (c == '[') {
            ++i_;
            auto a = std::make_shared<json_array>();
            if (!take(']')) {
                do a->push_back(parse(depth + 1));
                while (take(','));
                expect(']');
            }
            return {a};
        }
        if (c == '"') return {string()};
        if (s_.substr(i_, 4) == "true") return i_ += 4, json{true};
        if (s_.substr(i_, 5) == "false") return i_ += 5, json{false};
        if (s_.substr(i_, 4) == "null") return i_ += 4, json{nullptr};
        return {number()};
    }
    double number()
    {
        const std::size_t start = i_;
        while (i_ < s_.size() && (std::isdigit(static_cast<unsigned char>(s_[i_])) || s_[i_] == '-' || s_[i_] == '+' ||
                                  s_[i_] == '.' || s_[i_] == 'e' || s_[i_] == 'E'))
            ++i_;
        const std::string token(s_.substr(start, i_ - start));
        char* end = nullptr;
        const double v = token.empty() ? 0.0 : std::strtod(token.c_str(), &end);
        if (token.empty() || end != token.c_str() + token.size()) {
            i_ = start;
            fail("expected a value");
        }
        return v;
    }
    std::string string()
    {
        if (i_ >= s_.size() || s_[i_] != '"') fail("expected a string");
        ++i_;
        std::string out;
        while (true) {
            if (i_ >= s_.size()) fail("unterminated string");
            const char c = s_[i_++];
            if (c == '"') return out;
            if (c != '\\') {
                out += c;
                continue;
            }
            if (i_ >= s_.size()) fail("unterminated escape");
            const char e = s_[i_++];
            switch (e) {
                case 'n': out += '\n'; break;
                case 't': out += '\t'; break;
                case 'r': out += '\r'; break;
                case 'b': out += '\b'; break;
                case 'f': out += '\f'; break;
                case 'u': {
                    if (i_ + 4 > s_.size()) fail("short \\u escape");
                    const unsigned code = static_cast<unsigned>(std::strtoul(std::string(s_.substr(i_, 4)).c_str(), nullptr, 16));
                    i_ += 4;
                    if (code < 0x80) {
                        out += static_cast<char>(code);
                    } else if (code < 0x800) {
                        out += static_cast<char>(0xC0 | (code >> 6));
                        out += static_cast<char>(0x80 | (code & 0x3F));
                    } else {  // surrogate pairs are kept as two 3-byte sequences: names only, never compared
                        out += static_cast<char>(0xE0 | (code >> 12));
                        out += static_cast<char>(0x80 | ((code >> 6) & 0x3F));
                        out += static_cast<char>(0x80 | (code & 0x3F));
                    }
                    break;
                }
                default: out += e;  // \" \\ \/
            }
        }
    }

    std::string_view s_;
    const std::string& source_;
    std::size_t i_ = 0;
};

namespace bg = boost::geometry;
using bg_point = bg::model::d2::point_xy<double>;
using bg_polygon = bg::model::polygon<bg_point>;  // clockwise outer rings, closed

// The rings of a GeoJSON Polygon's coordinates, checked; throws naming the feature.
polygon polygon_of(const json& coordinates, const std::string& where)
{
    const json_array* rings = coordinates.array();
    if (!rings || rings->empty()) throw invalid_input(where + ": a Polygon needs at least its exterior ring");
    polygon p;
    for (const json& ring : *rings) {
        const json_array* positions = ring.array();
        if (!positions || positions->size() < 4)
            throw invalid_input(where + ": every ring needs at least 4 positions (closed, 3 distinct corners)");
        std::vector<std::array<double, 2>> out;
        for (const json& position : *positions) {
            const json_array* xy = position.array();
            if (!xy || xy->size() < 2 || !(*xy)[0].number() || !(*xy)[1].number())
                throw invalid_input(where + ": a position must be an array of numbers [x, y]");
            const double x = *(*xy)[0].number(), y = *(*xy)[1].number();
            if (!std::isfinite(x) || !std::isfinite(y)) throw invalid_input(where + ": a coordinate is not finite");
            out.push_back({x, y});
        }
        if (out.front() != out.back()) out.push_back(out.front());
        p.rings.push_back(std::move(out));
    }
    return p;
}

bg_polygon to_boost(const polygon& p)
{
    bg_polygon b;
    for (std::size_t k = 0; k < p.rings.size(); ++k) {
        auto& ring = k == 0 ? b.outer() : (b.inners().emplace_back(), b.inners().back());
        for (const auto& v : p.rings[k]) ring.push_back(bg_point(v[0], v[1]));
    }
    bg::correct(b);  // orientation and closure as Boost expects
    return b;
}

// Outer ring counter-clockwise, holes clockwise (RFC 7946), as lidarfx::polygon documents.
void orient(polygon& p)
{
    for (std::size_t k = 0; k < p.rings.size(); ++k) {
        auto& ring = p.rings[k];
        double area2 = 0;
        for (std::size_t i = 0; i + 1 < ring.size(); ++i) area2 += ring[i][0] * ring[i + 1][1] - ring[i + 1][0] * ring[i][1];
        if ((k == 0) != (area2 > 0)) std::reverse(ring.begin(), ring.end());
    }
}

}  // namespace

footprint_collection parse_footprints_geojson(const std::string& text, const std::string& source)
{
    const json doc = json_parser(text, source).document();
    const json* type = doc.member("type");
    if (!type || !type->string() || *type->string() != "FeatureCollection")
        throw invalid_input(source + ": expected a GeoJSON FeatureCollection of building footprints");
    const json* features = doc.member("features");
    if (!features || !features->array()) throw invalid_input(source + ": the FeatureCollection has no \"features\" array");
    footprint_collection out;
    std::map<std::int32_t, std::size_t> first_feature_of;
    const json_array& list = *features->array();
    for (std::size_t f = 0; f < list.size(); ++f) {
        const std::string where = detail::concat(source, ": feature ", f);
        const json* properties = list[f].member("properties");
        const json* id = properties ? properties->member("building_id") : nullptr;
        if (!id || !id->number())
            throw invalid_input(where + ": no integer \"building_id\" property (every footprint needs one)");
        const double idv = *id->number();
        if (idv != std::floor(idv) || idv < 1 || idv > 2147483647.0)
            throw invalid_input(detail::concat(where, ": building_id ", idv, " is not an integer in 1 .. 2147483647"));
        const auto building = static_cast<std::int32_t>(idv);
        if (const auto [it, fresh] = first_feature_of.emplace(building, f); !fresh)
            throw invalid_input(detail::concat(where, ": building_id ", building, " is used by feature ", it->second,
                                               " too; ids must be unique"));
        const std::string at = detail::concat(where, " (building_id ", building, ")");
        const json* geometry = list[f].member("geometry");
        const json* gtype = geometry ? geometry->member("type") : nullptr;
        const json* coordinates = geometry ? geometry->member("coordinates") : nullptr;
        if (!gtype || !gtype->string() || !coordinates)
            throw invalid_input(at + ": no Polygon or MultiPolygon geometry");
        footprint fp{building, {}, f};
        if (*gtype->string() == "Polygon") {
            fp.parts.push_back(polygon_of(*coordinates, at));
        } else if (*gtype->string() == "MultiPolygon") {
            const json_array* parts = coordinates->array();
            if (!parts || parts->empty()) throw invalid_input(at + ": an empty MultiPolygon");
            for (const json& part : *parts) fp.parts.push_back(polygon_of(part, at));
        } else {
            throw invalid_input(at + ": geometry type " + *gtype->string() + " is not Polygon or MultiPolygon");
        }
        bg::model::multi_polygon<bg_polygon> shape;
        for (const polygon& p : fp.parts) shape.push_back(to_boost(p));
        std::string reason;
        bool crossing = false;
        for (const bg_polygon& part : shape) crossing = crossing || bg::intersects(part);  // a ring crosses itself
        if (crossing) {
            out.problems.push_back({building, f, "invalid polygon: a ring crosses itself (self-intersection)"});
            continue;
        }
        if (!(bg::area(shape) > 0)) {
            out.problems.push_back({building, f, "empty (zero area)"});
            continue;
        }
        if (!bg::is_valid(shape, reason)) {
            out.problems.push_back({building, f, "invalid polygon: " + reason});
            continue;
        }
        for (polygon& p : fp.parts) orient(p);
        out.footprints.push_back(std::move(fp));
    }
    return out;
}

footprint_collection read_footprints_geojson(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error(path + ": cannot open the footprint file");
    std::ostringstream text;
    text << in.rdbuf();
    if (!in.good() && !in.eof()) throw std::runtime_error(path + ": cannot read the footprint file");
    return parse_footprints_geojson(text.str(), path);
}

}  // namespace lidarfx::io
