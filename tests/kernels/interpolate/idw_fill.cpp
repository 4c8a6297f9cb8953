// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include <lidarfx/kernels/interpolate/idw_fill.hpp>

#include "reference/idw.hpp"
#include "reference/progress.hpp"
#include "reference/rasterize.hpp"  // same_bits
#include "test_values.hpp"

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

using namespace lidarfx;

namespace {

raster<float> from_rows(std::ptrdiff_t rows, std::ptrdiff_t cols, std::vector<float> values)
{
    raster<float> out(rows, cols);
    std::copy(values.begin(), values.end(), out.begin());
    return out;
}

/// Random values in [0, 100) with holes of the given kind: 0 random blobs and single cells, 1 a
/// checkerboard, 2 holes everywhere but a few cells, 3 a hole along every border.
raster<float> random_holes(std::mt19937& rng, std::ptrdiff_t rows, std::ptrdiff_t cols, int kind)
{
    std::uniform_real_distribution<float> value(0.0f, 100.0f);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    raster<float> z(rows, cols);
    for (auto& v : z) v = value(rng);
    const auto at = [&](std::ptrdiff_t n) { return std::uniform_int_distribution<std::ptrdiff_t>(0, n - 1)(rng); };
    switch (kind) {
        case 0:
            for (int blob = 0; blob < 1 + static_cast<int>(rows * cols / 200); ++blob) {
                const auto r0 = at(rows), c0 = at(cols);
                const double radius = 1.0 + 6.0 * unit(rng);
                for (std::ptrdiff_t r = 0; r < rows; ++r)
                    for (std::ptrdiff_t c = 0; c < cols; ++c)
                        if (std::hypot(static_cast<double>(r - r0), static_cast<double>(c - c0)) <= radius)
                            z(r, c) = nan_f;
            }
            for (auto& v : z)
                if (unit(rng) < 0.05) v = nan_f;
            break;
        case 1:
            for (std::ptrdiff_t r = 0; r < rows; ++r)
                for (std::ptrdiff_t c = 0; c < cols; ++c)
                    if ((r + c) % 2 == 0) z(r, c) = nan_f;
            break;
        case 2:
            for (auto& v : z)
                if (unit(rng) < 0.97) v = nan_f;
            break;
        default:
            for (std::ptrdiff_t r = 0; r < rows; ++r)
                for (std::ptrdiff_t c = 0; c < cols; ++c)
                    if (r == 0 || c == 0 || r == rows - 1 || c == cols - 1) z(r, c) = nan_f;
            break;
    }
    z(at(rows), at(cols)) = value(rng);  // at least one data cell
    return z;
}

/// Same NaN cells and values within 1e-6 relative: the kernel and the reference pick the same neighbours
/// and sum them in the same order, so only floating-point contraction (FMA) could separate them by an ulp;
/// a different neighbour would move the value by a sizeable share of the [0, 100) spread.
bool close(const raster<float>& a, const raster<float>& b)
{
    if (a.rows() != b.rows() || a.cols() != b.cols()) return false;
    for (std::ptrdiff_t i = 0; i < a.size(); ++i) {
        const float x = a.data()[i], y = b.data()[i];
        if (std::isnan(x) != std::isnan(y)) return false;
        if (!std::isnan(x) && std::abs(x - y) > 1e-6f * std::max(1.0f, std::abs(y))) return false;
    }
    return true;
}

std::size_t count_nan(raster_view<const float> z)
{
    std::size_t n = 0;
    for (std::ptrdiff_t r = 0; r < z.rows(); ++r)
        for (std::ptrdiff_t c = 0; c < z.cols(); ++c) n += std::isnan(z(r, c)) ? 1 : 0;
    return n;
}

/// A raster type that is not stored in rows (read through a function), to exercise the copying paths.
struct computed_raster {
    using value_type = double;
    std::ptrdiff_t rows() const { return 3; }
    std::ptrdiff_t cols() const { return 3; }
    double operator()(std::ptrdiff_t r, std::ptrdiff_t c) const
    {
        return (r == 1 && c == 1) ? std::numeric_limits<double>::quiet_NaN() : static_cast<double>(r * 3 + c);
    }
};

}  // namespace

TEST_CASE("raster/idw_fill: hand-checked weights, ties, power and radius")
{
    // Equal distances: the mean; k = 1 takes the tie with the smaller column.
    const auto row = from_rows(1, 3, {1.0f, nan_f, 3.0f});
    CHECK(idw_fill(row, 1.0).filled(0, 1) == 2.0f);
    CHECK(idw_fill(row, 1.0, {.k = 1}).filled(0, 1) == 1.0f);

    // 1/d weights interpolate linearly between two data cells: 0 _ _ 6 -> 0 2 4 6.
    const auto line = from_rows(1, 4, {0.0f, nan_f, nan_f, 6.0f});
    const auto filled = idw_fill(line, 1.0, {.k = 2});
    CHECK(filled.filled(0, 1) == doctest::Approx(2.0));
    CHECK(filled.filled(0, 2) == doctest::Approx(4.0));
    CHECK(filled.filled_cells == 2);
    CHECK(filled.unfilled_cells == 0);
    // power 2: weights 1 and 1/4 -> (0 + 6/4) / (5/4) = 1.2.
    CHECK(idw_fill(line, 1.0, {.k = 2, .power = 2.0}).filled(0, 1) == doctest::Approx(1.2));

    // The four edge neighbours (distance 1) win over the corners; the ties at distance 1 come by row, then col.
    const auto cross = from_rows(3, 3, {100, 1, 100, 2, nan_f, 3, 100, 4, 100});
    CHECK(idw_fill(cross, 1.0, {.k = 4}).filled(1, 1) == 2.5f);
    CHECK(idw_fill(cross, 1.0, {.k = 2}).filled(1, 1) == 1.5f);  // (0,1) and (1,0)
    CHECK(idw_fill(cross, 1.0, {.k = 5}).filled(1, 1) ==
          doctest::Approx((1 + 2 + 3 + 4 + 100 / std::sqrt(2.0)) / (4 + 1 / std::sqrt(2.0))));

    // Radius in metres, inclusive: 5 _ _ _ _ with cells of 1 m and radius 2 m fills two cells.
    const auto far = from_rows(1, 5, {5.0f, nan_f, nan_f, nan_f, nan_f});
    const auto limited = idw_fill(far, 1.0, {.radius_m = 2.0});
    CHECK(limited.filled(0, 2) == 5.0f);
    CHECK(std::isnan(limited.filled(0, 3)));
    CHECK(limited.filled_cells == 2);
    CHECK(limited.unfilled_cells == 2);
    CHECK(idw_fill(far, 0.5, {.radius_m = 2.0}).unfilled_cells == 0);
    CHECK(idw_fill(far, 1.0).unfilled_cells == 0);
    // 0.3 m at 0.1 m cells is three cells, although 3 * 0.1 != 0.3 in floating point.
    CHECK(idw_fill(far, 0.1, {.radius_m = 0.3}).unfilled_cells == 1);
    CHECK(idw_fill(far, 0.1, {.radius_m = 0.2999}).unfilled_cells == 2);
}

TEST_CASE("raster/idw_fill: data cells are copied; infinite cells are copied but never used")
{
    const float inf = std::numeric_limits<float>::infinity();
    const auto z = from_rows(1, 4, {inf, nan_f, 7.0f, -inf});
    const auto out = idw_fill(z, 1.0);
    CHECK(out.filled(0, 0) == inf);
    CHECK(out.filled(0, 1) == 7.0f);
    CHECK(out.filled(0, 2) == 7.0f);
    CHECK(out.filled(0, 3) == -inf);
    CHECK(out.filled_cells == 1);
}

TEST_CASE("raster/idw_fill: equals the brute-force nearest-k reference on random holes")
{
    const unsigned seed = 31337;
    std::mt19937 rng(seed);
    struct shape {
        std::ptrdiff_t rows, cols;
    };
    for (const shape s : {shape{1, 1}, shape{1, 29}, shape{23, 1}, shape{7, 13}, shape{20, 17}, shape{64, 80}}) {
        const bool big = s.rows * s.cols > 1000;
        for (int kind = 0; kind < 4; ++kind) {
            if (big && kind != 0 && kind != 2) continue;
            auto z = random_holes(rng, s.rows, s.cols, kind);
            if (s.rows * s.cols == 1) z(0, 0) = 4.0f;
            struct setting {
                double cell_m;
                idw_fill_options opt;
            };
            for (const setting& base :
                 {setting{1.0, {.k = 1}}, setting{2.0, {.k = 4, .radius_m = 7.5}}, setting{1.0, {.k = 8}},
                  setting{0.1, {.k = 8, .radius_m = 0.3, .power = 2.0}}}) {
                if (big && base.opt.k == 1) continue;
                CAPTURE(seed);
                CAPTURE(s.rows);
                CAPTURE(s.cols);
                CAPTURE(kind);
                CAPTURE(base.opt.k);
                CAPTURE(base.opt.radius_m);
                const auto expected = reference::idw_fill(z.view(), base.cell_m, base.opt);
                for (int threads : {1, 2, 3}) {
                    idw_fill_options opt = base.opt;
                    opt.run.threads = threads;
                    const auto got = idw_fill(z, base.cell_m, opt);
                    CHECK(close(got.filled, expected));
                    CHECK(got.unfilled_cells == count_nan(expected.view()));
                    CHECK(got.filled_cells + got.unfilled_cells == count_nan(z.view()));
                }
            }
        }
    }
}

TEST_CASE("raster/idw_fill: strided windows give the same result as contiguous copies")
{
    std::mt19937 rng(4242);
    for (int trial = 0; trial < 6; ++trial) {
        const auto big = random_holes(rng, 40, 37, trial % 4);
        const auto window = big.view().window(3, 2, 30, 31);  // row_stride 37 != cols 31
        const raster<float> copy(window);
        if (count_nan(copy.view()) == static_cast<std::size_t>(copy.size())) continue;
        const idw_fill_options opt{
            .k = 1 + trial, .radius_m = trial % 2 ? 0.0 : 9.0, .run = {.threads = 1 + trial % 3}};
        const double cell_m = 1.0;
        const auto from_window = idw_fill(window, cell_m, opt);
        CHECK(reference::same_bits(from_window.filled, idw_fill(copy, cell_m, opt).filled));
        CHECK(close(from_window.filled, reference::idw_fill(window, cell_m, opt)));

        // The into form writes through a strided output window too.
        raster<float> target(40, 50, -1.0f);
        const auto counts = idw_fill(window, target.view().window(5, 9, 30, 31), cell_m, opt);
        CHECK(counts.filled_cells == from_window.filled_cells);
        CHECK(reference::same_bits(raster<float>(target.view().window(5, 9, 30, 31)), from_window.filled));
        CHECK(target(4, 9) == -1.0f);
        CHECK(target(5, 8) == -1.0f);
    }
}

TEST_CASE("raster/idw_fill: constant rasters fill exactly")
{
    std::mt19937 rng(8);
    for (int kind = 0; kind < 4; ++kind) {
        auto z = random_holes(rng, 19, 23, kind);
        for (auto& v : z)
            if (!std::isnan(v)) v = 12.345f;
        for (int k : {1, 3, 8, 20}) {
            const auto out = idw_fill(z, 0.7, {.k = k, .power = 1.0 + 0.5 * kind, .run = {.threads = 2}});
            for (float v : out.filled) CHECK(v == 12.345f);
            CHECK(out.unfilled_cells == 0);
        }
    }
}

TEST_CASE("raster/idw_fill: any raster type in, double cells in, non-strided output")
{
    const auto out = idw_fill(computed_raster{}, 1.0, {.k = 4});
    CHECK(out.filled(1, 1) == 4.0f);  // neighbours 1, 3, 5, 7
    CHECK(out.filled(2, 2) == 8.0f);

    raster<double> z(2, 2, 1.5);
    z(0, 1) = std::numeric_limits<double>::quiet_NaN();
    CHECK(idw_fill(z, 1.0).filled(0, 1) == 1.5f);
}

TEST_CASE("raster/idw_fill: progress is monotone and ends at 1; returning false cancels")
{
    std::mt19937 rng(77);
    const auto z = random_holes(rng, 120, 60, 0);  // 15 blocks of 8 rows, after the index
    const auto want = idw_fill(z, 0.5);
    for (int threads : {1, 2}) {
        CAPTURE(threads);
        const reference::progress_log log;
        const auto got = idw_fill(z, 0.5, {.run = {.threads = threads, .progress = log.callback()}});
        CHECK(reference::same_bits(got.filled, want.filled));
        CHECK(log.monotone_to_one(threads == 1 ? 15 : 1));
        CHECK_THROWS_WITH_AS(idw_fill(z, 0.5, {.run = {.threads = threads, .progress = reference::cancel_at_once()}}),
                             "idw_fill: cancelled", cancelled);
    }
}

TEST_CASE("raster/idw_fill: bad arguments throw invalid_input")
{
    const auto z = from_rows(2, 2, {1.0f, nan_f, 2.0f, 3.0f});
    CHECK_THROWS_WITH_AS(idw_fill(z, 1.0, {.k = 0}), "idw_fill: k must be >= 1 (got 0)", invalid_input);
    CHECK_THROWS_WITH_AS(idw_fill(z, 1.0, {.radius_m = -1.0}),
                         "idw_fill: radius_m must be finite and >= 0 (0 = unlimited) (got -1)", invalid_input);
    CHECK_THROWS_WITH_AS(idw_fill(z, 1.0, {.power = 0.0}), "idw_fill: power must be finite and > 0 (got 0)",
                         invalid_input);
    CHECK_THROWS_WITH_AS(idw_fill(z, -2.0), "idw_fill: cell_m must be finite and > 0 (got -2)", invalid_input);
    CHECK_THROWS_AS(idw_fill(z, 0.0), invalid_input);
    CHECK_THROWS_WITH_AS(idw_fill(z, 1.0, {.run = {.threads = -1}}), "idw_fill: run.threads must be >= 0 (got -1)",
                         invalid_input);
    raster<float> wrong(3, 2);
    CHECK_THROWS_WITH_AS(idw_fill(z, wrong, 1.0), "idw_fill: z and out must have the same shape (got 2x2 and 3x2)",
                         invalid_input);
    raster<float> shared(3, 3, 1.0f);
    shared(1, 1) = nan_f;
    CHECK_THROWS_WITH_AS(idw_fill(shared, shared, 1.0), "idw_fill: out must not overlap z", invalid_input);
    const raster<float> all_nan(4, 5, nan_f);
    CHECK_THROWS_WITH_AS(idw_fill(all_nan, 1.0), "idw_fill: z has no finite cell to interpolate from", invalid_input);
    CHECK_THROWS_AS(idw_fill(raster<float>(0, 0), 1.0), invalid_input);
}

TEST_CASE("raster/idw_fill_reach_cells: the farthest hole a data cell fills along a row")
{
    // One data cell at column 0 of a row of holes: idw_fill fills exactly the holes within the reach.
    const struct {
        double radius_m, cell_m;
        std::ptrdiff_t reach;
    } cases[] = {{1.0, 1.0, 1}, {0.3, 0.1, 3}, {2.5, 0.5, 5}, {0.7, 0.25, 2}, {3.99, 1.0, 3}, {0.5, 1.0, 0}};
    for (const auto& k : cases) {
        CAPTURE(k.radius_m);
        CAPTURE(k.cell_m);
        const idw_fill_options opt{.k = 1, .radius_m = k.radius_m};
        CHECK(idw_fill_reach_cells(opt, k.cell_m) == k.reach);
        raster<float> row(1, k.reach + 3, nan_f);
        row(0, 0) = 7.0f;
        const raster<float> filled = idw_fill(row, k.cell_m, opt).filled;
        for (std::ptrdiff_t c = 1; c < row.cols(); ++c) CHECK(std::isnan(filled(0, c)) == (c > k.reach));
    }
    CHECK_THROWS_WITH_AS(idw_fill_reach_cells({.radius_m = 0}, 1.0),
                         "idw_fill_reach_cells: radius_m must be finite and > 0 (got 0); with radius_m 0 (unlimited) "
                         "idw_fill is not local",
                         invalid_input);
    CHECK_THROWS_AS(idw_fill_reach_cells({.radius_m = 1}, 0.0), invalid_input);
    CHECK_THROWS_AS(idw_fill_reach_cells({.radius_m = std::numeric_limits<double>::infinity()}, 1.0), invalid_input);
}
