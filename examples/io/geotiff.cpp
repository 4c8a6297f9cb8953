// SPDX-License-Identifier: Apache-2.0
#include "io/geotiff.hpp"
#include "io/gdal_session.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <lidarfx/core/error.hpp>

#ifdef LIDARFX_HAVE_GDAL
#include <cpl_conv.h>
#include <cpl_error.h>
#include <gdal.h>
#include <ogr_srs_api.h>

#include <cctype>
#include <memory>
#include <mutex>
#endif

namespace lidarfx::io {

#ifdef LIDARFX_HAVE_GDAL

namespace {

struct dataset_closer {
    void operator()(void* ds) const { GDALClose(static_cast<GDALDatasetH>(ds)); }
};
using dataset = std::unique_ptr<void, dataset_closer>;

/// The CRS given as "EPSG:n", "n", WKT or PROJ text, read by OGR; null when it cannot be read.
srs_ptr read_crs(const std::string& crs)
{
    std::string input = crs;
    if (std::all_of(crs.begin(), crs.end(), [](unsigned char ch) { return std::isdigit(ch) != 0; })) {
        input = "EPSG:" + crs;
    }
    srs_ptr srs(OSRNewSpatialReference(nullptr));
    if (OSRSetFromUserInput(srs.get(), input.c_str()) != OGRERR_NONE) return nullptr;
    OSRSetAxisMappingStrategy(srs.get(), OAMS_TRADITIONAL_GIS_ORDER);  // as GDALSetProjection sets it
    return srs;
}

/// A copy of the CRS given as text (as read_crs reads it), or null. Reading a CRS defined by its parameters
/// costs PROJ database lookups (about 10 ms), and a run writes all its rasters in one CRS: each text is read
/// once per process, and copies of it cost no lookup. OGR objects are not safe to share between threads, so
/// each caller gets its own copy, made under the lock.
srs_ptr crs_copy(const std::string& crs)
{
    static std::mutex mutex;
    static std::vector<std::pair<std::string, srs_ptr>> read;  // in the order first asked for; a run has few
    const std::lock_guard lock(mutex);
    auto known = std::find_if(read.begin(), read.end(), [&](const auto& r) { return r.first == crs; });
    if (known == read.end()) known = read.insert(read.end(), {crs, read_crs(crs)});
    return known->second ? srs_ptr(OSRClone(known->second.get())) : nullptr;
}

/// The CRS of write_geotiff's `crs_wkt_or_epsg`; null for "". @throws invalid_input when OGR cannot read it.
srs_ptr crs_for_writing(const std::string& crs)
{
    if (crs.empty()) return nullptr;
    srs_ptr srs = crs_copy(crs);
    if (!srs) {
        throw invalid_input(
            detail::concat("write_geotiff: crs_wkt_or_epsg must name a coordinate system GDAL "
                           "understands (got '",
                           crs, "')"));
    }
    return srs;
}

}  // namespace

bool geotiff_available() noexcept
{
    return true;
}

void write_geotiff(const std::string& path, raster_view<const float> values, const grid& g,
                   const std::string& crs_wkt_or_epsg)
{
    constexpr const char* fn = "write_geotiff";
    g.validate(fn);
    detail::require(values.rows() == g.rows && values.cols() == g.cols, fn, "values and grid must have the same shape");
    detail::require(!values.empty(), fn, "values must not be empty");
    register_gdal_drivers();
    const quiet_gdal quiet;
    const srs_ptr srs = crs_for_writing(crs_wkt_or_epsg);
    // The cells go into an in-memory dataset first: the COG driver writes a whole file at once (CreateCopy), with
    // its overviews before the full-resolution tiles.
    GDALDriverH mem_driver = GDALGetDriverByName("MEM");
    GDALDriverH cog_driver = GDALGetDriverByName("COG");
    if (mem_driver == nullptr || cog_driver == nullptr)
        throw std::runtime_error(path + ": GDAL has no MEM or COG driver (GDAL 3.1 or later is needed)");
    dataset mem(
        GDALCreate(mem_driver, "", static_cast<int>(g.cols), static_cast<int>(g.rows), 1, GDT_Float32, nullptr));
    if (!mem) throw std::runtime_error(path + ": cannot create the GeoTIFF in memory" + gdal_message());
    auto transform = to_gdal(g);
    bool ok = GDALSetGeoTransform(mem.get(), transform.data()) == CE_None;
    if (srs) ok = ok && GDALSetSpatialRef(mem.get(), srs.get()) == CE_None;
    GDALRasterBandH band = GDALGetRasterBand(mem.get(), 1);
    ok = ok && GDALSetRasterNoDataValue(band, geotiff_nodata) == CE_None;
    const auto cols = static_cast<std::size_t>(g.cols);
    std::vector<float> row(cols);
    for (std::ptrdiff_t r = 0; ok && r < g.rows; ++r) {
        const float* src = values.row(r);
        for (std::size_t c = 0; c < cols; ++c)
            row[c] = std::isnan(src[c]) ? static_cast<float>(geotiff_nodata) : src[c];
        ok = GDALRasterIO(band, GF_Write, 0, static_cast<int>(r), static_cast<int>(g.cols), 1, row.data(),
                          static_cast<int>(g.cols), 1, GDT_Float32, 0, 0) == CE_None;
    }
    if (!ok) throw std::runtime_error(path + ": preparing the GeoTIFF failed" + gdal_message());
    // Nearest-neighbour overviews: every value in them is a value of the grid (classes and labels stay whole).
    const char* options[] = {"COMPRESS=DEFLATE", "LEVEL=1",        "PREDICTOR=FLOATING_POINT",
                             "BLOCKSIZE=256",    "OVERVIEWS=AUTO", "OVERVIEW_RESAMPLING=NEAREST",
                             "BIGTIFF=IF_SAFER", nullptr};
    // The COG driver first writes the overviews into a temporary GeoTIFF beside the file, ZSTD-compressed by default:
    // compressing and decompressing them cost a quarter of the CPU time of a grid's file. Uncompressed, they take a
    // third of the grid's size on disk for the moment of the copy (GDAL's setting for this thread, restored after).
    const thread_config_option uncompressed_overviews("COG_TMP_COMPRESSION", "NONE");
    dataset ds(
        GDALCreateCopy(cog_driver, path.c_str(), mem.get(), FALSE, const_cast<char**>(options), nullptr, nullptr));
    if (!ds) throw std::runtime_error(path + ": writing the Cloud-Optimized GeoTIFF failed" + gdal_message());
    ds.reset();  // flushes and closes
    if (CPLGetLastErrorType() >= CE_Failure)
        throw std::runtime_error(path + ": closing the GeoTIFF failed" + gdal_message());
}

namespace {

/// The grid of an open dataset's band 1. @throws std::runtime_error naming the file.
grid grid_of(GDALDatasetH ds, const std::string& path)
{
    const int cols = GDALGetRasterXSize(ds), rows = GDALGetRasterYSize(ds);
    if (GDALGetRasterCount(ds) < 1) throw std::runtime_error(path + ": the file has no raster band");
    std::array<double, 6> gt{};
    if (GDALGetGeoTransform(ds, gt.data()) != CE_None)
        throw std::runtime_error(path + ": the file has no geotransform");
    try {
        return from_gdal(gt, rows, cols);
    } catch (const invalid_input& e) {
        throw std::runtime_error(path + ": unsupported georeferencing: " + e.what() +
                                 "; lidarfx reads north-up grids of square cells only: resample it first, e.g. "
                                 "gdalwarp -tr CELL CELL IN.tif OUT.tif");
    }
}

}  // namespace

grid read_geotiff_grid(const std::string& path)
{
    register_gdal_drivers();
    const quiet_gdal quiet;
    dataset ds(GDALOpen(path.c_str(), GA_ReadOnly));
    if (!ds) throw std::runtime_error(path + ": cannot open as a raster" + gdal_message());
    return grid_of(ds.get(), path);
}

std::string read_geotiff_crs(const std::string& path)
{
    register_gdal_drivers();
    const quiet_gdal quiet;
    dataset ds(GDALOpen(path.c_str(), GA_ReadOnly));
    if (!ds) throw std::runtime_error(path + ": cannot open as a raster" + gdal_message());
    const char* wkt = GDALGetProjectionRef(ds.get());
    return wkt != nullptr ? wkt : "";
}

geotiff_raster read_geotiff(const std::string& path)
{
    register_gdal_drivers();
    const quiet_gdal quiet;
    dataset ds(GDALOpen(path.c_str(), GA_ReadOnly));
    if (!ds) throw std::runtime_error(path + ": cannot open as a raster" + gdal_message());
    geotiff_raster out;
    out.g = grid_of(ds.get(), path);
    const auto rows = static_cast<int>(out.g.rows), cols = static_cast<int>(out.g.cols);
    const char* wkt = GDALGetProjectionRef(ds.get());
    out.crs_wkt = wkt != nullptr ? wkt : "";
    out.values = raster<float>(rows, cols);
    GDALRasterBandH band = GDALGetRasterBand(ds.get(), 1);
    if (GDALRasterIO(band, GF_Read, 0, 0, cols, rows, out.values.data(), cols, rows, GDT_Float32, 0, 0) != CE_None) {
        throw std::runtime_error(path + ": reading band 1 failed" + gdal_message());
    }
    int has_nodata = 0;
    const double nodata = GDALGetRasterNoDataValue(band, &has_nodata);
    const auto as_float = static_cast<float>(nodata);
    for (float& v : out.values) {
        if (has_nodata && (v == as_float || (std::isnan(nodata) && std::isnan(v)))) {
            v = NAN;
        } else if (!std::isfinite(v)) {
            ++out.non_finite_cells;  // no height: no data
            v = NAN;
        }
    }
    return out;
}

bool crs_understood(const std::string& crs) noexcept
{
    try {
        register_gdal_drivers();
        const quiet_gdal quiet;
        crs_for_writing(crs);  // throws when OGR cannot read it; "" is no CRS, which can be written
        return true;
    } catch (...) {
        return false;
    }
}

#else

bool crs_understood(const std::string&) noexcept
{
    return true;
}

namespace {

[[noreturn]] void no_gdal(const std::string& path)
{
    throw std::runtime_error(path +
                             ": GeoTIFF support needs GDAL, and lidarfx_io was built without it "
                             "(install libgdal-dev and reconfigure, or write PNG / ESRI ASCII instead)");
}

}  // namespace

bool geotiff_available() noexcept
{
    return false;
}

void write_geotiff(const std::string& path, raster_view<const float>, const grid&, const std::string&)
{
    no_gdal(path);
}

geotiff_raster read_geotiff(const std::string& path)
{
    no_gdal(path);
}

grid read_geotiff_grid(const std::string& path)
{
    no_gdal(path);
}

std::string read_geotiff_crs(const std::string& path)
{
    no_gdal(path);
}

#endif

}  // namespace lidarfx::io
