// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include <lidarfx/kernels/solar/shadow_probes.hpp>

#include "reference/components.hpp"

#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

using namespace lidarfx;

namespace {

/// The largest shadow key of the non-NaN cells before (r, c) on its ray line, by looking at every cell: a cell q
/// is on the line of (r, c) when both have the same line index (steep: c - shift[r]; shallow: r - shift[c]) and
/// comes before it when the walk away from the sun meets it first (rows or columns in the walk's direction).
double limit_by_search(const raster<float>& z, const ray_lines& l, const shadow_lifts& lift, std::ptrdiff_t r,
                       std::ptrdiff_t c)
{
    const std::vector<std::ptrdiff_t> sh = l.shifts();
    const auto line_of = [&](std::ptrdiff_t rr, std::ptrdiff_t cc) {
        return l.steep ? cc - sh[static_cast<std::size_t>(rr)] : rr - sh[static_cast<std::size_t>(cc)];
    };
    const auto before = [&](std::ptrdiff_t rr, std::ptrdiff_t cc) {
        const std::ptrdiff_t a = l.steep ? rr : cc, b = l.steep ? r : c;
        return l.forward() ? a < b : a > b;
    };
    double best = -std::numeric_limits<double>::infinity();
    for (std::ptrdiff_t rr = 0; rr < z.rows(); ++rr) {
        for (std::ptrdiff_t cc = 0; cc < z.cols(); ++cc) {
            if (line_of(rr, cc) != line_of(r, c) || !before(rr, cc) || std::isnan(z(rr, cc))) continue;
            const double key = static_cast<double>(z(rr, cc)) + (lift.col_lift[static_cast<std::size_t>(cc)] +
                                                                 lift.row_lift[static_cast<std::size_t>(rr)]);
            best = std::max(best, key);
        }
    }
    return best;
}

}  // namespace

TEST_CASE("solar/raylines_shadow_probed: lit cells are raylines_shadow's single family, limits a search of the line")
{
    std::mt19937 rng(41);
    std::uniform_real_distribution<double> azimuth(0.0, 360.0), elevation(2.0, 70.0), height(0.0, 12.0);
    std::uniform_int_distribution<int> percent(0, 99);
    std::size_t shaded_points = 0, points = 0;
    for (int scene = 0; scene < 12; ++scene) {
        const std::ptrdiff_t rows = 23 + scene, cols = 37 - scene;  // not square: a transposition mixed up shows
        raster<float> z(rows, cols);
        for (std::ptrdiff_t r = 0; r < rows; ++r)
            for (std::ptrdiff_t c = 0; c < cols; ++c)
                z(r, c) = percent(rng) < 5 ? std::numeric_limits<float>::quiet_NaN() : static_cast<float>(height(rng));
        const raster<float> zt = reference::transpose(z);
        std::vector<std::ptrdiff_t> pr, pc;
        for (int k = 0; k < 40; ++k) {
            pr.push_back(std::uniform_int_distribution<std::ptrdiff_t>(0, rows - 1)(rng));
            pc.push_back(std::uniform_int_distribution<std::ptrdiff_t>(0, cols - 1)(rng));
        }
        const shadow_probes probes = make_shadow_probes(rows, cols, pr, pc);
        // Random suns and the grid's axes and diagonals (where lines are straight).
        for (const double az : {azimuth(rng), azimuth(rng), azimuth(rng), 0.0, 90.0, 135.0, 270.0}) {
            const double el = elevation(rng);
            const ray_lines l = make_ray_lines(az, rows, cols);
            const shadow_lifts lift = make_shadow_lifts(l, 1.0, std::tan(el * std::numbers::pi / 180.0));
            const auto want = raylines_shadow(z, 1.0, az, el, {.nan_cell = 0, .line_phases = 1});
            for (const bool with_transposed : {false, true}) {
                const bool flip = with_transposed && !l.steep;
                raster<std::uint8_t> lit(flip ? cols : rows, flip ? rows : cols);
                std::vector<double> limit;
                raylines_shadow_probed(z.view(), with_transposed ? zt.view() : raster_view<const float>{}, l, lift,
                                       probes, limit, lit.view(),
                                       {.nan_cell = 0, .line_phases = 1, .run = {.threads = 2}});
                bool same = true;
                for (std::ptrdiff_t r = 0; r < rows; ++r)
                    for (std::ptrdiff_t c = 0; c < cols; ++c)
                        same = same && (flip ? lit(c, r) : lit(r, c)) == want(r, c);
                CHECK_MESSAGE(same, "azimuth ", az, ", transposed DSM ", with_transposed);
                for (std::size_t k = 0; k < pr.size(); ++k) {
                    CHECK(limit[k] == limit_by_search(z, l, lift, pr[k], pc[k]));
                    // A point 6 m up at the probe (mid-range of the heights) is in shadow iff the limit is higher.
                    const double key =
                        lift.col_lift[static_cast<std::size_t>(pc[k])] + lift.row_lift[static_cast<std::size_t>(pr[k])];
                    shaded_points += limit[k] > 6.0 + key ? 1 : 0;
                    ++points;
                }
            }
        }
    }
    // Both outcomes occur, so the limits are not trivially -infinity or huge.
    CHECK(shaded_points > points / 10);
    CHECK(shaded_points < points * 9 / 10);
}

TEST_CASE("solar/raylines_shadow_probed: with several line families and a NaN code, lit is raylines_shadow's")
{
    std::mt19937 rng(43);
    std::uniform_real_distribution<double> azimuth(0.0, 360.0), height(0.0, 12.0);
    std::uniform_int_distribution<int> percent(0, 99);
    const std::ptrdiff_t rows = 41, cols = 29;
    raster<float> z(rows, cols);
    for (std::ptrdiff_t r = 0; r < rows; ++r)
        for (std::ptrdiff_t c = 0; c < cols; ++c)
            z(r, c) = percent(rng) < 5 ? std::numeric_limits<float>::quiet_NaN() : static_cast<float>(height(rng));
    const raster<float> zt = reference::transpose(z);
    {
        // The library's transposed copy is the plain one, NaN cells included.
        const raster<float> made = transposed_dsm(z.view(), 2);
        REQUIRE(made.rows() == cols);
        REQUIRE(made.cols() == rows);
        bool same = true;
        for (std::ptrdiff_t r = 0; r < cols; ++r)
            for (std::ptrdiff_t c = 0; c < rows; ++c)
                same = same && (made(r, c) == zt(r, c) || (std::isnan(made(r, c)) && std::isnan(zt(r, c))));
        CHECK(same);
    }
    const shadow_probes none = make_shadow_probes(rows, cols, {}, {});
    std::size_t lit_cells = 0;
    for (int sun = 0; sun < 24; ++sun) {
        const double az = azimuth(rng), el = 20.0;
        const ray_lines l = make_ray_lines(az, rows, cols);
        const shadow_lifts lift = make_shadow_lifts(l, 1.0, std::tan(el * std::numbers::pi / 180.0));
        for (const int phases : {2, 4}) {
            const raylines_shadow_options opt{.nan_cell = 7, .line_phases = phases};
            const auto want = raylines_shadow(z, 1.0, az, el, opt);
            for (const bool with_transposed : {false, true}) {
                const bool flip = with_transposed && !l.steep;
                raster<std::uint8_t> lit(flip ? cols : rows, flip ? rows : cols);
                std::vector<double> limit;
                raylines_shadow_probed(z.view(), with_transposed ? zt.view() : raster_view<const float>{}, l, lift,
                                       none, limit, lit.view(), opt);
                bool same = true;
                for (std::ptrdiff_t r = 0; r < rows; ++r) {
                    for (std::ptrdiff_t c = 0; c < cols; ++c) {
                        same = same && (flip ? lit(c, r) : lit(r, c)) == want(r, c);
                        lit_cells += want(r, c) == 1 ? 1 : 0;
                    }
                }
                CHECK_MESSAGE(same, "azimuth ", az, ", ", phases, " families, transposed DSM ", with_transposed);
                CHECK(limit.empty());
            }
        }
    }
    CHECK(lit_cells > 0);
}

TEST_CASE("solar/make_shadow_probes: lists each row's probes by column and each column's by row; refusals")
{
    const shadow_probes p = make_shadow_probes(3, 4, {2, 0, 2, 1, 0}, {1, 3, 0, 1, 0});
    CHECK(p.row_first == std::vector<std::size_t>{0, 2, 3, 5});
    CHECK(p.in_row == std::vector<std::int32_t>{4, 1, 3, 2, 0});
    CHECK(p.col_first == std::vector<std::size_t>{0, 2, 4, 4, 5});
    CHECK(p.in_col == std::vector<std::int32_t>{4, 2, 3, 0, 1});
    CHECK_THROWS_AS(make_shadow_probes(3, 4, {0, 1}, {0}), invalid_input);
    CHECK_THROWS_AS(make_shadow_probes(3, 4, {3}, {0}), invalid_input);
    CHECK_THROWS_AS(make_shadow_probes(3, 4, {0}, {-1}), invalid_input);
    raster<float> z(3, 4, 1.0f);
    raster<std::uint8_t> wrong(4, 4);
    std::vector<double> limit;
    const ray_lines l = make_ray_lines(180.0, 3, 4);
    CHECK_THROWS_AS(raylines_shadow_probed(z.view(), {}, l, make_shadow_lifts(l, 1.0, 0.5), p, limit, wrong.view()),
                    invalid_input);
    raster<std::uint8_t> right(3, 4);
    const ray_lines other = make_ray_lines(180.0, 5, 4);  // lines of another raster
    CHECK_THROWS_AS(
        raylines_shadow_probed(z.view(), {}, other, make_shadow_lifts(other, 1.0, 0.5), p, limit, right.view()),
        invalid_input);
    CHECK_THROWS_AS(raylines_shadow_probed(z.view(), {}, l, make_shadow_lifts(other, 1.0, 0.5), p, limit, right.view()),
                    invalid_input);
    CHECK_THROWS_AS(raylines_shadow_probed(z.view(), {}, l, make_shadow_lifts(l, 1.0, 0.5), p, limit, right.view(),
                                           {.line_phases = 0}),
                    invalid_input);
}
