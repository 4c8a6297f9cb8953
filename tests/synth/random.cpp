// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include <lidarfx/synth/random.hpp>

#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

using namespace lidarfx::synth;

namespace {

// Plain splitmix64 generator (Vigna's splitmix64.c): state += golden ratio, then the finaliser.
std::uint64_t splitmix_reference(std::uint64_t& state)
{
    std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

}  // namespace

TEST_CASE("synth/mix64: is the splitmix64 finaliser")
{
    std::uint64_t state = 1234567;
    for (std::uint64_t k = 1; k <= 100; ++k) {
        const std::uint64_t expected = splitmix_reference(state);
        CHECK(mix64(1234567 + k * 0x9E3779B97F4A7C15ull) == expected);
    }
}

TEST_CASE("synth/rng: xoshiro256** reproduces its definition from a raw state")
{
    // Worked by hand from the definition. State {1, 2, 3, 4}: output 1 = rotl(2 * 5, 7) * 9 = 11520; the
    // step gives s = {7, 0, 262146, rotl(6, 45)}, so output 2 = rotl(0, 7) * 9 = 0; the next step gives
    // s1 = 262146 ^ 7 = 262149, so output 3 = rotl(262149 * 5, 7) * 9 = 1509978240.
    auto r = rng::from_state({1, 2, 3, 4});
    CHECK(r.next() == 11520u);
    CHECK(r.next() == 0u);
    CHECK(r.next() == 1509978240u);
}

TEST_CASE("synth/rng: same seed and stream give the same numbers, others differ")
{
    rng a(42, 7), b(42, 7), c(42, 8), d(43, 7);
    int same_c = 0, same_d = 0;
    for (int i = 0; i < 1000; ++i) {
        const auto x = a.next();
        CHECK(x == b.next());
        same_c += x == c.next();
        same_d += x == d.next();
    }
    CHECK(same_c == 0);
    CHECK(same_d == 0);
}

TEST_CASE("synth/rng: uniform, below, between, chance and triangular have their ranges and means")
{
    rng r(5);
    constexpr int n = 200000;
    double sum = 0, tri_sum = 0, tri_sq = 0;
    std::array<int, 7> hist{};
    int hits = 0, between_lo = 0, between_hi = 0;
    bool in_range = true;
    for (int i = 0; i < n; ++i) {
        const double u = r.uniform();
        const double v = r.uniform(-3.0, 5.0);
        const auto b = r.below(7);
        const int k = r.between(-2, 2);
        const double t = r.triangular();
        in_range =
            in_range && u >= 0.0 && u < 1.0 && v >= -3.0 && v < 5.0 && b < 7 && k >= -2 && k <= 2 && std::abs(t) < 1.0;
        sum += u;
        ++hist[b];
        between_lo += k == -2;
        between_hi += k == 2;
        hits += r.chance(0.3);
        tri_sum += t;
        tri_sq += t * t;
    }
    CHECK(in_range);
    // Tolerances: about 5 standard errors of each estimate at n = 200000.
    CHECK(sum / n == doctest::Approx(0.5).epsilon(0.01));
    for (int h : hist) CHECK(std::abs(h - n / 7.0) < 5 * std::sqrt(n / 7.0));
    CHECK(std::abs(between_lo - n / 5.0) < 5 * std::sqrt(n / 5.0));
    CHECK(std::abs(between_hi - n / 5.0) < 5 * std::sqrt(n / 5.0));
    CHECK(std::abs(hits - 0.3 * n) < 5 * std::sqrt(0.21 * n));
    CHECK(std::abs(tri_sum / n) < 0.005);
    CHECK(tri_sq / n == doctest::Approx(1.0 / 6.0).epsilon(0.02));
}

TEST_CASE("synth/hash64: depends on every key and is stable")
{
    const auto h = hash64(1, 2, 3, 4);
    CHECK(h == hash64(1, 2, 3, 4));
    CHECK(h != hash64(0, 2, 3, 4));
    CHECK(h != hash64(1, 0, 3, 4));
    CHECK(h != hash64(1, 2, 0, 4));
    CHECK(h != hash64(1, 2, 3, 0));
    CHECK(hash64(1, 2) != hash64(2, 1));
    double sum = 0;
    bool in_range = true;
    for (std::uint64_t i = 0; i < 10000; ++i) {
        const double u = hash_unit(9, i);
        in_range = in_range && u >= 0.0 && u < 1.0;
        sum += u;
    }
    CHECK(in_range);
    CHECK(sum / 10000 == doctest::Approx(0.5).epsilon(0.03));
    static_assert(unit_from_bits(~std::uint64_t{0}) < 1.0);
    static_assert(unit_from_bits(0) == 0.0);
}
