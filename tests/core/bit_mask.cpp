// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include <lidarfx/core/bit_mask.hpp>

#include <cstdint>
#include <random>
#include <vector>

using namespace lidarfx;

TEST_CASE("core/bit_mask: packing, SIMD and portable, keeps every cell")
{
    std::mt19937 rng(13);
    std::uniform_int_distribution<int> byte(0, 255), coin(0, 2);
    for (std::ptrdiff_t cols : {1, 63, 64, 65, 200}) {
        std::vector<std::uint8_t> cells(static_cast<std::size_t>(cols));
        for (auto& v : cells) v = coin(rng) == 0 ? 0 : static_cast<std::uint8_t>(byte(rng));  // 0 and any nonzero
        std::vector<detail::mask_word> bits(static_cast<std::size_t>(detail::mask_words(cols)));
        detail::pack_mask_row(cells.data(), cols, bits.data());
        for (std::ptrdiff_t c = 0; c < cols; ++c) CHECK(((bits[c / 64] >> (c % 64)) & 1U) == (cells[c] != 0 ? 1U : 0U));
        for (std::ptrdiff_t c = cols; c < 64 * detail::mask_words(cols); ++c)
            CHECK(((bits[c / 64] >> (c % 64)) & 1U) == 0U);
        for (std::ptrdiff_t c = 0; c + 64 <= cols; c += 64)
            CHECK(detail::pack64_portable(cells.data() + c) == bits[c / 64]);
        std::vector<std::uint8_t> back(static_cast<std::size_t>(cols));
        detail::unpack_mask_row(bits.data(), cols, back.data());
        for (std::ptrdiff_t c = 0; c < cols; ++c) CHECK(back[c] == (cells[c] != 0 ? 1 : 0));
    }
}

TEST_CASE("core/bit_mask: bits_from reads 64 bits at any offset")
{
    std::mt19937_64 rng(7);
    std::vector<detail::mask_word> a(4);
    for (auto& w : a) w = rng();
    const auto bit = [&](std::ptrdiff_t i) { return (a[static_cast<std::size_t>(i / 64)] >> (i % 64)) & 1U; };
    for (std::ptrdiff_t q = 0; q < 3; ++q) {
        for (int s = 0; s < 64; ++s) {
            const detail::mask_word got = detail::bits_from(a.data(), q, s);
            for (int j = 0; j < 64; ++j) REQUIRE(((got >> j) & 1U) == bit(64 * q + s + j));
        }
    }
}
