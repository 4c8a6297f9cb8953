// SPDX-License-Identifier: Apache-2.0
// count_points_above: the points of each cell at least a height above a reference surface, against a direct count.
#include <doctest/doctest.h>

#include <lidarfx/kernels/points/count_points_above.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

using namespace lidarfx;

namespace {

struct xyz_points {
    std::vector<double> xs, ys, zs;
    std::size_t size() const { return xs.size(); }
    double x(std::size_t i) const { return xs[i]; }
    double y(std::size_t i) const { return ys[i]; }
    double z(std::size_t i) const { return zs[i]; }
};

/// The count by definition: for each cell, every point whose grid::cell_of is that cell and whose z is at least
/// the reference plus the height.
raster<std::uint32_t> points_above_by_definition(const xyz_points& p, const grid& g, const raster<float>& reference,
                                                 double height_m)
{
    raster<std::uint32_t> out(g.rows, g.cols);
    for (std::ptrdiff_t r = 0; r < g.rows; ++r)
        for (std::ptrdiff_t c = 0; c < g.cols; ++c)
            for (std::size_t i = 0; i < p.size(); ++i) {
                const auto at = g.cell_of(p.xs[i], p.ys[i]);
                if (at && at->row == r && at->col == c && std::isfinite(p.zs[i]) &&
                    p.zs[i] >= static_cast<double>(reference(r, c)) + height_m)
                    ++out(r, c);
            }
    return out;
}

bool same_counts(const raster<std::uint32_t>& a, const raster<std::uint32_t>& b)
{
    return a.rows() == b.rows() && a.cols() == b.cols() && std::equal(a.data(), a.data() + a.size(), b.data());
}

}  // namespace

TEST_CASE("count_points_above: a point counts in its cell when it stands the height above the reference there")
{
    const grid g{100.0, 220.0, 2.0, 6, 9};
    raster<float> reference(g.rows, g.cols);
    std::mt19937 rng(20261206);
    std::uniform_real_distribution<double> u(0, 1);
    for (std::ptrdiff_t r = 0; r < g.rows; ++r)
        for (std::ptrdiff_t c = 0; c < g.cols; ++c) reference(r, c) = static_cast<float>(10 + 3 * u(rng));
    reference(2, 3) = std::numeric_limits<float>::quiet_NaN();  // a cell without terrain counts nothing
    xyz_points p;
    for (int i = 0; i < 3000; ++i) {
        // Over the grid and a little beyond it, some on lattice lines and borders, some with NaN coordinates.
        double x = 98 + 22 * u(rng), y = 207 + 15 * u(rng);
        if (i % 37 == 0) x = 100 + 2 * std::floor(9 * u(rng));
        if (i % 41 == 0) y = 220 - 2 * std::floor(7 * u(rng));
        double z = 8 + 10 * u(rng);
        if (i % 97 == 0) z = std::numeric_limits<double>::quiet_NaN();
        if (i % 101 == 0) x = std::numeric_limits<double>::infinity();
        p.xs.push_back(x), p.ys.push_back(y), p.zs.push_back(z);
    }
    // Points exactly at the reference plus the height count; a hair below does not.
    const double at_height = static_cast<double>(reference(1, 1)) + 2.5;
    p.xs.push_back(103.0), p.ys.push_back(217.0), p.zs.push_back(at_height);
    p.xs.push_back(103.0), p.ys.push_back(217.0), p.zs.push_back(std::nextafter(at_height, 0.0));

    for (const double height : {2.5, 0.0, -1.0}) {
        const raster<std::uint32_t> expected = points_above_by_definition(p, g, reference, height);
        const raster<std::uint32_t> got = count_points_above(p, g, reference.view(), height);
        CHECK(same_counts(got, expected));
        CHECK(got(2, 3) == 0);
        // Chunk by chunk into one raster: the same counts.
        raster<std::uint32_t> chunked(g.rows, g.cols);
        for (std::size_t start = 0; start < p.size(); start += 700) {
            xyz_points chunk;
            for (std::size_t i = start; i < std::min(p.size(), start + 700); ++i)
                chunk.xs.push_back(p.xs[i]), chunk.ys.push_back(p.ys[i]), chunk.zs.push_back(p.zs[i]);
            count_points_above(chunk, g, reference.view(), height, chunked.view());
        }
        CHECK(same_counts(chunked, expected));
    }
    const raster<std::uint32_t> at_25 = count_points_above(p, g, reference.view(), 2.5);
    const raster<std::uint32_t> at_25_without_pair = [&] {
        xyz_points q = p;
        q.xs.resize(q.size() - 2), q.ys.resize(q.size() - 2), q.zs.resize(q.size() - 2);
        return count_points_above(q, g, reference.view(), 2.5);
    }();
    CHECK(at_25(1, 1) == at_25_without_pair(1, 1) + 1);
}

TEST_CASE("count_points_above: bad grids, heights and shapes are refused")
{
    const grid g{0.0, 10.0, 1.0, 10, 10};
    const raster<float> reference(10, 10);
    const xyz_points none;
    CHECK_THROWS_AS(count_points_above(none, g, reference.view(), std::nan("")), invalid_input);
    CHECK_THROWS_AS(count_points_above(none, g, raster<float>(9, 10).view(), 2.5), invalid_input);
    raster<std::uint32_t> wrong(10, 11);
    CHECK_THROWS_AS(count_points_above(none, g, reference.view(), 2.5, wrong.view()), invalid_input);
    CHECK_THROWS_AS(count_points_above(none, grid{0.0, 10.0, 0.0, 10, 10}, reference.view(), 2.5), invalid_input);
}

TEST_CASE("count_points_above: the lowest of the counted points of each cell, whole or chunk by chunk")
{
    const grid g{0.0, 12.0, 1.5, 8, 7};
    raster<float> reference(g.rows, g.cols);
    std::mt19937 rng(20261207);
    std::uniform_real_distribution<double> u(0, 1);
    for (std::ptrdiff_t r = 0; r < g.rows; ++r)
        for (std::ptrdiff_t c = 0; c < g.cols; ++c) reference(r, c) = static_cast<float>(2 * u(rng));
    reference(4, 4) = std::numeric_limits<float>::quiet_NaN();
    xyz_points p;
    for (int i = 0; i < 2000; ++i) {
        double z = 6 * u(rng);
        if (i % 89 == 0) z = std::numeric_limits<double>::quiet_NaN();
        p.xs.push_back(-1 + 13 * u(rng)), p.ys.push_back(-1 + 14 * u(rng)), p.zs.push_back(z);
    }
    const double height = 2.5;
    // By definition: the least z of the points that count_points_above counts; NaN where none counts.
    raster<float> expected(g.rows, g.cols, std::numeric_limits<float>::quiet_NaN());
    for (std::size_t i = 0; i < p.size(); ++i) {
        const auto at = g.cell_of(p.xs[i], p.ys[i]);
        if (!at || !std::isfinite(p.zs[i])) continue;
        const float ref = reference(at->row, at->col);
        if (!std::isfinite(ref) || !(p.zs[i] >= static_cast<double>(ref) + height)) continue;
        float& e = expected(at->row, at->col);
        e = std::isnan(e) ? static_cast<float>(p.zs[i]) : std::min(e, static_cast<float>(p.zs[i]));
    }
    const auto same_lowest = [&](const raster<float>& got) {
        for (std::ptrdiff_t i = 0; i < got.size(); ++i) {
            const float a = got.data()[i], b = expected.data()[i];
            if (!(a == b || (std::isnan(a) && std::isnan(b)))) return false;
        }
        return true;
    };
    raster<std::uint32_t> counts(g.rows, g.cols);
    raster<float> lowest(g.rows, g.cols, std::numeric_limits<float>::quiet_NaN());
    count_points_above(p, g, reference.view(), height, counts.view(), lowest.view());
    CHECK(same_counts(counts, points_above_by_definition(p, g, reference, height)));
    CHECK(same_lowest(lowest));
    CHECK(std::isnan(lowest(4, 4)));
    std::size_t cells_with_lowest = 0;
    for (std::ptrdiff_t i = 0; i < lowest.size(); ++i) cells_with_lowest += std::isfinite(lowest.data()[i]) ? 1 : 0;
    CHECK(cells_with_lowest > 40);  // the check above compares numbers, not only NaNs
    // Chunks in reverse order: the same rasters.
    raster<std::uint32_t> chunked(g.rows, g.cols);
    raster<float> chunked_lowest(g.rows, g.cols, std::numeric_limits<float>::quiet_NaN());
    for (std::size_t end = p.size(); end > 0; end = end > 300 ? end - 300 : 0) {
        xyz_points chunk;
        for (std::size_t i = end > 300 ? end - 300 : 0; i < end; ++i)
            chunk.xs.push_back(p.xs[i]), chunk.ys.push_back(p.ys[i]), chunk.zs.push_back(p.zs[i]);
        count_points_above(chunk, g, reference.view(), height, chunked.view(), chunked_lowest.view());
    }
    CHECK(same_counts(chunked, counts));
    CHECK(same_lowest(chunked_lowest));
    raster<float> wrong(g.rows, g.cols + 1);
    CHECK_THROWS_AS(count_points_above(p, g, reference.view(), height, counts.view(), wrong.view()), invalid_input);
}
