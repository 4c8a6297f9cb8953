// SPDX-License-Identifier: Apache-2.0
// Implementation of kernels/stats/ks_one_sided.hpp: the statistic from histograms, from sorted copies, and from
// ordered keys by bucket-bound-and-refine. Included at the end of ks_one_sided.hpp, after the declarations it
// defines; not a public header.
#pragma once

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <ranges>
#include <span>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/raster.hpp"

namespace lidarfx {

namespace detail {

inline void check_ks_options(const ks_one_sided_options& opt)
{
    require(opt.alpha > 0 && opt.alpha < 1, "ks_one_sided", "alpha", "in (0, 1)", opt.alpha);
}

/// c(alpha) for the chosen critical-value convention.
inline double ks_coefficient(const ks_one_sided_options& opt) noexcept
{
    if (opt.critical == ks_critical::one_sided) return std::sqrt(-std::log(opt.alpha) / 2);
    constexpr std::pair<double, double> table[] = {{0.10, 1.22}, {0.05, 1.36},  {0.025, 1.48},
                                                   {0.01, 1.63}, {0.005, 1.73}, {0.001, 1.95}};
    for (const auto& [alpha, c] : table) {
        if (opt.alpha == alpha) return c;
    }
    return std::sqrt(-std::log(opt.alpha / 2) / 2);
}

inline ks_result ks_finish(double d, std::uint64_t n, std::uint64_t m, const ks_one_sided_options& opt) noexcept
{
    const auto nn = static_cast<double>(n), mm = static_cast<double>(m);
    const double critical = ks_coefficient(opt) * std::sqrt((nn + mm) / (nn * mm));
    return {d, critical, d > critical, std::exp(-2 * d * d * nn * mm / (nn + mm))};
}

inline void require_sample(std::uint64_t size, const char* name, const char* what = "non-NaN value")
{
    require(size > 0, "ks_one_sided", [&] { return concat(name, " must hold at least one ", what, " (got none)"); });
}

/// D = max over value steps of i/n - j/m, i and j the cumulative counts of both histograms at the step.
/// Each term is computed as scipy.stats.ks_2samp computes it (two divisions, one subtraction), so D agrees
/// with it bit for bit.
template <class Count>
double ks_statistic_from_counts(std::span<const Count> previous, std::span<const Count> current, std::uint64_t n,
                                std::uint64_t m) noexcept
{
    const auto nn = static_cast<double>(n), mm = static_cast<double>(m);
    std::uint64_t i = 0, j = 0;
    double d = 0;
    for (std::size_t b = 0; b < previous.size() && i < n; ++b) {
        if (previous[b] == 0 && current[b] == 0) continue;
        i += previous[b];
        j += current[b];
        const double diff = static_cast<double>(i) / nn - static_cast<double>(j) / mm;
        d = diff > d ? diff : d;
    }
    return d;
}

/// D by a merge of two sorted samples; ties are consumed on both sides before each comparison.
template <class T>
double ks_statistic_sorted(const std::vector<T>& previous, const std::vector<T>& current) noexcept
{
    const std::size_t n = previous.size(), m = current.size();
    const auto nn = static_cast<double>(n), mm = static_cast<double>(m);
    std::size_t i = 0, j = 0;
    double d = 0;
    while (i < n) {  // once previous is used up, F_previous = 1 and the difference only falls
        const T v = j == m || previous[i] <= current[j] ? previous[i] : current[j];
        while (i < n && previous[i] == v) ++i;
        while (j < m && current[j] == v) ++j;
        const double diff = static_cast<double>(i) / nn - static_cast<double>(j) / mm;
        d = diff > d ? diff : d;
    }
    return d;
}

/// Copies the non-NaN values of a range as T.
template <class T, class R>
std::vector<T> ks_values(const R& values)
{
    std::vector<T> out;
    if constexpr (std::ranges::sized_range<R>) out.reserve(static_cast<std::size_t>(std::ranges::size(values)));
    for (const auto& v : values) {
        if constexpr (std::is_floating_point_v<std::remove_cvref_t<decltype(v)>>) {
            if (v != v) continue;
        }
        out.push_back(static_cast<T>(v));
    }
    return out;
}

/// Types whose values ks_key maps to unsigned keys: float, double and integers of up to 64 bits.
template <class T>
inline constexpr bool ks_keyed = std::is_same_v<T, float> || std::is_same_v<T, double> ||
                                 (std::is_integral_v<T> && sizeof(T) <= 8);

template <class T>
using ks_key_t = sortable_key_t<T>;

/// Unsigned key in the order of the values: equal values (-0 and +0 included) give equal keys. Floats:
/// IEEE bits with negatives reversed below positives; signed integers: sign bit flipped. NaN never gets here.
template <class T>
ks_key_t<T> ks_key(T v) noexcept
{
    using K = ks_key_t<T>;
    constexpr K sign = K{1} << (8 * sizeof(K) - 1);
    if constexpr (std::is_floating_point_v<T>) {
        const auto bits = std::bit_cast<K>(v == T(0) ? T(0) : v);
        return bits & sign ? static_cast<K>(~bits) : static_cast<K>(bits | sign);
    } else if constexpr (std::is_signed_v<T>) {
        return static_cast<K>(static_cast<K>(static_cast<std::make_signed_t<K>>(v)) ^ sign);
    } else {
        return static_cast<K>(v);
    }
}

/// Keys of a sample: a buffer that is written in full before it is read (no zeroing), huge pages when large.
template <class K>
using ks_key_buffer = std::vector<K, raster_allocator<K>>;

/// Keys of the non-NaN values of a range of T, in the order of the range.
template <class T, class R>
ks_key_buffer<ks_key_t<T>> ks_keys(const R& values)
{
    ks_key_buffer<ks_key_t<T>> out;
    if constexpr (std::ranges::contiguous_range<R> && std::ranges::sized_range<R>) {
        // One pass, no branch: every value is written, a NaN's slot is taken by the next value.
        const auto n = static_cast<std::size_t>(std::ranges::size(values));
        out.resize(n);
        const auto* in = std::ranges::data(values);
        std::size_t kept = 0;
        for (std::size_t k = 0; k < n; ++k) {
            const auto t = static_cast<T>(in[k]);
            out[kept] = ks_key<T>(t);
            if constexpr (std::is_floating_point_v<T>) {
                kept += t == t;
            } else {
                ++kept;
            }
        }
        out.resize(kept);
    } else {
        if constexpr (std::ranges::sized_range<R>) out.reserve(static_cast<std::size_t>(std::ranges::size(values)));
        for (const auto& v : values) {
            const auto t = static_cast<T>(v);
            if constexpr (std::is_floating_point_v<T>) {
                if (t != t) continue;
            }
            out.push_back(ks_key<T>(t));
        }
    }
    return out;
}

/// Totals of the whole samples and the lower bound on D found so far, shared by the levels of ks_refine.
struct ks_totals {
    double nn, mm;  ///< sample sizes n and m
    double d = 0;   ///< D so far: a value of the statistic's expression at a real x, never above the true D
    /// F_previous - F_current from cumulative counts, as scipy computes it (two divisions, one subtraction):
    /// monotone (non-decreasing in i, non-increasing in j) under IEEE rounding, which the bounds rely on.
    double diff(std::uint64_t i, std::uint64_t j) const noexcept
    {
        return static_cast<double>(i) / nn - static_cast<double>(j) / mm;
    }
};

/// Raises t.d to the largest diff over the distinct values of two sorted key runs, i0 / j0 values of the
/// samples lying below both runs.
template <class K>
void ks_sweep_sorted(std::span<const K> p, std::span<const K> c, std::uint64_t i0, std::uint64_t j0,
                     ks_totals& t) noexcept
{
    std::size_t i = 0, j = 0;
    while (i < p.size()) {  // steps where only current rises lower the difference: skip them
        const K v = p[i];
        while (j < c.size() && c[j] < v) ++j;
        while (i < p.size() && p[i] == v) ++i;
        while (j < c.size() && c[j] == v) ++j;
        const double diff = t.diff(i0 + i, j0 + j);
        t.d = diff > t.d ? diff : t.d;
    }
}

template <class K>
void ks_refine(std::span<const K> p, std::span<const K> c, std::uint64_t i0, std::uint64_t j0, ks_totals& t);

/// The smallest and largest key of both samples (p not empty).
template <class K>
std::pair<K, K> ks_key_range(std::span<const K> p, std::span<const K> c) noexcept
{
    K lo = p[0], hi = p[0];
    for (const K k : p) {
        lo = k < lo ? k : lo;
        hi = k > hi ? k : hi;
    }
    for (const K k : c) {
        lo = k < lo ? k : lo;
        hi = k > hi ? k : hi;
    }
    return {lo, hi};
}

/// Buckets per level of ks_refine: about a quarter of the values, 2^8 to 2^16.
inline int ks_bucket_bits(std::size_t values) noexcept
{
    return std::clamp(static_cast<int>(std::bit_width(values / 4)), 8, 16);
}

/// One level of bucket-bound-and-refine: count both samples (keys of one interval, unordered; i0 / j0 values
/// of the samples lie below it) in `buckets` buckets, bucket(k) being a non-decreasing map of the keys onto
/// [0, buckets), so equal keys share a bucket. The diff at each bucket's end is a value of the statistic
/// (lower bound), and no value inside bucket b exceeds diff(i after b, j before b) (upper bound). Only
/// buckets whose upper bound beats the best lower bound are gathered and refined (ks_refine), recursively,
/// small ones by sorting. The values reached are the same diffs a full sort-and-sweep computes, so D is
/// bit-identical to it. O(n + m) passes, 3 per level.
template <class K, class Bucket>
void ks_refine_buckets(std::span<const K> p, std::span<const K> c, std::uint64_t i0, std::uint64_t j0, ks_totals& t,
                       std::size_t buckets, Bucket bucket)
{
    ks_key_buffer<std::uint32_t> count_p(buckets), count_c(buckets);
    std::fill(count_p.begin(), count_p.end(), 0u);
    std::fill(count_c.begin(), count_c.end(), 0u);
    for (const K k : p) ++count_p[bucket(k)];
    for (const K k : c) ++count_c[bucket(k)];
    // Lower bounds: the diff at the end of every bucket, and the exact maximum of a bucket holding no current
    // value (its last previous value, j unchanged).
    std::uint64_t i = i0, j = j0;
    for (std::size_t b = 0; b < buckets; ++b) {
        i += count_p[b];
        const double exact_if_alone = t.diff(i, j);
        j += count_c[b];
        const double at_end = count_c[b] == 0 ? exact_if_alone : t.diff(i, j);
        t.d = at_end > t.d ? at_end : t.d;
    }
    // Buckets that may hold a larger value: gathered contiguously (start offsets in the count arrays' place).
    std::vector<std::size_t> refine;
    std::vector<std::uint64_t> below_p, below_c;
    std::size_t gathered_p = 0, gathered_c = 0;
    i = i0, j = j0;
    for (std::size_t b = 0; b < buckets; ++b) {
        const std::uint64_t ib = i + count_p[b];
        if (count_p[b] > 0 && count_c[b] > 0 && buckets > 1 && t.diff(ib, j) > t.d) {
            refine.push_back(b);
            below_p.push_back(i);
            below_c.push_back(j);
        }
        i = ib;
        j += count_c[b];
    }
    if (refine.empty()) return;
    constexpr std::uint32_t skip = std::numeric_limits<std::uint32_t>::max();
    for (std::size_t b = 0, r = 0; b < buckets; ++b) {
        const bool wanted = r < refine.size() && refine[r] == b;
        const std::uint32_t np = count_p[b], nc = count_c[b];
        count_p[b] = wanted ? static_cast<std::uint32_t>(gathered_p) : skip;
        count_c[b] = wanted ? static_cast<std::uint32_t>(gathered_c) : skip;
        if (wanted) {
            gathered_p += np;
            gathered_c += nc;
            ++r;
        }
    }
    ks_key_buffer<K> gp(gathered_p), gc(gathered_c);  // written in full by the gather
    for (const K k : p)
        if (const auto b = bucket(k); count_p[b] != skip) gp[count_p[b]++] = k;
    for (const K k : c)
        if (const auto b = bucket(k); count_c[b] != skip) gc[count_c[b]++] = k;
    // After the gather, count_x[b] is the end of bucket b's run: runs follow one another in bucket order.
    std::size_t start_p = 0, start_c = 0;
    for (std::size_t r = 0; r < refine.size(); ++r) {
        const std::size_t b = refine[r], end_p = count_p[b], end_c = count_c[b];
        if (t.diff(below_p[r] + (end_p - start_p), below_c[r]) > t.d) {  // the bound again, with t.d raised
            ks_refine<K>(std::span<const K>(gp).subspan(start_p, end_p - start_p),
                         std::span<const K>(gc).subspan(start_c, end_c - start_c), below_p[r], below_c[r], t);
        }
        start_p = end_p;
        start_c = end_c;
    }
}

/// Raises t.d to the largest diff over the distinct values of p, where p and c hold (unordered) the keys of
/// both samples inside one key interval and i0 / j0 count the values below it (see ks_refine_buckets):
/// buckets split the key interval evenly, the interval shrinking by the bucket count at each level; small
/// intervals are sorted and swept.
template <class K>
void ks_refine(std::span<const K> p, std::span<const K> c, std::uint64_t i0, std::uint64_t j0, ks_totals& t)
{
    if (p.empty()) return;  // inside this interval only current rises
    if (p.size() + c.size() <= 96) {
        std::vector<K> sp(p.begin(), p.end()), sc(c.begin(), c.end());
        std::sort(sp.begin(), sp.end());
        std::sort(sc.begin(), sc.end());
        ks_sweep_sorted<K>(sp, sc, i0, j0, t);
        return;
    }
    const auto [lo, hi] = ks_key_range(p, c);
    const int wanted_bits = ks_bucket_bits(p.size() + c.size());
    const int shift = std::max(0, static_cast<int>(std::bit_width(static_cast<K>(hi - lo))) - wanted_bits);
    const std::size_t buckets = static_cast<std::size_t>(static_cast<K>(hi - lo) >> shift) + 1;
    ks_refine_buckets<K>(p, c, i0, j0, t, buckets,
                         [lo = lo, shift](K k) { return static_cast<std::size_t>(static_cast<K>(k - lo) >> shift); });
}

/// The value of a key of ks_key<T> (T float or double): its inverse.
template <class T>
T ks_value(ks_key_t<T> k) noexcept
{
    using K = ks_key_t<T>;
    constexpr K sign = K{1} << (8 * sizeof(K) - 1);
    return std::bit_cast<T>(k & sign ? static_cast<K>(k ^ sign) : static_cast<K>(~k));
}

/// The first level for floating samples: buckets split the *value* range evenly, bucket = floor((v - lo) *
/// scale), which is non-decreasing in v under IEEE rounding. Keys split by their top bits put a value range
/// such as 4096..8191 into a few buckets (one per 2^-4 of an octave), which then all need refining when the
/// values are tied integers; even value buckets hold one or a few values each. Infinite or NaN range: keys.
template <class T>
void ks_refine_by_value(std::span<const ks_key_t<T>> p, std::span<const ks_key_t<T>> c, ks_totals& t)
{
    using K = ks_key_t<T>;
    if (p.empty()) return;
    const auto [lo_key, hi_key] = ks_key_range(p, c);
    const double lo = static_cast<double>(ks_value<T>(lo_key)), span = static_cast<double>(ks_value<T>(hi_key)) - lo;
    if (p.size() + c.size() <= 96 || !(span > 0) || !std::isfinite(span)) return ks_refine<K>(p, c, 0, 0, t);
    const std::size_t buckets = std::size_t{1} << ks_bucket_bits(p.size() + c.size());
    const double scale = static_cast<double>(buckets - 1) / span;
    if (!std::isfinite(scale)) return ks_refine<K>(p, c, 0, 0, t);
    ks_refine_buckets<K>(p, c, 0, 0, t, buckets, [lo, scale, buckets](K k) {
        const double x = (static_cast<double>(ks_value<T>(k)) - lo) * scale;  // in [0, buckets - 1]
        return std::min(static_cast<std::size_t>(x), buckets - 1);
    });
}

/// D of two samples of keys of T, bit-identical to sorting both and sweeping them once.
template <class T>
double ks_statistic_keys(std::span<const ks_key_t<T>> previous, std::span<const ks_key_t<T>> current)
{
    ks_totals t{static_cast<double>(previous.size()), static_cast<double>(current.size())};
    if constexpr (std::is_floating_point_v<T>) {
        ks_refine_by_value<T>(previous, current, t);
    } else {
        ks_refine<ks_key_t<T>>(previous, current, 0, 0, t);
    }
    return t.d;
}

/// Value types both of whose values a double holds exactly (so comparing as double changes no order).
template <class V>
inline constexpr bool ks_exact_in_double = std::is_same_v<V, float> || std::is_same_v<V, double> ||
                                           (std::is_integral_v<V> && sizeof(V) <= 4);

template <class A, class B>
ks_result ks_sorted_path(const A& previous, const B& current, const ks_one_sided_options& opt)
{
    using VA = std::ranges::range_value_t<A>;
    using VB = std::ranges::range_value_t<B>;
    // Mixed value types compare as double when it holds both exactly, else as long double, which holds every
    // float, double and 64-bit integer exactly on x86-64 and AArch64 Linux.
    using T =
        std::conditional_t<std::is_same_v<VA, VB>, VA,
                           std::conditional_t<ks_exact_in_double<VA> && ks_exact_in_double<VB>, double, long double>>;
    if constexpr (ks_keyed<T>) {
        const auto p = ks_keys<T>(previous);
        const auto c = ks_keys<T>(current);
        require_sample(p.size(), "previous");
        require_sample(c.size(), "current");
        constexpr std::size_t counted = std::numeric_limits<std::uint32_t>::max();  // bucket counts are 32-bit
        if (p.size() < counted && c.size() < counted) {
            using K = ks_key_t<T>;
            return ks_finish(ks_statistic_keys<T>(std::span<const K>(p), std::span<const K>(c)), p.size(), c.size(),
                             opt);
        }
        std::vector<ks_key_t<T>> sp(p.begin(), p.end()), sc(c.begin(), c.end());
        std::sort(sp.begin(), sp.end());
        std::sort(sc.begin(), sc.end());
        return ks_finish(ks_statistic_sorted(sp, sc), p.size(), c.size(), opt);
    } else {
        auto p = ks_values<T>(previous);
        auto c = ks_values<T>(current);
        require_sample(p.size(), "previous");
        require_sample(c.size(), "current");
        std::sort(p.begin(), p.end());
        std::sort(c.begin(), c.end());
        return ks_finish(ks_statistic_sorted(p, c), p.size(), c.size(), opt);
    }
}

/// Integer types of at most 16 bits: histograms of every representable value, O(n + m + 2^bits).
template <class A, class B>
ks_result ks_histogram_path(const A& previous, const B& current, const ks_one_sided_options& opt)
{
    using VA = std::ranges::range_value_t<A>;
    using VB = std::ranges::range_value_t<B>;
    constexpr long lowest = std::min<long>(std::numeric_limits<VA>::min(), std::numeric_limits<VB>::min());
    constexpr long highest = std::max<long>(std::numeric_limits<VA>::max(), std::numeric_limits<VB>::max());
    std::vector<std::uint64_t> hp(static_cast<std::size_t>(highest - lowest + 1)), hc(hp.size());
    std::uint64_t n = 0, m = 0;
    for (const auto& v : previous) {
        ++hp[static_cast<std::size_t>(static_cast<long>(v) - lowest)];
        ++n;
    }
    for (const auto& v : current) {
        ++hc[static_cast<std::size_t>(static_cast<long>(v) - lowest)];
        ++m;
    }
    require_sample(n, "previous");
    require_sample(m, "current");
    return ks_finish(ks_statistic_from_counts<std::uint64_t>(hp, hc, n, m), n, m, opt);
}

template <class V>
inline constexpr bool ks_small_integer = std::is_integral_v<V> && sizeof(V) <= 2;

}  // namespace detail

template <ks_sample Previous, ks_sample Current>
ks_result ks_one_sided(const Previous& previous, const Current& current, const ks_one_sided_options& opt)
{
    detail::check_ks_options(opt);
    using VA = std::ranges::range_value_t<Previous>;
    using VB = std::ranges::range_value_t<Current>;
    if constexpr (detail::ks_small_integer<VA> && detail::ks_small_integer<VB>) {
        // Small samples sort faster than they clear 2^16 bins; both paths give the same D.
        if constexpr (std::ranges::sized_range<Previous> && std::ranges::sized_range<Current>) {
            const auto total = static_cast<std::size_t>(std::ranges::size(previous) + std::ranges::size(current));
            if (sizeof(VA) == 2 && sizeof(VB) == 2 && total < 4096) {
                return detail::ks_sorted_path(previous, current, opt);
            }
        }
        return detail::ks_histogram_path(previous, current, opt);
    } else {
        return detail::ks_sorted_path(previous, current, opt);
    }
}

template <ks_sample Previous, ks_sample Current>
ks_result ks_one_sided(const Previous& previous, const Current& current, double alpha)
{
    return ks_one_sided(previous, current, ks_one_sided_options{.alpha = alpha});
}

inline ks_result ks_one_sided(const ks_histogram& previous, const ks_histogram& current,
                              const ks_one_sided_options& opt)
{
    detail::check_ks_options(opt);
    detail::require(previous.max_value() == current.max_value(), "ks_one_sided", [&] {
        return detail::concat("previous and current must have the same max_value (got ", previous.max_value(), " and ",
                              current.max_value(), ")");
    });
    detail::require_sample(previous.size(), "previous", "value");
    detail::require_sample(current.size(), "current", "value");
    const double d =
        detail::ks_statistic_from_counts(previous.counts(), current.counts(), previous.size(), current.size());
    return detail::ks_finish(d, previous.size(), current.size(), opt);
}

inline ks_result ks_one_sided(const ks_histogram& previous, const ks_histogram& current, double alpha)
{
    return ks_one_sided(previous, current, ks_one_sided_options{.alpha = alpha});
}

template <class T>
sortable_key_t<T> sortable_key(T v) noexcept
{
    return detail::ks_key(v);
}

template <class T>
T from_sortable_key(sortable_key_t<T> k) noexcept
{
    return detail::ks_value<T>(k);
}

}  // namespace lidarfx
