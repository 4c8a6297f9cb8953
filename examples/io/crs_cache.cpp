// SPDX-License-Identifier: Apache-2.0
#include "io/crs_cache.hpp"
#include "io/file_output.hpp"
#include "io/sha256.hpp"

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <random>
#include <sstream>
#include <stdexcept>
#include <system_error>

#ifdef LIDARFX_HAVE_GDAL
#include <gdal.h>
#include <ogr_srs_api.h>
#endif

namespace lidarfx::io {

#if defined(LIDARFX_HAVE_GDAL) && defined(LIDARFX_CRS_CODE_SHA256)
namespace {

constexpr const char* answer_format = "lidarfx crs answer 1";

/// The key of h's CRS records for this build: everything crs_of's answer depends on.
std::string answer_key(const las_header& h, const char* code_digest)
{
    std::ostringstream k;
    k << answer_format << '\n' << code_digest << '\n';
    int major = 0, minor = 0, patch = 0;
    OSRGetPROJVersion(&major, &minor, &patch);
    k << "GDAL " << GDALVersionInfo("RELEASE_NAME") << " PROJ " << major << '.' << minor << '.' << patch << '\n';
    k << "version " << h.version_major << '.' << h.version_minor << " encoding " << h.global_encoding << '\n';
    k << "keys " << h.geo_keys.size() << ':';
    for (const auto& g : h.geo_keys) k << ' ' << g.id << ',' << g.location << ',' << g.count << ',' << g.value;
    k << "\ndoubles " << h.geo_doubles.size() << ':';
    for (const double d : h.geo_doubles) k << ' ' << std::hexfloat << d;
    k << std::defaultfloat << "\nascii " << h.geo_ascii.size() << '\n' << h.geo_ascii;
    k << "\nwkt " << h.has_wkt_record << ' ' << h.wkt.size() << '\n' << h.wkt;
    return sha256_hex(k.str());
}

void put_text(std::ostream& o, const std::string& s)
{
    o << s.size() << '\n' << s << '\n';
}

bool get_text(std::istream& in, std::string& s)
{
    std::size_t n = 0;
    if (!(in >> n) || in.get() != '\n' || n > (std::size_t{1} << 24)) return false;
    s.assign(n, '\0');
    if (n != 0 && !in.read(s.data(), static_cast<std::streamsize>(n))) return false;
    return in.get() == '\n';
}

std::string encoded(const survey_crs& c, const std::string& key)
{
    std::ostringstream o;
    o << answer_format << '\n'
      << key << '\n'
      << c.epsg << ' ' << c.geographic << ' ' << std::hexfloat << c.horizontal_unit_m << ' ' << c.vertical_unit_m
      << std::defaultfloat << '\n';
    for (const std::string* s : {&c.wkt, &c.horizontal_unit, &c.vertical_unit, &c.source}) put_text(o, *s);
    o << c.warnings.size() << '\n';
    for (const auto& w : c.warnings) put_text(o, w);
    o << "end\n";
    return o.str();
}

/// The answer in `text`, when it is exactly one written by `encoded` for `key`.
std::optional<survey_crs> decoded(const std::string& text, const std::string& key)
{
    std::istringstream in(text);
    std::string format, stored_key, h_unit, v_unit;
    survey_crs c;
    int geographic = 0;
    if (!std::getline(in, format) || format != answer_format || !std::getline(in, stored_key) || stored_key != key) {
        return std::nullopt;
    }
    if (!(in >> c.epsg >> geographic >> h_unit >> v_unit) || in.get() != '\n' || (geographic != 0 && geographic != 1)) {
        return std::nullopt;
    }
    c.geographic = geographic == 1;
    char* end = nullptr;
    c.horizontal_unit_m = std::strtod(h_unit.c_str(), &end);  // hexadecimal: exact
    if (*end != '\0') return std::nullopt;
    c.vertical_unit_m = std::strtod(v_unit.c_str(), &end);
    if (*end != '\0') return std::nullopt;
    for (std::string* s : {&c.wkt, &c.horizontal_unit, &c.vertical_unit, &c.source}) {
        if (!get_text(in, *s)) return std::nullopt;
    }
    std::size_t warnings = 0;
    if (!(in >> warnings) || in.get() != '\n' || warnings > 1000) return std::nullopt;
    c.warnings.resize(warnings);
    for (auto& w : c.warnings) {
        if (!get_text(in, w)) return std::nullopt;
    }
    std::string last, rest;
    if (!std::getline(in, last) || last != "end" || std::getline(in, rest)) return std::nullopt;
    return c;
}

std::optional<std::string> file_text(const std::filesystem::path& p)
{
    std::ifstream f(p, std::ios::binary);
    if (!f) return std::nullopt;
    std::string text((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
    if (f.bad()) return std::nullopt;
    return text;
}

/// Writes `text` to `p` through a fresh temporary name in the same folder; false (and no file left) on failure.
bool write_atomically(const std::filesystem::path& p, const std::string& text)
{
    std::error_code ec;
    std::filesystem::create_directories(p.parent_path(), ec);
    if (ec) return false;
    std::random_device rd;
    const auto temporary = p.parent_path() / (p.filename().string() + ".tmp" + std::to_string(rd()));
    try {
        write_file(temporary.string(), text);
    } catch (const std::runtime_error&) {
        std::filesystem::remove(temporary, ec);
        return false;
    }
    std::filesystem::rename(temporary, p, ec);
    if (ec) std::filesystem::remove(temporary, ec);
    return !ec;
}

}  // namespace
#endif

std::optional<std::filesystem::path> crs_cache_folder()
{
    if (const char* dir = std::getenv("LIDARFX_CACHE_DIR")) {
        if (*dir == '\0') return std::nullopt;
        return std::filesystem::path(dir) / "crs";
    }
    if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg != nullptr && *xdg == '/') {
        return std::filesystem::path(xdg) / "lidarfx" / "crs";
    }
    if (const char* home = std::getenv("HOME"); home != nullptr && *home == '/') {
        return std::filesystem::path(home) / ".cache" / "lidarfx" / "crs";
    }
    return std::nullopt;
}

survey_crs crs_of_remembered(const las_header& h, const std::optional<std::filesystem::path>& folder)
{
#if defined(LIDARFX_HAVE_GDAL) && defined(LIDARFX_CRS_CODE_SHA256)
    if (!folder) return crs_of(h);
    const std::string key = answer_key(h, LIDARFX_CRS_CODE_SHA256);
    const auto path = *folder / (key + ".txt");
    if (const auto text = file_text(path)) {
        if (auto remembered = decoded(*text, key)) return std::move(*remembered);
    }
    survey_crs c = crs_of(h);
    write_atomically(path, encoded(c, key));
    return c;
#else  // without GDAL crs_of is cheap; without the code's digest an answer could outlive the code that gave it
    (void)folder;
    return crs_of(h);
#endif
}

}  // namespace lidarfx::io
