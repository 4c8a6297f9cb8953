// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include <lidarfx/core/raster.hpp>
#include <lidarfx/pipelines/water/grow_waterbody.hpp>
#include <lidarfx/pipelines/water/water_surface_slope.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <thread>
#include <type_traits>
#include <vector>

using namespace lidarfx;

namespace {

/// The definition, cell by cell in double: the least-squares plane through the window's heights within band of
/// the cell's own (the same float test |z - z0| <= band), NaN as the kernel's rules say.
raster<float> slope_by_definition(const raster<float>& z, double cell_m, int k, std::size_t min_cells, float band)
{
    raster<float> out(z.rows(), z.cols(), NAN);
    for (std::ptrdiff_t r = 0; r < z.rows(); ++r) {
        for (std::ptrdiff_t c = 0; c < z.cols(); ++c) {
            const float z0 = z(r, c);
            double n = 0, sx = 0, sy = 0, sxx = 0, syy = 0, sxy = 0, sz = 0, sxz = 0, syz = 0;
            for (std::ptrdiff_t rr = std::max<std::ptrdiff_t>(0, r - k); rr <= std::min(z.rows() - 1, r + k); ++rr) {
                for (std::ptrdiff_t cc = std::max<std::ptrdiff_t>(0, c - k); cc <= std::min(z.cols() - 1, c + k);
                     ++cc) {
                    const float d = z(rr, cc) - z0;
                    if (!(std::fabs(d) <= band)) continue;
                    const double x = static_cast<double>(cc - c), y = static_cast<double>(rr - r);
                    n += 1, sx += x, sy += y, sxx += x * x, syy += y * y, sxy += x * y;
                    sz += d, sxz += d * x, syz += d * y;
                }
            }
            if (n < static_cast<double>(min_cells)) continue;
            const double cxx = sxx - sx * sx / n, cyy = syy - sy * sy / n, cxy = sxy - sx * sy / n;
            const double cxz = sxz - sx * sz / n, cyz = syz - sy * sz / n, det = cxx * cyy - cxy * cxy;
            if (!(det > 1e-6 * (cxx * cyy + 1))) continue;
            const double b = (cxz * cyy - cyz * cxy) / det, g = (cyz * cxx - cxz * cxy) / det;
            out(r, c) = static_cast<float>(std::sqrt(b * b + g * g) / cell_m);
        }
    }
    return out;
}

}  // namespace

TEST_CASE("water/water_surface_slope: the slope of a tilted plane, 0 on a level one, NaN without returns")
{
    // z = 100 + 0.01 x + 0.005 y (metres, cells of 2 m): slope sqrt(0.01² + 0.005²) m/m everywhere.
    raster<float> tilted(15, 15), level(15, 15, 100.0f);
    for (std::ptrdiff_t r = 0; r < 15; ++r)
        for (std::ptrdiff_t c = 0; c < 15; ++c)
            tilted.view()(r, c) =
                static_cast<float>(100.0 + 0.01 * 2.0 * static_cast<double>(c) + 0.005 * 2.0 * static_cast<double>(r));
    level.view()(7, 7) = NAN;
    const auto s = water_surface_slope(tilted, 2.0);
    const auto f = water_surface_slope(level, 2.0);
    for (std::ptrdiff_t r = 0; r < 15; ++r) {
        for (std::ptrdiff_t c = 0; c < 15; ++c) {
            // float heights near 100 m carry ~1e-5 m of rounding; over a 6-cell window that is < 1e-5 m/m
            CHECK(s(r, c) == doctest::Approx(std::sqrt(0.01 * 0.01 + 0.005 * 0.005)).epsilon(1e-3));
            if (r == 7 && c == 7)
                CHECK(std::isnan(f(r, c)));
            else
                CHECK(f(r, c) == 0.0f);  // every height equal: exactly level
        }
    }
    // Too few returns in the window: unknown.
    raster<float> sparse(9, 9, NAN);
    sparse.view()(4, 4) = 100.0f;
    sparse.view()(4, 5) = 100.0f;
    CHECK(std::isnan(water_surface_slope(sparse, 2.0)(4, 4)));
    CHECK_THROWS_AS(water_surface_slope(level, 0.0), invalid_input);
    CHECK_THROWS_AS(water_surface_slope(level, 2.0, {.radius_cells = 0}), invalid_input);
}

TEST_CASE("water/water_surface_slope: water next to a bank is level (the band keeps the bank out); strided views")
{
    // Water at 100 m in cols 0-9, a bank at 101.5 m from col 10: the water cell next to the bank fits the water.
    raster<float> big(14, 24, 0.0f);
    auto z = big.view().window(1, 2, 12, 20);  // row_stride 24 != cols 20
    for (std::ptrdiff_t r = 0; r < 12; ++r)
        for (std::ptrdiff_t c = 0; c < 20; ++c) z(r, c) = c < 10 ? 100.0f : 101.5f;
    raster<float> copy(12, 20);
    for (std::ptrdiff_t r = 0; r < 12; ++r)
        for (std::ptrdiff_t c = 0; c < 20; ++c) copy.view()(r, c) = z(r, c);
    const auto banded = water_surface_slope(z, 2.0);
    const auto unbanded = water_surface_slope(z, 2.0, {.band_m = 10.0});
    CHECK(banded(6, 9) == 0.0f);
    CHECK(unbanded(6, 9) > 0.1f);  // the bank's 1.5 m step tilts a plane through both
    const auto contiguous = water_surface_slope(copy, 2.0);
    for (std::ptrdiff_t r = 0; r < 12; ++r)
        for (std::ptrdiff_t c = 0; c < 20; ++c) CHECK(banded(r, c) == contiguous(r, c));
}

TEST_CASE("water/grow_waterbody level_follow_max_slope: the level follows a river, not a gentle beach")
{
    // 10 x 120, cells of 0.25 m: water at 100 m in cols 0-9 (a seed of dropouts in cols 0-3), then a beach rising
    // 0.004 m per cell (1.6 %, slower than the 5 mm level drift per cell). Without the cue the flood's level
    // climbs the whole beach; with it, the beach passes the level on unchanged and the gate stops the flood
    // 0.15 m above the water.
    const std::ptrdiff_t rows = 10, cols = 120;
    raster<float> min_z(rows, cols);
    std::vector<std::ptrdiff_t> seed;
    for (std::ptrdiff_t r = 0; r < rows; ++r) {
        for (std::ptrdiff_t c = 0; c < cols; ++c) {
            min_z.view()(r, c) = c < 10 ? 100.0f : 100.0f + 0.004f * static_cast<float>(c - 9);
            if (c <= 3) {
                min_z.view()(r, c) = NAN;
                seed.push_back(r * cols + c);
            }
        }
    }
    const auto slope = water_surface_slope(min_z, 0.25);
    water_field field{raster<float>(rows, cols, 0.0f),
                      raster<std::uint8_t>(rows, cols, 1),
                      raster<std::int32_t>(rows, cols, 0),
                      1,
                      min_z,
                      slope};
    for (std::ptrdiff_t i = 0; i < min_z.size(); ++i)
        if (std::isnan(min_z.data()[i])) field.intensity_bin.data()[i] = -1;
    grow_waterbody_workspace workspace;
    const auto climbed = grow_waterbody(field, seed, {}, workspace);
    CHECK(climbed.cells.size() == static_cast<std::size_t>(rows * cols));
    grow_waterbody_options cue;
    cue.level_follow_max_slope = 0.008;
    const auto stopped = grow_waterbody(field, seed, cue, workspace);
    // Beach cells up to 0.15 m above 100 m: cols 10-46 (0.004 · 37 = 0.148); with the water, 47 columns.
    CHECK(stopped.cells.size() == static_cast<std::size_t>(rows * 47));
}

TEST_CASE("water/water_surface_slope: equals the definition on random rasters, every radius, NaN holes, borders")
{
    // Heights within a few band widths of each other, so that the band test selects part of every window; NaN
    // holes; shapes narrower and shorter than the window; radii with the unrolled window (1-4) and without (5).
    const unsigned seed = 4242;
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> height(99.7f, 100.3f), share(0.0f, 1.0f);
    int trial = 0;
    for (const auto& item : std::vector<std::pair<std::ptrdiff_t, std::ptrdiff_t>>{
             {1, 1}, {1, 30}, {30, 1}, {5, 7}, {9, 9}, {23, 41}, {64, 37}}) {
        const auto& rows = std::get<0>(item);
        const auto& cols = std::get<1>(item);
        for (int k : {1, 2, 3, 4, 5}) {
            ++trial;
            INFO("seed " << seed << ", trial " << trial << ": " << rows << "x" << cols << ", radius " << k);
            raster<float> z(rows, cols);
            for (auto& v : z) v = share(rng) < 0.15f ? NAN : height(rng);
            const water_surface_slope_options opt{.radius_cells = k, .min_cells = 3, .band_m = 0.15};
            const auto got = water_surface_slope(z, 2.0, opt);
            const auto want = slope_by_definition(z, 2.0, k, 3, 0.15f);
            std::ptrdiff_t unequal = 0;
            for (std::ptrdiff_t i = 0; i < z.size(); ++i) {
                const float g = got.data()[i], w = want.data()[i];
                // float sums of differences up to 0.15 m over <= 121 cells: a few 1e-6 m of rounding, against
                // slopes of order 0.05 m/m; a nearly singular window may tip either way (both then NaN or not).
                if (std::isnan(g) != std::isnan(w))
                    ++unequal;
                else if (!std::isnan(w) && std::fabs(g - w) > 1e-4 * (1 + std::fabs(w)))
                    ++unequal;
            }
            CHECK(unequal == 0);
        }
    }
}

TEST_CASE("water/water_surface_slope: threads reading the lazy slope at once read the whole raster's values")
{
    // 4 threads read every cell of a 200 x 300 raster (13 x 5 tiles), each in its own random order, so tiles are
    // computed by whichever thread comes first while others wait for them or compute other tiles.
    const unsigned seed = 78;
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> height(99.7f, 100.3f), share(0.0f, 1.0f);
    raster<float> z(200, 300);
    for (auto& v : z) v = share(rng) < 0.1f ? NAN : height(rng);
    const water_surface_slope_options opt{.radius_cells = 3, .min_cells = 5, .band_m = 0.2};
    const auto whole = water_surface_slope(z, 2.0, opt);
    for (int trial = 0; trial < 3; ++trial) {
        INFO("seed " << seed << ", trial " << trial);
        lazy_water_surface_slope lazy(z, 2.0, opt);
        std::vector<std::vector<std::ptrdiff_t>> orders(4);
        for (auto& order : orders) {
            order.resize(static_cast<std::size_t>(z.rows() * z.cols()));
            for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<std::ptrdiff_t>(i);
            std::shuffle(order.begin(), order.end(), rng);
        }
        std::vector<std::ptrdiff_t> unequal(orders.size(), 0);
        std::vector<std::thread> readers;
        for (std::size_t t = 0; t < orders.size(); ++t) {
            readers.emplace_back([&, t] {
                for (const auto i : orders[t]) {
                    const float got = lazy(i / z.cols(), i % z.cols()), want = whole(i / z.cols(), i % z.cols());
                    unequal[t] += std::memcmp(&got, &want, sizeof got) != 0;
                }
            });
        }
        for (auto& r : readers) r.join();
        for (const auto u : unequal) CHECK(u == 0);
    }
}

TEST_CASE("water/water_surface_slope: the lazy slope equals the whole raster's bit for bit, read in any order")
{
    // Shapes smaller than, equal to and straddling the 16 x 64 tiles, strided views, every radius; cells read
    // in a random order, so tiles are computed in any order and some never.
    const unsigned seed = 77;
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> height(99.7f, 100.3f), share(0.0f, 1.0f);
    int trial = 0;
    for (const auto& item : std::vector<std::pair<std::ptrdiff_t, std::ptrdiff_t>>{
             {1, 1}, {3, 200}, {16, 64}, {17, 65}, {40, 130}, {70, 9}}) {
        const auto& rows = std::get<0>(item);
        const auto& cols = std::get<1>(item);
        for (int k : {1, 3, 4, 5}) {
            ++trial;
            INFO("seed " << seed << ", trial " << trial << ": " << rows << "x" << cols << ", radius " << k);
            raster<float> big(rows + 2, cols + 3);
            for (auto& v : big) v = share(rng) < 0.1f ? NAN : height(rng);
            const raster_view<const float> z = big.view().window(1, 2, rows, cols);  // row_stride cols + 3
            const water_surface_slope_options opt{.radius_cells = k, .min_cells = 5, .band_m = 0.2};
            const auto whole = water_surface_slope(z, 2.0, opt);
            lazy_water_surface_slope lazy(z, 2.0, opt);
            const surface_slope_source source(lazy);
            CHECK(source.rows() == rows);
            CHECK(source.cols() == cols);
            std::vector<std::ptrdiff_t> order(static_cast<std::size_t>(rows * cols));
            for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<std::ptrdiff_t>(i);
            std::shuffle(order.begin(), order.end(), rng);
            order.resize(order.size() / 2 + 1);  // half the cells: some tiles stay unread
            std::ptrdiff_t unequal = 0;
            for (const auto i : order) {
                const float got = source(i / cols, i % cols), want = whole(i / cols, i % cols);
                unequal += std::memcmp(&got, &want, sizeof got) != 0;
            }
            CHECK(unequal == 0);
        }
    }
    CHECK(surface_slope_source().empty());
    // From a raster, a view of it and a view of mutable cells (as raster::view() gives): the raster's cells.
    raster<float> cells(3, 4, 0.5f);
    cells(2, 3) = 0.25f;
    raster_view<float> mutable_view = cells.view();
    for (const surface_slope_source s : {surface_slope_source(cells), surface_slope_source(mutable_view),
                                         surface_slope_source(raster_view<const float>(cells))}) {
        CHECK(s.rows() == 3);
        CHECK(s.cols() == 4);
        CHECK(s(2, 3) == 0.25f);
        CHECK(s(0, 0) == 0.5f);
    }
    static_assert(!std::is_constructible_v<surface_slope_source, raster<float>&&>,
                  "a temporary raster's cells would be gone before they are read");
    CHECK_THROWS_AS(lazy_water_surface_slope(raster<float>(4, 4, 1.0f), 0.0), invalid_input);
}
