// SPDX-License-Identifier: Apache-2.0
// min_filter_rows / max_filter_rows / for_each_row_strip against a plain window scan.
#include <doctest/doctest.h>

#include <lidarfx/kernels/filter/min_max_filter.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <type_traits>
#include <vector>

using namespace lidarfx;

namespace {

/// The plain definition over a (2 kx + 1) x (2 ky + 1) window clipped at the border: NaN cells skipped, the
/// neutral (+inf / max for min, -inf / lowest for max) when nothing is left.
template <class T>
std::vector<T> brute(const std::vector<T>& in, std::ptrdiff_t rows, std::ptrdiff_t cols, std::ptrdiff_t kx,
                     std::ptrdiff_t ky, bool want_min)
{
    using lim = std::numeric_limits<T>;
    const T neutral = want_min ? (lim::has_infinity ? lim::infinity() : lim::max())
                               : (lim::has_infinity ? -lim::infinity() : lim::lowest());
    std::vector<T> out(in.size(), neutral);
    for (std::ptrdiff_t r = 0; r < rows; ++r) {
        for (std::ptrdiff_t c = 0; c < cols; ++c) {
            T v = neutral;
            for (std::ptrdiff_t rr = std::max<std::ptrdiff_t>(0, r - ky); rr <= std::min(rows - 1, r + ky); ++rr) {
                for (std::ptrdiff_t cc = std::max<std::ptrdiff_t>(0, c - kx); cc <= std::min(cols - 1, c + kx); ++cc) {
                    const T x = in[static_cast<std::size_t>(rr * cols + cc)];
                    if constexpr (std::is_floating_point_v<T>) {
                        if (std::isnan(x)) continue;
                    }
                    v = want_min ? std::min(v, x) : std::max(v, x);
                }
            }
            out[static_cast<std::size_t>(r * cols + c)] = v;
        }
    }
    return out;
}

/// Runs min_filter_rows or max_filter_rows over the whole raster in strips of `strip` rows on `threads`.
template <class T>
std::vector<T> filtered(const std::vector<T>& in, std::ptrdiff_t rows, std::ptrdiff_t cols, std::ptrdiff_t kx,
                        std::ptrdiff_t ky, bool want_min, std::ptrdiff_t strip, int threads)
{
    std::vector<T> out(in.size());
    struct scratch {
        min_max_workspace<T> ws;
    };
    for_each_row_strip<scratch>(
        rows, strip, threads,
        [&](std::ptrdiff_t r0, std::ptrdiff_t r1, scratch& s) {
            const auto load = [&](std::ptrdiff_t r, T* dst) {
                std::copy(in.begin() + r * cols, in.begin() + (r + 1) * cols, dst);
            };
            T* dst = out.data() + r0 * cols;
            if (want_min)
                min_filter_rows(rows, cols, kx, ky, r0, r1, load, dst, s.ws);
            else
                max_filter_rows(rows, cols, kx, ky, r0, r1, load, dst, s.ws);
        },
        {}, "test");
    return out;
}

/// Equal cell by cell (bitwise for floats, so NaN and the sign of zero count).
template <class T>
bool same(const std::vector<T>& a, const std::vector<T>& b)
{
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i) {
        if constexpr (std::is_floating_point_v<T>) {
            if (std::isnan(a[i]) != std::isnan(b[i])) return false;
            if (!std::isnan(a[i]) && a[i] != b[i]) return false;
        } else {
            if (a[i] != b[i]) return false;
        }
    }
    return true;
}

std::vector<float> random_floats(std::mt19937& rng, std::size_t n, double nan_share)
{
    std::uniform_real_distribution<float> value(-50.0f, 50.0f);
    std::uniform_real_distribution<double> u(0, 1);
    std::vector<float> v(n);
    for (auto& x : v) {
        const double p = u(rng);
        x = p < nan_share ? std::numeric_limits<float>::quiet_NaN() : (p < nan_share + 0.02 ? -0.0f : value(rng));
    }
    return v;
}

}  // namespace

TEST_CASE("filter/min_filter_rows: matches brute force on random rasters with NaN, any strip and thread count")
{
    const unsigned seed = 20261204;
    std::mt19937 rng(seed);
    for (int trial = 0; trial < 50; ++trial) {
        std::uniform_int_distribution<int> size(1, 40), radius(0, 6);
        const std::ptrdiff_t rows = size(rng), cols = size(rng), kx = radius(rng), ky = radius(rng);
        const auto in = random_floats(rng, static_cast<std::size_t>(rows * cols), trial % 5 == 0 ? 0.9 : 0.2);
        const std::ptrdiff_t strip = 1 + trial % 7;
        const int threads = trial % 3;
        INFO("seed " << seed << " trial " << trial << ": " << rows << "x" << cols << " kx " << kx << " ky " << ky
                     << " strip " << strip << " threads " << threads);
        CHECK(same(filtered(in, rows, cols, kx, ky, true, strip, threads), brute(in, rows, cols, kx, ky, true)));
        CHECK(same(filtered(in, rows, cols, kx, ky, false, strip, threads), brute(in, rows, cols, kx, ky, false)));
    }
}

TEST_CASE("filter/max_filter_rows: integers, 1-wide and 1-tall rasters, windows wider than the raster")
{
    std::mt19937 rng(7);
    std::uniform_int_distribution<int> value(0, 65535);
    for (const auto& shape : {std::pair<std::ptrdiff_t, std::ptrdiff_t>{1, 1}, {1, 17}, {23, 1}, {5, 3}}) {
        const std::ptrdiff_t rows = shape.first, cols = shape.second;  // (INFO's lambda cannot capture a binding)
        std::vector<std::uint16_t> in(static_cast<std::size_t>(rows * cols));
        for (auto& x : in) x = static_cast<std::uint16_t>(value(rng));
        for (const std::ptrdiff_t k : {0, 1, 2, 3, 9, 40}) {
            INFO(rows << "x" << cols << " radius " << k);
            CHECK(same(filtered(in, rows, cols, k, k, false, 4, 1), brute(in, rows, cols, k, k, false)));
            CHECK(same(filtered(in, rows, cols, k, 0, true, 2, 2), brute(in, rows, cols, k, 0, true)));
            CHECK(same(filtered(in, rows, cols, 0, k, true, 3, 0), brute(in, rows, cols, 0, k, true)));
        }
    }
}

TEST_CASE("filter/min_filter_rows: all-NaN windows give the neutral; infinities are values; empty strips write nothing")
{
    constexpr float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    const std::vector<float> in = {nan, nan, nan, -inf, nan, nan, nan, nan, inf};  // 3 x 3
    min_max_workspace<float> ws;
    const auto load = [&](std::ptrdiff_t r, float* dst) { std::copy(in.begin() + 3 * r, in.begin() + 3 * r + 3, dst); };
    std::vector<float> lo(9), hi(9);
    min_filter_rows(3, 3, 0, 0, 0, 3, load, lo.data(), ws);
    max_filter_rows(3, 3, 0, 0, 0, 3, load, hi.data(), ws);
    CHECK(lo[0] == inf);   // NaN only: the neutral of min
    CHECK(hi[0] == -inf);  // and of max
    CHECK(lo[3] == -inf);
    CHECK(hi[8] == inf);
    min_filter_rows(3, 3, 1, 1, 0, 3, load, lo.data(), ws);
    CHECK(lo[4] == -inf);
    std::vector<float> untouched(3, 42.0f);
    min_filter_rows(3, 3, 1, 1, 2, 2, load, untouched.data(), ws);  // r0 == r1: no row
    CHECK(untouched == std::vector<float>(3, 42.0f));
}

TEST_CASE("filter/for_each_row_strip: every row once, in strips of the given size; min_max_strip_rows in range")
{
    for (const std::ptrdiff_t rows : {0, 1, 7, 100, 1000}) {
        for (const std::ptrdiff_t strip : {1, 3, 64}) {
            std::vector<std::atomic<int>> seen(static_cast<std::size_t>(rows));
            std::atomic<bool> sized = true;
            struct scratch {};
            for_each_row_strip<scratch>(
                rows, strip, 2,
                [&](std::ptrdiff_t r0, std::ptrdiff_t r1, scratch&) {
                    if (r0 % strip != 0 || r1 - r0 > strip || r1 <= r0) sized = false;
                    for (std::ptrdiff_t r = r0; r < r1; ++r) ++seen[static_cast<std::size_t>(r)];
                },
                {}, "test");
            CHECK(sized);
            CHECK(std::all_of(seen.begin(), seen.end(), [](const std::atomic<int>& n) { return n == 1; }));
        }
        for (const std::ptrdiff_t cols : {1, 100, 100000}) {
            for (const std::ptrdiff_t radius : {0, 1, 50}) {
                const auto s = min_max_strip_rows(rows, cols, radius);
                CHECK(s >= 1);
                CHECK(s <= std::max<std::ptrdiff_t>(rows, 1));
            }
        }
    }
}
