// SPDX-License-Identifier: Apache-2.0
// point_cloud: the concept algorithms read points through, optional attributes, and zero-copy adapters.
#pragma once

#include <concepts>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <type_traits>

#include "lidarfx/core/error.hpp"

namespace lidarfx {

/// Index-based point access: x, y, z in projected metres. SoA buffers, AoS structs and matrices all fit.
template <class C>
concept point_cloud = requires(const C& c, std::size_t i)
{
    {
        c.size()
        } -> std::convertible_to<std::size_t>;
    {
        c.x(i)
        } -> std::convertible_to<double>;
    {
        c.y(i)
        } -> std::convertible_to<double>;
    {
        c.z(i)
        } -> std::convertible_to<double>;
};

/// Optional attributes, detected at compile time and never required by point_cloud itself: each reads as
/// a number for every point index (intensity as double; return number, number of returns, class as int).
template <class C>
concept has_intensity = point_cloud<C> && requires(const C& c, std::size_t i)
{
    double(c.intensity(i));
};
template <class C>
concept has_return_number = point_cloud<C> && requires(const C& c, std::size_t i)
{
    int(c.return_number(i));
};
template <class C>
concept has_number_of_returns = point_cloud<C> && requires(const C& c, std::size_t i)
{
    int(c.number_of_returns(i));
};
template <class C>
concept has_classification = point_cloud<C> && requires(const C& c, std::size_t i)
{
    int(c.classification(i));
};

/// Struct-of-arrays cloud over caller spans (no copy). x, y, z are required and of equal length; each
/// optional span is either empty (attribute absent: intensity 0, return 1 of 1, class 0) or of that length.
template <class Real = double, class Intensity = std::uint16_t, class Small = std::uint8_t>
class soa_cloud {
public:
    soa_cloud(std::span<const Real> x, std::span<const Real> y, std::span<const Real> z,
              std::span<const Intensity> intensity = {}, std::span<const Small> return_number = {},
              std::span<const Small> number_of_returns = {}, std::span<const Small> classification = {})
        : x_(x), y_(y), z_(z), i_(intensity), rn_(return_number), nr_(number_of_returns), cls_(classification)
    {
        const auto n = x.size();
        detail::require(y.size() == n && z.size() == n, "soa_cloud", "x, y and z must have the same length");
        const auto optional_ok = [n](std::size_t k) { return k == 0 || k == n; };
        detail::require(optional_ok(intensity.size()), "soa_cloud", "intensity", "empty or of length x.size()",
                        intensity.size());
        detail::require(optional_ok(return_number.size()), "soa_cloud", "return_number", "empty or of length x.size()",
                        return_number.size());
        detail::require(optional_ok(number_of_returns.size()), "soa_cloud", "number_of_returns",
                        "empty or of length x.size()", number_of_returns.size());
        detail::require(optional_ok(classification.size()), "soa_cloud", "classification",
                        "empty or of length x.size()", classification.size());
    }

    std::size_t size() const noexcept { return x_.size(); }
    double x(std::size_t i) const noexcept { return static_cast<double>(x_[i]); }
    double y(std::size_t i) const noexcept { return static_cast<double>(y_[i]); }
    double z(std::size_t i) const noexcept { return static_cast<double>(z_[i]); }
    double intensity(std::size_t i) const noexcept { return i_.empty() ? 0.0 : static_cast<double>(i_[i]); }
    int return_number(std::size_t i) const noexcept { return rn_.empty() ? 1 : static_cast<int>(rn_[i]); }
    int number_of_returns(std::size_t i) const noexcept { return nr_.empty() ? 1 : static_cast<int>(nr_[i]); }
    int classification(std::size_t i) const noexcept { return cls_.empty() ? 0 : static_cast<int>(cls_[i]); }

    bool has_intensity_values() const noexcept { return !i_.empty(); }
    bool has_return_values() const noexcept { return !nr_.empty(); }

private:
    std::span<const Real> x_, y_, z_;
    std::span<const Intensity> i_;
    std::span<const Small> rn_, nr_, cls_;
};

/// Placeholder projection for an attribute an aos_cloud does not have.
struct no_attribute {};

namespace detail {
template <class A>
concept given_attribute = !std::is_same_v<A, no_attribute>;  // an aos_cloud projection that was passed
}  // namespace detail

/// Array-of-structs cloud: reads attributes of P through projections (member pointers or callables),
/// without copying. Attributes given as no_attribute are absent (and not detected by the concepts).
template <class P, class X, class Y, class Z, class I = no_attribute, class R = no_attribute, class N = no_attribute,
          class K = no_attribute>
class aos_cloud {
public:
    aos_cloud(std::span<const P> points, X x, Y y, Z z, I intensity = {}, R return_number = {},
              N number_of_returns = {}, K classification = {})
        : pts_(points), x_(x), y_(y), z_(z), i_(intensity), r_(return_number), n_(number_of_returns), k_(classification)
    {
    }

    std::size_t size() const noexcept { return pts_.size(); }
    double x(std::size_t i) const { return static_cast<double>(std::invoke(x_, pts_[i])); }
    double y(std::size_t i) const { return static_cast<double>(std::invoke(y_, pts_[i])); }
    double z(std::size_t i) const { return static_cast<double>(std::invoke(z_, pts_[i])); }
    // Optional attributes exist only when a projection for them was given.
    double intensity(std::size_t i) const requires detail::given_attribute<I> { return read<double>(i_, i); }
    int return_number(std::size_t i) const requires detail::given_attribute<R> { return read<int>(r_, i); }
    int number_of_returns(std::size_t i) const requires detail::given_attribute<N> { return read<int>(n_, i); }
    int classification(std::size_t i) const requires detail::given_attribute<K> { return read<int>(k_, i); }

private:
    template <class T, class Projection>
    T read(const Projection& p, std::size_t i) const
    {
        return static_cast<T>(std::invoke(p, pts_[i]));
    }

    std::span<const P> pts_;
    [[no_unique_address]] X x_;
    [[no_unique_address]] Y y_;
    [[no_unique_address]] Z z_;
    [[no_unique_address]] I i_;
    [[no_unique_address]] R r_;
    [[no_unique_address]] N n_;
    [[no_unique_address]] K k_;
};

template <class P, class... Proj>
aos_cloud(std::span<const P>, Proj...) -> aos_cloud<P, Proj...>;
template <class P, class... Proj>
aos_cloud(std::span<P>, Proj...) -> aos_cloud<P, Proj...>;

/// Per-point attribute readers with the documented defaults for absent attributes.
template <point_cloud C>
double intensity_of(const C& c, std::size_t i)
{
    if constexpr (has_intensity<C>)
        return c.intensity(i);
    else
        return 0.0;
}
template <point_cloud C>
int return_number_of(const C& c, std::size_t i)
{
    if constexpr (has_return_number<C>)
        return c.return_number(i);
    else
        return 1;
}
template <point_cloud C>
int number_of_returns_of(const C& c, std::size_t i)
{
    if constexpr (has_number_of_returns<C>)
        return c.number_of_returns(i);
    else
        return 1;
}

}  // namespace lidarfx
