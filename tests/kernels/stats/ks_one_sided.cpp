// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include <lidarfx/kernels/stats/ks_one_sided.hpp>

#include "fixtures/ks_scipy_fixtures.hpp"
#include "reference/ks.hpp"

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <list>
#include <random>
#include <set>
#include <span>
#include <vector>

using namespace lidarfx;

namespace {

// D is a difference of two quotients of counts, computed as scipy computes it: the fixtures should match
// exactly; 1e-12 leaves room for a different order of the same operations.
constexpr double d_tolerance = 1e-12;

template <class T>
std::vector<T> random_sample(std::mt19937& rng, std::size_t n, double lo, double hi)
{
    std::uniform_real_distribution<double> u(lo, hi);
    std::vector<T> out(n);
    for (auto& v : out) v = static_cast<T>(u(rng));
    return out;
}

}  // namespace

TEST_CASE("stats/ks_one_sided: D equals scipy's ks_2samp(alternative='greater') on the fixtures")
{
    for (const auto& f : fixtures::ks_float_cases) {
        CAPTURE(f.name);
        CHECK(std::fabs(ks_one_sided(f.previous, f.current).d - f.d) <= d_tolerance);
    }
    for (const auto& f : fixtures::ks_uint16_cases) {
        CAPTURE(f.name);
        // Sized samples this small sort; a std::list is not sized and goes through the 2^16-bin histograms,
        // and so does the histogram API.
        const std::list<std::uint16_t> previous_list(f.previous.begin(), f.previous.end());
        ks_histogram hp, hc;
        hp.add(f.previous);
        hc.add(f.current);
        CHECK(std::fabs(ks_one_sided(f.previous, f.current).d - f.d) <= d_tolerance);
        CHECK(std::fabs(ks_one_sided(previous_list, f.current).d - f.d) <= d_tolerance);
        CHECK(std::fabs(ks_one_sided(hp, hc).d - f.d) <= d_tolerance);
    }
}

TEST_CASE("stats/ks_one_sided: matches the direct supremum over the empirical CDFs")
{
    const unsigned seed = 1951;
    std::mt19937 rng(seed);
    std::bernoulli_distribution nan_here(0.1);
    for (int trial = 0; trial < 50; ++trial) {
        INFO("seed " << seed << ", trial " << trial);
        const std::size_t n = 1 + (trial * 37) % 300, m = 1 + (trial * 53) % 250;
        const double shift = (trial % 5 - 2) * 0.5;
        // float with NaN values
        auto pf = random_sample<float>(rng, n, 0, 10), cf = random_sample<float>(rng, m, shift, 10 + shift);
        for (auto& v : pf) v = nan_here(rng) ? std::numeric_limits<float>::quiet_NaN() : v;
        if (reference::without_nan(pf).empty()) pf.push_back(1.0f);
        CHECK(std::fabs(ks_one_sided(pf, cf).d - reference::ks_statistic(pf, cf)) <= d_tolerance);

        // 16-bit integers with many ties (sorted when small, histograms when large)
        const auto pu = random_sample<std::uint16_t>(rng, n * 8, 0, 40);
        const auto cu = random_sample<std::uint16_t>(rng, m * 8, shift, 40 + shift);
        CHECK(std::fabs(ks_one_sided(pu, cu).d - reference::ks_statistic(pu, cu)) <= d_tolerance);

        // signed and mixed value types
        const auto p8 = random_sample<std::int8_t>(rng, n, -100, 100);
        const auto c16 = random_sample<std::int16_t>(rng, m, -120 + 10 * shift, 90);
        CHECK(std::fabs(ks_one_sided(p8, c16).d - reference::ks_statistic(p8, c16)) <= d_tolerance);
        const auto pi = random_sample<int>(rng, n, -1000, 1000);
        const auto cd = random_sample<double>(rng, m, -1000, 1000 + 100 * shift);
        CHECK(std::fabs(ks_one_sided(pi, cd).d - reference::ks_statistic(pi, cd)) <= d_tolerance);

        // 32-bit integers (radix-sorted keys) and doubles (std::sort), many ties
        const auto p32 = random_sample<std::int32_t>(rng, n, -50, 50);
        const auto c32 = random_sample<std::int32_t>(rng, m, -50 + 10 * shift, 50);
        CHECK(std::fabs(ks_one_sided(p32, c32).d - reference::ks_statistic(p32, c32)) <= d_tolerance);
        const auto pu32 = random_sample<std::uint32_t>(rng, n, 0, 4e9);
        const auto cu32 = random_sample<std::uint32_t>(rng, m, 1e8 * shift + 2e8, 4e9);
        CHECK(std::fabs(ks_one_sided(pu32, cu32).d - reference::ks_statistic(pu32, cu32)) <= d_tolerance);
        const auto pdd = random_sample<double>(rng, n, -3, 3), cdd = random_sample<double>(rng, m, -3 + shift, 3);
        CHECK(std::fabs(ks_one_sided(pdd, cdd).d - reference::ks_statistic(pdd, cdd)) <= d_tolerance);
    }
}

TEST_CASE("stats/ks_one_sided: identical, shifted and disjoint samples")
{
    std::mt19937 rng(4);
    const auto a = random_sample<float>(rng, 500, 0, 1);
    const auto same = ks_one_sided(a, a);
    CHECK(same.d == 0.0);
    CHECK(same.p_value == 1.0);
    CHECK_FALSE(same.reject);

    // previous entirely below current: F_previous reaches 1 before F_current leaves 0.
    std::vector<double> low(40, 1.0), high(30, 2.0);
    CHECK(ks_one_sided(low, high).d == 1.0);
    CHECK(ks_one_sided(low, high).reject);
    CHECK(ks_one_sided(high, low).d == 0.0);

    // Shifting both samples by the same amount changes nothing; shifting current up raises D.
    std::vector<int> p(300), c(300);
    for (std::size_t i = 0; i < p.size(); ++i) {
        p[i] = static_cast<int>(rng() % 100);
        c[i] = static_cast<int>(rng() % 100);
    }
    const double d = ks_one_sided(p, c).d;
    for (auto& v : p) v += 1000;
    for (auto& v : c) v += 1000;
    CHECK(ks_one_sided(p, c).d == d);
    for (auto& v : c) v += 20;
    CHECK(ks_one_sided(p, c).d > d);
}

TEST_CASE("stats/ks_one_sided: floats order through negatives, both zeros and infinities")
{
    const float inf = std::numeric_limits<float>::infinity();
    const std::vector<float> previous = {-inf, -2.5f, -0.0f, 1e-30f, 3.0f, inf};
    const std::vector<float> current = {-1e30f, 0.0f, -0.0f, 0.0f, 2.0f, 7.0f, inf};
    CHECK(ks_one_sided(previous, current).d == reference::ks_statistic(previous, current));
    // -0 and +0 are one value: samples differing only in the sign of zero are identical.
    CHECK(ks_one_sided(std::vector<float>{-0.0f, 1.0f}, std::vector<float>{0.0f, 1.0f}).d == 0.0);
    CHECK(ks_one_sided(std::vector<float>{0.0f, 1.0f}, std::vector<float>{-0.0f, 1.0f}).d == 0.0);
}

TEST_CASE("stats/ks_one_sided: float and double samples give the sort-and-sweep D bit for bit")
{
    // The keyed path sorts only the buckets that may hold the maximum; its D must be the very double a full
    // sort-and-sweep computes (same i / n - j / m at the same value), so these compare with ==.
    const unsigned seed = 20261202;
    std::mt19937 rng(seed);
    const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
    for (int trial = 0; trial < 40; ++trial) {
        INFO("seed " << seed << ", trial " << trial);
        const std::size_t n = 1 + (trial * 7919) % 20000, m = 1 + (trial * 104729) % 15000;
        std::normal_distribution<double> normal(0, 1);
        std::vector<double> p(n), c(m);
        const double shift = (trial % 7 - 3) * 0.05;
        switch (trial % 4) {
            case 0:  // continuous
                for (auto& v : p) v = normal(rng);
                for (auto& v : c) v = normal(rng) + shift;
                break;
            case 1:  // heavy ties: a few hundred distinct values
                for (auto& v : p) v = std::round(normal(rng) * 50);
                for (auto& v : c) v = std::round((normal(rng) + shift) * 50);
                break;
            case 2:  // NaN, infinities, both zeros, denormals and huge values mixed in
                for (auto& v : p)
                    v = rng() % 10 == 0 ? nan : normal(rng) * std::pow(10.0, static_cast<int>(rng() % 600) - 300);
                for (auto& v : c) v = rng() % 10 == 0 ? -0.0 : normal(rng) + shift;
                p.push_back(inf);
                c.push_back(-inf);
                c.push_back(4.9e-324);
                p.push_back(0.0);
                break;
            default:  // a narrow cluster next to a far outlier: the buckets of the first level are uneven
                for (auto& v : p) v = 1.0 + normal(rng) * 1e-9;
                for (auto& v : c) v = 1.0 + (normal(rng) + shift) * 1e-9;
                p.push_back(1e300);
                break;
        }
        CHECK(ks_one_sided(p, c).d == reference::ks_statistic_sort_sweep(p, c));
        const std::vector<float> pf(p.begin(), p.end()), cf(c.begin(), c.end());
        CHECK(ks_one_sided(pf, cf).d == reference::ks_statistic_sort_sweep(pf, cf));
        CHECK(ks_one_sided(pf, c).d == reference::ks_statistic_sort_sweep(pf, c));  // mixed: compared as double
    }
}

TEST_CASE("stats/ks_one_sided: one value, all ties, all NaN and large samples")
{
    CHECK(ks_one_sided(std::vector<double>{1.0}, std::vector<double>{2.0}).d == 1.0);
    CHECK(ks_one_sided(std::vector<double>{2.0}, std::vector<double>{1.0}).d == 0.0);
    CHECK(ks_one_sided(std::vector<double>{1.0}, std::vector<double>(5000, 1.0)).d == 0.0);
    const std::vector<double> tied(100000, 3.5);
    CHECK(ks_one_sided(tied, tied).d == 0.0);
    // NaN values are dropped before n and m are counted: {NaN, 1} is the sample {1}.
    const double nan = std::numeric_limits<double>::quiet_NaN();
    CHECK(ks_one_sided(std::vector<double>{nan, 1.0}, std::vector<double>{2.0, nan, nan}).d == 1.0);
    CHECK_THROWS_AS(ks_one_sided(std::vector<double>{nan, nan}, std::vector<double>{1.0}), invalid_input);
    CHECK_THROWS_AS(ks_one_sided(std::vector<double>{1.0}, std::vector<double>{}), invalid_input);
    CHECK_THROWS_AS(ks_one_sided(std::vector<float>{}, std::vector<float>{1.0f}), invalid_input);

    std::mt19937_64 rng(77);
    std::exponential_distribution<double> e(1.0);
    std::vector<double> p(1'000'000), c(700'000);
    for (auto& v : p) v = e(rng);
    for (auto& v : c) v = e(rng) * 1.01;
    CHECK(ks_one_sided(p, c).d == reference::ks_statistic_sort_sweep(p, c));
    std::vector<std::int64_t> pi(p.size()), ci(c.size());
    for (std::size_t k = 0; k < p.size(); ++k) pi[k] = static_cast<std::int64_t>(p[k] * 1e15) - (std::int64_t{1} << 52);
    for (std::size_t k = 0; k < c.size(); ++k) ci[k] = static_cast<std::int64_t>(c[k] * 1e15) - (std::int64_t{1} << 52);
    CHECK(ks_one_sided(pi, ci).d == reference::ks_statistic_sort_sweep(pi, ci));
}

TEST_CASE("stats/ks_one_sided: critical values, p-value and rejection")
{
    std::vector<float> p(120), c(80);
    std::mt19937 rng(9);
    for (auto& v : p) v = static_cast<float>(rng() % 1000);
    for (auto& v : c) v = static_cast<float>(rng() % 1000 + 150);
    const double n = 120, m = 80, scale = std::sqrt((n + m) / (n * m));

    const std::array<std::pair<double, double>, 6> table = {
        {{0.10, 1.22}, {0.05, 1.36}, {0.025, 1.48}, {0.01, 1.63}, {0.005, 1.73}, {0.001, 1.95}}};
    for (const auto& entry : table) {
        const double alpha = entry.first, coefficient = entry.second;
        CAPTURE(alpha);
        const auto r = ks_one_sided(p, c, alpha);
        CHECK(r.critical == doctest::Approx(coefficient * scale).epsilon(1e-15));
        CHECK(r.reject == (r.d > r.critical));
        // The documents' coefficients are the two-sided formula rounded to two decimals.
        CHECK(std::fabs(coefficient - std::sqrt(-std::log(alpha / 2) / 2)) < 0.006);
        const auto one = ks_one_sided(p, c, {.alpha = alpha, .critical = ks_critical::one_sided});
        CHECK(one.critical == doctest::Approx(std::sqrt(-std::log(alpha) / 2) * scale).epsilon(1e-15));
        CHECK(one.critical < r.critical);
        CHECK(one.d == r.d);
    }
    const auto off_table = ks_one_sided(p, c, 0.2);
    CHECK(off_table.critical == doctest::Approx(std::sqrt(-std::log(0.1) / 2) * scale).epsilon(1e-15));
    CHECK(off_table.p_value == doctest::Approx(std::exp(-2 * off_table.d * off_table.d * n * m / (n + m))));
    CHECK(off_table.d > 0.1);
    CHECK(off_table.reject);
}

TEST_CASE("stats/ks_one_sided: accepts any range of numbers")
{
    const std::vector<float> vf = {1, 2, 3, 4};
    const std::vector<std::uint16_t> vu = {2, 3, 4, 5};
    const float carray[] = {1, 2, 3, 4};
    const std::array<double, 4> arr = {2, 3, 4, 5};
    const std::list<long> lst = {2, 3, 4, 5};
    const double expected = 0.25;  // at x = 1..4, F_previous - F_current = 1/4 each
    CHECK(ks_one_sided(vf, vu).d == expected);
    CHECK(ks_one_sided(std::span<const float>(vf), std::span<const std::uint16_t>(vu)).d == expected);
    CHECK(ks_one_sided(carray, arr).d == expected);
    CHECK(ks_one_sided(vf, lst).d == expected);
    CHECK(ks_one_sided(std::set<int>{4, 3, 2, 1}, lst, {.alpha = 0.1}).d == expected);
    static_assert(!ks_sample<std::vector<bool>>);
    static_assert(!ks_sample<int>);
}

TEST_CASE("stats/ks_one_sided: large 16-bit samples take the histogram path and agree with sorting")
{
    std::mt19937 rng(65535);
    std::vector<std::uint16_t> p(20000), c(15000);
    std::exponential_distribution<double> brightness(1 / 800.0);
    for (auto& v : p) v = static_cast<std::uint16_t>(std::min(65535.0, brightness(rng)));
    for (auto& v : c) v = static_cast<std::uint16_t>(std::min(65535.0, brightness(rng) * 1.05));
    const std::vector<float> pf(p.begin(), p.end()), cf(c.begin(), c.end());
    const auto histogram = ks_one_sided(p, c), sorted = ks_one_sided(pf, cf);
    CHECK(histogram.d == sorted.d);
    CHECK(histogram.critical == sorted.critical);
    CHECK(histogram.p_value == sorted.p_value);
}

TEST_CASE("stats/ks_histogram: grows by values, ranges and histograms; tests like the samples")
{
    std::mt19937 rng(30);
    ks_histogram region(255), grown(255);
    std::vector<int> region_values, grown_values;
    CHECK(region.empty());
    for (int step = 0; step < 6; ++step) {
        // Region growing: each step adds cells; the previous sample is the region before the step.
        std::vector<std::uint8_t> added(50 + 20 * step);
        for (auto& v : added) v = static_cast<std::uint8_t>(rng() % (60 + 30 * step));
        ks_histogram step_hist(255);
        step_hist.add(added);
        grown.add(step_hist);
        grown_values.insert(grown_values.end(), added.begin(), added.end());
        if (step > 0) {
            const auto from_histograms = ks_one_sided(region, grown, {.alpha = 0.01});
            const auto from_values = ks_one_sided(region_values, grown_values, {.alpha = 0.01});
            CHECK(from_histograms.d == from_values.d);
            CHECK(from_histograms.critical == from_values.critical);
            CHECK(from_histograms.reject == from_values.reject);
        }
        for (auto v : added) region.add(v);  // one value at a time
        region_values = grown_values;
        CHECK(region.size() == grown.size());
    }
    CHECK(region.counts().size() == 256);
    CHECK(region.size() == grown_values.size());
    region.clear();
    CHECK(region.size() == 0);
    CHECK(region.counts()[0] == 0);
}

TEST_CASE("stats/ks_one_sided: bad arguments throw with a clear message")
{
    const std::vector<float> a = {1, 2, 3}, empty;
    const std::vector<double> all_nan(4, std::numeric_limits<double>::quiet_NaN());
    CHECK_THROWS_WITH_AS(ks_one_sided(a, a, 0.0), "ks_one_sided: alpha must be in (0, 1) (got 0)", invalid_input);
    CHECK_THROWS_WITH_AS(ks_one_sided(a, a, 1.0), "ks_one_sided: alpha must be in (0, 1) (got 1)", invalid_input);
    CHECK_THROWS_AS(ks_one_sided(a, a, std::nan("")), invalid_input);
    CHECK_THROWS_AS(ks_one_sided(a, a, {.alpha = -0.5}), invalid_input);
    CHECK_THROWS_WITH_AS(ks_one_sided(empty, a),
                         "ks_one_sided: previous must hold at least one non-NaN value (got none)", invalid_input);
    CHECK_THROWS_WITH_AS(ks_one_sided(a, all_nan),
                         "ks_one_sided: current must hold at least one non-NaN value (got none)", invalid_input);
    const std::vector<std::uint16_t> none;
    CHECK_THROWS_AS(ks_one_sided(none, std::vector<std::uint16_t>{1}), invalid_input);
    CHECK_THROWS_AS(ks_one_sided(std::list<std::uint16_t>{1}, none), invalid_input);

    ks_histogram h(100), other(200), blank(100);
    CHECK_THROWS_WITH_AS(h.add(101), "ks_histogram::add: value must be in [0, 100] (got 101)", invalid_input);
    CHECK_THROWS_WITH_AS(h.add(-1), "ks_histogram::add: value must be in [0, 100] (got -1)", invalid_input);
    CHECK_THROWS_WITH_AS(h.add(other), "ks_histogram::add: other must have the same max_value (got 200 and 100)",
                         invalid_input);
    CHECK_THROWS_WITH_AS(ks_histogram(1u << 24), "ks_histogram: max_value must be <= 16777215 (got 16777216)",
                         invalid_input);
    h.add(5);
    other.add(5);
    CHECK_THROWS_WITH_AS(ks_one_sided(h, other),
                         "ks_one_sided: previous and current must have the same max_value (got 100 and 200)",
                         invalid_input);
    CHECK_THROWS_WITH_AS(ks_one_sided(h, blank), "ks_one_sided: current must hold at least one value (got none)",
                         invalid_input);
}

TEST_CASE("sortable_key orders values as < does and from_sortable_key inverts it")
{
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> wide(-1e6f, 1e6f);
    std::vector<float> v = {0.0f,
                            -0.0f,
                            1.0f,
                            -1.0f,
                            std::numeric_limits<float>::min(),
                            -std::numeric_limits<float>::min(),
                            std::numeric_limits<float>::denorm_min(),
                            std::numeric_limits<float>::max(),
                            -std::numeric_limits<float>::max(),
                            std::numeric_limits<float>::infinity(),
                            -std::numeric_limits<float>::infinity()};
    for (int i = 0; i < 2000; ++i) v.push_back(wide(rng));
    for (const float a : v) {
        for (const float b : {v[0], v[3], v[7], v[100], v[1500]}) {
            CHECK((a < b) == (lidarfx::sortable_key(a) < lidarfx::sortable_key(b)));
            CHECK((a == b) == (lidarfx::sortable_key(a) == lidarfx::sortable_key(b)));
        }
        const float back = lidarfx::from_sortable_key<float>(lidarfx::sortable_key(a));
        CHECK(back == a);
        if (back == 0.0f) CHECK_FALSE(std::signbit(back));  // -0 comes back as +0
    }
    CHECK(lidarfx::sortable_key(std::int64_t{-5}) < lidarfx::sortable_key(std::int64_t{3}));
    CHECK(lidarfx::sortable_key(-2.5) < lidarfx::sortable_key(-2.25));
    CHECK(lidarfx::from_sortable_key<double>(lidarfx::sortable_key(-2.5)) == -2.5);
}
