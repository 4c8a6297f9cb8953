// SPDX-License-Identifier: Apache-2.0
#include "io/sha256.hpp"

#include <algorithm>
#include <cstdio>
#include <cstring>

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#include <cpuid.h>
#include <immintrin.h>
#define LIDARFX_SHA_EXTENSIONS 1
#endif

namespace lidarfx::io {

namespace {

constexpr std::array<std::uint32_t, 64> round_constants{
    0x428a2f98, 0x71374491, 0xb5c0fbcf, 0xe9b5dba5, 0x3956c25b, 0x59f111f1, 0x923f82a4, 0xab1c5ed5,
    0xd807aa98, 0x12835b01, 0x243185be, 0x550c7dc3, 0x72be5d74, 0x80deb1fe, 0x9bdc06a7, 0xc19bf174,
    0xe49b69c1, 0xefbe4786, 0x0fc19dc6, 0x240ca1cc, 0x2de92c6f, 0x4a7484aa, 0x5cb0a9dc, 0x76f988da,
    0x983e5152, 0xa831c66d, 0xb00327c8, 0xbf597fc7, 0xc6e00bf3, 0xd5a79147, 0x06ca6351, 0x14292967,
    0x27b70a85, 0x2e1b2138, 0x4d2c6dfc, 0x53380d13, 0x650a7354, 0x766a0abb, 0x81c2c92e, 0x92722c85,
    0xa2bfe8a1, 0xa81a664b, 0xc24b8b70, 0xc76c51a3, 0xd192e819, 0xd6990624, 0xf40e3585, 0x106aa070,
    0x19a4c116, 0x1e376c08, 0x2748774c, 0x34b0bcb5, 0x391c0cb3, 0x4ed8aa4a, 0x5b9cca4f, 0x682e6ff3,
    0x748f82ee, 0x78a5636f, 0x84c87814, 0x8cc70208, 0x90befffa, 0xa4506ceb, 0xbef9a3f7, 0xc67178f2};

std::uint32_t rotr(std::uint32_t x, int n)
{
    return (x >> n) | (x << (32 - n));
}

/// The portable compression of `count` 64-byte blocks into state h.
void compress_portable(std::array<std::uint32_t, 8>& state, const unsigned char* block, std::size_t count)
{
    for (; count > 0; --count, block += 64) {
        std::array<std::uint32_t, 64> w;  // every word is written below
        for (int i = 0; i < 16; ++i) {
            w[i] = (std::uint32_t{block[4 * i]} << 24) | (std::uint32_t{block[4 * i + 1]} << 16) |
                   (std::uint32_t{block[4 * i + 2]} << 8) | std::uint32_t{block[4 * i + 3]};
        }
        for (int i = 16; i < 64; ++i) {
            const std::uint32_t s0 = rotr(w[i - 15], 7) ^ rotr(w[i - 15], 18) ^ (w[i - 15] >> 3);
            const std::uint32_t s1 = rotr(w[i - 2], 17) ^ rotr(w[i - 2], 19) ^ (w[i - 2] >> 10);
            w[i] = w[i - 16] + s0 + w[i - 7] + s1;
        }
        auto [a, b, c, d, e, f, g, h] = state;
        for (int i = 0; i < 64; ++i) {
            const std::uint32_t t1 =
                h + (rotr(e, 6) ^ rotr(e, 11) ^ rotr(e, 25)) + ((e & f) ^ (~e & g)) + round_constants[i] + w[i];
            const std::uint32_t t2 = (rotr(a, 2) ^ rotr(a, 13) ^ rotr(a, 22)) + ((a & b) ^ (a & c) ^ (b & c));
            h = g;
            g = f;
            f = e;
            e = d + t1;
            d = c;
            c = b;
            b = a;
            a = t1 + t2;
        }
        const std::array<std::uint32_t, 8> add{a, b, c, d, e, f, g, h};
        for (std::size_t i = 0; i < 8; ++i) state[i] += add[i];
    }
}

#ifdef LIDARFX_SHA_EXTENSIONS
/// The same compression with the SHA extensions: the state as the register pairs ABEF and CDGH, four rounds per
/// step (two sha256rnds2), the message schedule by sha256msg1 and sha256msg2 (Intel's SHA extensions paper, 2013).
__attribute__((target("sha,sse4.1"))) void compress_extensions(std::array<std::uint32_t, 8>& state,
                                                               const unsigned char* block, std::size_t count)
{
    const __m128i byte_swap = _mm_set_epi64x(0x0c0d0e0f08090a0bLL, 0x0405060700010203LL);
    __m128i dcba = _mm_loadu_si128(reinterpret_cast<const __m128i*>(&state[0]));
    __m128i hgfe = _mm_loadu_si128(reinterpret_cast<const __m128i*>(&state[4]));
    const __m128i cdab = _mm_shuffle_epi32(dcba, 0xB1);
    const __m128i efgh = _mm_shuffle_epi32(hgfe, 0x1B);
    __m128i abef = _mm_alignr_epi8(cdab, efgh, 8);
    __m128i cdgh = _mm_blend_epi16(efgh, cdab, 0xF0);
    for (; count > 0; --count, block += 64) {
        const __m128i abef_before = abef, cdgh_before = cdgh;
        __m128i w[4];  // the last four groups of four message words
        for (int i = 0; i < 16; ++i) {
            __m128i& wi = w[i % 4];
            if (i < 4) {
                wi = _mm_shuffle_epi8(_mm_loadu_si128(reinterpret_cast<const __m128i*>(block + 16 * i)), byte_swap);
            } else {
                const __m128i w1 = w[(i + 3) % 4];  // group i - 1
                const __m128i w2 = w[(i + 2) % 4];  // group i - 2
                const __m128i w3 = w[(i + 1) % 4];  // group i - 3
                wi = _mm_sha256msg2_epu32(_mm_add_epi32(_mm_sha256msg1_epu32(wi, w3), _mm_alignr_epi8(w1, w2, 4)), w1);
            }
            __m128i msg = _mm_add_epi32(wi, _mm_loadu_si128(reinterpret_cast<const __m128i*>(&round_constants[4 * i])));
            cdgh = _mm_sha256rnds2_epu32(cdgh, abef, msg);
            msg = _mm_shuffle_epi32(msg, 0x0E);
            abef = _mm_sha256rnds2_epu32(abef, cdgh, msg);
        }
        abef = _mm_add_epi32(abef, abef_before);
        cdgh = _mm_add_epi32(cdgh, cdgh_before);
    }
    const __m128i feba = _mm_shuffle_epi32(abef, 0x1B);
    const __m128i dchg = _mm_shuffle_epi32(cdgh, 0xB1);
    dcba = _mm_blend_epi16(feba, dchg, 0xF0);
    hgfe = _mm_alignr_epi8(dchg, feba, 8);
    _mm_storeu_si128(reinterpret_cast<__m128i*>(&state[0]), dcba);
    _mm_storeu_si128(reinterpret_cast<__m128i*>(&state[4]), hgfe);
}
#endif

}  // namespace

bool sha256_extensions_available()
{
#ifdef LIDARFX_SHA_EXTENSIONS
    unsigned a = 0, b = 0, c = 0, d = 0;
    if (__get_cpuid(1, &a, &b, &c, &d) == 0) return false;
    const bool sse41 = (c & bit_SSE4_1) != 0, ssse3 = (c & bit_SSSE3) != 0;
    if (__get_cpuid_count(7, 0, &a, &b, &c, &d) == 0) return false;
    return sse41 && ssse3 && (b & (1u << 29)) != 0;  // CPUID.(EAX=7, ECX=0):EBX bit 29: SHA
#else
    return false;
#endif
}

sha256::sha256(sha256_engine engine) : extensions_(engine == sha256_engine::fastest && sha256_extensions_available()) {}

void sha256::compress(const unsigned char* blocks, std::size_t count)
{
#ifdef LIDARFX_SHA_EXTENSIONS
    if (extensions_) {
        compress_extensions(h_, blocks, count);
        return;
    }
#endif
    compress_portable(h_, blocks, count);
}

void sha256::add(const unsigned char* data, std::size_t n)
{
    bytes_ += n;
    if (used_ > 0) {  // complete the pending block first
        const std::size_t take = std::min(n, std::size_t{64} - used_);
        std::memcpy(block_.data() + used_, data, take);
        used_ += take;
        data += take;
        n -= take;
        if (used_ < 64) return;
        compress(block_.data(), 1);
        used_ = 0;
    }
    compress(data, n / 64);  // whole blocks straight from the input
    data += n / 64 * 64;
    n %= 64;
    std::memcpy(block_.data(), data, n);
    used_ = n;
}

std::string sha256::hex()
{
    const std::uint64_t bits = bytes_ * 8;
    const unsigned char one = 0x80, zero = 0;
    add(&one, 1);
    while (used_ != 56) add(&zero, 1);
    for (int i = 7; i >= 0; --i) {
        const auto b = static_cast<unsigned char>(bits >> (8 * i));
        add(&b, 1);
    }
    std::string out;
    char buf[9];
    for (const std::uint32_t v : h_) {
        std::snprintf(buf, sizeof buf, "%08x", static_cast<unsigned>(v));
        out += buf;
    }
    return out;
}

std::string sha256_hex(std::string_view data, sha256_engine engine)
{
    sha256 hash(engine);
    hash.add(reinterpret_cast<const unsigned char*>(data.data()), data.size());
    return hash.hex();
}

}  // namespace lidarfx::io
