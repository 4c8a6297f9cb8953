// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include <lidarfx/kernels/points/scan_coverage.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

using namespace lidarfx;

namespace {

/// A 10 x 40 grid of 1 m cells with its west edge at x = 0 and north edge at y = 10.
const grid tile{0.0, 10.0, 1.0, 10, 40};

/// Points of one scan line along y = 5.5: x from 0.5 to 39.5 every 0.5 m, 10 µs apart, minus those with
/// 10 <= x < 30 (pulses lost over water).
struct sweep {
    std::vector<double> x, y, t;
};
sweep line_over_water(double t0 = 100.0)
{
    sweep s;
    for (int i = 1; i < 80; ++i) {
        const double x = 0.5 * i;
        if (x >= 10.0 && x < 30.0) continue;
        s.x.push_back(x);
        s.y.push_back(5.5);
        s.t.push_back(t0 + i * 1.0e-5);
    }
    return s;
}

int covered_in_row(const scan_coverage& cov, std::ptrdiff_t r, std::ptrdiff_t c0, std::ptrdiff_t c1)
{
    int n = 0;
    for (std::ptrdiff_t c = c0; c < c1; ++c) n += cov.covered()(r, c);
    return n;
}

}  // namespace

TEST_CASE("points/scan_coverage: the cells a scan line crossed while its pulses were lost are covered")
{
    const auto s = line_over_water();
    scan_coverage cov(tile);
    cov.add(s.x, s.y, s.t);
    CHECK(covered_in_row(cov, 4, 10, 30) == 20);  // the whole gap, row of y = 5.5
    CHECK(covered_in_row(cov, 3, 0, 40) == 0);    // nothing beside the line
    CHECK(covered_in_row(cov, 5, 0, 40) == 0);
}

TEST_CASE("points/scan_coverage: gaps longer in time or space than the options, and NaN, break the line")
{
    const auto s = line_over_water();
    scan_coverage slow(tile, {.max_time_gap_s = 1.0e-5});  // the gap took 21 pulses
    slow.add(s.x, s.y, s.t);
    CHECK(covered_in_row(slow, 4, 10, 30) == 0);
    scan_coverage short_span(tile, {.max_span_m = 15.0});  // the gap is 20.5 m
    short_span.add(s.x, s.y, s.t);
    CHECK(covered_in_row(short_span, 4, 10, 30) == 0);
    auto broken = s;
    broken.t[18] = NAN;  // the last return before the water
    scan_coverage nan_cov(tile);
    nan_cov.add(broken.x, broken.y, broken.t);
    CHECK(covered_in_row(nan_cov, 4, 10, 30) == 0);
}

TEST_CASE("points/scan_coverage: chunking does not change the result; end_sweep separates files")
{
    const auto s = line_over_water();
    scan_coverage whole(tile);
    whole.add(s.x, s.y, s.t);
    scan_coverage chunked(tile);
    for (std::size_t i = 0; i < s.x.size(); i += 7) {
        const std::size_t n = std::min<std::size_t>(7, s.x.size() - i);
        chunked.add(std::span(s.x).subspan(i, n), std::span(s.y).subspan(i, n), std::span(s.t).subspan(i, n));
    }
    CHECK(chunked.take() == whole.take());
    scan_coverage files(tile);
    const std::size_t split = 18;  // the first file ends at the water's edge, the second starts beyond it
    files.add(std::span(s.x).first(split + 1), std::span(s.y).first(split + 1), std::span(s.t).first(split + 1));
    files.end_sweep();
    files.add(std::span(s.x).subspan(split + 1), std::span(s.y).subspan(split + 1), std::span(s.t).subspan(split + 1));
    CHECK(covered_in_row(files, 4, 10, 30) == 0);
    CHECK_THROWS_AS(scan_coverage(tile, {.max_time_gap_s = 0.0}), invalid_input);
    CHECK_THROWS_AS(whole.add(s.x, s.y, std::span(s.t).first(3)), invalid_input);
}

TEST_CASE("points/scan_coverage: windows of a partition put together give the whole grid's coverage")
{
    // Diagonal and horizontal lines with gaps, on a grid whose cell is not a power of two (rounding differs
    // between the whole grid's coordinates and a window's own).
    const grid g{1000.3, 2000.7, 0.7, 23, 37};
    std::vector<double> x, y, t;
    for (int i = 0; i < 400; ++i) {
        const double f = i / 400.0;
        if (i % 50 > 20) continue;  // lost pulses
        x.push_back(1000.3 + f * 25.9);
        y.push_back(2000.7 - 0.05 - f * 16.0);
        t.push_back(i * 1.0e-5);
    }
    scan_coverage whole(g);
    whole.add(x, y, t);
    const auto expected = whole.take();
    REQUIRE(std::count(expected.data(), expected.data() + expected.size(), 1) > 20);
    raster<std::uint8_t> assembled(g.rows, g.cols, 7);
    for (std::ptrdiff_t r0 = 0; r0 < g.rows; r0 += 6) {
        for (std::ptrdiff_t c0 = 0; c0 < g.cols; c0 += 5) {
            const cell_box w{r0, c0, std::min(g.rows, r0 + 6) - 1, std::min(g.cols, c0 + 5) - 1};
            scan_coverage part(g, w);
            part.add(x, y, t);
            REQUIRE(part.covered().rows() == w.rows());
            for (std::ptrdiff_t r = 0; r < w.rows(); ++r)
                for (std::ptrdiff_t c = 0; c < w.cols(); ++c) assembled(r0 + r, c0 + c) = part.covered()(r, c);
        }
    }
    CHECK(assembled == expected);
    CHECK_THROWS_AS(scan_coverage(g, cell_box{0, 0, 23, 3}), invalid_input);
    CHECK_THROWS_AS(scan_coverage(g, cell_box{}), invalid_input);
}
