// SPDX-License-Identifier: Apache-2.0
// libFuzzer target for the LAS and LAZ reader: any bytes must give valid points or a std::runtime_error,
// never a crash, a sanitizer report or an allocation beyond a bounded multiple of the input's size (LAZ:
// only as the points are decoded); LAZ reads on 1 and 2 threads must decode the same records; accepted files must
// survive a round trip through the writer. The header bounds of every file whose header parses are also driven through
// snapped_grid and raster_accumulator at a few cell sizes, with the points read: invalid_input is an
// accepted outcome there, anything else (a crash, a sanitizer report, another exception, a point inside
// the bounds that misses the grid) is a bug. Built and run by scripts/fuzz.sh.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <span>
#include <stdexcept>

#include <lidarfx/core/error.hpp>
#include <lidarfx/core/grid.hpp>
#include <lidarfx/kernels/points/rasterize.hpp>

#include "io/las.hpp"
#include "io/las_writer.hpp"

namespace {

using lidarfx::io::las_points;

bool identical(const las_points& a, const las_points& b)
{
    return a.x == b.x && a.y == b.y && a.z == b.z && a.intensity == b.intensity && a.return_number == b.return_number &&
           a.number_of_returns == b.number_of_returns && a.classification == b.classification &&
           a.classification_flags == b.classification_flags && a.scan_angle_deg == b.scan_angle_deg &&
           a.gps_time.size() == b.gps_time.size();
}

/// True when integer * scale + offset round-trips through the writer's quantization exactly: scales of a
/// normal size and offsets small against 2^52 quanta (else the double sum loses the integer).
bool exact_lattice(const lidarfx::io::las_header& h)
{
    for (std::size_t k = 0; k < 3; ++k) {
        const double s = h.scale[k], o = h.offset[k];
        if (!(s > 1e-200 && s < 1e200) || !(std::abs(o) / s < 0x1p45)) return false;
    }
    return true;
}

template <class T>
bool same_bits(const lidarfx::raster<T>& a, const lidarfx::raster<T>& b)
{
    return a.rows() == b.rows() && a.cols() == b.cols() &&
           (a.size() == 0 || std::memcmp(a.data(), b.data(), sizeof(T) * static_cast<std::size_t>(a.size())) == 0);
}

/// The header's x/y bounds through snapped_grid (cells of 1, 0.59 and 0.32 units and 1/7 and 1/300 of the
/// larger span) and the points through raster_accumulator on each grid of at most 2^22 cells.
void rasterize_on_header_bounds(const lidarfx::io::las_header& h, const las_points& points)
{
    constexpr std::ptrdiff_t cell_cap = std::ptrdiff_t{1} << 22, finish_cap = std::ptrdiff_t{1} << 16;
    const lidarfx::bounds b{h.min[0], h.min[1], h.max[0], h.max[1]};
    const double span = std::max(b.xmax - b.xmin, b.ymax - b.ymin);  // may be NaN, infinite or negative
    const auto cloud = points.cloud();
    const std::size_t n = cloud.size();
    for (const double cell_m : {1.0, 0.59, 0.32, span / 7, span / 300}) {
        lidarfx::grid g;
        try {
            g = lidarfx::snapped_grid(b, cell_m);
        } catch (const lidarfx::invalid_input&) {
            continue;  // bounds or cell it cannot represent: refused with a message, as documented
        }
        g.validate("fuzz");  // what snapped_grid returns is valid: an exception here escapes as a bug
        if (g.size() > cell_cap) continue;
        lidarfx::raster_accumulator acc(g);
        acc.add(cloud);
        if (acc.points_used() + acc.points_outside() + acc.points_nan() != n) std::abort();
        // The one rounding rule: every finite point inside the closed header bounds lands in the grid.
        std::size_t inside = 0;
        for (std::size_t i = 0; i < n; ++i) {
            const double x = cloud.x(i), y = cloud.y(i), z = cloud.z(i);
            if (std::isfinite(z) && x >= b.xmin && x <= b.xmax && y >= b.ymin && y <= b.ymax) {
                ++inside;
                if (!g.cell_of(x, y)) std::abort();
            }
        }
        if (acc.points_used() < inside) std::abort();
        if (g.size() > finish_cap) continue;
        // Any split of the points, merged, gives the same bits; the counts add up to the points used.
        lidarfx::raster_accumulator first(g), second(g);
        first.add(cloud, 0, n / 3);
        second.add(cloud, n / 3, n);
        second.merge(first);
        const auto want = acc.finish(), got = second.finish();
        if (!same_bits(want.min_z, got.min_z) || !same_bits(want.max_z, got.max_z) ||
            !same_bits(want.mean_intensity, got.mean_intensity) || !same_bits(want.count, got.count) ||
            !same_bits(want.dropout, got.dropout) || !same_bits(want.multiple_returns, got.multiple_returns) ||
            got.points_used != want.points_used) {
            std::abort();
        }
        std::uint64_t counted = 0;
        for (const std::uint32_t c : want.count) counted += c;
        if (counted != want.points_used) std::abort();
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    las_points all;
    lidarfx::io::las_header header;
    bool have_header = false;
    try {
        lidarfx::io::las_reader r(std::span<const std::uint8_t>(data, size), "fuzz");
        r.set_memory_budget(std::uint64_t{256} << 20);  // a LAZ chunk over 128 MiB is refused (invalid_input)
        header = r.header();
        have_header = true;
        if (header.compressed) {
            // Chunk-parallel decoding gives the same bytes as sequential decoding (or the same error).
            std::vector<std::uint8_t> one, two;
            std::string error_one, error_two;
            try {
                r.read_records(one, static_cast<std::size_t>(r.point_count()));
            } catch (const std::runtime_error& e) {
                error_one = e.what();
            } catch (const lidarfx::invalid_input& e) {  // a LAZ chunk over the memory budget
                error_one = e.what();
            }
            r.seek(0);
            r.set_threads(2);
            try {
                r.read_records(two, static_cast<std::size_t>(r.point_count()));
            } catch (const std::runtime_error& e) {
                error_two = e.what();
            } catch (const lidarfx::invalid_input& e) {  // a LAZ chunk over the memory budget
                error_two = e.what();
            }
            if (error_one != error_two || (error_one.empty() && one != two)) std::abort();
            r.seek(0);
            r.set_threads(1);
        }
        las_points chunk;
        std::uint64_t total = 0;
        const std::size_t step = 1 + size % 13;  // odd chunk sizes
        while (const std::size_t k = r.read(chunk, step)) total += k;
        if (total != r.point_count()) std::abort();
        all = r.read_all();
        if (all.size() != total || r.position() != total) std::abort();
        if (!header.compressed && total * header.point_record_length + header.offset_to_point_data > size) std::abort();
        (void)all.cloud();
    } catch (const std::runtime_error&) {
        if (have_header) rasterize_on_header_bounds(header, las_points{});  // the bounds alone
        return 0;
    } catch (const lidarfx::invalid_input&) {  // a LAZ chunk over the memory budget, refused before decoding
        if (have_header) rasterize_on_header_bounds(header, las_points{});
        return 0;
    }
    rasterize_on_header_bounds(header, all);

    // Round trip: what the reader accepted, the writer writes back to the same points (when it can hold them).
    if (!exact_lattice(header)) return 0;
    std::vector<std::uint8_t> bytes;
    try {
        bytes = lidarfx::io::encode_las(
            all,
            {.version_minor = 4, .point_format = header.point_format, .scale = header.scale, .offset = header.offset});
    } catch (const lidarfx::invalid_input&) {
        return 0;  // e.g. a legacy scan angle outside [-90, 90], which the reader reports as stored
    }
    lidarfx::io::las_reader again(bytes, "fuzz round trip");
    if (!identical(again.read_all(), all)) std::abort();
    return 0;
}
