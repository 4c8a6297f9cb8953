// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include <lidarfx/kernels/filter/morphology.hpp>

#include "reference/morphology.hpp"
#include "reference/progress.hpp"

#include <array>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

using namespace lidarfx;

namespace {

enum class op { dilate, erode, open, close };
constexpr std::array<op, 4> all_ops{op::dilate, op::erode, op::open, op::close};

const char* name(op o)
{
    switch (o) {
        case op::dilate:
            return "dilate";
        case op::erode:
            return "erode";
        case op::open:
            return "open";
        default:
            return "close";
    }
}

template <class In>
raster<std::uint8_t> run(op o, const In& m, const morphology_options& opt)
{
    switch (o) {
        case op::dilate:
            return morph_dilate(m, opt);
        case op::erode:
            return morph_erode(m, opt);
        case op::open:
            return morph_open(m, opt);
        default:
            return morph_close(m, opt);
    }
}

template <class View>
reference::mask brute(op o, const View& m, const morphology_options& opt)
{
    const int h = opt.height_cells == 0 ? opt.size_cells : opt.height_cells;
    switch (o) {
        case op::dilate:
            return reference::dilate(m, opt.size_cells, h);
        case op::erode:
            return reference::erode(m, opt.size_cells, h);
        case op::open:
            return reference::open(m, opt.size_cells, h);
        default:
            return reference::close(m, opt.size_cells, h);
    }
}

bool is_subset(const reference::mask& a, const reference::mask& b)  // a <= b cell by cell
{
    for (std::ptrdiff_t i = 0; i < a.size(); ++i)
        if (a.data()[i] > b.data()[i]) return false;
    return true;
}

// A host mask type without contiguous rows (read through one copy by the kernels).
struct computed_mask {
    using value_type = int;
    std::ptrdiff_t rows() const { return 9; }
    std::ptrdiff_t cols() const { return 11; }
    int operator()(std::ptrdiff_t r, std::ptrdiff_t c) const { return (r * 7 + c * 3) % 5 == 0 ? 3 : 0; }
};

}  // namespace

// The plain spellings the library promises compile and agree with each other.
TEST_CASE("filter/morph_open: the design's plain spellings compile")
{
    std::mt19937 rng(11);
    const auto m = reference::random_mask(rng, 20, 30, 0.6);
    const raster_view<const std::uint8_t> v = m;
    CHECK(morph_open(v, 5) == morph_open(m, 5));
    CHECK(morph_close(v, 3) == morph_close(m, morphology_options{.size_cells = 3}));
    CHECK(morph_dilate(v, 1) == morph_dilate(m, 1));
    CHECK(morph_erode(v, 7) == morph_erode(m, 7));
    raster<std::uint8_t> out(20, 30);
    morph_open(v, out, {.size_cells = 5});
    CHECK(out == morph_open(v, 5));
    morph_open(m, out.view(), {.size_cells = 3, .height_cells = 5});
    CHECK(out == reference::open(m, 3, 5));
}

TEST_CASE("filter/morph_dilate: hand-checked cases, with the border clipped")
{
    reference::mask dot(5, 6);
    dot(2, 2) = 1;
    const auto d = morph_dilate(dot, 3);
    for (std::ptrdiff_t r = 0; r < 5; ++r)
        for (std::ptrdiff_t c = 0; c < 6; ++c) CHECK(d(r, c) == ((r >= 1 && r <= 3 && c >= 1 && c <= 3) ? 1 : 0));

    reference::mask corner(4, 4);
    corner(0, 0) = 9;  // nonzero counts as 1; output is 0/1
    const auto dc = morph_dilate(corner, morphology_options{.size_cells = 3, .height_cells = 5});
    const reference::mask expected_corner = [] {
        reference::mask e(4, 4);
        for (std::ptrdiff_t r = 0; r <= 2; ++r)
            for (std::ptrdiff_t c = 0; c <= 1; ++c) e(r, c) = 1;
        return e;
    }();
    CHECK(dc == expected_corner);

    CHECK(morph_dilate(reference::mask(7, 13, 0), 25) == reference::mask(7, 13, 0));
    CHECK(morph_dilate(reference::mask(1, 1, 4), 5) == reference::mask(1, 1, 1));
    CHECK(morph_dilate(reference::mask(0, 5), 5).rows() == 0);
}

TEST_CASE("filter/morph_erode: cells outside the raster are ignored, not zero")
{
    CHECK(morph_erode(reference::mask(7, 13, 1), 25) == reference::mask(7, 13, 1));
    CHECK(morph_erode(reference::mask(65, 64, 200), 5) == reference::mask(65, 64, 1));
    reference::mask hole(5, 5, 1);
    hole(4, 4) = 0;
    const auto e = morph_erode(hole, 3);
    for (std::ptrdiff_t r = 0; r < 5; ++r)
        for (std::ptrdiff_t c = 0; c < 5; ++c) CHECK(e(r, c) == ((r >= 3 && c >= 3) ? 0 : 1));
}

TEST_CASE("filter/morphology: all four operations match the brute-force window min/max")
{
    const unsigned seed = 20240611;
    std::mt19937 rng(seed);
    INFO("seed " << seed);
    struct shape {
        std::ptrdiff_t rows, cols;
    };
    const std::vector<shape> shapes{{1, 1}, {1, 200}, {150, 1}, {7, 13}, {65, 64}, {64, 65}, {63, 127}, {257, 131}};
    const std::vector<std::array<int, 2>> elements{{1, 0}, {3, 0},  {5, 0},  {7, 0},   {25, 0},
                                                   {3, 7}, {25, 1}, {1, 25}, {131, 3}, {5, 151}};
    int trial = 0;
    for (const auto& s : shapes) {
        for (double density : {0.02, 0.1, 0.5, 0.9, 0.98}) {
            const auto m = reference::random_mask(rng, s.rows, s.cols, density);
            for (const auto& e : elements) {
                // The brute force costs cells * window: on the largest raster test a rotating subset.
                if (s.rows * s.cols > 10000 && (trial++ % 4) != 0) continue;
                const morphology_options opt{.size_cells = e[0], .height_cells = e[1]};
                for (op o : all_ops) {
                    INFO(name(o) << " " << s.rows << "x" << s.cols << " density " << density << " size " << e[0]
                                 << " height " << e[1]);
                    CHECK(run(o, m, opt) == brute(o, m, opt));
                }
            }
        }
    }
}

TEST_CASE("filter/morphology: wide windows place single cells and single holes exactly")
{
    // Random masks say little about wide windows (dilation fills, erosion empties): move one cell
    // across word boundaries instead.
    for (std::ptrdiff_t cols : {64, 130, 200}) {
        for (std::ptrdiff_t at : {std::ptrdiff_t{0}, std::ptrdiff_t{1}, std::ptrdiff_t{63}, cols / 2 + 1, cols - 1}) {
            reference::mask dot(5, cols, 0), hole(5, cols, 1);
            dot(2, at) = 1;
            hole(2, at) = 0;
            for (int size : {63, 65, 127, 129, 151}) {
                const morphology_options opt{.size_cells = size, .height_cells = 3};
                INFO(cols << " columns, cell " << at << ", size " << size);
                CHECK(morph_dilate(dot, opt) == reference::dilate(dot, size, 3));
                CHECK(morph_erode(hole, opt) == reference::erode(hole, size, 3));
                const morphology_options tall{.size_cells = 3, .height_cells = size};
                const auto column = reference::mask(raster_view<const std::uint8_t>(dot.data(), cols, 5));
                CHECK(morph_dilate(column, tall) == reference::dilate(column, 3, size));
            }
        }
    }
}

TEST_CASE("filter/morphology: all-0, all-1 and checkerboard masks")
{
    for (const auto& shape : std::vector<std::array<std::ptrdiff_t, 2>>{{1, 1}, {7, 13}, {63, 127}, {64, 65}}) {
        const std::ptrdiff_t rows = shape[0], cols = shape[1];
        for (int size : {1, 3, 25}) {
            const morphology_options opt{.size_cells = size};
            const reference::mask zeros(rows, cols, 0), ones(rows, cols, 1);
            for (op o : all_ops) {
                INFO(name(o) << " " << rows << "x" << cols << " size " << size);
                CHECK(run(o, zeros, opt) == zeros);
                CHECK(run(o, ones, opt) == ones);
                for (std::ptrdiff_t cell : {1, 2, 3}) {
                    const auto board = reference::checkerboard(rows, cols, cell);
                    CHECK(run(o, board, opt) == brute(o, board, opt));
                }
            }
        }
    }
}

TEST_CASE("filter/morphology: strided sub-views give the contiguous result")
{
    std::mt19937 rng(7);
    for (int trial = 0; trial < 12; ++trial) {
        const std::ptrdiff_t rows = 1 + trial * 11, cols = 1 + trial * 13;
        const auto m = reference::random_mask(rng, rows, cols, 0.5);
        const morphology_options opt{.size_cells = 1 + 2 * (trial % 4), .height_cells = trial % 3 == 0 ? 0 : 3};
        for (std::uint8_t fill : {std::uint8_t{0}, std::uint8_t{1}}) {  // cells around the view must not leak in
            const auto e = reference::embed(m, 3, 2 + trial % 5, fill);
            REQUIRE(e.view.row_stride() > e.view.cols());
            for (op o : all_ops) {
                INFO(name(o) << " trial " << trial << " fill " << int(fill));
                CHECK(run(o, e.view, opt) == run(o, m, opt));
            }
        }
    }
}

TEST_CASE("filter/morphology: results are identical for 1, 2 and 3 threads")
{
    std::mt19937 rng(99);
    const auto m = reference::random_mask(rng, 301, 263, 0.5);
    for (const auto& e : std::vector<std::array<int, 2>>{{5, 0}, {25, 0}, {3, 9}}) {
        const morphology_options one{.size_cells = e[0], .height_cells = e[1], .run = {.threads = 1}};
        for (op o : all_ops) {
            const auto expected = run(o, m, one);
            CHECK(expected == brute(o, m, one));
            for (int threads : {2, 3}) {
                INFO(name(o) << " size " << e[0] << " height " << e[1] << " threads " << threads);
                const morphology_options opt{.size_cells = e[0], .height_cells = e[1], .run = {.threads = threads}};
                CHECK(run(o, m, opt) == expected);
            }
        }
    }
}

TEST_CASE("filter/morphology: progress is monotone and ends at 1; returning false cancels")
{
    std::mt19937 rng(41);
    const auto m = reference::random_mask(rng, 700, 90, 0.5);  // three strips of rows
    for (op o : all_ops) {
        for (int threads : {1, 2}) {
            INFO(name(o) << " threads " << threads);
            const reference::progress_log log;
            const auto out = run(o, m, {.size_cells = 5, .run = {.threads = threads, .progress = log.callback()}});
            CHECK(log.monotone_to_one(threads == 1 ? 3 : 1));  // with helpers, the caller may run few strips
            CHECK(out == run(o, m, {.size_cells = 5}));
            CHECK_THROWS_WITH_AS(
                run(o, m, {.size_cells = 5, .run = {.threads = threads, .progress = reference::cancel_at_once()}}),
                (std::string("morph_") + name(o) + ": cancelled").c_str(), cancelled);
        }
    }
    const reference::progress_log empty;  // nothing to do is done at once
    morph_open(reference::mask(0, 4), morphology_options{.run = {.progress = empty.callback()}});
    CHECK(empty.monotone_to_one());
}

TEST_CASE("filter/morphology: opening and closing are (anti-)extensive, idempotent and dual")
{
    std::mt19937 rng(5);
    for (int trial = 0; trial < 20; ++trial) {
        const auto m = reference::complement(reference::complement(
            reference::random_mask(rng, 20 + trial, 70 - trial, 0.2 + 0.03 * trial)));  // 0/1 values
        const morphology_options opt{.size_cells = 1 + 2 * (trial % 5), .height_cells = trial % 2 == 0 ? 0 : 5};
        INFO("trial " << trial);
        const auto opened = morph_open(m, opt), closed = morph_close(m, opt);
        CHECK(is_subset(opened, m));
        CHECK(is_subset(m, closed));
        CHECK(morph_open(opened, opt) == opened);
        CHECK(morph_close(closed, opt) == closed);
        // With the clipped border the dualities hold on every cell, borders included.
        const auto inverse = reference::complement(m);
        CHECK(morph_dilate(m, opt) == reference::complement(morph_erode(inverse, opt)));
        CHECK(opened == reference::complement(morph_close(inverse, opt)));
        CHECK(is_subset(morph_erode(m, opt), opened));
        CHECK(is_subset(closed, morph_dilate(m, opt)));
    }
}

TEST_CASE("filter/morph_open: the output may be the input; other value types and host types work")
{
    std::mt19937 rng(3);
    auto m = reference::random_mask(rng, 70, 90, 0.7);
    const auto expected = morph_open(m, 5);
    morph_open(m, m, {.size_cells = 5});
    CHECK(m == expected);
    // Tall enough for several strips of rows, each reading rows of the next: in place still works.
    // (Dilation, not opening or closing: those are idempotent, so mixing in already processed rows would
    // not show.)
    const auto tall_input = reference::random_mask(rng, 700, 40, 0.05);
    const auto tall_expected = morph_dilate(tall_input, morphology_options{.size_cells = 3, .height_cells = 9});
    for (int threads : {1, 2}) {
        auto tall = tall_input;
        morph_dilate(tall, tall.view(), {.size_cells = 3, .height_cells = 9, .run = {.threads = threads}});
        CHECK(tall == tall_expected);
    }

    raster<float> f(70, 90);
    for (std::ptrdiff_t r = 0; r < 70; ++r)
        for (std::ptrdiff_t c = 0; c < 90; ++c) f(r, c) = expected(r, c) != 0 ? 0.25f : 0.0f;
    CHECK(morph_close(f, 3) == morph_close(expected, 3));

    const computed_mask host;
    CHECK(morph_dilate(host, morphology_options{.size_cells = 3}) == reference::dilate(host, 3, 3));
}

TEST_CASE("filter/morphology: bad input throws invalid_input naming the argument")
{
    const reference::mask m(4, 5, 1);
    CHECK_THROWS_WITH_AS(morph_open(m, 4), "morph_open: size_cells must be odd and >= 1 (got 4)", invalid_input);
    CHECK_THROWS_WITH_AS(morph_close(m, 0), "morph_close: size_cells must be odd and >= 1 (got 0)", invalid_input);
    CHECK_THROWS_WITH_AS(morph_dilate(m, -3), "morph_dilate: size_cells must be odd and >= 1 (got -3)", invalid_input);
    CHECK_THROWS_WITH_AS(morph_erode(m, morphology_options{.size_cells = 3, .height_cells = 2}),
                         "morph_erode: height_cells must be 0 (square) or odd and >= 1 (got 2)", invalid_input);
    CHECK_THROWS_WITH_AS(morph_erode(m, morphology_options{.size_cells = 3, .height_cells = -1}),
                         "morph_erode: height_cells must be 0 (square) or odd and >= 1 (got -1)", invalid_input);
    CHECK_THROWS_WITH_AS(morph_open(m, morphology_options{.size_cells = 3, .run = {.threads = -1}}),
                         "morph_open: run.threads must be >= 0 (got -1)", invalid_input);
    raster<std::uint8_t> wrong(5, 4);
    CHECK_THROWS_WITH_AS(morph_close(m, wrong, {.size_cells = 3}),
                         "morph_close: m and out must have the same shape (got 4x5 and 5x4)", invalid_input);
}
