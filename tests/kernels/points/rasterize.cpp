// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include <lidarfx/kernels/points/rasterize.hpp>

#include "reference/progress.hpp"
#include "reference/rasterize.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <random>
#include <set>
#include <span>
#include <vector>

using namespace lidarfx;

namespace {

/// A cloud as plain columns (what a LAS reader hands over), viewable as soa_cloud.
struct columns {
    std::vector<double> x, y, z;
    std::vector<std::uint16_t> intensity;
    std::vector<std::uint8_t> number_of_returns;

    soa_cloud<> soa() const { return soa_cloud<>(x, y, z, intensity, {}, number_of_returns); }
    std::size_t size() const { return x.size(); }
    void push(double xi, double yi, double zi, std::uint16_t i, std::uint8_t n)
    {
        x.push_back(xi);
        y.push_back(yi);
        z.push_back(zi);
        intensity.push_back(i);
        number_of_returns.push_back(n);
    }
};

/// Random points for grid g: inside, exactly on lattice lines, on the far east/south border, outside, and
/// with NaN/infinite coordinates.
columns random_cloud(std::mt19937& rng, const grid& g, std::size_t n)
{
    columns out;
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::uniform_int_distribution<int> intensity(0, 65535), kind(0, 19), returns(1, 3);
    const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
    const double w = static_cast<double>(g.cols) * g.cell, h = static_cast<double>(g.rows) * g.cell;
    for (std::size_t i = 0; i < n; ++i) {
        double x = g.x0 + u(rng) * w, y = g.y0 - u(rng) * h, z = 100.0 + 50.0 * u(rng);
        switch (kind(rng)) {
            case 0:  // on a lattice line (cell edges, the west/north edges and the east/south border included)
                x = g.x0 + static_cast<double>(std::uniform_int_distribution<std::ptrdiff_t>(0, g.cols)(rng)) * g.cell;
                break;
            case 1:
                y = g.y0 - static_cast<double>(std::uniform_int_distribution<std::ptrdiff_t>(0, g.rows)(rng)) * g.cell;
                break;
            case 2:
                x = g.x1();
                y = g.y1();
                break;  // far south-east corner
            case 3:
                x = g.x0 - g.cell * u(rng) - 1e-9;
                break;  // west of the grid
            case 4:
                y = g.y1() - g.cell * u(rng) - 1e-9;
                break;  // south of the grid
            case 5:
                x = g.x1() + 1e-7;
                break;
            case 6:
                x = nan;
                break;
            case 7:
                z = (i % 2) ? nan : -inf;
                break;
            case 8:
                y = inf;
                break;
            case 9:
                z = std::round(z);
                break;  // ties between points of one cell
            default:
                break;
        }
        out.push(x, y, z, static_cast<std::uint16_t>(intensity(rng)),
                 static_cast<std::uint8_t>(returns(rng) == 3 ? 2 : 1));
    }
    return out;
}

std::vector<grid> test_grids()
{
    return {
        grid{0.0, 0.0, 1.0, 1, 1},        grid{512345.25, 4100000.5, 2.0, 1, 17}, grid{-3.5, 7.0, 0.5, 19, 1},
        grid{1000.0, 2000.0, 0.3, 7, 13}, grid{300000.0, 5000000.0, 2.0, 37, 23}, grid{-12.25, -40.75, 0.25, 257, 131}};
}

/// A point type a host might have, read through its own methods (no lidarfx adaptor).
struct host_cloud {
    struct point {
        float x, y, z;
        float intensity;
        int returns;
    };
    std::vector<point> points;
    std::size_t size() const { return points.size(); }
    double x(std::size_t i) const { return points[i].x; }
    double y(std::size_t i) const { return points[i].y; }
    double z(std::size_t i) const { return points[i].z; }
    double intensity(std::size_t i) const { return points[i].intensity; }
    int number_of_returns(std::size_t i) const { return points[i].returns; }
};

}  // namespace

TEST_CASE("raster/rasterize: a hand-checked 2x3 grid")
{
    // Cells are 10 m; the grid spans x 100..130 and y 200..180.
    const grid g{100.0, 200.0, 10.0, 2, 3};
    columns pts;
    pts.push(101, 199, 5.0, 10, 1);  // (0, 0)
    pts.push(109, 191, 7.0, 21, 2);  // (0, 0), multiple returns
    pts.push(110, 200, 1.5, 7, 1);   // west edge of (0, 1), on the north edge
    pts.push(130, 180, 9.0, 4, 1);   // far south-east corner -> (1, 2)
    pts.push(125, 190, 3.0, 8, 1);   // on the row edge -> (1, 2)
    pts.push(131, 185, 0.0, 0, 1);   // outside (east)
    pts.push(std::nan(""), 185, 0.0, 0, 1);
    const auto out = rasterize(pts.soa(), g);
    CHECK(out.points_used == 5);
    CHECK(out.points_outside == 1);
    CHECK(out.points_nan == 1);
    CHECK(out.count(0, 0) == 2);
    CHECK(out.min_z(0, 0) == 5.0f);
    CHECK(out.max_z(0, 0) == 7.0f);
    CHECK(out.mean_intensity(0, 0) == 15.5f);
    CHECK(out.multiple_returns(0, 0) == 1);
    CHECK(out.count(0, 1) == 1);
    CHECK(out.min_z(0, 1) == 1.5f);
    CHECK(out.count(1, 2) == 2);
    CHECK(out.min_z(1, 2) == 3.0f);
    CHECK(out.max_z(1, 2) == 9.0f);
    CHECK(out.mean_intensity(1, 2) == 6.0f);
    CHECK(out.multiple_returns(1, 2) == 0);
    for (auto [r, c] : {std::pair{0, 2}, {1, 0}, {1, 1}}) {
        CHECK(out.dropout(r, c) == 1);
        CHECK(out.count(r, c) == 0);
        CHECK(std::isnan(out.min_z(r, c)));
        CHECK(std::isnan(out.max_z(r, c)));
        CHECK(out.mean_intensity(r, c) == 0.0f);
    }
    CHECK(out.dropout(0, 0) == 0);
    CHECK(out.dropout(1, 2) == 0);
}

TEST_CASE("raster/rasterize: equals the per-point reference on random clouds with edge, outside and NaN points")
{
    const unsigned seed = 20240611;
    std::mt19937 rng(seed);
    for (const grid& g : test_grids()) {
        for (std::size_t n : {0u, 1u, 50u, 3000u}) {
            CAPTURE(seed);
            CAPTURE(g.rows);
            CAPTURE(g.cols);
            CAPTURE(n);
            const auto pts = random_cloud(rng, g, n);
            const auto expected = reference::rasterize(pts.soa(), g);
            CHECK(reference::same_bits(rasterize(pts.soa(), g), expected));
            CHECK(expected.points_used + expected.points_outside + expected.points_nan == n);
        }
    }
}

TEST_CASE("raster/rasterize: any chunking, merge order or thread count gives bit-identical rasters")
{
    const unsigned seed = 77;
    std::mt19937 rng(seed);
    const grid g{2000.0, 3000.0, 0.7, 23, 31};
    const auto pts = random_cloud(rng, g, 20000);
    const auto cloud = pts.soa();
    const auto expected = rasterize(cloud, g);
    REQUIRE(reference::same_bits(expected, reference::rasterize(cloud, g)));

    for (int threads : {1, 2, 3}) {
        for (std::size_t chunk : {std::size_t{1}, std::size_t{7}, std::size_t{1000}, std::size_t{1} << 20}) {
            CAPTURE(threads);
            CAPTURE(chunk);
            const rasterize_options opt{.chunk_points = chunk, .run = {.threads = threads}};
            CHECK(reference::same_bits(rasterize(cloud, g, opt), expected));
        }
    }

    // Random pieces added to random accumulators in random order, merged in random order.
    for (int trial = 0; trial < 10; ++trial) {
        CAPTURE(trial);
        std::vector<std::size_t> cuts{0, pts.size()};
        for (int k = 0; k < 1 + trial * 3; ++k)
            cuts.push_back(std::uniform_int_distribution<std::size_t>(0, pts.size())(rng));
        std::sort(cuts.begin(), cuts.end());
        std::vector<std::size_t> pieces(cuts.size() - 1);
        std::iota(pieces.begin(), pieces.end(), std::size_t{0});
        std::shuffle(pieces.begin(), pieces.end(), rng);
        std::vector<raster_accumulator> parts(1 + trial % 4, raster_accumulator(g));
        for (std::size_t p : pieces) parts[p % parts.size()].add(cloud, cuts[p], cuts[p + 1]);
        std::shuffle(parts.begin(), parts.end(), rng);
        for (std::size_t k = 1; k < parts.size(); ++k) parts[0].merge(parts[k]);
        CHECK(parts[0].points_used() == expected.points_used);
        CHECK(reference::same_bits(parts[0].finish(), expected));
    }
}

TEST_CASE("raster/rasterize: soa_cloud, aos_cloud and a host type give the same rasters")
{
    std::mt19937 rng(5);
    const grid g{10.0, 20.0, 1.0, 9, 11};
    auto pts = random_cloud(rng, g, 2000);
    // Floats in the host type: keep coordinates representable so all three clouds hold the same points.
    host_cloud host;
    for (std::size_t i = 0; i < pts.size(); ++i) {
        pts.x[i] = static_cast<float>(pts.x[i]);
        pts.y[i] = static_cast<float>(pts.y[i]);
        pts.z[i] = static_cast<float>(pts.z[i]);
        host.points.push_back({static_cast<float>(pts.x[i]), static_cast<float>(pts.y[i]), static_cast<float>(pts.z[i]),
                               static_cast<float>(pts.intensity[i]), pts.number_of_returns[i]});
    }
    struct las_point {
        double x, y, z;
        std::uint16_t intensity;
        std::uint8_t returns;
    };
    std::vector<las_point> aos;
    for (std::size_t i = 0; i < pts.size(); ++i)
        aos.push_back({pts.x[i], pts.y[i], pts.z[i], pts.intensity[i], pts.number_of_returns[i]});
    const aos_cloud aos_view(std::span<const las_point>(aos), &las_point::x, &las_point::y, &las_point::z,
                             &las_point::intensity, no_attribute{}, &las_point::returns);

    const auto expected = reference::rasterize(pts.soa(), g);
    CHECK(reference::same_bits(rasterize(pts.soa(), g), expected));
    CHECK(reference::same_bits(rasterize(aos_view, g), expected));
    CHECK(reference::same_bits(rasterize(host, g, {.chunk_points = 300, .run = {.threads = 2}}), expected));
}

TEST_CASE("raster/rasterize: clouds without intensity or returns read 0 and single returns")
{
    const grid g{0.0, 4.0, 2.0, 2, 2};
    const std::vector<double> x{1, 3, 3}, y{3, 1, 1.5}, z{1, 2, 3};
    const auto out = rasterize(soa_cloud<>(x, y, z), g);
    CHECK(out.count(0, 0) == 1);
    CHECK(out.count(1, 1) == 2);
    CHECK(out.mean_intensity(1, 1) == 0.0f);
    CHECK(out.multiple_returns(1, 1) == 0);
    CHECK(out.dropout(0, 1) == 1);
}

TEST_CASE("raster/rasterize: an empty cloud rasterizes to all dropout")
{
    const grid g{0.0, 0.0, 1.0, 3, 4};
    const std::vector<double> none;
    const auto out = rasterize(soa_cloud<>(none, none, none), g, {.run = {.threads = 3}});
    CHECK(out.points_used + out.points_outside + out.points_nan == 0);
    for (std::ptrdiff_t r = 0; r < g.rows; ++r) {
        for (std::ptrdiff_t c = 0; c < g.cols; ++c) {
            CHECK(out.dropout(r, c) == 1);
            CHECK(out.count(r, c) == 0);
            CHECK(std::isnan(out.min_z(r, c)));
            CHECK(std::isnan(out.max_z(r, c)));
            CHECK(out.mean_intensity(r, c) == 0.0f);
            CHECK(out.multiple_returns(r, c) == 0);
        }
    }
    const auto zero = rasterize(soa_cloud<>(none, none, none), grid{0.0, 0.0, 1.0, 0, 0});
    CHECK(zero.count.size() == 0);
}

TEST_CASE("raster/rasterize: non-integer intensities are summed in steps of 2^-16")
{
    const grid g{0.0, 1.0, 1.0, 1, 1};
    host_cloud host;
    // 0.5 and 0.25 are multiples of 2^-16: exact. 2^-18 rounds to 0 and 3*2^-18 to 2^-16 (half away from zero).
    host.points = {{0.5f, 0.5f, 1.0f, 0.5f, 1}, {0.5f, 0.5f, 1.0f, 0.25f, 1}};
    CHECK(rasterize(host, g).mean_intensity(0, 0) == 0.375f);
    host.points = {{0.5f, 0.5f, 1.0f, std::ldexp(1.0f, -18), 1}, {0.5f, 0.5f, 1.0f, std::ldexp(3.0f, -18), 1}};
    CHECK(rasterize(host, g).mean_intensity(0, 0) == std::ldexp(1.0f, -17));
    host.points = {{0.5f, 0.5f, 1.0f, -3.0f, 1}, {0.5f, 0.5f, 1.0f, 1.0f, 1}};
    CHECK(rasterize(host, g).mean_intensity(0, 0) == -1.0f);
    // NaN intensities count as 0, huge ones clamp to 2^24.
    host.points = {{0.5f, 0.5f, 1.0f, std::nanf(""), 1}, {0.5f, 0.5f, 1.0f, 4.0f, 1}, {0.5f, 0.5f, 1.0f, 1e30f, 1}};
    CHECK(rasterize(host, g).mean_intensity(0, 0) == static_cast<float>((4.0 + 16777216.0) / 3.0));
}

TEST_CASE("raster/rasterize: z beyond the float range saturates")
{
    const grid g{0.0, 1.0, 1.0, 1, 1};
    const std::vector<double> x{0.5, 0.5, 0.5}, y{0.5, 0.5, 0.5}, z{1e300, -1e300, 3.0};
    const auto out = rasterize(soa_cloud<>(x, y, z), g);
    CHECK(out.max_z(0, 0) == std::numeric_limits<float>::max());
    CHECK(out.min_z(0, 0) == -std::numeric_limits<float>::max());
    CHECK(out.points_used == 3);
}

TEST_CASE("raster/rasterize: zeros of both signs in one cell give +0 whatever their order, chunking or threads")
{
    const grid g{0.0, 1.0, 1.0, 1, 2};
    const std::vector<double> x{0.5, 0.5, 0.5, 1.5}, y{0.5, 0.5, 0.5, 0.5};
    // Tiny z round to a float zero of their sign (the LAS fuzzer found -1e-236 and +1e-239 in one cell).
    for (const std::vector<double>& z :
         {std::vector<double>{-0.0, 0.0, 1.0, -0.0}, std::vector<double>{0.0, -0.0, 1.0, -0.0},
          std::vector<double>{-1e-236, 1e-239, 1.0, -1e-300}, std::vector<double>{1e-239, -1e-236, 1.0, -1e-300}}) {
        for (std::size_t chunk : {std::size_t{1}, std::size_t{2}, std::size_t{4}}) {
            for (int threads : {1, 2}) {
                const auto out =
                    rasterize(soa_cloud<>(x, y, z), g, {.chunk_points = chunk, .run = {.threads = threads}});
                CHECK_FALSE(std::signbit(out.min_z(0, 0)));
                CHECK(out.min_z(0, 0) == 0.0f);
                CHECK(out.max_z(0, 0) == 1.0f);
                CHECK_FALSE(std::signbit(out.min_z(0, 1)));  // a lone -0 is stored as +0 too
                CHECK_FALSE(std::signbit(out.max_z(0, 1)));
            }
        }
    }
}

TEST_CASE("raster/rasterize: progress is monotone and ends at 1; returning false cancels")
{
    std::mt19937 rng(9);
    const grid g{0.0, 0.0, 1.0, 8, 8};
    const auto pts = random_cloud(rng, g, 1000);
    const auto want = rasterize(pts.soa(), g);
    for (int threads : {1, 2}) {
        CAPTURE(threads);
        const reference::progress_log log;
        const rasterize_options opt{.chunk_points = 100, .run = {.threads = threads, .progress = log.callback()}};
        const auto got = rasterize(pts.soa(), g, opt);
        CHECK(reference::same_bits(got, want));
        CHECK(log.monotone_to_one(threads == 1 ? 10 : 1));  // one report per chunk of 100 points
        const rasterize_options stop{.chunk_points = 100,
                                     .run = {.threads = threads, .progress = reference::cancel_at_once()}};
        CHECK_THROWS_WITH_AS(rasterize(pts.soa(), g, stop), "rasterize: cancelled", cancelled);
    }
    const std::vector<double> none;  // no point: done at once
    const reference::progress_log empty;
    rasterize(soa_cloud<>(none, none, none), g, {.run = {.progress = empty.callback()}});
    CHECK(empty.monotone_to_one());
}

TEST_CASE("raster/rasterize: bad arguments throw invalid_input")
{
    const std::vector<double> v{1.0};
    const soa_cloud<> cloud(v, v, v);
    CHECK_THROWS_WITH_AS(rasterize(cloud, grid{0, 0, 0.0, 1, 1}), "rasterize: grid.cell must be finite and > 0 (got 0)",
                         invalid_input);
    CHECK_THROWS_WITH_AS(rasterize(cloud, grid{0, 0, 1.0, -1, 1}), "rasterize: grid.rows must be >= 0 (got -1)",
                         invalid_input);
    CHECK_THROWS_WITH_AS(rasterize(cloud, grid{0, 0, 1.0, 1, 1}, {.chunk_points = 0}),
                         "rasterize: chunk_points must be >= 1 (got 0)", invalid_input);
    CHECK_THROWS_WITH_AS(rasterize(cloud, grid{0, 0, 1.0, 1, 1}, {.run = {.threads = -1}}),
                         "rasterize: run.threads must be >= 0 (got -1)", invalid_input);

    raster_accumulator a(grid{0, 0, 1.0, 2, 2});
    CHECK_THROWS_WITH_AS(a.merge(raster_accumulator(grid{0, 0, 1.0, 2, 3})),
                         "raster_accumulator::merge: other accumulator must be on the same grid", invalid_input);
    CHECK_THROWS_WITH_AS(a.add(cloud, 0, 2),
                         "raster_accumulator::add: range [first, last) must lie in [0, 1] (got [0, 2))", invalid_input);
    CHECK_THROWS_AS(raster_accumulator(grid{0, 0, -1.0, 2, 2}), invalid_input);
}

TEST_CASE("raster/raster_accumulator: grids whose size would overflow are refused, naming the sizes")
{
    const std::ptrdiff_t big = std::ptrdiff_t{1} << 32;
    CHECK_THROWS_WITH_AS(
        raster_accumulator(grid{0, 0, 1.0, big, big}),
        "raster_accumulator: grid.rows x grid.cols must be <= 2^40 cells (got 4294967296 x 4294967296)", invalid_input);
    const std::vector<double> v{1.0};
    CHECK_THROWS_WITH_AS(rasterize(soa_cloud<>(v, v, v), grid{0, 0, 1.0, big, big}),
                         "rasterize: grid.rows x grid.cols must be <= 2^40 cells (got 4294967296 x 4294967296)",
                         invalid_input);
    // Header bounds near 2^48 (a crafted LAS file) never reach the accumulator: snapped_grid refuses them.
    const double far = std::ldexp(1.0, 48);
    CHECK_THROWS_AS(raster_accumulator(snapped_grid({far - 1e9, far - 1e9, far, far}, 1.0)), invalid_input);
    // A large grid costs nothing until a point arrives but its tile directory (8 bytes per 1024 cells:
    // 8 MiB for these 2^30 cells).
    raster_accumulator huge(grid{0, 0, 1.0, std::ptrdiff_t{1} << 15, std::ptrdiff_t{1} << 15});
    CHECK(huge.allocated_cells() == 0);
    const std::vector<double> x{5.5, 30000.5}, y{-5.5, -20000.5}, z{1.0, 2.0};
    huge.add(soa_cloud<>(x, y, z));
    CHECK(huge.points_used() == 2);
    CHECK(huge.allocated_cells() == 2 * 1024);
}

TEST_CASE("raster/raster_accumulator: tiny and thin grids (1 cell, none, one row, one column)")
{
    std::mt19937 rng(13);
    for (const grid& g : {grid{0, 0, 1.0, 0, 0}, grid{0, 0, 1.0, 0, 5}, grid{0, 0, 1.0, 5, 0}, grid{3, 4, 0.5, 1, 1},
                          grid{0, 0, 1.0, 1, 5000}, grid{0, 0, 1.0, 5000, 1}, grid{0, 0, 1.0, 3, 70}}) {
        CAPTURE(g.rows);
        CAPTURE(g.cols);
        const auto pts = random_cloud(rng, g, 300);
        const auto expected = reference::rasterize(pts.soa(), g);
        raster_accumulator a(g);
        a.add(pts.soa(), 0, 100);
        raster_accumulator b(g);
        b.add(pts.soa(), 100, 300);
        a.merge(b);
        CHECK(reference::same_bits(a.finish(), expected));
        CHECK(reference::same_bits(rasterize(pts.soa(), g, {.chunk_points = 37, .run = {.threads = 2}}), expected));
        CHECK(a.finish().count.size() == g.size());
    }
}

TEST_CASE("raster/raster_accumulator: points scattered at random turn it dense early, local points keep tiles")
{
    // 2.5 km x 2.5 km at 1 m: 6241 tiles. 6000 points at random hold about 3000 tiles after their first 4096,
    // about one point each: such points would soon hold every tile one point at a time, so the accumulator is dense. As
    // many points per tile, eight each, over a quarter of the tiles (a flight line's order) stay in tiles.
    const grid g{500000.0, 4200000.0, 1.0, 2500, 2500};
    std::mt19937 rng(22);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    columns scattered, local;
    for (int i = 0; i < 6000; ++i) scattered.push(g.x0 + u(rng) * 2500, g.y0 - u(rng) * 2500, 100 * u(rng), 7, 1);
    for (int t = 0; t < 1600; ++t)  // tiles of 32 x 32 cells in the grid's west quarter, 8 points each
        for (int k = 0; k < 8; ++k)
            local.push(g.x0 + (t % 20) * 32 + u(rng) * 32, g.y0 - (t / 20) * 31.0 - u(rng) * 31, 100 * u(rng), 7, 1);
    raster_accumulator a(g), b(g);
    a.add(scattered.soa());
    b.add(local.soa());
    CHECK(a.allocated_cells() == static_cast<std::size_t>(g.size()));
    CHECK(b.allocated_cells() < static_cast<std::size_t>(g.size()) / 2);
    CHECK(reference::same_bits(a.finish(), reference::rasterize(scattered.soa(), g)));
    CHECK(reference::same_bits(b.finish(), reference::rasterize(local.soa(), g)));
}

TEST_CASE("raster/raster_accumulator: memory follows the occupied cells of a sparse survey")
{
    // 300 points over 2.5 km x 2.5 km at 1 m: 6.25 M cells in 6241 tiles, of which at most 300 are held.
    const grid g{500000.0, 4200000.0, 1.0, 2500, 2500};
    std::mt19937 rng(21);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    columns pts;
    for (int i = 0; i < 300; ++i) pts.push(g.x0 + u(rng) * 2500, g.y0 - u(rng) * 2500, 100 * u(rng), 7, 1);
    raster_accumulator acc(g);
    acc.add(pts.soa());
    CHECK(acc.allocated_cells() <= 300 * 1024);  // stayed sparse: 7 MB of statistics, not 150 MB
    const auto out = acc.finish();
    CHECK(out.points_used == 300);
    std::uint64_t counted = 0, wet = 0;
    for (std::ptrdiff_t i = 0; i < out.count.size(); ++i) {
        counted += out.count.data()[i];
        wet += out.dropout.data()[i] == 0;
    }
    CHECK(counted == 300);
    std::set<std::ptrdiff_t> occupied;
    for (std::size_t i = 0; i < pts.size(); ++i) {
        const auto at = g.cell_of(pts.x[i], pts.y[i]);
        REQUIRE(at);
        occupied.insert(at->row * g.cols + at->col);
        CHECK(out.count(at->row, at->col) >= 1);
        CHECK(out.min_z(at->row, at->col) <= static_cast<float>(pts.z[i]));
        CHECK(out.mean_intensity(at->row, at->col) == 7.0f);
    }
    CHECK(wet == occupied.size());  // every other cell is written as an empty (dropout) cell
    // The same through rasterize, on one and two threads, and through a copy.
    CHECK(reference::same_bits(rasterize(pts.soa(), g), out));
    CHECK(reference::same_bits(rasterize(pts.soa(), g, {.chunk_points = 300, .run = {.threads = 2}}), out));
    const raster_accumulator copy = acc;
    CHECK(copy.allocated_cells() == acc.allocated_cells());
    CHECK(reference::same_bits(copy.finish(), out));
}

TEST_CASE("raster/raster_accumulator: sparse and dense accumulators merge to the same bits in any mix")
{
    // 300 x 500 cells = 160 tiles. Pieces of a few points stay sparse; a piece with more points than cells
    // turns dense. Every mix of merges must give the reference's bits.
    const unsigned seed = 4242;
    std::mt19937 rng(seed);
    const grid g{1000.0, 5000.0, 0.5, 300, 500};
    const auto pts = random_cloud(rng, g, 200000);
    const auto cloud = pts.soa();
    const auto expected = reference::rasterize(cloud, g);
    for (int trial = 0; trial < 6; ++trial) {
        CAPTURE(seed);
        CAPTURE(trial);
        // Cuts: a few tiny pieces (sparse), the rest in one or two big ones (dense).
        std::vector<std::size_t> cuts{0, 7, 40, 41, 300, 2000, pts.size()};
        if (trial % 2) cuts.push_back(151000 + static_cast<std::size_t>(trial) * 1000);
        std::sort(cuts.begin(), cuts.end());
        std::vector<raster_accumulator> parts;
        for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
            parts.emplace_back(g);
            parts.back().add(cloud, cuts[k], cuts[k + 1]);
        }
        // A dense accumulator holds exactly the grid's cells; tiles come in multiples of 1024.
        const auto is_dense = [&](const raster_accumulator& p) {
            return p.allocated_cells() == static_cast<std::size_t>(g.size());
        };
        std::size_t dense = 0, sparse = 0;
        for (const auto& p : parts) (is_dense(p) ? dense : sparse) += 1;
        CHECK(dense >= 1);
        CHECK(sparse >= 3);
        std::shuffle(parts.begin(), parts.end(), rng);
        raster_accumulator all = parts[0];
        for (std::size_t k = 1; k < parts.size(); ++k) all.merge(parts[k]);
        CHECK(reference::same_bits(all.finish(), expected));
        // Sparse into sparse only (the tiny pieces), then into the dense rest.
        raster_accumulator small(g);
        for (const auto& p : parts) {
            if (!is_dense(p)) small.merge(p);
        }
        for (const auto& p : parts) {
            if (is_dense(p)) small.merge(p);
        }
        CHECK(reference::same_bits(small.finish(), expected));
    }
    // rasterize: fewer points than cells starts sparse (workers may turn dense), more starts dense.
    for (std::size_t n : {std::size_t{5000}, std::size_t{200000}}) {
        for (int threads : {1, 2, 3}) {
            CAPTURE(n);
            CAPTURE(threads);
            const auto part =
                soa_cloud<>(std::span(pts.x).first(n), std::span(pts.y).first(n), std::span(pts.z).first(n),
                            std::span(pts.intensity).first(n), {}, std::span(pts.number_of_returns).first(n));
            const auto want = reference::rasterize(part, g);
            CHECK(reference::same_bits(rasterize(part, g, {.chunk_points = 1500, .run = {.threads = threads}}), want));
        }
    }
}

TEST_CASE("raster/bounds_of: box of the finite points, fits snapped_grid")
{
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const std::vector<double> x{3.0, -1.0, nan, 7.5, 100.0}, y{2.0, 5.0, 0.0, -4.0, 1.0}, z{0.0, 1.0, 1.0, 2.0, nan};
    const soa_cloud<> cloud(x, y, z);
    CHECK(bounds_of(cloud) == bounds{-1.0, -4.0, 7.5, 5.0});
    const auto g = snapped_grid(bounds_of(cloud), 2.0);
    const auto out = rasterize(cloud, g);
    CHECK(out.points_outside == 0);
    CHECK(out.points_used == 3);

    const std::vector<double> none;
    CHECK_THROWS_WITH_AS(bounds_of(soa_cloud<>(none, none, none)),
                         "bounds_of: cloud has no point with finite x, y and z", invalid_input);
    const std::vector<double> bad{nan};
    CHECK_THROWS_AS(bounds_of(soa_cloud<>(bad, bad, bad)), invalid_input);
}
