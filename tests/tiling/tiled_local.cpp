// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include <lidarfx/kernels/filter/angular_filter.hpp>
#include <lidarfx/kernels/filter/morphology.hpp>
#include <lidarfx/kernels/filter/slope_aspect.hpp>
#include <lidarfx/kernels/interpolate/idw_fill.hpp>
#include <lidarfx/kernels/solar/horizon_map.hpp>
#include <lidarfx/kernels/solar/raylines_shadow.hpp>
#include <lidarfx/pipelines/water/water_angles.hpp>
#include <lidarfx/pipelines/water/water_vegetation.hpp>
#include <lidarfx/tiling/halo.hpp>
#include <lidarfx/tiling/tiled_local.hpp>

#include "reference/angular_filter.hpp"
#include "reference/morphology.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

using namespace lidarfx;

namespace {

constexpr std::array<std::ptrdiff_t, 4> tile_sizes{1, 7, 60, 1000};

// Same bits in every cell (NaN payloads included), so "equal" means bit for bit.
template <class A, class B>
bool same_bits(const A& a, const B& b)
{
    if (a.rows() != b.rows() || a.cols() != b.cols()) return false;
    for (std::ptrdiff_t r = 0; r < a.rows(); ++r) {
        for (std::ptrdiff_t c = 0; c < a.cols(); ++c) {
            const auto x = a(r, c), y = b(r, c);
            if constexpr (std::is_same_v<std::remove_cv_t<decltype(x)>, float>) {
                if (std::bit_cast<std::uint32_t>(x) != std::bit_cast<std::uint32_t>(y)) return false;
            } else if (x != y) {
                return false;
            }
        }
    }
    return true;
}

// A 53 x 47 window (row_stride 52) of a larger random surface with NaN holes: tiles see strided views.
struct surface {
    raster<float> big;
    raster_view<const float> z;
};

surface random_surface(std::mt19937& rng, double nan_share)
{
    surface s{reference::random_raster(rng, 60, 52, 0.0, 10.0, nan_share), {}};
    s.z = raster_view<const float>(s.big.view()).window(3, 2, 53, 47);
    return s;
}

// True if tiled_local with `reach` differs from the whole-raster call for some tile size in {1, 2, 7}.
template <class Step, class Whole>
bool differs_somewhere(raster_view<const float> z, std::ptrdiff_t reach, Step step, const Whole& whole)
{
    for (const std::ptrdiff_t t : {1, 2, 7})
        if (!same_bits(tiled_local(z, reach, t, step), whole)) return true;
    return false;
}

}  // namespace

TEST_CASE("tiling/tiled_local: angular_filter with its reach equals the whole raster, one less does not")
{
    std::mt19937 rng(1501);
    for (const int radius : {1, 2, 3, 5}) {
        const surface s = random_surface(rng, 0.1);
        const angular_filter_options opt{.radius_cells = radius};
        const auto step = [&](raster_view<const float> w) { return angular_filter(w, 0.5, opt); };
        const raster<float> whole = angular_filter(s.z, 0.5, opt);
        const std::ptrdiff_t reach = angular_filter_reach(opt);
        CHECK(reach == radius);
        for (const std::ptrdiff_t t : tile_sizes) {
            CAPTURE(radius);
            CAPTURE(t);
            CHECK(same_bits(tiled_local(s.z, reach, t, step), whole));
            CHECK(same_bits(tiled_local(s.z, reach + 3, t, step, {.threads = 2}), whole));
        }
        // One cell less cuts off a neighbour that decides some cell: on sparse data far neighbours win.
        const surface sparse = random_surface(rng, 0.9);
        CHECK(differs_somewhere(sparse.z, reach - 1, step, angular_filter(sparse.z, 0.5, opt)));
    }
}

TEST_CASE("tiling/tiled_local: morphology open and close with their reach equal the whole raster")
{
    std::mt19937 rng(1502);
    for (int trial = 0; trial < 8; ++trial) {
        const reference::mask big = reference::random_mask(rng, 70, 61, trial % 2 ? 0.7 : 0.35);
        const raster_view<const std::uint8_t> m = raster_view<const std::uint8_t>(big.view()).window(5, 4, 60, 55);
        const morphology_options opt{.size_cells = 3 + 2 * (trial % 3), .height_cells = trial % 4 == 3 ? 7 : 0};
        const std::ptrdiff_t reach = morphology_reach(opt, 2);
        CHECK(reach == 2 * std::max(opt.size_cells / 2, (opt.height_cells ? opt.height_cells : opt.size_cells) / 2));
        const auto open = [&](raster_view<const std::uint8_t> w) { return morph_open(w, opt); };
        const auto close = [&](raster_view<const std::uint8_t> w) { return morph_close(w, opt); };
        const raster<std::uint8_t> opened = morph_open(m, opt), closed = morph_close(m, opt);
        for (const std::ptrdiff_t t : tile_sizes) {
            CAPTURE(trial);
            CAPTURE(t);
            CHECK(same_bits(tiled_local(m, reach, t, open), opened));
            CHECK(same_bits(tiled_local(m, reach, t, close), closed));
        }
    }
    // One cell less: some window cuts off an input that mattered (dense masks for opening, sparse for closing,
    // where squares that fit are common).
    for (const int size : {3, 5}) {
        const morphology_options opt{.size_cells = size};
        const std::ptrdiff_t reach = morphology_reach(opt, 2);
        const reference::mask dense = reference::random_mask(rng, 60, 55, 0.8),
                              sparse = reference::random_mask(rng, 60, 55, 0.2);
        const auto open = [&](raster_view<const std::uint8_t> w) { return morph_open(w, opt); };
        const auto close = [&](raster_view<const std::uint8_t> w) { return morph_close(w, opt); };
        bool open_differs = false, close_differs = false;
        for (const std::ptrdiff_t t : {1, 2, 7}) {
            open_differs = open_differs || !same_bits(tiled_local(dense, reach - 1, t, open), morph_open(dense, opt));
            close_differs =
                close_differs || !same_bits(tiled_local(sparse, reach - 1, t, close), morph_close(sparse, opt));
        }
        CAPTURE(size);
        CHECK(open_differs);
        CHECK(close_differs);
    }
}

TEST_CASE("tiling/tiled_local: slope_aspect with reach 1 equals the whole raster, reach 0 does not")
{
    std::mt19937 rng(1503);
    const surface s = random_surface(rng, 0.1);
    const slope_aspect_result whole = slope_aspect(s.z, 2.0);
    const auto slope = [](raster_view<const float> w) { return slope_aspect(w, 2.0).slope_deg; };
    const auto aspect = [](raster_view<const float> w) { return slope_aspect(w, 2.0).aspect_deg; };
    const auto flat = [](raster_view<const float> w) { return slope_aspect(w, 2.0).flat; };
    for (const std::ptrdiff_t t : tile_sizes) {
        CAPTURE(t);
        CHECK(same_bits(tiled_local(s.z, slope_aspect_reach(), t, slope), whole.slope_deg));
        CHECK(same_bits(tiled_local(s.z, slope_aspect_reach(), t, aspect), whole.aspect_deg));
        CHECK(same_bits(tiled_local(s.z, slope_aspect_reach(), t, flat), whole.flat));
    }
    CHECK(differs_somewhere(s.z, 0, slope, whole.slope_deg));
}

TEST_CASE("tiling/tiled_local: idw_fill with a search radius equals the whole raster")
{
    std::mt19937 rng(1504);
    for (const double radius_m : {1.0, 2.5, 3.0, 4.2}) {
        const surface s = random_surface(rng, 0.6);
        const idw_fill_options opt{.k = 6, .radius_m = radius_m};
        // A window without data keeps its holes, as the whole raster does where nothing is in reach.
        const auto step = [&](raster_view<const float> w) {
            for (std::ptrdiff_t r = 0; r < w.rows(); ++r)
                for (std::ptrdiff_t c = 0; c < w.cols(); ++c)
                    if (std::isfinite(w(r, c))) return idw_fill(w, 1.0, opt).filled;
            return raster<float>(w);
        };
        const raster<float> whole = idw_fill(s.z, 1.0, opt).filled;
        const std::ptrdiff_t reach = idw_fill_reach(opt, 1.0);
        CHECK(reach == static_cast<std::ptrdiff_t>(radius_m));
        for (const std::ptrdiff_t t : tile_sizes) {
            CAPTURE(radius_m);
            CAPTURE(t);
            CHECK(same_bits(tiled_local(s.z, reach, t, step), whole));
        }
        CHECK(differs_somewhere(s.z, reach - 1, step, whole));
    }
    CHECK(idw_fill_reach({.radius_m = 0.3}, 0.1) == 3);  // exactly 3 cells despite 0.3 / 0.1 < 3 in double
    CHECK_THROWS_AS(idw_fill_reach({.radius_m = 0}, 1.0), invalid_input);
}

TEST_CASE("tiling/tiled_local: horizons above the lowest sun and shadows along the grid axes")
{
    std::mt19937 rng(1505);
    const surface s = random_surface(rng, 0.05);
    const double min_elevation_deg = 35;
    double zmin = 1e300, zmax = -1e300;
    for (std::ptrdiff_t r = 0; r < s.z.rows(); ++r)
        for (std::ptrdiff_t c = 0; c < s.z.cols(); ++c)
            if (std::isfinite(s.z(r, c)))
                zmin = std::min(zmin, double(s.z(r, c))), zmax = std::max(zmax, double(s.z(r, c)));
    const std::ptrdiff_t reach = shadow_reach(zmax - zmin, min_elevation_deg, 1.0);
    CHECK(reach == static_cast<std::ptrdiff_t>(std::ceil((zmax - zmin) / std::tan(min_elevation_deg * M_PI / 180))));
    for (const double azimuth : {0.0, 90.0, 180.0, 270.0}) {
        // The horizon counts where it hides a sun at min_elevation_deg or higher; lower angles become 0.
        const auto horizon = [&](raster_view<const float> w) {
            raster<float> h = horizon_map(w, 1.0, azimuth);
            for (float& v : h) v = v >= min_elevation_deg ? v : 0.0f;
            return h;
        };
        const auto shadow = [&](raster_view<const float> w) { return raylines_shadow(w, 1.0, azimuth, 40.0); };
        const raster<float> whole_horizon = horizon(s.z);
        const raster<std::uint8_t> whole_shadow = shadow(s.z);
        for (const std::ptrdiff_t t : tile_sizes) {
            CAPTURE(azimuth);
            CAPTURE(t);
            CHECK(same_bits(tiled_local(s.z, reach, t, horizon), whole_horizon));
            CHECK(same_bits(tiled_local(s.z, reach, t, shadow), whole_shadow));
        }
    }
}

TEST_CASE("tiling/tiled_local: the step may take the window's box; refusals")
{
    std::mt19937 rng(1506);
    const surface s = random_surface(rng, 0.0);
    // A step that reads another raster through the box: the sum of two rasters, reach 0.
    const raster<float> other = reference::random_raster(rng, 53, 47);
    const auto sum = [&](raster_view<const float> w, const cell_box& box) {
        raster<float> out(w.rows(), w.cols());
        for (std::ptrdiff_t r = 0; r < w.rows(); ++r)
            for (std::ptrdiff_t c = 0; c < w.cols(); ++c) out(r, c) = w(r, c) + other(box.row_min + r, box.col_min + c);
        return out;
    };
    const raster<float> got = tiled_local(s.z, 0, 5, sum);
    bool all = true;
    for (std::ptrdiff_t r = 0; r < 53; ++r)
        for (std::ptrdiff_t c = 0; c < 47; ++c) all = all && got(r, c) == s.z(r, c) + other(r, c);
    CHECK(all);

    const auto copy = [](raster_view<const float> w) { return raster<float>(w); };
    CHECK_THROWS_AS(tiled_local(s.z, -1, 5, copy), invalid_input);
    CHECK_THROWS_AS(tiled_local(s.z, 0, 0, copy), invalid_input);
    const auto wrong = [](raster_view<const float> w) { return raster<float>(w.rows() + 1, w.cols()); };
    CHECK_THROWS_AS(tiled_local(s.z, 1, 5, wrong), invalid_input);
    CHECK(tiled_local(raster_view<const float>(nullptr, 0, 0, 0), 2, 5, copy).empty());
}

TEST_CASE("tiling/water_reach: the waterbody method's local steps, tiled with their reach, equal the whole rasters")
{
    std::mt19937 rng(1507);
    const std::ptrdiff_t rows = 57, cols = 49;
    // Random survey rasters: min z with dropouts (NaN), max z above it, multiple returns.
    raster<float> min_z = reference::random_raster(rng, rows, cols, 0.0, 3.0, 0.25), max_z(rows, cols);
    raster<std::uint8_t> dropout(rows, cols), multiple = reference::random_mask(rng, rows, cols, 0.1);
    raster<float> intensity(rows, cols, 10.0f);
    std::uniform_real_distribution<double> rise(0, 4);
    for (std::ptrdiff_t r = 0; r < rows; ++r)
        for (std::ptrdiff_t c = 0; c < cols; ++c) {
            dropout(r, c) = std::isnan(min_z(r, c));
            max_z(r, c) = min_z(r, c) + float(rise(rng));
        }
    const auto window = [&](const cell_box& b) {
        const auto w = [&](const auto& x) { return x.view().window(b.row_min, b.col_min, b.rows(), b.cols()); };
        return water_rasters{w(min_z), w(max_z), w(intensity), w(dropout), w(multiple)};
    };
    const water_rasters whole = window({0, 0, rows - 1, cols - 1});
    const extract_waterbodies_options opt{
        .vegetation = {.closing_size_cells = 5}, .angles = {.radius_cells = 2}, .seeds = {.opening_size_cells = 3}};
    const water_step_reach reach = water_reach(opt);
    CHECK(reach.vegetation_closing == 4);
    CHECK(reach.angles == 2);
    CHECK(reach.seed_opening == 2);
    CHECK(reach.largest() == 4);
    const auto vegetation = [&](raster_view<const float>, const cell_box& b) {
        return water_vegetation(window(b), {.closing_size_cells = opt.vegetation.closing_size_cells});
    };
    const auto angles = [&](raster_view<const float>, const cell_box& b) {
        return water_angles(window(b), 2.0, {.radius_cells = opt.angles.radius_cells});
    };
    const raster<std::uint8_t> whole_vegetation = water_vegetation(whole, {.closing_size_cells = 5});
    const raster<float> whole_angles = water_angles(whole, 2.0, {.radius_cells = 2});
    const raster_view<const float> z = min_z.view();
    for (const std::ptrdiff_t t : tile_sizes) {
        CAPTURE(t);
        CHECK(same_bits(tiled_local(z, reach.vegetation_closing, t, vegetation), whole_vegetation));
        CHECK(same_bits(tiled_local(z, reach.angles, t, angles), whole_angles));
    }
    CHECK_THROWS_AS(water_reach({.angles = {.input = angular_input::idw_filled}}), invalid_input);
}
