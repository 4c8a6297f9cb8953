// SPDX-License-Identifier: Apache-2.0
// Portable pseudo-random numbers for synthetic scenes: splitmix64 hashing and the xoshiro256** generator.
#pragma once

#include <array>
#include <cstdint>

namespace lidarfx::synth {

/// splitmix64 finaliser (Steele, Lea & Flood 2014): a bijective 64-bit mix with full avalanche.
/// Unlike std::*_distribution, everything in this header gives the same numbers on every platform.
constexpr std::uint64_t mix64(std::uint64_t z) noexcept
{
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

/// Hash of up to four 64-bit keys (a seed, a purpose tag, lattice coordinates): counter-based randomness,
/// so a value depends only on its keys, never on how many numbers were drawn before. O(1).
constexpr std::uint64_t hash64(std::uint64_t a, std::uint64_t b = 0, std::uint64_t c = 0, std::uint64_t d = 0) noexcept
{
    constexpr std::uint64_t golden = 0x9E3779B97F4A7C15ull;
    std::uint64_t h = mix64(a + golden);
    h = mix64(h ^ (b + 2 * golden));
    h = mix64(h ^ (c + 3 * golden));
    return mix64(h ^ (d + 4 * golden));
}

/// The top 53 bits of `bits` as a double in [0, 1).
constexpr double unit_from_bits(std::uint64_t bits) noexcept
{
    return static_cast<double>(bits >> 11) * 0x1.0p-53;
}

/// Uniform double in [0, 1) hashed from the keys (see hash64).
constexpr double hash_unit(std::uint64_t a, std::uint64_t b = 0, std::uint64_t c = 0, std::uint64_t d = 0) noexcept
{
    return unit_from_bits(hash64(a, b, c, d));
}

/// xoshiro256** (Blackman & Vigna 2018) seeded through splitmix64 from (seed, stream): independent streams
/// for independent purposes (tree placement, scan jitter, ...), so changing one part of a scene does not
/// shift the random numbers of another. Sequential; about 1 ns per number.
class rng {
public:
    explicit constexpr rng(std::uint64_t seed, std::uint64_t stream = 0) noexcept
    {
        std::uint64_t x = hash64(seed, stream);
        for (auto& word : s_) {
            x += 0x9E3779B97F4A7C15ull;
            word = mix64(x);
        }
    }

    /// Generator with the given raw state (not all zero), e.g. to check against published sequences.
    static constexpr rng from_state(const std::array<std::uint64_t, 4>& state) noexcept
    {
        rng r(0);
        r.s_ = state;
        return r;
    }

    /// Next 64 random bits.
    constexpr std::uint64_t next() noexcept
    {
        const std::uint64_t result = rotl(s_[1] * 5, 7) * 9;
        const std::uint64_t t = s_[1] << 17;
        s_[2] ^= s_[0];
        s_[3] ^= s_[1];
        s_[1] ^= s_[2];
        s_[0] ^= s_[3];
        s_[2] ^= t;
        s_[3] = rotl(s_[3], 45);
        return result;
    }

    /// Uniform in [0, 1).
    constexpr double uniform() noexcept { return unit_from_bits(next()); }

    /// Uniform in [lo, hi).
    constexpr double uniform(double lo, double hi) noexcept { return lo + (hi - lo) * uniform(); }

    /// Uniform integer in [0, n) without modulo bias (rejection); n must be >= 1.
    constexpr std::uint64_t below(std::uint64_t n) noexcept
    {
        const std::uint64_t limit = ~std::uint64_t{0} - (~std::uint64_t{0} % n);
        std::uint64_t v = next();
        while (v >= limit) v = next();
        return v % n;
    }

    /// Uniform integer in [lo, hi] (inclusive); requires lo <= hi.
    constexpr int between(int lo, int hi) noexcept
    {
        return lo + static_cast<int>(below(static_cast<std::uint64_t>(hi - lo) + 1));
    }

    /// True with probability p.
    constexpr bool chance(double p) noexcept { return uniform() < p; }

    /// Triangular number in (-1, 1), mean 0, standard deviation 1/sqrt(6): bounded measurement noise
    /// without transcendental functions (so it is bit-identical everywhere).
    constexpr double triangular() noexcept { return uniform() + uniform() - 1.0; }

private:
    static constexpr std::uint64_t rotl(std::uint64_t x, int k) noexcept { return (x << k) | (x >> (64 - k)); }

    std::array<std::uint64_t, 4> s_{};
};

}  // namespace lidarfx::synth
