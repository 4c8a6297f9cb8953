// SPDX-License-Identifier: Apache-2.0
#include "io/footprints.hpp"

#include "io/vectors.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string_view>
#include <system_error>
#include <utility>

#include <unistd.h>

#include <boost/geometry.hpp>
#include <boost/geometry/geometries/point_xy.hpp>
#include <boost/geometry/geometries/polygon.hpp>

#include <lidarfx/core/error.hpp>

namespace lidarfx::io {
namespace {

namespace bg = boost::geometry;
using bg_point = bg::model::d2::point_xy<double>;
using bg_polygon = bg::model::polygon<bg_point>;  // clockwise outer rings, closed

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
void orient_part(polygon& p)
{
    for (std::size_t k = 0; k < p.rings.size(); ++k) {
        auto& ring = p.rings[k];
        double area2 = 0;
        for (std::size_t i = 0; i + 1 < ring.size(); ++i)
            area2 += ring[i][0] * ring[i + 1][1] - ring[i + 1][0] * ring[i][1];
        if ((k == 0) != (area2 > 0)) std::reverse(ring.begin(), ring.end());
    }
}

std::uint64_t budget_of(const footprint_read_options& opt)
{
    return footprint_memory_budget(opt);
}

// What one feature of the file says, as far as footprints need it: its building_id (as written), its
// geometry's type, and its coordinates flattened (vertices, the end of each ring, the end of each part).
struct feature_text {
    bool object = true;
    int id_kind = 0;  // 0: no building_id, 1: a number, 2: something else
    double id = 0;
    std::string id_token;
    bool have_type = false, have_coordinates = false;
    std::string type;
    int height = 0;  // nesting of the coordinates: 1 a position, 2 a ring, 3 a Polygon, 4 a MultiPolygon
    std::vector<std::array<double, 2>> vertices;
    std::vector<std::size_t> ring_end, part_end;  // vertices before each ring's end, rings before each part's end
    std::string shape_error, bad_value;           // the first of each, if any

    void clear()
    {
        object = true;
        id_kind = 0;
        id = 0;
        id_token.clear();
        have_type = have_coordinates = false;
        type.clear();
        height = 0;
        vertices.clear();
        ring_end.clear();
        part_end.clear();
        shape_error.clear();
        bad_value.clear();
    }
    void shape(const std::string& what)
    {
        if (shape_error.empty()) shape_error = what;
    }
};

// One pass over GeoJSON text that keeps only what footprints need: no document tree, one feature's
// coordinates at a time. Values it does not need are checked for syntax and passed over.
class geojson_reader {
public:
    geojson_reader(std::string_view text, const std::string& source, std::uint64_t budget, std::string id_field)
        : s_(text),
          source_(source),
          budget_(budget),
          id_field_(std::move(id_field)),
          text_bytes_(static_cast<double>(text.size()))
    {
    }

    footprint_collection read()
    {
        if (s_.substr(0, 3) == "\xEF\xBB\xBF") i_ = 3;  // a UTF-8 byte order mark, as some GIS tools write
        charge(0);
        skip_space();
        const auto not_a_collection = [&] {
            return invalid_input(source_ + ": expected a GeoJSON FeatureCollection of building footprints");
        };
        if (i_ >= s_.size() || s_[i_] != '{') {
            skip_value(0);
            end_of_text();
            throw not_a_collection();
        }
        ++i_;
        bool type_seen = false, features_seen = false;
        if (!take('}')) {
            do {
                skip_space();
                const std::string key = string();
                expect(':');
                skip_space();
                if (key == "type" && !type_seen) {
                    type_seen = true;
                    if (!(peek('"') && string() == "FeatureCollection")) throw not_a_collection();
                } else if (key == "crs" && out_.crs.empty() && peek('{')) {
                    crs_member();
                } else if (key == "features" && !features_seen) {
                    features_seen = true;
                    if (!peek('[')) throw invalid_input(source_ + ": the FeatureCollection has no \"features\" array");
                    features();
                } else {
                    skip_value(1);
                }
            } while (take(','));
            expect('}');
        }
        end_of_text();
        if (!type_seen) throw not_a_collection();
        if (!features_seen) throw invalid_input(source_ + ": the FeatureCollection has no \"features\" array");
        out_.peak_bytes = static_cast<std::uint64_t>(peak_);
        return std::move(out_);
    }

private:
    static constexpr int max_depth = 64;

    // ---- memory ----

    // Counts `transient` bytes (the feature being read) on top of what is held, against the budget.
    void charge(double transient)
    {
        const double need = text_bytes_ + kept_bytes_ + transient;
        peak_ = std::max(peak_, need);
        if (budget_ > 0 && need > static_cast<double>(budget_)) {
            // What the whole file would need if the rest is like what was read so far.
            const double read = std::max(1.0, static_cast<double>(i_)), share = std::min(1.0, read / text_bytes_);
            const double projected = std::max(need, text_bytes_ + (need - text_bytes_) / share);
            throw invalid_input(
                detail::concat(source_, ": reading the footprints needs about ", footprint_size_text(projected),
                               " (the file's ", footprint_size_text(text_bytes_), ", and ", kept_vertices_,
                               " vertices kept by feature ", feature_, " in its first ", std::floor(100 * share),
                               " %), over the memory budget of ", footprint_size_text(static_cast<double>(budget_)),
                               "; split the file into smaller ones or use a larger --memory"));
        }
    }

    // ---- syntax ----

    [[noreturn]] void fail(const std::string& what) const
    {
        const auto line =
            1 + std::count(s_.begin(), s_.begin() + static_cast<std::ptrdiff_t>(std::min(i_, s_.size())), '\n');
        throw invalid_input(detail::concat(source_, ": not valid JSON at byte ", i_, " (line ", line, "): ", what));
    }
    void skip_space()
    {
        while (i_ < s_.size() && (s_[i_] == ' ' || s_[i_] == '\t' || s_[i_] == '\n' || s_[i_] == '\r')) ++i_;
    }
    bool peek(char c) const { return i_ < s_.size() && s_[i_] == c; }
    bool take(char c)
    {
        skip_space();
        if (peek(c)) {
            ++i_;
            return true;
        }
        return false;
    }
    void expect(char c)
    {
        if (!take(c)) fail(std::string("expected '") + c + "'");
    }
    void end_of_text()
    {
        skip_space();
        if (i_ != s_.size()) fail("unexpected text after the JSON value");
    }
    bool number_next() const { return i_ < s_.size() && (s_[i_] == '-' || (s_[i_] >= '0' && s_[i_] <= '9')); }

    // A number as written, and its value: +-inf beyond a double's range (`in_range` false), 0 below it.
    struct number_text {
        std::string_view token;
        double value = 0;
        bool in_range = true;
    };
    number_text number()
    {
        const std::size_t start = i_;
        while (i_ < s_.size() && ((s_[i_] >= '0' && s_[i_] <= '9') || s_[i_] == '-' || s_[i_] == '+' || s_[i_] == '.' ||
                                  s_[i_] == 'e' || s_[i_] == 'E'))
            ++i_;
        number_text n{s_.substr(start, i_ - start)};
        const auto [end, ec] = std::from_chars(n.token.data(), n.token.data() + n.token.size(), n.value);
        if (n.token.empty() || end != n.token.data() + n.token.size() ||
            (ec != std::errc{} && ec != std::errc::result_out_of_range)) {
            i_ = start;
            fail("expected a value");
        }
        if (ec == std::errc::result_out_of_range) {
            n.value = std::strtod(std::string(n.token).c_str(), nullptr);  // +-HUGE_VAL, or 0 / subnormal
            n.in_range = !std::isinf(n.value);
        }
        return n;
    }
    std::string string()
    {
        if (!peek('"')) fail("expected a string");
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
                case 'n':
                    out += '\n';
                    break;
                case 't':
                    out += '\t';
                    break;
                case 'r':
                    out += '\r';
                    break;
                case 'b':
                    out += '\b';
                    break;
                case 'f':
                    out += '\f';
                    break;
                case 'u': {
                    if (i_ + 4 > s_.size()) fail("short \\u escape");
                    const unsigned code =
                        static_cast<unsigned>(std::strtoul(std::string(s_.substr(i_, 4)).c_str(), nullptr, 16));
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
                default:
                    out += e;  // \" \\ \/
            }
        }
    }
    void skip_string()
    {
        if (!peek('"')) fail("expected a string");
        ++i_;
        while (true) {
            if (i_ >= s_.size()) fail("unterminated string");
            const char c = s_[i_++];
            if (c == '"') return;
            if (c == '\\') {
                if (i_ >= s_.size()) fail("unterminated escape");
                if (s_[i_++] == 'u') {
                    if (i_ + 4 > s_.size()) fail("short \\u escape");
                    i_ += 4;
                }
            }
        }
    }
    // Checks one value's syntax and passes over it, keeping nothing.
    void skip_value(int depth)
    {
        if (depth > max_depth) fail("nesting deeper than 64 levels");
        skip_space();
        if (i_ >= s_.size()) fail("unexpected end");
        const char c = s_[i_];
        if (c == '{') {
            ++i_;
            if (!take('}')) {
                do {
                    skip_space();
                    skip_string();
                    expect(':');
                    skip_value(depth + 1);
                } while (take(','));
                expect('}');
            }
        } else if (c == '[') {
            ++i_;
            if (!take(']')) {
                do skip_value(depth + 1);
                while (take(','));
                expect(']');
            }
        } else if (c == '"') {
            skip_string();
        } else if (s_.substr(i_, 4) == "true" || s_.substr(i_, 4) == "null") {
            i_ += 4;
        } else if (s_.substr(i_, 5) == "false") {
            i_ += 5;
        } else {
            (void)number();
        }
    }

    // Passes over one value; returns its text (the first 40 bytes) for a message.
    std::string skipped(int depth)
    {
        skip_space();
        const std::size_t start = i_;
        skip_value(depth);
        return i_ - start <= 40 ? std::string(s_.substr(start, i_ - start)) : std::string(s_.substr(start, 40)) + "...";
    }

    // ---- structure ----

    // {"type": "name", "properties": {"name": "urn:ogc:def:crs:EPSG::32613"}}: the name, as written.
    void crs_member()
    {
        object_members(1, [&](const std::string& key) {
            if (key != "properties" || !peek('{')) return false;
            object_members(2, [&](const std::string& name) {
                if (name != "name" || !peek('"')) return false;
                out_.crs = string();
                return true;
            });
            return true;
        });
    }

    void features()
    {
        ++i_;  // '['
        if (take(']')) return;
        do {
            feature();
            finish();
            ++feature_;
        } while (take(','));
        expect(']');
    }

    void feature()
    {
        feature_text& t = text_;
        t.clear();
        skip_space();
        if (!peek('{')) {
            t.object = false;
            skip_value(2);
            return;
        }
        ++i_;
        bool properties_seen = false, geometry_seen = false;
        if (take('}')) return;
        do {
            skip_space();
            const std::string key = string();
            expect(':');
            skip_space();
            if (key == "properties" && !properties_seen && peek('{')) {
                properties_seen = true;
                object_members(3, [&](const std::string& name) {
                    if (name != id_field_ || t.id_kind != 0) return false;
                    if (number_next()) {
                        const number_text n = number();
                        t.id_kind = 1;
                        t.id = n.value;
                        t.id_token = n.token;
                    } else {
                        t.id_kind = 2;
                        t.id_token = skipped(4);
                    }
                    return true;
                });
            } else if (key == "geometry" && !geometry_seen && peek('{')) {
                geometry_seen = true;
                object_members(3, [&](const std::string& name) {
                    if (name == "type" && !t.have_type && peek('"')) {
                        t.have_type = true;
                        t.type = string();
                        return true;
                    }
                    if (name == "coordinates" && !t.have_coordinates) {
                        t.have_coordinates = true;
                        if (peek('['))
                            t.height = coordinates(4, true);
                        else
                            t.shape("the coordinates must be an array");
                        return true;
                    }
                    return false;
                });
            } else {
                skip_value(3);
            }
        } while (take(','));
        expect('}');
    }

    // The members of the object at '{': `use(key)` reads the value it wants (and returns true), the rest are
    // passed over.
    template <class Use>
    void object_members(int depth, Use use)
    {
        ++i_;  // '{'
        if (take('}')) return;
        do {
            skip_space();
            const std::string key = string();
            expect(':');
            skip_space();
            if (!use(key)) skip_value(depth + 1);
        } while (take(','));
        expect('}');
    }

    // One array of coordinates at '[': its height (1 for a position of numbers, 1 + its elements' height
    // above them, 0 for an empty array), its vertices and ring and part ends appended to the feature's.
    int coordinates(int depth, bool top)
    {
        if (depth > max_depth) fail("nesting deeper than 64 levels");
        feature_text& t = text_;
        ++i_;  // '['
        if (take(']')) {
            if (!top) t.shape("an empty ring or part (every ring needs at least 4 positions)");
            return 0;
        }
        skip_space();
        if (peek('[')) {
            int height = -1;
            do {
                skip_space();
                if (!peek('[')) {
                    t.shape("a ring or part mixes positions [x, y] with numbers or other values");
                    skip_value(depth + 1);
                    continue;
                }
                const int h = coordinates(depth + 1, false);
                if (height < 0)
                    height = h;
                else if (h != height)
                    t.shape("the coordinates mix arrays of different depths");
            } while (take(','));
            expect(']');
            if (height == 1)
                t.ring_end.push_back(t.vertices.size());
            else if (height == 2)
                t.part_end.push_back(t.ring_end.size());
            else if (height > 3)
                t.shape("the coordinates are nested deeper than a MultiPolygon's");
            return height < 0 ? 0 : height + 1;
        }
        // A position: x, y and maybe more numbers (z, m), which are not kept.
        std::array<double, 2> xy{};
        std::size_t n = 0;
        do {
            skip_space();
            if (!number_next()) {
                const std::string value = skipped(depth + 1);
                t.shape(detail::concat("a position must be an array of numbers [x, y] (vertex ", t.vertices.size(),
                                       " has ", value, ")"));
                continue;
            }
            const number_text v = number();
            if (n < 2) {
                xy[n] = v.value;
                if (t.bad_value.empty() && (!v.in_range || !(std::abs(v.value) <= footprint_max_abs_coordinate))) {
                    t.bad_value = detail::concat(n == 0 ? "x" : "y", " = ", v.token, " of vertex ", t.vertices.size(),
                                                 v.in_range ? " is beyond +-1e9, the largest magnitude a footprint"
                                                              " coordinate may have (units of the file's CRS)"
                                                            : " is beyond the range of a double");
                }
            }
            ++n;
        } while (take(','));
        expect(']');
        if (n < 2) t.shape("a position must be an array of numbers [x, y]");
        if (t.vertices.size() == t.vertices.capacity())
            charge(16.0 * (3.0 * static_cast<double>(t.vertices.capacity()) + 16.0));  // old and grown buffer
        t.vertices.push_back(xy);
        return 1;
    }

    // Checks the feature just read and keeps its footprint (or its problem), in the order of the file.
    void finish()
    {
        feature_text& t = text_;
        const std::string where = detail::concat(source_, ": feature ", feature_);
        if (!t.object) throw invalid_input(where + ": not a GeoJSON Feature object");
        if (t.id_kind == 0)
            throw invalid_input(where + ": no integer \"" + id_field_ + "\" property (every footprint needs one)");
        if (t.id_kind == 2)
            throw invalid_input(where + ": " + id_field_ + " " + t.id_token +
                                " is not an integer (every footprint needs one)");
        if (t.id != std::floor(t.id) || t.id < 1 || t.id > 2147483647.0)
            throw invalid_input(
                detail::concat(where, ": ", id_field_, " ", t.id_token, " is not an integer in 1 .. 2147483647"));
        const auto building = static_cast<std::int32_t>(t.id);
        if (const auto [it, fresh] = first_feature_of_.emplace(building, feature_); !fresh)
            throw invalid_input(detail::concat(where, ": building_id ", building, " is used by feature ", it->second,
                                               " too; ids must be unique"));
        const std::string at = detail::concat(where, " (building_id ", building, ")");
        if (!t.have_type || !t.have_coordinates) throw invalid_input(at + ": no Polygon or MultiPolygon geometry");
        const bool multi = t.type == "MultiPolygon";
        if (!multi && t.type != "Polygon")
            throw invalid_input(at + ": geometry type " + t.type + " is not Polygon or MultiPolygon");
        if (!t.bad_value.empty()) throw invalid_input(at + ": coordinate " + t.bad_value);
        if (!t.shape_error.empty()) throw invalid_input(at + ": " + t.shape_error);
        if (t.height == 0)
            throw invalid_input(at +
                                (multi ? ": an empty MultiPolygon" : ": a Polygon needs at least its exterior ring"));
        if (t.height != (multi ? 4 : 3))
            throw invalid_input(at +
                                (multi ? ": a MultiPolygon's coordinates must be polygons of rings of positions [x, y]"
                                       : ": a Polygon's coordinates must be rings of positions [x, y]"));
        charge(16.0 * (static_cast<double>(t.vertices.capacity()) + 2.0 * static_cast<double>(t.vertices.size())));
        footprint fp{building, {}, feature_};
        std::size_t ring = 0;
        for (const std::size_t part_end : t.part_end) {
            polygon p;
            for (; ring < part_end; ++ring) {
                const std::size_t a = ring == 0 ? 0 : t.ring_end[ring - 1], b = t.ring_end[ring];
                if (b - a < 4)
                    throw invalid_input(at + ": every ring needs at least 4 positions (closed, 3 distinct corners)");
                std::vector<std::array<double, 2>> r;
                r.reserve(b - a + 1);
                r.assign(t.vertices.begin() + static_cast<std::ptrdiff_t>(a),
                         t.vertices.begin() + static_cast<std::ptrdiff_t>(b));
                if (r.front() != r.back()) r.push_back(r.front());
                p.rings.push_back(std::move(r));
            }
            fp.parts.push_back(std::move(p));
        }
        keep_footprint(std::move(fp), at, out_, kept_bytes_, kept_vertices_);
    }

    std::string_view s_;
    const std::string& source_;
    std::uint64_t budget_;
    std::string id_field_;
    std::size_t i_ = 0;
    std::size_t feature_ = 0;
    double text_bytes_, kept_bytes_ = 0, peak_ = 0;
    std::size_t kept_vertices_ = 0;
    feature_text text_;
    std::map<std::int32_t, std::size_t> first_feature_of_;
    footprint_collection out_;
};

}  // namespace

std::uint64_t footprint_memory_budget(const footprint_read_options& opt)
{
    if (opt.memory_budget_bytes) return opt.memory_budget_bytes;
    const long pages = ::sysconf(_SC_PHYS_PAGES), page = ::sysconf(_SC_PAGESIZE);
    return pages > 0 && page > 0 ? static_cast<std::uint64_t>(pages) * static_cast<std::uint64_t>(page) / 2 : 0;
}

// Why the footprint cannot be used as drawn ("" when it can): a ring crossing itself, zero area, or another
// reason of Boost.Geometry's is_valid.
std::string footprint_geometry_problem(const footprint& fp)
{
    bg::model::multi_polygon<bg_polygon> shape;
    for (const polygon& p : fp.parts) shape.push_back(to_boost(p));
    for (const bg_polygon& part : shape)
        if (bg::intersects(part)) return "invalid polygon: a ring crosses itself (self-intersection)";
    if (!(bg::area(shape) > 0)) return "empty (zero area)";
    std::string reason;
    if (!bg::is_valid(shape, reason)) return "invalid polygon: " + reason;
    return {};
}

std::string footprint_size_text(double bytes)
{
    std::ostringstream s;
    s << std::setprecision(3);
    if (bytes >= 1073741824.0)
        s << bytes / 1073741824.0 << " GiB";
    else
        s << bytes / 1048576.0 << " MiB";
    return s.str();
}

void orient_footprint(footprint& fp)
{
    for (polygon& p : fp.parts) orient_part(p);
}

void keep_footprint(footprint&& fp, const std::string& at, footprint_collection& out, double& kept_bytes,
                    std::size_t& kept_vertices)
{
    std::string problem;
    try {
        problem = footprint_geometry_problem(fp);
    } catch (const std::exception& e) {  // Boost.Geometry's own exceptions (e.g. a numeric cast)
        throw invalid_input(at + ": the polygon checks failed: " + e.what());
    }
    if (!problem.empty()) {
        kept_bytes += 2.0 * sizeof(footprint_problem) + 64.0 + static_cast<double>(problem.size());
        out.problems.push_back({fp.building_id, fp.feature, std::move(problem)});
        return;
    }
    orient_footprint(fp);
    for (const polygon& p : fp.parts) {
        kept_bytes += 48.0;
        for (const auto& r : p.rings) {
            kept_vertices += r.size();
            kept_bytes += 48.0 + 16.0 * static_cast<double>(r.size());
        }
    }
    kept_bytes += 2.0 * sizeof(footprint) + 64.0;
    out.footprints.push_back(std::move(fp));
}

footprint_collection parse_footprints_geojson(const std::string& text, const std::string& source,
                                              const footprint_read_options& opt)
{
    return geojson_reader(text, source, budget_of(opt), opt.id_field.empty() ? "building_id" : opt.id_field).read();
}

footprint_collection read_footprints_geojson(const std::string& path, const footprint_read_options& opt)
{
    std::ifstream in(path, std::ios::binary | std::ios::ate);
    if (!in) throw std::runtime_error(path + ": cannot open the footprint file");
    const std::streamoff size = in.tellg();
    if (size < 0) throw std::runtime_error(path + ": cannot read the footprint file");
    const std::uint64_t budget = budget_of(opt);
    if (budget > 0 && static_cast<std::uint64_t>(size) > budget) {
        throw invalid_input(detail::concat(path, ": reading the footprints needs more than the file's ",
                                           footprint_size_text(static_cast<double>(size)),
                                           ", over the memory budget of ",
                                           footprint_size_text(static_cast<double>(budget)),
                                           "; split the file into smaller ones or use a larger --memory"));
    }
    std::string text(static_cast<std::size_t>(size), '\0');
    in.seekg(0);
    if (!in.read(text.data(), size)) throw std::runtime_error(path + ": cannot read the footprint file");
    return parse_footprints_geojson(text, path, {.memory_budget_bytes = budget, .id_field = opt.id_field});
}

bool is_geojson_name(const std::string& path)
{
    std::string lower = path;
    std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return std::tolower(c); });
    const auto ends = [&](std::string_view end) {
        return lower.size() >= end.size() && lower.compare(lower.size() - end.size(), end.size(), end) == 0;
    };
    return ends(".geojson") || ends(".json");
}

footprint_collection read_footprints(const std::string& path, const footprint_read_options& opt)
{
    if (is_geojson_name(path)) return read_footprints_geojson(path, opt);
    if (!vectors_available())
        throw std::runtime_error(path +
                                 ": footprints other than GeoJSON (GeoPackage, Shapefile, FlatGeobuf) are read "
                                 "through OGR, and " +
                                 vectors_rebuild_hint + "; or convert the file to GeoJSON (ogr2ogr out.geojson " +
                                 path + ")");
    return read_footprints_ogr(path, opt);
}

}  // namespace lidarfx::io
