// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include <lidarfx/core/error.hpp>
#include <lidarfx/kernels/filter/surface_outliers.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

using namespace lidarfx;

namespace {

/// The definition, cell by cell: sort every window's finite neighbours, count the supporting ones.
surface_outliers_result outliers_by_sorting(const raster<float>& z, const surface_outliers_options& o)
{
    surface_outliers_result out{z, raster<std::uint8_t>(z.rows(), z.cols(), 0), 0, 0};
    for (std::ptrdiff_t r = 0; r < z.rows(); ++r)
        for (std::ptrdiff_t c = 0; c < z.cols(); ++c) {
            if (std::isnan(z(r, c))) continue;
            std::vector<double> around;
            int inside = 0;
            for (std::ptrdiff_t dr = -o.radius_cells; dr <= o.radius_cells; ++dr)
                for (std::ptrdiff_t dc = -o.radius_cells; dc <= o.radius_cells; ++dc) {
                    const std::ptrdiff_t rr = r + dr, cc = c + dc;
                    if ((dr == 0 && dc == 0) || rr < 0 || cc < 0 || rr >= z.rows() || cc >= z.cols()) continue;
                    ++inside;
                    if (!std::isnan(z(rr, cc))) around.push_back(z(rr, cc));
                }
            std::sort(around.begin(), around.end());
            const auto n = static_cast<std::ptrdiff_t>(around.size());
            const int full = (2 * o.radius_cells + 1) * (2 * o.radius_cells + 1) - 1;
            const int k = std::max(1, static_cast<int>(std::ceil(double(o.min_support_cells) * inside / full)));
            if (n < k) continue;
            const auto above =
                std::count_if(around.begin(), around.end(), [&](double q) { return q >= z(r, c) - o.spike_height_m; });
            const auto below =
                std::count_if(around.begin(), around.end(), [&](double q) { return q <= z(r, c) + o.pit_depth_m; });
            if (above >= k && below >= k) continue;
            out.surface(r, c) = static_cast<float>(around[static_cast<std::size_t>((n - 1) / 2)]);
            out.outlier(r, c) = above < k ? 1 : 2;
            ++(above < k ? out.spikes : out.pits);
        }
    return out;
}

raster<float> rough_surface(std::ptrdiff_t rows, std::ptrdiff_t cols, unsigned seed, double spike_share)
{
    std::mt19937 rng(seed);
    std::normal_distribution<double> noise(0.0, 2.0);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    raster<float> z(rows, cols);
    for (std::ptrdiff_t r = 0; r < rows; ++r)
        for (std::ptrdiff_t c = 0; c < cols; ++c) {
            double v = 100 + 0.3 * static_cast<double>(r) + noise(rng);
            const double k = u(rng);
            if (k < spike_share)
                v += 30 + 150 * u(rng);  // a bird
            else if (k < 2 * spike_share)
                v -= 12 + 10 * u(rng);  // a gap to the ground
            else if (k < 2 * spike_share + 0.02)
                v = std::numeric_limits<double>::quiet_NaN();  // no return
            z(r, c) = static_cast<float>(v);
        }
    return z;
}

bool same(const raster<float>& a, const raster<float>& b)
{
    for (std::ptrdiff_t r = 0; r < a.rows(); ++r)
        for (std::ptrdiff_t c = 0; c < a.cols(); ++c)
            if (!(a(r, c) == b(r, c) || (std::isnan(a(r, c)) && std::isnan(b(r, c))))) return false;
    return true;
}

}  // namespace

TEST_CASE("filter/remove_surface_outliers: equals sorting every window, on random surfaces and any thread count")
{
    for (unsigned seed = 1; seed <= 12; ++seed) {
        const raster<float> z = rough_surface(37 + seed, 41, seed, seed % 3 == 0 ? 0.08 : 0.02);
        surface_outliers_options o;
        o.radius_cells = 1 + static_cast<int>(seed % 3);
        o.min_support_cells = 1 + static_cast<int>(seed % 4);
        o.spike_height_m = seed % 2 ? 10.0 : 6.0;
        const surface_outliers_result want = outliers_by_sorting(z, o);
        for (int threads : {1, 2, 3}) {
            o.run.threads = threads;
            const surface_outliers_result got = remove_surface_outliers(z, o);
            CAPTURE(seed);
            CAPTURE(threads);
            CHECK(same(got.surface, want.surface));
            CHECK(got.spikes == want.spikes);
            CHECK(got.pits == want.pits);
            bool flags_equal = true;
            for (std::ptrdiff_t r = 0; r < z.rows(); ++r)
                for (std::ptrdiff_t c = 0; c < z.cols(); ++c) flags_equal &= got.outlier(r, c) == want.outlier(r, c);
            CHECK(flags_equal);
        }
        CHECK(want.spikes + want.pits > 0);
    }
}

TEST_CASE(
    "filter/remove_surface_outliers: a bird and a canopy gap go, a building's corner, a chimney and an alley stay")
{
    raster<float> z(30, 30, 100.0f);
    for (std::ptrdiff_t r = 5; r < 15; ++r)
        for (std::ptrdiff_t c = 5; c < 15; ++c) z(r, c) = 125.0f;  // a 25 m tower, 10 x 10 cells
    z(9, 9) = z(9, 10) = z(10, 9) = z(10, 10) = 131.0f;            // a 2 x 2 chimney on it, 6 m
    for (std::ptrdiff_t r = 18; r < 30; ++r) {                     // two blocks with a one-cell alley between
        for (std::ptrdiff_t c = 0; c < 30; ++c) z(r, c) = c == 15 ? 100.0f : 118.0f;
    }
    z(2, 25) = 260.0f;  // a bird, 160 m up
    z(22, 5) = 97.0f;   // a return through a gap, 21 m below the roof
    const surface_outliers_result got = remove_surface_outliers(z);
    CHECK(got.spikes == 1);
    CHECK(got.pits == 1);
    CHECK(got.outlier(2, 25) == 1);
    CHECK(got.surface(2, 25) == 100.0f);
    CHECK(got.outlier(22, 5) == 2);
    CHECK(got.surface(22, 5) == 118.0f);
    CHECK(got.outlier(5, 5) == 0);    // the tower's corner: 8 tower cells around it
    CHECK(got.outlier(9, 9) == 0);    // the chimney
    CHECK(got.outlier(25, 15) == 0);  // the alley
    CHECK(got.outlier(29, 15) == 0);  // and its end at the raster's border, with half a window of support
    raster<float> edge(10, 10, 100.0f);
    edge(0, 0) = 200.0f;  // a bird in the corner: 3 neighbours, none near it
    CHECK(remove_surface_outliers(edge).outlier(0, 0) == 1);
    CHECK(got.surface(5, 5) == 125.0f);
}

TEST_CASE("filter/remove_surface_outliers: NaN stays NaN, sparse windows are left alone, bad options are refused")
{
    const float nan = std::numeric_limits<float>::quiet_NaN();
    raster<float> z(5, 5, nan);
    z(2, 2) = 500.0f;
    z(0, 0) = 100.0f;
    const surface_outliers_result got = remove_surface_outliers(z);
    CHECK(got.spikes == 0);  // one finite neighbour: too little is known
    CHECK(std::isnan(got.surface(1, 1)));
    CHECK(got.surface(2, 2) == 500.0f);
    CHECK_THROWS_AS(remove_surface_outliers(z, {.radius_cells = 0}), invalid_input);
    CHECK_THROWS_AS(remove_surface_outliers(z, {.spike_height_m = -1}), invalid_input);
    CHECK_THROWS_AS(remove_surface_outliers(z, {.pit_depth_m = std::numeric_limits<double>::infinity()}),
                    invalid_input);
    CHECK_THROWS_AS(remove_surface_outliers(z, {.min_support_cells = 0}), invalid_input);
}
