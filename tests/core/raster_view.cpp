// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include <lidarfx/core/raster.hpp>
#include <lidarfx/core/raster_view.hpp>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <numeric>
#include <random>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

using namespace lidarfx;

namespace {

// A host image type that is not lidarfx's: models strided_raster (like a wrapped cv::Mat or GDAL buffer).
struct host_image {
    using value_type = float;
    float* pixels;
    int height, width, step;  // step in elements
    std::ptrdiff_t rows() const { return height; }
    std::ptrdiff_t cols() const { return width; }
    std::ptrdiff_t row_stride() const { return step; }
    const float* data() const { return pixels; }
    float& operator()(std::ptrdiff_t r, std::ptrdiff_t c) const { return pixels[r * step + c]; }
};

// Indexable but without contiguous rows (e.g. a tiled host raster): accepted, read through a copy.
struct computed_raster {
    using value_type = int;
    std::ptrdiff_t rows() const { return 3; }
    std::ptrdiff_t cols() const { return 2; }
    int operator()(std::ptrdiff_t r, std::ptrdiff_t c) const { return static_cast<int>(10 * r + c); }
};

// Writable but not strided: results go through a scratch raster.
struct int_sink {
    using value_type = int;
    int* p;
    std::ptrdiff_t rows() const { return 3; }
    std::ptrdiff_t cols() const { return 3; }
    int& operator()(std::ptrdiff_t r, std::ptrdiff_t c) const { return p[r * 4 + c]; }
};

struct no_value_type {
    std::ptrdiff_t rows() const { return 1; }
    std::ptrdiff_t cols() const { return 1; }
    float operator()(std::ptrdiff_t, std::ptrdiff_t) const { return 0; }
};

}  // namespace

static_assert(raster_input<raster<float>>);
static_assert(raster_input<raster_view<const float>>);
static_assert(raster_input<host_image>);
static_assert(raster_input<computed_raster>);
static_assert(!raster_input<no_value_type>);
static_assert(!raster_input<std::vector<float>>);
static_assert(strided_raster<host_image>);
static_assert(!strided_raster<computed_raster>);
static_assert(raster_output_of<raster_view<float>, float>);
static_assert(raster_output_of<raster<float>&, float>);
static_assert(!raster_output_of<raster_view<const float>, float>);
static_assert(!raster_output_of<computed_raster, int>);
// Constness lives in the element type: a const view converts from a mutable one, never the reverse.
static_assert(std::is_convertible_v<raster_view<float>, raster_view<const float>>);
static_assert(!std::is_convertible_v<raster_view<const float>, raster_view<float>>);
static_assert(std::is_convertible_v<raster<float>&, raster_view<float>>);
static_assert(std::is_convertible_v<const raster<float>&, raster_view<const float>>);
static_assert(!std::is_convertible_v<const raster<float>&, raster_view<float>>);
static_assert(std::is_trivially_copyable_v<raster_view<float>>);

TEST_CASE("core/raster: construction, fill and indexing are row-major")
{
    raster<int> r(2, 3, 7);
    CHECK(r.rows() == 2);
    CHECK(r.cols() == 3);
    CHECK(r.size() == 6);
    CHECK(r(1, 2) == 7);
    r(1, 0) = 5;
    CHECK(r.data()[3] == 5);
    CHECK(r.row(1)[0] == 5);
    raster<int> empty(0, 4);
    CHECK(empty.empty());
    CHECK_THROWS_WITH_AS(raster<int>(-1, 2), "raster: rows must be >= 0 (got -1)", invalid_input);
}

TEST_CASE("core/raster_view: strides and windows address the right cells")
{
    std::vector<int> buf(5 * 8);
    std::iota(buf.begin(), buf.end(), 0);
    raster_view<int> v(buf.data(), 5, 6, 8);  // two padding cells per row
    CHECK(v(0, 0) == 0);
    CHECK(v(1, 0) == 8);
    CHECK(v(4, 5) == 37);
    CHECK_FALSE(v.is_contiguous());

    auto w = v.window(1, 2, 3, 4);
    CHECK(w.rows() == 3);
    CHECK(w.cols() == 4);
    CHECK(w.row_stride() == 8);
    CHECK(w(0, 0) == 10);
    CHECK(w(2, 3) == 3 * 8 + 5);
    auto ww = w.window(1, 1, 1, 1);
    CHECK(ww(0, 0) == 19);
    ww(0, 0) = -1;
    CHECK(buf[19] == -1);

    CHECK(v.window(5, 6, 0, 0).empty());
    CHECK_THROWS_AS(v.window(4, 0, 2, 1), invalid_input);
    CHECK_THROWS_AS(v.window(-1, 0, 1, 1), invalid_input);
    CHECK_THROWS_WITH_AS(raster_view<int>(buf.data(), 2, 6, 5), "raster_view: row_stride must be >= cols (got 5)",
                         invalid_input);
    CHECK_THROWS_AS(raster_view<int>(nullptr, 2, 2), invalid_input);
    CHECK_NOTHROW(raster_view<int>(nullptr, 0, 0));
}

TEST_CASE("core/raster: sizes above max_raster_cells (2^40) are refused before anything is allocated")
{
    static_assert(max_raster_cells == std::int64_t{1} << 40);
    const std::ptrdiff_t big = std::ptrdiff_t{1} << 32, most = std::numeric_limits<std::ptrdiff_t>::max();
    CHECK_THROWS_WITH_AS(raster<float>(big, big),
                         "raster: rows x cols must be <= 2^40 cells (got 4294967296 x 4294967296)", invalid_input);
    CHECK_THROWS_AS(raster<float>(big, big, uninitialized), invalid_input);
    CHECK_THROWS_AS(raster<std::uint8_t>(most, most), invalid_input);  // rows * cols would overflow
    CHECK_THROWS_AS(raster<std::uint8_t>(2, most), invalid_input);
    // One extent alone is bounded too: an empty raster cannot carry an extent past the limit.
    CHECK_THROWS_WITH_AS(raster<float>(0, (std::ptrdiff_t{1} << 40) + 1),
                         "raster: rows x cols must be <= 2^40 cells (got 0 x 1099511627777)", invalid_input);
    CHECK_NOTHROW(raster<float>(std::ptrdiff_t{1} << 40, 0));
    CHECK(raster<float>(std::ptrdiff_t{1} << 40, 0).empty());
    CHECK_NOTHROW(raster<float>(1, 1));
    CHECK_NOTHROW(raster<float>(0, 0));
}

TEST_CASE("core/raster_view: sizes and strides that overflow are refused; the limit itself is accepted")
{
    std::uint8_t cell = 0;
    const std::ptrdiff_t m = std::ptrdiff_t{1} << 20, most = std::numeric_limits<std::ptrdiff_t>::max();
    // Views never touch memory on construction: a view of exactly 2^40 cells is fine, one more column is not.
    CHECK(raster_view<std::uint8_t>(&cell, m, m).size() == max_raster_cells);
    CHECK_THROWS_WITH_AS(raster_view<std::uint8_t>(&cell, m, m + 1),
                         "raster_view: rows x cols must be <= 2^40 cells (got 1048576 x 1048577)", invalid_input);
    CHECK_THROWS_AS(raster_view<std::uint8_t>(&cell, most, most, most), invalid_input);
    // Few cells, but a stride that addresses more bytes than a pointer can span.
    double d = 0;
    CHECK_THROWS_WITH_AS(raster_view<double>(&d, 3, 1, most / 4),
                         "raster_view: (rows - 1) * row_stride + cols cells must fit in the address space (got 3 rows, "
                         "row_stride 2305843009213693951)",
                         invalid_input);
    CHECK_NOTHROW(raster_view<double>(&d, 1, 1, most / 4));  // one row: the stride is never applied
    CHECK_NOTHROW(raster_view<double>(nullptr, 0, 5));
    CHECK_NOTHROW(raster_view<double>(nullptr, 5, 0));
    // Windows whose end would overflow are refused, not wrapped around.
    const raster_view<double> v(&d, 1, 1);
    CHECK_THROWS_AS(v.window(1, 0, most, 1), invalid_input);
    CHECK_THROWS_AS(v.window(0, 1, 1, most), invalid_input);
    CHECK_THROWS_AS(v.window(most, 0, 1, 1), invalid_input);
    CHECK(v.window(1, 1, 0, 0).empty());
}

TEST_CASE("core/raster_view: views of a raster share its cells; const views read them")
{
    raster<float> r(3, 3, 0.0f);
    raster_view<float> v = r;
    v(2, 1) = 4.0f;
    CHECK(r(2, 1) == 4.0f);
    const raster<float>& cr = r;
    raster_view<const float> cv = cr;
    CHECK(cv(2, 1) == 4.0f);
    CHECK(cv.data() == r.data());
    CHECK(v.as_const().row(2) == r.row(2));
}

TEST_CASE("core/raster_view: host types are viewed without copying, others are copied once")
{
    std::vector<float> pixels(4 * 10, 1.0f);
    host_image img{pixels.data(), 4, 7, 10};
    const auto v = view_of(img);
    CHECK(v.data() == pixels.data());
    CHECK(v.row_stride() == 10);
    detail::readable<host_image> read_img(img);
    CHECK(read_img.view().data() == pixels.data());

    detail::readable<computed_raster> read_computed{computed_raster{}};
    CHECK(read_computed.view().rows() == 3);
    CHECK(read_computed.view()(2, 1) == 21);

    raster<int> copy{computed_raster{}};
    CHECK(copy(1, 1) == 11);
}

TEST_CASE("core/raster: write_through writes into strided and non-strided outputs alike")
{
    const auto fill_diag = [](raster_view<int> out) {
        for (std::ptrdiff_t r = 0; r < out.rows(); ++r)
            for (std::ptrdiff_t c = 0; c < out.cols(); ++c) out(r, c) = r == c ? 1 : 0;
    };
    raster<int> direct(3, 3, 9);
    detail::write_through<int>(direct.view(), fill_diag);
    CHECK(direct(1, 1) == 1);
    CHECK(direct(0, 1) == 0);

    std::vector<int> pixels(3 * 4, -1);
    int_sink sink{pixels.data()};
    detail::write_through<int>(sink, fill_diag);
    CHECK(pixels[0] == 1);
    CHECK(pixels[1] == 0);
    CHECK(pixels[3] == -1);  // padding untouched
    CHECK(pixels[5] == 1);
}

TEST_CASE("core/raster: large rasters are 2 MiB aligned (huge pages) and behave like small ones")
{
    raster<std::int32_t> big(1100, 1000, 7);  // 4.4 MB: the huge-page path
    CHECK(reinterpret_cast<std::uintptr_t>(big.data()) % (std::size_t{2} << 20) == 0);
    CHECK(big(1099, 999) == 7);
    raster<std::int32_t> copy = big;
    copy(0, 0) = 1;
    CHECK(big(0, 0) == 7);
    CHECK(copy != big);
    big = raster<std::int32_t>(3, 3, 1);  // the large block is released through the same path
    CHECK(big.size() == 9);
}

TEST_CASE("core/raster: uninitialized rasters have the shape and take writes")
{
    raster<float> r(300, 700, uninitialized);  // large: the huge-page path
    CHECK(r.rows() == 300);
    CHECK(r.cols() == 700);
    r.fill(2.5f);
    CHECK(r(299, 699) == 2.5f);
    raster<std::int32_t> small(2, 3, uninitialized);
    small.fill(4);
    CHECK(small == raster<std::int32_t>(2, 3, 4));
    CHECK_THROWS_AS(raster<int>(-1, 3, uninitialized), invalid_input);
}

TEST_CASE("core/raster_view: cell_splitter splits linear indices exactly as / and % do")
{
    std::mt19937_64 rng(17);
    const std::ptrdiff_t limit = static_cast<std::ptrdiff_t>(lidarfx::max_raster_cells);
    const std::vector<std::ptrdiff_t> widths{
        1, 2, 3, 7, 1000, 4096, 4097, 65535, 1 << 20, 999'999'937, std::ptrdiff_t{1} << 39, limit - 1, limit};
    for (const std::ptrdiff_t cols : widths) {
        const lidarfx::detail::cell_splitter split(cols);
        const std::ptrdiff_t rows = std::max<std::ptrdiff_t>(1, limit / cols);
        std::vector<std::ptrdiff_t> probes{0, cols - 1, rows * cols - 1};
        for (std::ptrdiff_t r : {std::ptrdiff_t{1}, rows / 2, rows - 1})  // both sides of row starts
            for (std::ptrdiff_t d : {-1, 0, 1})
                if (const std::ptrdiff_t i = r * cols + d; i >= 0 && i < rows * cols) probes.push_back(i);
        std::uniform_int_distribution<std::ptrdiff_t> any(0, rows * cols - 1);
        for (int k = 0; k < 2000; ++k) probes.push_back(any(rng));
        for (const std::ptrdiff_t i : probes) {
            const auto [r, c] = split(i);
            REQUIRE(r == i / cols);
            REQUIRE(c == i % cols);
        }
    }
}

TEST_CASE("core/raster: a moved-from raster is empty, not a shape without cells")
{
    raster<int> a(3, 4, 7);
    raster<int> b(std::move(a));
    CHECK(b.rows() == 3);
    CHECK(b.cols() == 4);
    CHECK(b(2, 3) == 7);
    CHECK(a.rows() == 0);  // NOLINT(bugprone-use-after-move): the state after a move is what is tested
    CHECK(a.cols() == 0);
    CHECK(a.size() == 0);
    raster<int> c(2, 2, 1);
    c = std::move(b);
    CHECK(c.rows() == 3);
    CHECK(b.rows() == 0);  // NOLINT(bugprone-use-after-move)
    CHECK(b.view().empty());
    raster<int> d(2, 2, 5);
    auto& self = d;
    d = std::move(self);  // self-move leaves it whole
    CHECK(d.rows() == 2);
    CHECK(d(1, 1) == 5);
}
