// SPDX-License-Identifier: Apache-2.0
// rank_components_by_size and relabel_components against plain references.
#include <doctest/doctest.h>

#include <lidarfx/kernels/label/connected_components.hpp>

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <random>
#include <vector>

using namespace lidarfx;

namespace {

/// The plain definition: order labels 1..n by size, largest first, ties by label; rank = position + 1.
std::vector<std::int32_t> brute_ranks(const std::vector<std::size_t>& sizes)
{
    const std::size_t n = sizes.empty() ? 0 : sizes.size() - 1;
    std::vector<std::int32_t> rank(n + 1, 0);
    for (std::size_t l = 1; l <= n; ++l) {
        std::size_t before = 0;  // labels ranked ahead of l
        for (std::size_t m = 1; m <= n; ++m) before += sizes[m] > sizes[l] || (sizes[m] == sizes[l] && m < l);
        rank[l] = static_cast<std::int32_t>(before + 1);
    }
    return rank;
}

}  // namespace

TEST_CASE("label/rank_components_by_size: matches brute force on random sizes with ties")
{
    const unsigned seed = 4036;
    std::mt19937 rng(seed);
    for (int trial = 0; trial < 50; ++trial) {
        std::uniform_int_distribution<std::size_t> count(0, 60), size(1, trial % 2 ? 4 : 1000);
        std::vector<std::size_t> sizes(count(rng) + 1);
        for (auto& s : sizes) s = size(rng);
        INFO("seed " << seed << " trial " << trial);
        CHECK(rank_components_by_size(sizes) == brute_ranks(sizes));
    }
}

TEST_CASE("label/rank_components_by_size: empty, background only, equal sizes keep label order")
{
    CHECK(rank_components_by_size({}) == std::vector<std::int32_t>{0});
    CHECK(rank_components_by_size({17}) == std::vector<std::int32_t>{0});
    CHECK(rank_components_by_size({0, 5, 5, 5}) == std::vector<std::int32_t>{0, 1, 2, 3});
    CHECK(rank_components_by_size({9, 1, 3, 2}) == std::vector<std::int32_t>{0, 3, 1, 2});
}

TEST_CASE("label/relabel_components: matches a cell-by-cell map on random labels, strided views; <= 0 stay")
{
    const unsigned seed = 9117;
    std::mt19937 rng(seed);
    for (int trial = 0; trial < 50; ++trial) {
        std::uniform_int_distribution<int> dim(1, 30), label(-2, 12), run(1, 6);
        const std::ptrdiff_t rows = dim(rng), cols = dim(rng);
        raster<std::int32_t> big(rows + 2, cols + 3, 99);
        auto view = big.view().window(1, 2, rows, cols);  // row_stride > cols
        for (std::ptrdiff_t r = 0; r < rows; ++r)
            for (std::ptrdiff_t c = 0; c < cols;) {  // runs of one label, as components have
                const std::int32_t l = label(rng);
                for (int k = run(rng); k > 0 && c < cols; --k) view(r, c++) = l;
            }
        std::vector<std::int32_t> to(13);
        std::iota(to.begin(), to.end(), 100);
        std::shuffle(to.begin() + 1, to.end(), rng);
        raster<std::int32_t> expected(rows, cols);
        for (std::ptrdiff_t r = 0; r < rows; ++r)
            for (std::ptrdiff_t c = 0; c < cols; ++c)
                expected(r, c) = view(r, c) > 0 ? to[static_cast<std::size_t>(view(r, c))] : view(r, c);
        relabel_components(view, to);
        INFO("seed " << seed << " trial " << trial);
        bool equal = true, border = true;
        for (std::ptrdiff_t r = 0; r < rows; ++r)
            for (std::ptrdiff_t c = 0; c < cols; ++c) equal = equal && view(r, c) == expected(r, c);
        for (std::ptrdiff_t c = 0; c < big.cols(); ++c) border = border && big(0, c) == 99;
        CHECK(equal);
        CHECK(border);
    }
}

TEST_CASE("label/relabel_components: an empty raster and a 1-wide one")
{
    raster<std::int32_t> none(0, 0);
    relabel_components(none, {0});
    raster<std::int32_t> column(4, 1);
    column(0, 0) = 1;
    column(1, 0) = 0;
    column(2, 0) = 2;
    column(3, 0) = -1;
    relabel_components(column, {0, 2, 1});
    CHECK(column(0, 0) == 2);
    CHECK(column(1, 0) == 0);
    CHECK(column(2, 0) == 1);
    CHECK(column(3, 0) == -1);
}
