// SPDX-License-Identifier: Apache-2.0
// ks_one_sided: one-sided two-sample Kolmogorov-Smirnov test, on ranges of numbers or on integer histograms.
// Implementation in detail/ks_one_sided_impl.hpp.
#pragma once

#include <algorithm>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <ranges>
#include <span>
#include <type_traits>
#include <utility>
#include <vector>

#include "lidarfx/core/error.hpp"

namespace lidarfx {

/// Which coefficient c(alpha) sets the critical value c(alpha) * sqrt((n + m) / (n m)).
enum class ks_critical {
    /// The documents' table (alpha 0.10, 0.05, 0.025, 0.01, 0.005, 0.001 -> 1.22, 1.36, 1.48, 1.63, 1.73, 1.95),
    /// which is the two-sided sqrt(-ln(alpha / 2) / 2) rounded; that formula for any other alpha. Conservative
    /// for a one-sided test; reproduces the documents.
    documents_table,
    /// The asymptotic one-sided coefficient sqrt(-ln(alpha) / 2) (Smirnov), consistent with p_value.
    one_sided,
};

/// Settings of ks_one_sided.
struct ks_one_sided_options {
    double alpha = 0.05;                                  ///< significance level, in (0, 1)
    ks_critical critical = ks_critical::documents_table;  ///< how c(alpha) is chosen
};

/// Outcome of ks_one_sided.
struct ks_result {
    double d = 0;         ///< statistic sup_x (F_previous(x) - F_current(x)), in [0, 1]
    double critical = 0;  ///< c(alpha) * sqrt((n + m) / (n m))
    bool reject = false;  ///< d > critical: current is significantly larger (shifted up) than previous
    double p_value = 1;   ///< asymptotic one-sided p-value exp(-2 d^2 n m / (n + m)), in (0, 1]
};

/// A sample of numbers for ks_one_sided: any input range of arithmetic values other than bool
/// (std::vector<float>, std::span<const std::uint16_t>, a C array, std::list<double>, a views pipeline, ...).
template <class R>
concept ks_sample = std::ranges::input_range<R> && std::is_arithmetic_v<std::ranges::range_value_t<R>> &&
    !std::same_as<std::ranges::range_value_t<R>, bool>;

/// An integer type other than bool: a value ks_histogram counts.
template <class V>
concept ks_integer = std::integral<V> && !std::same_as<V, bool>;

/// Counts of integer values 0..max_value: a KS sample that grows by adding values or other histograms, for
/// callers that test a growing region step after step (O(1) per added value, O(bins) per test).
class ks_histogram {
public:
    static constexpr std::uint32_t largest_max_value = (1u << 24) - 1;  ///< caps memory at 128 MiB

    /// Empty histogram of max_value + 1 bins. @throws invalid_input if max_value > largest_max_value.
    explicit ks_histogram(std::uint32_t max_value = 65535) : counts_(checked_bins(max_value)) {}

    /// Adds one value. @throws invalid_input if value is outside [0, max_value()].
    template <ks_integer V>
    void add(V value)
    {
        if (std::cmp_less(value, 0) || std::cmp_greater(value, max_value())) {
            throw invalid_input(
                detail::concat("ks_histogram::add: value must be in [0, ", max_value(), "] (got ", +value, ")"));
        }
        ++counts_[static_cast<std::size_t>(value)];
        ++size_;
    }

    /// Adds every value of a range of integers. @throws invalid_input on a value outside [0, max_value()]
    /// (the values before it stay added).
    template <ks_sample R>
    requires std::integral<std::ranges::range_value_t<R>>
    void add(const R& values)
    {
        for (const auto& v : values) add(v);
    }

    /// Adds all counts of `other`. @throws invalid_input if other.max_value() differs.
    void add(const ks_histogram& other)
    {
        if (other.max_value() != max_value()) {
            throw invalid_input(detail::concat("ks_histogram::add: other must have the same max_value (got ",
                                               other.max_value(), " and ", max_value(), ")"));
        }
        for (std::size_t b = 0; b < counts_.size(); ++b) counts_[b] += other.counts_[b];
        size_ += other.size_;
    }

    std::uint64_t size() const noexcept { return size_; }  ///< number of values added
    bool empty() const noexcept { return size_ == 0; }
    std::uint32_t max_value() const noexcept { return static_cast<std::uint32_t>(counts_.size() - 1); }
    std::span<const std::uint64_t> counts() const noexcept { return counts_; }  ///< counts()[v] = count of v
    void clear() noexcept
    {
        std::fill(counts_.begin(), counts_.end(), 0);
        size_ = 0;
    }

private:
    static std::size_t checked_bins(std::uint32_t max_value)
    {
        detail::require(max_value <= largest_max_value, "ks_histogram", "max_value", "<= 16777215", max_value);
        return static_cast<std::size_t>(max_value) + 1;
    }

    std::vector<std::uint64_t> counts_;
    std::uint64_t size_ = 0;
};

/// One-sided two-sample Kolmogorov-Smirnov test of whether `current` is stochastically larger than `previous`
/// (its CDF lies below): D = sup_x (F_previous(x) - F_current(x)) >= 0 over the empirical CDFs, equal to
/// scipy.stats.ks_2samp(previous, current, alternative='greater').statistic; reject when D > c(alpha)
/// sqrt((n + m) / (n m)) (Massey 1951; c(alpha) per opt.critical); p_value = exp(-2 D^2 n m / (n + m)).
/// NaN values are ignored (dropped from both samples before n and m are counted). Integer values of at most 16
/// bits go through histograms, O(n + m + 2^16); float, double and integers of up to 64 bits map to ordered
/// unsigned keys and go through bucket-bound-and-refine (a few O(n + m) passes, sorting only the
/// few buckets that may hold the maximum; D bit-identical to a sort-and-sweep); long double sorts copies.
/// @throws invalid_input if alpha is outside (0, 1) or a sample has no non-NaN value.
template <ks_sample Previous, ks_sample Current>
ks_result ks_one_sided(const Previous& previous, const Current& current, const ks_one_sided_options& opt);

/// ks_one_sided with only the significance level set (documents' table for c(alpha)).
template <ks_sample Previous, ks_sample Current>
ks_result ks_one_sided(const Previous& previous, const Current& current, double alpha = 0.05);

/// ks_one_sided on two histograms of the same max_value, O(bins): the test a region-growing caller runs after
/// each step without re-reading its samples. @throws invalid_input if max_values differ, a histogram is
/// empty, or alpha is outside (0, 1).
inline ks_result ks_one_sided(const ks_histogram& previous, const ks_histogram& current,
                              const ks_one_sided_options& opt);

/// ks_one_sided on two histograms with only the significance level set.
inline ks_result ks_one_sided(const ks_histogram& previous, const ks_histogram& current, double alpha = 0.05);

/// The unsigned type of sortable_key<T>: 32 bits for T of up to 4 bytes, 64 bits otherwise.
template <class T>
using sortable_key_t = std::conditional_t<sizeof(T) <= 4, std::uint32_t, std::uint64_t>;

/// An unsigned key in the order of v, for radix and histogram selection of values: a < b exactly when
/// sortable_key(a) < sortable_key(b), and equal values (-0 and +0 included) give equal keys. T: float, double
/// or an integer of up to 64 bits; v is not NaN. Floats: IEEE bits with the negatives reversed below the
/// positives; signed integers: sign bit flipped. O(1).
template <class T>
sortable_key_t<T> sortable_key(T v) noexcept;

/// The value of a key of sortable_key<T> for T float or double (-0 comes back as +0). O(1).
template <class T>
T from_sortable_key(sortable_key_t<T> k) noexcept;

}  // namespace lidarfx

#include "lidarfx/kernels/stats/detail/ks_one_sided_impl.hpp"
