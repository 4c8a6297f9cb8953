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

}  // namespace reference
