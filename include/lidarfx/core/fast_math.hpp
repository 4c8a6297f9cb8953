// SPDX-License-Identifier: Apache-2.0
// fast_math: branch-free elementary functions that let kernel loops vectorize on any x86-64 level (SSE2, AVX2,
// AVX-512) and on ARM64, without libm calls.
//
// Why: compilers vectorize a loop that calls std::atan / std::atan2 only where a vector libm is available and
// enabled (glibc's libmvec with -ffast-math), and keep a branch around std::sqrt for errno. They also refuse to
// if-convert a floating-point operation that sits under a condition unless the target has masked arithmetic
// (AVX-512 does, AVX2 and SSE do not): `c ? 90 - a : a` keeps an AVX2 loop scalar. So the functions here compute
// every term for every lane and select between finished values with bit masks (select_bits).
//
// Accuracy (tested against libm in double over dense sweeps of the whole domain, tests/core/fast_math.cpp):
//   fast_atan:      |error| <= 2e-7 rad (measured 1.7e-7), relative error <= 2e-7 for |x| <= 1
//   fast_atan2:     |error| <= 3e-7 rad (measured 2.6e-7), std::atan2's special cases (signed zeros, infinities)
//   atan_deg:       |error| <= 1e-5 degrees for x >= 0 (measured 8.2e-6)
//   sqrt_one_plus:  relative error <= 2e-7 on [0, 1] in float (measured 1.0e-7)
#pragma once

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <numbers>
#include <type_traits>
#include <utility>

/// Put before a loop whose stores never feed its own loads, such as a gather from a lookup table into a
/// raster: GCC then vectorizes the gather, which it otherwise refuses for a possible alias between the
/// two. Expands to nothing on compilers without such a hint.
#if defined(__clang__)
#define LIDARFX_IVDEP _Pragma("clang loop vectorize(assume_safety)")
#elif defined(__GNUC__)
#define LIDARFX_IVDEP _Pragma("GCC ivdep")
#else
#define LIDARFX_IVDEP
#endif

/// Put among the attributes of a hot kernel written to vectorize (`[[gnu::noinline, LIDARFX_VECTORIZE]]`):
/// GCC at -O2 (CMake's RelWithDebInfo, distributions' builds) keeps loops scalar that need an epilogue or
/// whose inner loops must be unrolled first; this asks for -O3's cost model and unrolling in that function
/// only (water_surface_slope's window: 750 -> 48 ms at 2048² and -O2, as at -O3; same results). Nothing on
/// other compilers (clang vectorizes such loops at -O2).
#if defined(__GNUC__) && !defined(__clang__)
#define LIDARFX_VECTORIZE gnu::optimize("vect-cost-model=dynamic", "unroll-loops")
#else
#define LIDARFX_VECTORIZE
#endif

namespace lidarfx::detail {

/// Polynomial c[0] x^(N-1) + c[1] x^(N-2) + ... + c[N-1] by Horner's scheme, p = p * x + c[i]; the loop is
/// unrolled, so kernel loops that call it still vectorize.
template <class T, std::size_t N>
constexpr T horner(T x, const T (&c)[N]) noexcept
{
    T p = c[0];
    for (std::size_t i = 1; i < N; ++i) p = p * x + c[i];
    return p;
}

/// atan(t) in radians for t in [-1, 1] (float): t P(t^2) with P a degree-8 minimax fit; relative error
/// <= 2e-7. Outside [-1, 1] the result is meaningless.
constexpr float atan_unit(float t) noexcept
{
    const float s = t * t;
    return t *
           horner(s, {0.0029035008046776056f, -0.01628280244767666f, 0.04303903877735138f, -0.07533648610115051f,
                      0.10654664784669876f, -0.14207130670547485f, 0.19993053376674652f, -0.3333309292793274f, 1.0f});
}

/// `c ? a : b` for two values already computed (float or double), as a bit mask: a plain select lets compilers
/// move the computation of the value not taken under a branch (jump threading), and the loop no longer
/// vectorizes on targets without masked arithmetic.
template <class T>
constexpr T select_bits(bool c, T a, T b) noexcept
{
    using bits = std::conditional_t<sizeof(T) == 4, std::uint32_t, std::uint64_t>;
    const bits m = c ? ~bits{0} : bits{0};
    return std::bit_cast<T>(static_cast<bits>((std::bit_cast<bits>(a) & m) | (std::bit_cast<bits>(b) & ~m)));
}

/// The reflection k - a when `flip`, else a, both computed for every lane (see select_bits).
template <class T>
constexpr T reflect_if(bool flip, T k, T a) noexcept
{
    return select_bits(flip, k - a, a);
}

/// atan(x) in degrees for x >= 0 in float arithmetic (+inf gives 90, NaN gives NaN), branch-free so that loops
/// calling it vectorize (16 lanes with AVX-512, 8 with AVX2). t = min(x, 1/x) in [0, 1], atan(t) by atan_unit,
/// and atan(x) = 90 - atan(1/x) degrees for x > 1. |error| <= 1e-5 degrees.
constexpr float atan_deg(float x) noexcept
{
    // The reciprocal is taken for every x and compared with x: as the select needs its value, compilers cannot
    // move the division under a branch (AVX2 has no masked divide). x = 0 gives 1/x = inf and t = 0.
    const float inv = 1.0f / x;
    const float t = x < inv ? x : inv;
    const float a = atan_unit(t) * static_cast<float>(180 / std::numbers::pi);
    return reflect_if(x > 1.0f, 90.0f, a);
}

/// out[i] = atan_deg(x[i]) for i in [0, n), bit for bit. Blocks of 64 values all in [0, 1] (the usual case for
/// slopes between neighbours: below 45 degrees) skip the reciprocal, whose division costs more than the rest of
/// atan_deg: for x <= 1, t = x. The test is a maximum over the bit patterns, which order non-negative floats;
/// NaN, negative values and x > 1 take the full atan_deg. out may equal x.
inline void atan_deg_span(const float* x, float* out, std::ptrdiff_t n) noexcept
{
    constexpr std::ptrdiff_t block = 64;
    constexpr std::uint32_t one_bits = 0x3f800000u;
    constexpr float to_deg = static_cast<float>(180 / std::numbers::pi);
    const std::ptrdiff_t whole = n - n % block;
    for (std::ptrdiff_t i = 0; i < whole; i += block) {
        std::uint32_t widest = 0;
        for (std::ptrdiff_t k = 0; k < block; ++k) {
            const std::uint32_t b = std::bit_cast<std::uint32_t>(x[i + k]);
            widest = b > widest ? b : widest;
        }
        if (widest <= one_bits) {
            for (std::ptrdiff_t k = 0; k < block; ++k) out[i + k] = atan_unit(x[i + k]) * to_deg;
        } else {
            for (std::ptrdiff_t k = 0; k < block; ++k) out[i + k] = atan_deg(x[i + k]);
        }
    }
    for (std::ptrdiff_t i = whole; i < n; ++i) out[i] = atan_deg(x[i]);
}

/// x with the sign bit of `sign` (std::copysign without the libm call; compiles to bit operations).
constexpr float with_sign_of(float x, float sign) noexcept
{
    const std::uint32_t magnitude = std::bit_cast<std::uint32_t>(x) & 0x7fffffffu;
    return std::bit_cast<float>(magnitude | (std::bit_cast<std::uint32_t>(sign) & 0x80000000u));
}

/// atan(x) in radians for every float x (float arithmetic, branch-free): +-inf gives +-pi/2, NaN gives NaN,
/// -0 gives -0. |error| <= 2e-7 rad against the exact atan.
constexpr float fast_atan(float x) noexcept
{
    const float ax = with_sign_of(x, 1.0f);
    const float inv = 1.0f / ax;
    const float t = ax < inv ? ax : inv;
    const float a = reflect_if(ax > 1.0f, static_cast<float>(std::numbers::pi / 2), atan_unit(t));
    return with_sign_of(a, x);
}

/// atan2(y, x) in radians in [-pi, pi] for every pair of floats (float arithmetic, branch-free): the angle of
/// (x, y) from the +x axis, with std::atan2's special cases: atan2(+-0, +0) = +-0, atan2(+-0, -0) = +-pi,
/// atan2(+-inf, +-inf) = +-pi/4 or +-3pi/4, NaN in either gives NaN. |error| <= 3e-7 rad.
/// With lo = min(|x|, |y|), hi = max: atan(lo / hi) in [0, pi/4], reflected to pi/2 - a when |y| > |x|, to
/// pi - a when x is negative (sign bit set), and given the sign of y.
constexpr float fast_atan2(float y, float x) noexcept
{
    const float ax = with_sign_of(x, 1.0f), ay = with_sign_of(y, 1.0f);
    const bool steep = ay > ax;
    const float hi = steep ? ay : ax, lo = steep ? ax : ay;
    // hi = 0 (both zero): 0 / 1 = 0. hi = lo = inf: the quotient is NaN and becomes 1 (pi/4). A NaN input also
    // makes a NaN quotient; it is restored below.
    // (hi + 0 or 0 + 1: an addition rather than a select of the divisor, which compilers would turn into a
    // branch around the division.)
    const float q = lo / (hi + (hi > 0.0f ? 0.0f : 1.0f));
    // (A plain select would let compilers specialize atan_unit(1) under a branch.)
    const float t = select_bits(q <= 1.0f, q, 1.0f);
    float a = reflect_if(steep, static_cast<float>(std::numbers::pi / 2), atan_unit(t));
    a = reflect_if(std::bit_cast<std::int32_t>(x) < 0, static_cast<float>(std::numbers::pi), a);
    // NaN in, NaN out, by adding NaN or 0 (a >= 0 here, so + 0 changes nothing): a select against the constant
    // NaN would let compilers put all of the above under a branch.
    a += x != x || y != y ? std::numeric_limits<float>::quiet_NaN() : 0.0f;
    return with_sign_of(a, y);
}

/// sqrt(1 + u) for u in [0, 1] in float (relative error <= 2e-7): a degree-7 polynomial fitted for least
/// maximum relative error. std::sqrt would do, but it may set errno, so compilers keep a branch around it and
/// do not vectorize the loop.
constexpr float sqrt_one_plus(float u) noexcept
{
    return horner(u, {0.0014404128305613995f, -0.0075965444557368755f, 0.019566621631383896f, -0.036124978214502335f,
                      0.0618608333170414f, -0.12492980808019638f, 0.4999970495700836f, 1.0f});
}

/// out[i] = sqrt(x[i]) · scale, correctly rounded square roots (NaN and negative x give NaN, as std::sqrt,
/// without touching errno). GCC keeps a loop of std::sqrt scalar unless the whole translation unit is built
/// with -fno-math-errno (the optimize attribute does not reach it), so on x86-64 the square roots are taken
/// with the vector instruction directly: 8 lanes with AVX, else 4 with SSE2, through the compiler's
/// builtins on vector types (GCC and clang; no <immintrin.h>, which triples this header's compile time).
inline void sqrt_span(const float* x, float* out, std::ptrdiff_t n, float scale) noexcept
{
    std::ptrdiff_t i = 0;
#if defined(__GNUC__) && (defined(__AVX__) || defined(__SSE2__))
#if defined(__AVX__)
    typedef float lanes __attribute__((vector_size(32)));
#else
    typedef float lanes __attribute__((vector_size(16)));
#endif
    constexpr std::ptrdiff_t width = sizeof(lanes) / sizeof(float);
    for (; i + width <= n; i += width) {
        lanes v;
        std::memcpy(&v, x + i, sizeof v);
#if defined(__AVX__)
        v = __builtin_ia32_sqrtps256(v) * scale;
#else
        v = __builtin_ia32_sqrtps(v) * scale;
#endif
        std::memcpy(out + i, &v, sizeof v);
    }
#endif
    for (; i < n; ++i) out[i] = std::sqrt(x[i]) * scale;
}

/// The largest float f with f <= t (t not NaN): for every float x, x <= f exactly when double(x) <= t, so a
/// threshold given in double is compared in float (float-to-double compares keep loops scalar on SSE2, and
/// float compares vectorize next to byte masks) with the same outcome.
inline float float_at_most(double t) noexcept
{
    const float f = static_cast<float>(t);  // nearest, or +-inf beyond the float range
    return static_cast<double>(f) > t ? std::nextafter(f, -std::numeric_limits<float>::infinity()) : f;
}

/// Hints that *p will soon be read (no-op where the compiler has no prefetch builtin).
inline void prefetch_read([[maybe_unused]] const void* p) noexcept
{
#if defined(__GNUC__) || defined(__clang__)
    __builtin_prefetch(p, 0);
#endif
}

/// Hints that *p will soon be written (no-op where the compiler has no prefetch builtin).
inline void prefetch_write([[maybe_unused]] const void* p) noexcept
{
#if defined(__GNUC__) || defined(__clang__)
    __builtin_prefetch(p, 1);
#endif
}

/// The first column >= c of `row` (cols values) holding a positive value, cols if none: blocks of 64 with
/// none are passed over by a vectorized maximum (labels and masks are mostly 0 or runs of one value; a
/// shorter block would be unrolled into a scalar chain).
template <class T>
std::ptrdiff_t next_positive(const T* row, std::ptrdiff_t c, std::ptrdiff_t cols) noexcept
{
    constexpr std::ptrdiff_t block = 64;
    for (; c + block <= cols; c += block) {
        T high = 0;
        for (std::ptrdiff_t i = 0; i < block; ++i) high = std::max(high, row[c + i]);
        if (high > 0) break;
    }
    while (c < cols && !(row[c] > 0)) ++c;
    return c;
}

/// min(0, smallest label) and max(0, largest label) of one row of `cols` labels: a vectorized min / max
/// (a caller then reads the row's runs while it is in cache, or passes over a row of land).
inline std::pair<std::int32_t, std::int32_t> row_label_range(const std::int32_t* row, std::ptrdiff_t cols) noexcept
{
    std::int32_t lo = 0, hi = 0;
    for (std::ptrdiff_t c = 0; c < cols; ++c) {
        lo = std::min(lo, row[c]);
        hi = std::max(hi, row[c]);
    }
    return {lo, hi};
}

/// Calls visit(value, from, to) for each run [from, to) of one positive value in row[0, cols), left to
/// right; values <= 0 (land, background) are passed over by next_positive. Each run is found before it is
/// visited, so visit may rewrite row[from, to).
template <class T, class Visit>
void for_each_run(const T* row, std::ptrdiff_t cols, Visit&& visit)
{
    for (std::ptrdiff_t c = next_positive(row, 0, cols); c < cols; c = next_positive(row, c, cols)) {
        const T value = row[c];
        const std::ptrdiff_t from = c;
        while (c < cols && row[c] == value) ++c;
        visit(value, from, c);
    }
}

}  // namespace lidarfx::detail

namespace lidarfx {

/// Degrees to radians: deg * (pi / 180), the constant rounded once (pi from <numbers>).
constexpr double deg_to_rad(double deg) noexcept
{
    return deg * (std::numbers::pi / 180);
}

/// Radians to degrees: rad * (180 / pi), the constant rounded once (pi from <numbers>).
constexpr double rad_to_deg(double rad) noexcept
{
    return rad * (180 / std::numbers::pi);
}

}  // namespace lidarfx
