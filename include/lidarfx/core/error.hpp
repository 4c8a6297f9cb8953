// SPDX-License-Identifier: Apache-2.0
// Errors: one exception type for bad input, one for cancellation, and the helpers that build their messages.
#pragma once

#include <cstddef>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>

namespace lidarfx {

/// Thrown when a caller passes input that violates a documented precondition (mismatched shapes,
/// non-positive cell size, options out of range). The message names the function, the argument and
/// the offending value, e.g. "angular_filter: cell_m must be finite and > 0 (got -1)".
struct invalid_input : std::invalid_argument {
    using std::invalid_argument::invalid_argument;
};

/// Thrown when a progress callback asks a long-running algorithm to stop. Outputs are then unspecified.
struct cancelled : std::runtime_error {
    using std::runtime_error::runtime_error;
};

namespace detail {

template <class... Parts>
[[nodiscard]] std::string concat(const Parts&... parts)
{
    std::ostringstream os;
    os.precision(17);
    (os << ... << parts);
    return os.str();
}

/// Throws invalid_input with "<function>: <argument> must be <requirement> (got <value>)" unless `ok`.
template <class Value>
void require(bool ok, std::string_view function, std::string_view argument, std::string_view requirement,
             const Value& value)
{
    if (!ok) {
        throw invalid_input(concat(function, ": ", argument, " must be ", requirement, " (got ", value, ")"));
    }
}

/// Throws invalid_input with "<function>: <message>" unless `ok`.
inline void require(bool ok, std::string_view function, std::string_view message)
{
    if (!ok) throw invalid_input(concat(function, ": ", message));
}

/// As above, with the message made by make_message() only when the check fails: for checks on hot paths
/// (per row, per tile, per test), where building the text every time would cost more than the work.
template <class MakeMessage>
requires std::is_invocable_r_v<std::string, MakeMessage&>
void require(bool ok, std::string_view function, MakeMessage make_message)
{
    if (!ok) throw invalid_input(concat(function, ": ", make_message()));
}

/// Requires a finite value > 0 (cell sizes, distances).
inline void require_positive(double value, std::string_view function, std::string_view argument)
{
    require(value > 0 && value <= 1.0e300, function, argument, "finite and > 0", value);
}

/// Requires two extents to match: "<function>: <a> and <b> must have the same shape (got 3x4 and 4x3)".
template <class A, class B>
void require_same_shape(const A& a, const B& b, std::string_view function, std::string_view a_name,
                        std::string_view b_name)
{
    if (a.rows() != b.rows() || a.cols() != b.cols()) {
        throw invalid_input(concat(function, ": ", a_name, " and ", b_name, " must have the same shape (got ", a.rows(),
                                   "x", a.cols(), " and ", b.rows(), "x", b.cols(), ")"));
    }
}

/// Requires a count raster `part` (points of some kind per cell) not to exceed `whole` (all the points) in any
/// cell; both of the same shape (checked by the caller). Throws "<function>: <message>".
template <class Part, class Whole>
void require_counts_within(const Part& part, const Whole& whole, std::string_view function, std::string_view message)
{
    for (std::ptrdiff_t r = 0; r < part.rows(); ++r)
        for (std::ptrdiff_t c = 0; c < part.cols(); ++c)
            if (part(r, c) > whole(r, c)) throw invalid_input(concat(function, ": ", message));
}

}  // namespace detail
}  // namespace lidarfx

/// Internal invariant check: active when NDEBUG is not defined; a host may define its own before including.
#ifndef LIDARFX_ASSERT
#ifdef NDEBUG
#define LIDARFX_ASSERT(cond) ((void)0)
#else
#include <cassert>
#define LIDARFX_ASSERT(cond) assert(cond)
#endif
#endif
