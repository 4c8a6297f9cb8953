// SPDX-License-Identifier: Apache-2.0
#include "io/crs.hpp"
#include "io/gdal_session.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <iomanip>
#include <optional>
#include <sstream>

#ifdef LIDARFX_HAVE_GDAL
#include <atomic>
#include <memory>
#include <mutex>

#include <cpl_conv.h>
#include <cpl_error.h>
#include <cpl_vsi.h>
#include <gdal.h>
#include <ogr_srs_api.h>
#endif

namespace lidarfx::io {

namespace {

// GeoKey ids (GeoTIFF 1.1, OGC 19-008r4) and the tags their values may live in.
constexpr std::uint16_t model_type_key = 1024;  // 1 projected, 2 geographic, 3 geocentric
constexpr std::uint16_t geographic_type_key = 2048;
constexpr std::uint16_t projected_type_key = 3072;
constexpr std::uint16_t proj_linear_units_key = 3076;
constexpr std::uint16_t proj_linear_unit_size_key = 3077;  // metres per unit when 3076 is user-defined
constexpr std::uint16_t vertical_type_key = 4096;
constexpr std::uint16_t vertical_units_key = 4099;
constexpr std::uint16_t double_params_tag = 34736;
constexpr std::uint16_t user_defined = 32767;

struct linear_unit {
    int code;  // EPSG unit code
    double m;  // metres per unit
    const char* name;
};

// EPSG linear units a GeoTIFF key may name (the common ones; GDAL knows every other).
constexpr std::array<linear_unit, 8> linear_units{{{9001, metre_m, "metre"},
                                                   {9002, international_foot_m, "foot"},
                                                   {9003, us_survey_foot_m, "US survey foot"},
                                                   {9005, 0.3047972654, "Clarke's foot"},
                                                   {9014, 1.8288, "fathom"},
                                                   {9015, 1852.0, "nautical mile"},
                                                   {9030, 1852.0, "nautical mile"},
                                                   {9036, 1000.0, "kilometre"}}};

const linear_unit* unit_by_code(int code)
{
    const auto it =
        std::find_if(linear_units.begin(), linear_units.end(), [&](const linear_unit& u) { return u.code == code; });
    return it == linear_units.end() ? nullptr : &*it;
}

/// The unit's name when it is one of the table's (within 1e-9 relative), else "unit of x m".
std::string unit_name(double m)
{
    for (const auto& u : linear_units)
        if (std::abs(u.m - m) <= 1e-9 * u.m) return u.name;
    std::ostringstream s;
    s << "unit of " << std::setprecision(10) << m << " m";
    return s.str();
}

const las_geo_key* find_key(const las_header& h, std::uint16_t id)
{
    const auto it =
        std::find_if(h.geo_keys.begin(), h.geo_keys.end(), [&](const las_geo_key& k) { return k.id == id; });
    return it == h.geo_keys.end() ? nullptr : &*it;
}

/// A key's value stored in place (SHORT), nullopt when absent or stored elsewhere.
std::optional<int> short_key(const las_header& h, std::uint16_t id)
{
    const las_geo_key* k = find_key(h, id);
    if (k == nullptr || k->location != 0) return std::nullopt;
    return k->value;
}

/// A key's DOUBLE value (GeoDoubleParams), nullopt when absent or out of range.
std::optional<double> double_key(const las_header& h, std::uint16_t id)
{
    const las_geo_key* k = find_key(h, id);
    if (k == nullptr || k->location != double_params_tag || k->count < 1 || k->value >= h.geo_doubles.size()) {
        return std::nullopt;
    }
    return h.geo_doubles[k->value];
}

/// An EPSG code stored in a key (0 when absent, user-defined or not a code).
int code_key(const las_header& h, std::uint16_t id)
{
    const auto v = short_key(h, id);
    return v && *v != 0 && *v != user_defined ? *v : 0;
}

/// The unit a unit key names explicitly: the table's, or a user-defined one with its size (3077 for 3076);
/// nullopt when the key is absent or names a unit not known here.
std::optional<linear_unit> known_unit(const las_header& h, std::uint16_t id)
{
    const auto code = short_key(h, id);
    if (!code) return std::nullopt;
    if (const linear_unit* u = unit_by_code(*code)) return *u;
    if (*code == user_defined && id == proj_linear_units_key) {
        if (const auto size = double_key(h, proj_linear_unit_size_key); size && *size > 0 && std::isfinite(*size)) {
            return linear_unit{user_defined, *size, "user-defined unit"};
        }
    }
    return std::nullopt;
}

/// known_unit, with a warning when the key names a unit that is not known.
std::optional<linear_unit> explicit_unit(const las_header& h, std::uint16_t id, survey_crs& c)
{
    const auto u = known_unit(h, id);
    if (!u && short_key(h, id)) {
        c.warnings.push_back("GeoKey " + std::to_string(id) + " names linear unit " +
                             std::to_string(*short_key(h, id)) + ", which is not known here; it is ignored");
    }
    return u;
}

bool has_crs_keys(const las_header& h)
{
    return std::any_of(h.geo_keys.begin(), h.geo_keys.end(), [](const las_geo_key& k) {
        return k.id == model_type_key || k.id == geographic_type_key || k.id == projected_type_key ||
               k.id == vertical_type_key || k.id == proj_linear_units_key || k.id == vertical_units_key;
    });
}

bool blank(const std::string& s)
{
    return std::all_of(s.begin(), s.end(),
                       [](unsigned char ch) { return std::isspace(ch) || ch == '\'' || ch == '"'; });
}

// ---- WKT without GDAL: a small tree of nodes, enough to find the units and the EPSG code. ----

struct wkt_node {
    std::string keyword;              // upper case
    std::vector<std::string> values;  // literal children (quotes removed)
    std::vector<wkt_node> children;
};

/// Parses WKT1 or WKT2 text (KEYWORD[value, "text", CHILD[...]...], brackets or parentheses).
std::optional<wkt_node> parse_wkt(const std::string& text)
{
    std::size_t i = 0;
    const auto skip = [&] {
        while (i < text.size() && std::isspace(static_cast<unsigned char>(text[i]))) ++i;
    };
    std::function<std::optional<wkt_node>(int)> node = [&](int depth) -> std::optional<wkt_node> {
        if (depth > 64) return std::nullopt;
        skip();
        wkt_node n;
        while (i < text.size() && (std::isalnum(static_cast<unsigned char>(text[i])) || text[i] == '_')) {
            n.keyword += static_cast<char>(std::toupper(static_cast<unsigned char>(text[i++])));
        }
        skip();
        if (n.keyword.empty() || i >= text.size() || (text[i] != '[' && text[i] != '(')) return std::nullopt;
        const char close = text[i++] == '[' ? ']' : ')';
        for (;;) {
            skip();
            if (i >= text.size()) return std::nullopt;
            if (text[i] == '"') {
                std::string v;
                for (++i; i < text.size(); ++i) {
                    if (text[i] == '"' && i + 1 < text.size() && text[i + 1] == '"')
                        v += text[++i];
                    else if (text[i] == '"')
                        break;
                    else
                        v += text[i];
                }
                if (i++ >= text.size()) return std::nullopt;
                n.values.push_back(v);
            } else if (std::isalpha(static_cast<unsigned char>(text[i]))) {
                const std::size_t start = i;
                while (i < text.size() && (std::isalnum(static_cast<unsigned char>(text[i])) || text[i] == '_')) ++i;
                skip();
                if (i < text.size() && (text[i] == '[' || text[i] == '(')) {
                    i = start;
                    auto child = node(depth + 1);
                    if (!child) return std::nullopt;
                    n.children.push_back(std::move(*child));
                } else {
                    n.values.push_back(text.substr(start, i - start));  // an enumeration such as NORTH
                }
            } else {
                const std::size_t start = i;
                while (i < text.size() && text[i] != ',' && text[i] != close) ++i;
                n.values.push_back(text.substr(start, i - start));
            }
            skip();
            if (i < text.size() && text[i] == ',') {
                ++i;
                continue;
            }
            if (i < text.size() && text[i] == close) {
                ++i;
                return n;
            }
            return std::nullopt;
        }
    };
    auto root = node(0);
    skip();
    if (!root || i != text.size()) return std::nullopt;
    return root;
}

const wkt_node* child_of(const wkt_node& n, std::initializer_list<const char*> keywords)
{
    for (const auto& c : n.children)
        for (const char* k : keywords)
            if (c.keyword == k) return &c;
    return nullptr;
}

/// Metres per unit of the linear UNIT / LENGTHUNIT of a projected or vertical node (nullopt when none).
std::optional<double> wkt_linear_unit(const wkt_node& n)
{
    const wkt_node* u = child_of(n, {"UNIT", "LENGTHUNIT"});
    if (u == nullptr) {  // WKT2 may give the unit in each AXIS
        if (const wkt_node* axis = child_of(n, {"AXIS"})) u = child_of(*axis, {"UNIT", "LENGTHUNIT"});
    }
    if (u == nullptr || u->values.size() < 2) return std::nullopt;
    char* end = nullptr;
    const double m = std::strtod(u->values[1].c_str(), &end);
    return end != u->values[1].c_str() && m > 0 && std::isfinite(m) ? std::optional<double>(m) : std::nullopt;
}

int wkt_epsg(const wkt_node& n)
{
    const wkt_node* id = child_of(n, {"AUTHORITY", "ID"});
    if (id == nullptr || id->values.size() < 2 || id->values[0] != "EPSG") return 0;
    return std::atoi(id->values[1].c_str());
}

bool is_one_of(const std::string& keyword, std::initializer_list<const char*> names)
{
    return std::any_of(names.begin(), names.end(), [&](const char* n) { return keyword == n; });
}

constexpr std::initializer_list<const char*> projected_keywords = {"PROJCS", "PROJCRS", "PROJECTEDCRS"};
constexpr std::initializer_list<const char*> geographic_keywords = {"GEOGCS", "GEOGCRS", "GEOGRAPHICCRS", "GEODCRS",
                                                                    "GEODETICCRS"};
constexpr std::initializer_list<const char*> vertical_keywords = {"VERT_CS", "VERTCRS", "VERTICALCRS"};

/// What one record (the GeoKeys or the WKT) says, before the rules of crs_of are applied.
struct found {
    bool crs = false;  // a horizontal CRS was found
    std::string wkt;   // horizontal CRS for outputs (empty: none or no GDAL)
    int epsg = 0;
    bool geographic = false;
    std::optional<double> horizontal_m;  // metres per unit of x and y, when the CRS says
    std::optional<double> vertical_m;    // metres per unit of z, when a vertical CRS says
};

/// Units and EPSG code from WKT text without GDAL; crs false when the text is not WKT of a CRS.
found from_wkt_text(const std::string& text, survey_crs& c)
{
    found f;
    const auto root = parse_wkt(text);
    if (!root) return f;
    const wkt_node* horizontal = &*root;
    const wkt_node* vertical = nullptr;
    if (is_one_of(root->keyword, {"COMPD_CS", "COMPOUNDCRS"})) {
        horizontal = nullptr;
        for (const auto& part : root->children) {
            if (is_one_of(part.keyword, projected_keywords) || is_one_of(part.keyword, geographic_keywords))
                horizontal = &part;
            if (is_one_of(part.keyword, vertical_keywords)) vertical = &part;
        }
        if (horizontal == nullptr) return f;
    }
    if (is_one_of(horizontal->keyword, geographic_keywords)) {
        f.geographic = true;
    } else if (is_one_of(horizontal->keyword, projected_keywords)) {
        f.horizontal_m = wkt_linear_unit(*horizontal);
        if (!f.horizontal_m) c.warnings.push_back("the WKT record names no linear unit");
    } else {
        return f;
    }
    f.crs = true;
    f.wkt = text;
    f.epsg = wkt_epsg(*horizontal);
    if (vertical != nullptr) f.vertical_m = wkt_linear_unit(*vertical);
    return f;
}

/// The GeoKeys without GDAL: EPSG codes as they are, geographic from the model type key or the code's range
/// (EPSG's geographic 2D CRSs are 4001..4999), units of EPSG codes unknown.
found from_keys_alone(const las_header& h)
{
    found f;
    const int projected = code_key(h, projected_type_key), geographic = code_key(h, geographic_type_key);
    const auto model = short_key(h, model_type_key);
    f.geographic = model ? *model == 2 : projected == 0 && geographic != 0;
    f.epsg = f.geographic ? geographic : projected;
    if (f.geographic && f.epsg == 0 && projected >= 4001 && projected <= 4999) f.epsg = projected;
    f.crs = f.epsg != 0;
    return f;
}

#ifdef LIDARFX_HAVE_GDAL

srs_ptr srs_from_epsg(int code)
{
    srs_ptr srs(OSRNewSpatialReference(nullptr));
    if (OSRImportFromEPSG(srs.get(), code) != OGRERR_NONE) return nullptr;
    return srs;
}

/// The CRS as WKT1, or WKT2 when it has no WKT1 form; "" when it cannot be exported.
std::string wkt_of(OGRSpatialReferenceH srs)
{
    char* wkt = nullptr;
    std::string out;
    if (OSRExportToWkt(srs, &wkt) == OGRERR_NONE && wkt != nullptr) out = wkt;
    CPLFree(wkt);
    if (out.empty()) {
        wkt = nullptr;
        const char* options[] = {"FORMAT=WKT2_2019", nullptr};
        if (OSRExportToWktEx(srs, &wkt, options) == OGRERR_NONE && wkt != nullptr) out = wkt;
        CPLFree(wkt);
    }
    return out;
}

bool same_unit(double a_m, double b_m)
{
    return std::abs(a_m - b_m) <= 1e-12 * b_m;
}

/// What an OGR spatial reference says: horizontal part as WKT, its EPSG code (or the only EPSG CRS that
/// matches it exactly), geographic or not, units of the horizontal and vertical parts.
found from_srs(OGRSpatialReferenceH srs, bool find_epsg = true)
{
    found f;
    if (OSRIsCompound(srs) || OSRIsVertical(srs)) {
        const double m = OSRGetTargetLinearUnits(srs, "VERT_CS", nullptr);
        if (m > 0 && std::isfinite(m)) f.vertical_m = m;
    }
    srs_ptr horizontal(OSRClone(srs));
    if (OSRIsCompound(horizontal.get())) OSRStripVertical(horizontal.get());
    bool horizontal_replaced = false;  // the horizontal CRS is rebuilt from its code in another unit
    OGRSpatialReferenceH hz = horizontal.get();
    if (OSRIsGeographic(hz)) {
        f.geographic = true;
    } else if (OSRIsProjected(hz) || OSRIsLocal(hz)) {
        const double m = OSRGetLinearUnits(hz, nullptr);
        if (m > 0 && std::isfinite(m)) f.horizontal_m = m;
        if (OSRIsLocal(hz)) return f;  // a unit without a place on Earth: nothing to carry
    } else {
        return f;  // geocentric or vertical only: nothing to carry
    }
    f.crs = true;
    const char* authority = OSRGetAuthorityName(hz, nullptr);
    const char* code = OSRGetAuthorityCode(hz, nullptr);
    if (authority != nullptr && code != nullptr && std::strcmp(authority, "EPSG") == 0) f.epsg = std::atoi(code);
    if (f.epsg != 0 && f.horizontal_m) {
        // GDAL keeps the code of "EPSG:26995 in US survey feet"; that code names the CRS in metres, so the
        // outputs get the CRS without it (its parameters in the new unit, as GDAL gives them).
        const srs_ptr by_code = srs_from_epsg(f.epsg);
        if (by_code &&
            std::abs(OSRGetLinearUnits(by_code.get(), nullptr) - *f.horizontal_m) > 1e-12 * *f.horizontal_m) {
            char* name = nullptr;
            OSRGetLinearUnits(hz, &name);
            const std::string unit = name != nullptr ? name : unit_name(*f.horizontal_m);
            horizontal.reset(OSRClone(by_code.get()));
            hz = horizontal.get();
            horizontal_replaced = true;
            OSRSetLinearUnitsAndUpdateParameters(hz, unit.c_str(), *f.horizontal_m);
            f.epsg = 0;
        }
    }
    if (f.epsg == 0 && find_epsg) {  // the one EPSG CRS that matches exactly, if any (a user-defined CRS may be one)
        int count = 0;
        int* confidence = nullptr;
        OGRSpatialReferenceH* matches = OSRFindMatches(hz, nullptr, &count, &confidence);
        int exact = 0, exact_count = 0;
        for (int i = 0; i < count; ++i) {
            if (confidence[i] < 100) continue;
            const char* a = OSRGetAuthorityName(matches[i], nullptr);
            const char* c = OSRGetAuthorityCode(matches[i], nullptr);
            if (a != nullptr && c != nullptr && std::strcmp(a, "EPSG") == 0) exact = std::atoi(c), ++exact_count;
        }
        if (matches != nullptr) OSRFreeSRSArray(matches);
        CPLFree(confidence);
        if (exact_count == 1) f.epsg = exact;
    }
    // The vertical part travels with the horizontal one when heights can be written in its unit: when it is the
    // horizontal unit (outputs hold heights in that unit, and an ESRI .prj can carry the horizontal part only).
    const bool keep_vertical = OSRIsCompound(srs) && !horizontal_replaced && f.vertical_m && f.horizontal_m &&
                               same_unit(*f.vertical_m, *f.horizontal_m);
    f.wkt = wkt_of(keep_vertical ? srs : hz);
    return f;
}

/// A one-pixel little-endian TIFF whose GeoTIFF tags are the file's GeoKeys (34735, with 34736 and 34737),
/// so that GDAL's GeoTIFF driver interprets them exactly as it does for a GeoTIFF.
std::vector<std::uint8_t> tiff_with_geokeys(const las_header& h)
{
    struct entry {
        std::uint16_t tag, type;  // type: 2 ASCII, 3 SHORT, 4 LONG, 12 DOUBLE
        std::uint32_t count;
        std::vector<std::uint8_t> bytes;
    };
    const auto shorts = [](std::uint16_t tag, const std::vector<std::uint16_t>& v) {
        entry e{tag, 3, static_cast<std::uint32_t>(v.size()), std::vector<std::uint8_t>(2 * v.size())};
        if (!v.empty()) std::memcpy(e.bytes.data(), v.data(), e.bytes.size());
        return e;
    };
    const auto doubles = [](std::uint16_t tag, const std::vector<double>& v) {
        entry e{tag, 12, static_cast<std::uint32_t>(v.size()), std::vector<std::uint8_t>(8 * v.size())};
        if (!v.empty()) std::memcpy(e.bytes.data(), v.data(), e.bytes.size());
        return e;
    };
    std::vector<std::uint16_t> directory{1, 1, 0, static_cast<std::uint16_t>(h.geo_keys.size())};
    for (const auto& k : h.geo_keys) directory.insert(directory.end(), {k.id, k.location, k.count, k.value});
    std::vector<entry> entries{shorts(256, {1}),
                               shorts(257, {1}),
                               shorts(258, {8}),
                               shorts(259, {1}),
                               shorts(262, {1}),
                               entry{273, 4, 1, {}},
                               shorts(277, {1}),
                               shorts(278, {1}),
                               entry{279, 4, 1, {1, 0, 0, 0}},
                               doubles(33550, {1.0, 1.0, 0.0}),
                               doubles(33922, {0, 0, 0, 0, 0, 0}),
                               shorts(34735, directory)};
    if (!h.geo_doubles.empty()) entries.push_back(doubles(34736, h.geo_doubles));
    if (!h.geo_ascii.empty()) {
        std::vector<std::uint8_t> text(h.geo_ascii.begin(), h.geo_ascii.end());
        if (text.back() != 0) text.push_back(0);
        entries.push_back(entry{34737, 2, static_cast<std::uint32_t>(text.size()), text});
    }
    const std::size_t ifd_size = 2 + 12 * entries.size() + 4;
    std::size_t data_at = 8 + ifd_size;
    std::vector<std::uint8_t> out(data_at, 0);
    const auto put16 = [&](std::size_t at, std::uint16_t v) { std::memcpy(out.data() + at, &v, 2); };
    const auto put32 = [&](std::size_t at, std::uint32_t v) { std::memcpy(out.data() + at, &v, 4); };
    out[0] = out[1] = 'I';
    put16(2, 42);
    put32(4, 8);
    put16(8, static_cast<std::uint16_t>(entries.size()));
    std::size_t strip_entry = 0;
    for (std::size_t i = 0; i < entries.size(); ++i) {
        const entry& e = entries[i];
        const std::size_t at = 10 + 12 * i;
        put16(at, e.tag);
        put16(at + 2, e.type);
        put32(at + 4, e.count);
        if (e.tag == 273) strip_entry = at + 8;
        if (e.bytes.size() <= 4) {
            if (!e.bytes.empty()) std::memcpy(out.data() + at + 8, e.bytes.data(), e.bytes.size());
        } else {
            if (out.size() % 2) out.push_back(0);  // values start on a word boundary
            put32(at + 8, static_cast<std::uint32_t>(out.size()));
            out.insert(out.end(), e.bytes.begin(), e.bytes.end());
        }
    }
    put32(strip_entry, static_cast<std::uint32_t>(out.size()));  // the one pixel, last
    out.push_back(0);
    return out;
}

/// The GeoKeys as GDAL's GeoTIFF driver reads them; null (with the reason in `why`) when it finds no CRS.
srs_ptr srs_from_geokeys(const las_header& h, std::string& why)
{
    static std::atomic<unsigned> serial{0};
    const std::string name = "/vsimem/lidarfx_geokeys_" + std::to_string(serial++) + ".tif";
    auto bytes = tiff_with_geokeys(h);
    VSILFILE* file = VSIFileFromMemBuffer(name.c_str(), bytes.data(), bytes.size(), FALSE);
    if (file == nullptr) {
        why = "GDAL cannot hold them in memory" + gdal_message();
        return nullptr;
    }
    VSIFCloseL(file);
    srs_ptr srs;
    const char* drivers[] = {"GTiff", nullptr};
    if (GDALDatasetH ds = GDALOpenEx(name.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY, drivers, nullptr, nullptr)) {
        if (OGRSpatialReferenceH s = GDALGetSpatialRef(ds)) srs.reset(OSRClone(s));
        GDALClose(ds);
    }
    VSIUnlink(name.c_str());
    if (!srs) why = "GDAL finds no coordinate system in them" + gdal_message();
    return srs;
}

#endif

/// The GeoKeys interpreted (by GDAL's GeoTIFF driver when `use_gdal`); warnings go to c.
found from_keys(const las_header& h, bool use_gdal, survey_crs& c)
{
#ifdef LIDARFX_HAVE_GDAL
    if (use_gdal) {
        register_gdal_drivers();
        const quiet_gdal quiet;
        CPLErrorReset();
        std::string why;
        srs_ptr srs = srs_from_geokeys(h, why);
        if (srs && !OSRIsProjected(srs.get()) && !OSRIsGeographic(srs.get())) {
            const found local = from_srs(srs.get());  // a LOCAL_CS: units only
            if (!code_key(h, projected_type_key) && !code_key(h, geographic_type_key)) return local;
            srs.reset();
        }
        if (!srs) {  // GDAL could not read the whole directory, but the EPSG code itself may still be known
            if (const found alone = from_keys_alone(h); alone.crs) srs = srs_from_epsg(alone.epsg);
        }
        if (!srs) {
            if (find_key(h, projected_type_key) || find_key(h, geographic_type_key)) {
                c.warnings.push_back("its GeoKeys cannot be turned into a coordinate system: " + why);
            }
            return {};
        }
        // ProjLinearUnitsGeoKey overrides the unit of the code (GDAL applies it; this holds if it did not).
        const auto unit = known_unit(h, proj_linear_units_key);
        if (unit && OSRIsProjected(srs.get()) &&
            std::abs(OSRGetLinearUnits(srs.get(), nullptr) - unit->m) > 1e-12 * unit->m) {
            OSRSetLinearUnitsAndUpdateParameters(srs.get(), unit->name, unit->m);
        }
        found f = from_srs(srs.get());
        const int vertical = code_key(h, vertical_type_key);
        if (!f.vertical_m && vertical != 0) {
            if (const auto v = srs_from_epsg(vertical); v && OSRIsVertical(v.get())) {
                f.vertical_m = OSRGetTargetLinearUnits(v.get(), "VERT_CS", nullptr);
                // VerticalCSTypeGeoKey names an EPSG vertical CRS: it travels with the horizontal one (as from a
                // compound WKT) when its unit is the horizontal unit.
                if (f.crs && !f.geographic && f.epsg != 0 && f.horizontal_m && f.vertical_m > 0 &&
                    same_unit(*f.vertical_m, *f.horizontal_m)) {
                    srs_ptr compound(OSRNewSpatialReference(nullptr));
                    srs_ptr horizontal = srs_from_epsg(f.epsg);
                    const char* hname = horizontal ? OSRGetName(horizontal.get()) : nullptr;
                    const char* vname = OSRGetName(v.get());
                    const std::string name = std::string(hname ? hname : "") + " + " + (vname ? vname : "");
                    if (horizontal &&
                        OSRSetCompoundCS(compound.get(), name.c_str(), horizontal.get(), v.get()) == OGRERR_NONE) {
                        if (std::string w = wkt_of(compound.get()); !w.empty()) f.wkt = std::move(w);
                    }
                }
            }
        }
        return f;
    }
#else
    (void)use_gdal;
#endif
    found f = from_keys_alone(h);
    if (f.crs && !f.geographic) {
        const auto unit = known_unit(h, proj_linear_units_key);
        if (!unit) {
            c.warnings.push_back("the unit of EPSG:" + std::to_string(f.epsg) +
                                 " is not known without GDAL; metres are assumed");
        } else if (unit->code != 9001) {
            c.warnings.push_back("EPSG:" + std::to_string(f.epsg) + " is given in " + unit->name +
                                 "; without GDAL nothing checks that the code names a CRS in that unit");
        }
    }
    if (!f.crs && (find_key(h, projected_type_key) || find_key(h, geographic_type_key))) {
        c.warnings.push_back(
            "its GeoKeys define a coordinate system by parameters, which needs GDAL to be "
            "carried; outputs carry no CRS");
    }
    return f;
}

/// The WKT record interpreted (by OGR when `use_gdal`); crs false when unreadable. Without `find_epsg` no EPSG
/// code is looked for when the WKT names none (the search costs about 0.1 s: only for a record whose CRS is used).
found from_wkt(const std::string& wkt, bool use_gdal, survey_crs& c, bool find_epsg = true)
{
#ifdef LIDARFX_HAVE_GDAL
    if (use_gdal) {
        register_gdal_drivers();
        const quiet_gdal quiet;
        srs_ptr srs(OSRNewSpatialReference(nullptr));
        if (OSRSetFromUserInput(srs.get(), wkt.c_str()) != OGRERR_NONE) return {};
        return from_srs(srs.get(), find_epsg);
    }
#else
    (void)use_gdal;
    (void)find_epsg;
#endif
    return from_wkt_text(wkt, c);
}

}  // namespace

bool same_crs_records(const las_header& a, const las_header& b)
{
    const auto wkt_flag = [](const las_header& h) { return h.version_minor >= 4 && (h.global_encoding & 16) != 0; };
    return a.geo_keys == b.geo_keys && a.geo_doubles == b.geo_doubles && a.geo_ascii == b.geo_ascii && a.wkt == b.wkt &&
           a.has_wkt_record == b.has_wkt_record && wkt_flag(a) == wkt_flag(b);
}

bool crs_gdal_available() noexcept
{
#ifdef LIDARFX_HAVE_GDAL
    return true;
#else
    return false;
#endif
}

std::string survey_crs::for_outputs() const
{
    if (!wkt.empty()) return wkt;
    return epsg != 0 ? "EPSG:" + std::to_string(epsg) : std::string();
}

std::string survey_crs::describe() const
{
    std::string what = epsg != 0 ? "EPSG:" + std::to_string(epsg) : !source.empty() ? "a user-defined CRS" : "no CRS";
    if (epsg == 0 && !wkt.empty()) {  // the CRS's name, as its WKT gives it: KEYWORD["name", ...
        const auto open = wkt.find("[\""), close = open == std::string::npos ? open : wkt.find('"', open + 2);
        if (close != std::string::npos && close > open + 2) what = wkt.substr(open + 2, close - open - 2);
    }
    return what + " (" + (geographic ? std::string("degrees") : horizontal_unit) + ")";
}

survey_crs crs_of(const las_header& h, bool use_gdal)
{
    survey_crs c;
    use_gdal = use_gdal && crs_gdal_available();
    const bool wkt_flag = h.version_minor >= 4 && (h.global_encoding & 16) != 0;
    const bool keys = has_crs_keys(h);
    std::optional<found> from_record;
    found wkt_found;
    bool wkt_tried = false;
    // A record read only to report it when unreadable (its CRS not used) is not matched to an EPSG code.
    const auto try_wkt = [&](bool used = true) {
        if (!wkt_tried && h.has_wkt_record) {
            wkt_tried = true;
            wkt_found = blank(h.wkt) ? found{} : from_wkt(h.wkt, use_gdal, c, used);
            if (!wkt_found.crs) {
                c.warnings.push_back(std::string("its WKT record is ") + (blank(h.wkt) ? "empty" : "unreadable") +
                                     "; it is ignored");
            }
        }
        return wkt_found.crs;
    };
    if (wkt_flag && try_wkt()) {
        from_record = wkt_found, c.source = "WKT";
    } else if (keys) {
        found k = from_keys(h, use_gdal, c);
        if (k.crs || !try_wkt())
            from_record = k, c.source = k.crs ? "GeoKeys" : "";
        else
            from_record = wkt_found, c.source = "WKT";
    } else if (try_wkt()) {
        from_record = wkt_found, c.source = "WKT";
    }
    try_wkt(false);  // an unreadable WKT record is reported even when the GeoKeys are used
    const found f = from_record.value_or(found{});
    c.wkt = f.wkt;
    c.epsg = f.epsg;
    c.geographic = f.geographic;

    // Units: explicit unit keys first (they override the units of an EPSG code), then the CRS's own.
    std::optional<double> horizontal = f.horizontal_m, vertical = f.vertical_m;
    if (c.source != "WKT") {
        if (const auto u = explicit_unit(h, proj_linear_units_key, c); u && !c.geographic) {
            if (horizontal && std::abs(*horizontal - u->m) > 1e-12 * u->m) {
                // Only when GDAL could not apply the key: the CRS would place the data elsewhere.
                c.warnings.push_back("ProjLinearUnitsGeoKey names " + std::string(u->name) + " but its CRS is in " +
                                     unit_name(*horizontal) + "; the key's unit is used and outputs carry no CRS");
                c.wkt.clear();
                c.epsg = 0;
            }
            horizontal = u->m;
        }
        if (const auto u = explicit_unit(h, vertical_units_key, c)) vertical = u->m;
    }
    if (c.geographic) {
        c.horizontal_unit_m = 1;
        c.horizontal_unit = "degree";
    } else {
        c.horizontal_unit_m = horizontal.value_or(1.0);
        c.horizontal_unit = unit_name(c.horizontal_unit_m);
    }
    // z without a unit of its own is in the unit of x and y (metres when those are degrees).
    c.vertical_unit_m = vertical.value_or(c.geographic ? 1.0 : c.horizontal_unit_m);
    c.vertical_unit = unit_name(c.vertical_unit_m);
    if (!c.source.empty() && c.epsg == 0) {
        c.warnings.push_back(
            "no EPSG code names its CRS exactly: GeoTIFF outputs carry the CRS as WKT, the GeoJSON "
            "carries none");
    }
    if (c.source.empty()) {
        c.warnings.push_back(std::string("it names no coordinate system: outputs carry none") +
                             (horizontal || vertical ? "" : ", and x, y and z are taken as metres"));
    }
    return c;
}

std::string esri_prj_text(const std::string& crs)
{
    if (blank(crs)) return {};
#ifdef LIDARFX_HAVE_GDAL
    register_gdal_drivers();
    const quiet_gdal quiet;
    std::string input = crs;
    if (std::all_of(crs.begin(), crs.end(), [](unsigned char ch) { return std::isdigit(ch) != 0; }))
        input = "EPSG:" + crs;
    srs_ptr srs(OSRNewSpatialReference(nullptr));
    if (OSRSetFromUserInput(srs.get(), input.c_str()) != OGRERR_NONE) return {};
    const char* options[] = {"FORMAT=WKT1_ESRI", nullptr};
    const auto export_esri = [&]() -> std::string {
        char* wkt = nullptr;
        const bool ok = OSRExportToWktEx(srs.get(), &wkt, options) == OGRERR_NONE && wkt != nullptr;
        std::string out = ok ? wkt : "";
        CPLFree(wkt);
        return out;
    };
    // GDAL's AAIGrid driver cannot read a .prj with a VERTCS after the PROJCS (it then reads no CRS at all), so the
    // .prj holds the horizontal part; heights are in its unit (see survey_crs::wkt).
    if (OSRIsCompound(srs.get())) OSRStripVertical(srs.get());
    return export_esri();
#else
    return crs.find('[') != std::string::npos ? crs : std::string();
#endif
}

survey_crs crs_of_wkt(const std::string& wkt, bool use_gdal)
{
    las_header h;  // a LAS 1.4 header whose only CRS record is the WKT
    h.version_minor = 4;
    h.global_encoding = 16;
    h.has_wkt_record = !wkt.empty();
    h.wkt = wkt;
    return crs_of(h, use_gdal);
}

}  // namespace lidarfx::io
