// SPDX-License-Identifier: Apache-2.0
// Masks packed to bits: 64 cells per word, for the kernels that work on whole words (morphology, labelling).
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <type_traits>
#include <vector>

#if defined(__SSE2__) || defined(__AVX2__)
#include <immintrin.h>
#endif

namespace lidarfx::detail {

using mask_word = std::uint64_t;

/// Number of 64-bit words holding `cols` bits.
constexpr std::ptrdiff_t mask_words(std::ptrdiff_t cols) noexcept
{
    return (cols + 63) / 64;
}

/// Bits of 64 one-byte cells (bit j = cell j is nonzero), without SIMD: 8 cells at a time, flag the
/// nonzero bytes in their low bit, then gather the 8 flags into the top byte with one multiplication
/// (no two partial products share a bit).
template <class T>
mask_word pack64_portable(const T* src) noexcept
{
    static_assert(sizeof(T) == 1);
    mask_word bits = 0;
    for (int q = 0; q < 8; ++q) {
        std::uint64_t v;
        std::memcpy(&v, src + 8 * q, 8);
        const std::uint64_t low7 = 0x7f7f7f7f7f7f7f7fULL;
        const std::uint64_t flags = ((((v & low7) + low7) | v) >> 7) & 0x0101010101010101ULL;
        bits |= ((flags * 0x0102040810204080ULL) >> 56) << (8 * q);
    }
    return bits;
}

/// Packs a row of `cols` cells into bits (bit j of word w = cell 64w + j is nonzero); bits past `cols`
/// in the last word are 0.
template <class T>
void pack_mask_row(const T* src, std::ptrdiff_t cols, mask_word* dst) noexcept
{
    std::ptrdiff_t c = 0, w = 0;
    if constexpr (sizeof(T) == 1 && std::is_integral_v<T>) {
        for (; c + 64 <= cols; c += 64, ++w) {
#if defined(__AVX2__)
            const __m256i zero = _mm256_setzero_si256();
            const auto lo = static_cast<std::uint32_t>(_mm256_movemask_epi8(
                _mm256_cmpeq_epi8(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(src + c)), zero)));
            const auto hi = static_cast<std::uint32_t>(_mm256_movemask_epi8(
                _mm256_cmpeq_epi8(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(src + c + 32)), zero)));
            dst[w] = ~(mask_word{lo} | (mask_word{hi} << 32));
#elif defined(__SSE2__)
            const __m128i zero = _mm_setzero_si128();
            mask_word zeros = 0;
            for (int q = 0; q < 4; ++q) {
                const __m128i v = _mm_loadu_si128(reinterpret_cast<const __m128i*>(src + c + 16 * q));
                zeros |= mask_word{static_cast<std::uint16_t>(_mm_movemask_epi8(_mm_cmpeq_epi8(v, zero)))} << (16 * q);
            }
            dst[w] = ~zeros;
#else
            dst[w] = pack64_portable(src + c);
#endif
        }
    }
    for (; c < cols; c += 64, ++w) {
        mask_word bits = 0;
        const std::ptrdiff_t n = std::min<std::ptrdiff_t>(64, cols - c);
        for (std::ptrdiff_t j = 0; j < n; ++j) bits |= mask_word{src[c + j] != T{}} << j;
        dst[w] = bits;
    }
}

/// Writes the first `cols` bits of `src` as 0/1 bytes.
inline void unpack_mask_row(const mask_word* src, std::ptrdiff_t cols, std::uint8_t* dst) noexcept
{
    std::ptrdiff_t c = 0;
#if defined(__AVX2__)
    // 32 bits -> 32 bytes: byte i takes source byte i/8, keeps bit i%8, and becomes 0 or 1.
    const __m256i spread = _mm256_setr_epi8(0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 1, 1, 1, 1,  //
                                            2, 2, 2, 2, 2, 2, 2, 2, 3, 3, 3, 3, 3, 3, 3, 3);
    const __m256i select = _mm256_set1_epi64x(static_cast<long long>(0x8040201008040201ULL));
    const __m256i one = _mm256_set1_epi8(1);
    for (; c + 32 <= cols; c += 32) {
        const auto bits = static_cast<int>(static_cast<std::uint32_t>(src[c / 64] >> (c % 64)));
        __m256i v = _mm256_shuffle_epi8(_mm256_set1_epi32(bits), spread);
        v = _mm256_and_si256(_mm256_cmpeq_epi8(_mm256_and_si256(v, select), select), one);
        _mm256_storeu_si256(reinterpret_cast<__m256i*>(dst + c), v);
    }
#endif
    // Portable: replicate 8 bits into 8 bytes, keep bit i in byte i, and turn each nonzero byte into 1.
    for (; c + 8 <= cols; c += 8) {
        const std::uint64_t byte = (src[c / 64] >> (c % 64)) & 0xffU;
        const std::uint64_t kept = (byte * 0x0101010101010101ULL) & 0x8040201008040201ULL;
        const std::uint64_t v = ((kept + 0x7f7f7f7f7f7f7f7fULL) >> 7) & 0x0101010101010101ULL;
        std::memcpy(dst + c, &v, 8);
    }
    for (; c < cols; ++c) dst[c] = static_cast<std::uint8_t>((src[c / 64] >> (c % 64)) & 1U);
}

/// 64 bits of `a` starting at bit 64 * q + s (0 <= s < 64); reads a[q] and a[q + 1].
inline mask_word bits_from(const mask_word* a, std::ptrdiff_t q, int s) noexcept
{
    return (a[q] >> s) | ((a[q + 1] << 1) << (63 - s));  // the split shift is 0 for s = 0, never UB
}

/// Bit rows of a mask: `rows` rows of `words` words each, contiguous.
struct bit_rows {
    std::ptrdiff_t rows = 0, words = 0;
    std::vector<mask_word> bits;
    void resize(std::ptrdiff_t r, std::ptrdiff_t w)
    {
        rows = r;
        words = w;
        bits.resize(static_cast<std::size_t>(r * w));
    }
    mask_word* row(std::ptrdiff_t r) noexcept { return bits.data() + r * words; }
    const mask_word* row(std::ptrdiff_t r) const noexcept { return bits.data() + r * words; }
};

}  // namespace lidarfx::detail
