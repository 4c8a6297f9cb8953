// SPDX-License-Identifier: Apache-2.0
// Reference one-sided KS statistic: the supremum taken directly over the empirical CDFs at every sample value.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace reference {

/// Values of a sample other than NaN, as long double (exact for every type the tests use).
template <class T>
std::vector<long double> without_nan(const std::vector<T>& values)
{
    std::vector<long double> out;
    for (const T& v : values) {
        if (v == v) out.push_back(static_cast<long double>(v));
    }
    return out;
}

/// D = max(0, max over every value x of either sample of F_previous(x) - F_current(x)), F(x) = share of the
/// sample <= x, by counting: O((n + m)^2).
template <class A, class B>
double ks_statistic(const std::vector<A>& previous, const std::vector<B>& current)
{
    const auto p = without_nan(previous), c = without_nan(current);
    std::vector<long double> points = p;
    points.insert(points.end(), c.begin(), c.end());
    double d = 0;
    for (const long double x : points) {
        const auto at_most = [x](const std::vector<long double>& s) {
            return static_cast<double>(std::count_if(s.begin(), s.end(), [x](long double v) { return v <= x; }));
        };
        d = std::max(d, at_most(p) / static_cast<double>(p.size()) - at_most(c) / static_cast<double>(c.size()));
    }
    return d;
}

/// The same D by sorting both samples (as long double) and sweeping them once: every distinct value x of
/// either sample, i and j the counts <= x, diff = i / n - j / m in double. O((n + m) log(n + m)), for
/// samples too large for ks_statistic; the kernel's D must equal it bit for bit.
template <class A, class B>
double ks_statistic_sort_sweep(const std::vector<A>& previous, const std::vector<B>& current)
{
    auto p = without_nan(previous), c = without_nan(current);
    std::sort(p.begin(), p.end());
    std::sort(c.begin(), c.end());
    const auto n = static_cast<double>(p.size()), m = static_cast<double>(c.size());
    std::size_t i = 0, j = 0;
    double d = 0;
    while (i < p.size() || j < c.size()) {
        const long double x = j == c.size() || (i < p.size() && p[i] <= c[j]) ? p[i] : c[j];
        while (i < p.size() && p[i] == x) ++i;
        while (j < c.size() && c[j] == x) ++j;
        d = std::max(d, static_cast<double>(i) / n - static_cast<double>(j) / m);
    }
    return d;
}

}  // namespace reference
