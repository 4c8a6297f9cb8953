// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include <lidarfx/core/fast_math.hpp>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <vector>

using namespace lidarfx;

namespace {

constexpr float inf = std::numeric_limits<float>::infinity();
constexpr float not_a_number = std::numeric_limits<float>::quiet_NaN();

/// Every 997th non-negative finite float (zero, subnormals, tiny, huge: all binades, ~2.1 million values) plus
/// the largest float and +inf.
std::vector<float> dense_non_negative_floats()
{
    std::vector<float> v;
    for (std::uint64_t bits = 0; bits < 0x7f800000u; bits += 997) {
        v.push_back(std::bit_cast<float>(static_cast<std::uint32_t>(bits)));
    }
    v.push_back(std::numeric_limits<float>::max());
    v.push_back(std::numeric_limits<float>::denorm_min());
    v.push_back(1.0f);
    v.push_back(inf);
    return v;
}

/// ~1600 magnitudes spread over all binades (bit patterns 0 .. +inf in equal steps) plus 0, 1, max and inf.
std::vector<float> magnitudes()
{
    std::vector<float> v;
    for (std::uint64_t bits = 0; bits < 0x7f800000u; bits += 0x7f800000u / 1600) {
        v.push_back(std::bit_cast<float>(static_cast<std::uint32_t>(bits)));
    }
    for (float x : {0.0f, 1.0f, 3.0f, std::numeric_limits<float>::max(), inf}) v.push_back(x);
    return v;
}

}  // namespace

TEST_CASE("core/fast_math: fast_atan is within 2e-7 rad of atan over every binade, both signs")
{
    double worst = 0, worst_relative = 0;
    for (float x : dense_non_negative_floats()) {
        const double exact = std::atan(static_cast<double>(x));
        worst = std::max(worst, std::fabs(detail::fast_atan(x) - exact));
        worst = std::max(worst, std::fabs(detail::fast_atan(-x) + exact));
        if (x > 0 && x <= 1) worst_relative = std::max(worst_relative, std::fabs(detail::fast_atan(x) - exact) / exact);
    }
    CHECK(worst <= 2e-7);
    CHECK(worst_relative <= 2e-7);
    CHECK(detail::fast_atan(inf) == static_cast<float>(std::numbers::pi / 2));
    CHECK(detail::fast_atan(-inf) == -static_cast<float>(std::numbers::pi / 2));
    CHECK(std::signbit(detail::fast_atan(-0.0f)));
    CHECK(detail::fast_atan(0.0f) == 0.0f);
    CHECK(std::isnan(detail::fast_atan(not_a_number)));
}

TEST_CASE("core/fast_math: atan_deg is within 1e-5 degrees of atan for x >= 0")
{
    double worst = 0;
    for (float x : dense_non_negative_floats()) {
        const double exact_deg = std::atan(static_cast<double>(x)) * (180 / std::numbers::pi);
        worst = std::max(worst, std::fabs(detail::atan_deg(x) - exact_deg));
    }
    CHECK(worst <= 1e-5);
    CHECK(detail::atan_deg(0.0f) == 0.0f);
    CHECK(detail::atan_deg(inf) == 90.0f);
    CHECK(std::isnan(detail::atan_deg(not_a_number)));
}

TEST_CASE("core/fast_math: fast_atan2 is within 3e-7 rad of atan2 in all four quadrants, huge to tiny")
{
    const auto mags = magnitudes();
    double worst = 0;
    for (float a : mags) {
        for (float b : mags) {
            for (float y : {a, -a}) {
                for (float x : {b, -b}) {
                    const double exact = std::atan2(static_cast<double>(y), static_cast<double>(x));
                    worst = std::max(worst, std::fabs(detail::fast_atan2(y, x) - exact));
                }
            }
        }
    }
    CHECK(worst <= 3e-7);
}

TEST_CASE("core/fast_math: fast_atan2 keeps atan2's special cases")
{
    const float pi = static_cast<float>(std::numbers::pi);
    // Signed zeros pick the half-plane as std::atan2 does.
    CHECK(detail::fast_atan2(0.0f, 0.0f) == 0.0f);
    CHECK_FALSE(std::signbit(detail::fast_atan2(0.0f, 0.0f)));
    CHECK(std::signbit(detail::fast_atan2(-0.0f, 0.0f)));
    CHECK(detail::fast_atan2(0.0f, -0.0f) == pi);
    CHECK(detail::fast_atan2(-0.0f, -0.0f) == -pi);
    CHECK(detail::fast_atan2(0.0f, -1.0f) == pi);
    CHECK(detail::fast_atan2(-0.0f, -1.0f) == -pi);
    // Infinities.
    CHECK(detail::fast_atan2(inf, inf) == doctest::Approx(std::numbers::pi / 4).epsilon(1e-7));
    CHECK(detail::fast_atan2(inf, -inf) == doctest::Approx(3 * std::numbers::pi / 4).epsilon(1e-7));
    CHECK(detail::fast_atan2(-inf, -inf) == doctest::Approx(-3 * std::numbers::pi / 4).epsilon(1e-7));
    CHECK(detail::fast_atan2(1.0f, inf) == 0.0f);
    CHECK(detail::fast_atan2(1.0f, -inf) == pi);
    CHECK(detail::fast_atan2(-inf, 1.0f) == -static_cast<float>(std::numbers::pi / 2));
    // NaN in either argument.
    CHECK(std::isnan(detail::fast_atan2(not_a_number, 1.0f)));
    CHECK(std::isnan(detail::fast_atan2(1.0f, not_a_number)));
    CHECK(std::isnan(detail::fast_atan2(not_a_number, inf)));
    CHECK(std::isnan(detail::fast_atan2(0.0f, not_a_number)));
}

TEST_CASE("core/fast_math: sqrt_one_plus is within 2e-7 relative of sqrt(1 + u) on [0, 1]")
{
    // Every float in [0, 1] from 2^-30 up (below it sqrt(1 + u) rounds to 1), in steps of at most 2^-24.
    double worst = 0;
    const auto check = [&](float u) {
        worst = std::max(worst, std::fabs(double(detail::sqrt_one_plus(u)) / std::sqrt(1.0 + double(u)) - 1));
    };
    check(0.0f);
    for (float u = 0x1p-30f; u < 1.0f; u = std::max(std::nextafter(u, 2.0f), u + 0x1p-24f)) check(u);
    check(1.0f);
    CHECK(worst <= 2e-7);
    CHECK(worst > 0);  // the sweep reached the polynomial
}

TEST_CASE("core/fast_math: select_bits picks a finished value, NaNs and signed zeros intact")
{
    CHECK(detail::select_bits(true, 1.5f, 2.5f) == 1.5f);
    CHECK(detail::select_bits(false, 1.5f, 2.5f) == 2.5f);
    CHECK(std::isnan(detail::select_bits(true, not_a_number, 0.0f)));
    CHECK(std::signbit(detail::select_bits(false, 1.0f, -0.0f)));
    CHECK(detail::reflect_if(true, 90.0f, 30.0f) == 60.0f);
    CHECK(detail::reflect_if(false, 90.0f, 30.0f) == 30.0f);
}

TEST_CASE("core/fast_math: float_at_most compares in float as the double threshold does")
{
    for (double t : {0.1, 0.15, 1.0 / 3.0, -0.2, 0.0, 2.0, 1e-40, 1e300, -1e300}) {
        const float f = detail::float_at_most(t);
        CHECK(static_cast<double>(f) <= t);
        // The floats around the threshold: each is <= f exactly when it is <= t in double.
        float x = static_cast<float>(t);
        for (int i = 0; i < 3; ++i) x = std::nextafter(x, -std::numeric_limits<float>::infinity());
        for (int i = 0; i < 7; ++i, x = std::nextafter(x, std::numeric_limits<float>::infinity())) {
            INFO("t = " << t << ", x = " << x);
            CHECK((x <= f) == (static_cast<double>(x) <= t));
        }
    }
}

TEST_CASE("core/fast_math: atan_deg_span equals atan_deg value by value, whichever path a block takes")
{
    // Blocks of 64 that are all in [0, 1] take the division-free path; any value above 1, NaN or negative
    // sends its block to atan_deg. Mixed lengths cover whole blocks, a tail, and an empty span.
    std::vector<float> x;
    for (int i = 0; i < 64; ++i) x.push_back(static_cast<float>(i) / 63.0f);   // [0, 1], 1 included
    for (int i = 0; i < 64; ++i) x.push_back(i == 17 ? 1.0000001f : 0.5f);     // one just above 1
    for (int i = 0; i < 64; ++i) x.push_back(i == 40 ? not_a_number : 0.25f);  // one NaN
    for (int i = 0; i < 64; ++i) x.push_back(i == 3 ? inf : 1e-30f);           // inf and a tiny value
    for (int i = 0; i < 64; ++i) x.push_back(i == 9 ? -0.0f : 0.75f);          // signed zero
    const auto dense = dense_non_negative_floats();
    x.insert(x.end(), dense.begin(), dense.begin() + 1000);
    for (std::ptrdiff_t n : {std::ptrdiff_t{0}, std::ptrdiff_t{1}, std::ptrdiff_t{63}, std::ptrdiff_t{64},
                             std::ptrdiff_t{65}, static_cast<std::ptrdiff_t>(x.size())}) {
        std::vector<float> got(static_cast<std::size_t>(n) + 1, 7.0f);
        detail::atan_deg_span(x.data(), got.data(), n);
        for (std::ptrdiff_t i = 0; i < n; ++i) {
            INFO("n = " << n << ", i = " << i << ", x = " << x[i]);
            CHECK(std::bit_cast<std::uint32_t>(got[i]) == std::bit_cast<std::uint32_t>(detail::atan_deg(x[i])));
        }
        CHECK(got[n] == 7.0f);  // nothing written past the end
    }
    std::vector<float> in_place(x.begin(), x.begin() + 200);
    detail::atan_deg_span(in_place.data(), in_place.data(), 200);
    for (std::size_t i = 0; i < in_place.size(); ++i)
        CHECK(std::bit_cast<std::uint32_t>(in_place[i]) == std::bit_cast<std::uint32_t>(detail::atan_deg(x[i])));
}

TEST_CASE("core/fast_math: sqrt_span is the correctly rounded square root times scale, at every length")
{
    // All binades, the special values, and lengths that leave every remainder of the 8- and 4-lane loops.
    std::vector<float> x = dense_non_negative_floats();
    for (const float v : {-0.0f, -1.0f, -inf, not_a_number, 0.0f, 2.0f}) x.push_back(v);
    std::vector<float> out(x.size());
    for (const float scale : {1.0f, 0.5f, 0.3f}) {
        detail::sqrt_span(x.data(), out.data(), static_cast<std::ptrdiff_t>(x.size()), scale);
        std::size_t differ = 0;
        for (std::size_t i = 0; i < x.size(); ++i) {
            const float want = std::sqrt(x[i]) * scale;
            differ += std::isnan(want) ? !std::isnan(out[i])
                                       : std::bit_cast<std::uint32_t>(out[i]) != std::bit_cast<std::uint32_t>(want);
        }
        CHECK(differ == 0);
    }
    for (std::ptrdiff_t n = 0; n <= 19; ++n) {
        std::vector<float> in(static_cast<std::size_t>(n) + 1, 4.0f), got(in.size(), -7.0f);
        detail::sqrt_span(in.data(), got.data(), n, 1.0f);
        for (std::ptrdiff_t i = 0; i < n; ++i) CHECK(got[static_cast<std::size_t>(i)] == 2.0f);
        CHECK(got[static_cast<std::size_t>(n)] == -7.0f);  // nothing written past n
    }
}
