// SPDX-License-Identifier: Apache-2.0
// What every binding shares: NumPy arrays in (read in place when the layout allows) and out (owning the
// library's result), the run settings (threads, progress, Ctrl-C) and the errors turned into Python's.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <lidarfx/core/error.hpp>
#include <lidarfx/core/parallel.hpp>
#include <lidarfx/core/raster.hpp>
#include <lidarfx/core/raster_view.hpp>
#include <lidarfx/kernels/solar/irradiance_record.hpp>

namespace lidarfx::python {

namespace py = pybind11;

/// A 2-D array argument as the library reads it: a view of the caller's cells when the array's layout is one
/// the library reads in place (cells of the wanted type, columns adjacent, rows any whole number of cells
/// apart, row stride >= 0), else a view of a converted copy held here. `copied` says which.
template <class T>
class array_input {
public:
    array_input(const py::handle& array, const char* function, const char* argument);
    raster_view<const T> view() const noexcept { return view_; }
    bool copied() const noexcept { return copy_.has_value(); }
    std::ptrdiff_t rows() const noexcept { return view_.rows(); }
    std::ptrdiff_t cols() const noexcept { return view_.cols(); }

private:
    py::array held_;                 // keeps the caller's array (or its converted copy) alive
    std::optional<py::array> copy_;  // the converted copy, when one was needed
    raster_view<const T> view_;
};

/// A 1-D array argument of type T (converted when its dtype differs; read in place when contiguous).
template <class T>
py::array_t<T, py::array::c_style | py::array::forcecast> vector_input(const py::handle& array, const char* function,
                                                                       const char* argument);

/// The raster as a NumPy array that owns its cells (moved, not copied). Masks (0/1 uint8) come out as `bool`
/// when `as_bool`.
template <class T>
py::array to_numpy(raster<T>&& cells, bool as_bool = false);

/// The `threads=` and `progress=` keywords with Ctrl-C: `run()` gives the library's execution settings, whose
/// progress callback takes the GIL, calls the user's callable (if any) and checks for signals, cancelling the
/// call on Ctrl-C, a False return or an exception in the callable. Wrap the library call in `call()`, which
/// releases the GIL and turns a cancellation into KeyboardInterrupt, the callable's exception or
/// lidarfx.Cancelled.
class run_settings {
public:
    run_settings(int threads, py::object progress);
    execution run() const;

    template <class Work>
    auto call(Work&& work) -> decltype(work())
    {
        try {
            py::gil_scoped_release release;
            return work();
        } catch (const cancelled&) {
            rethrow_cancellation();
            throw;
        }
    }

private:
    void rethrow_cancellation() const;
    int threads_;
    py::object progress_;
    struct state {
        bool interrupted = false;  // Ctrl-C (or another signal handler raised)
        py::object error;          // an exception raised by the callable
        py::object error_type, error_traceback;
    };
    std::shared_ptr<state> state_ = std::make_shared<state>();
};

/// The module's exception raised when a progress callable cancels a call (returns False).
py::object cancelled_exception();

/// Registers the translators (invalid_input -> ValueError, cancelled -> lidarfx.Cancelled) and Cancelled.
void register_errors(py::module_& m);

/// A lidarfx.Weather of the records, with the site they belong to (solar.cpp; read_tmy3 uses it too).
py::object weather_from_records(const std::vector<irradiance_record>& records, double latitude_deg,
                                double longitude_deg, double utc_offset_h);

/// "name: message" as a ValueError.
[[noreturn]] void value_error(const char* function, const std::string& message);

/// A dataclass instance of lidarfx._types (the results' Python classes): `make_result("Components", kwargs)`.
py::object make_result(const char* type, const py::dict& fields);

// The bindings of each area, defined in their own translation units.
void bind_kernels(py::module_& m);
void bind_solar(py::module_& m);
void bind_water(py::module_& m);
void bind_buildings(py::module_& m);
void bind_io(py::module_& m);

// ---------------------------------------------------------------- templates

template <class T>
array_input<T>::array_input(const py::handle& array, const char* function, const char* argument)
{
    if (!py::isinstance<py::array>(array)) {
        throw py::type_error(std::string(function) + ": " + argument + " must be a NumPy array (got " +
                             std::string(py::str(py::type::of(array).attr("__name__"))) + ")");
    }
    held_ = py::reinterpret_borrow<py::array>(array);
    if (held_.ndim() != 2) {
        value_error(function, std::string(argument) + " must be 2-D (got " + std::to_string(held_.ndim()) + "-D)");
    }
    const py::dtype dt = held_.dtype();
    const char kind = dt.kind();
    const bool is_mask = std::is_same_v<T, std::uint8_t>;
    const char order = dt.byteorder();
    const bool native = order == '=' || order == '|' || (order == '<') == (std::endian::native == std::endian::little);
    const char want_kind = std::is_floating_point_v<T> ? 'f' : (std::is_signed_v<T> ? 'i' : 'u');
    const bool same_type = native && (is_mask ? (kind == 'b' || (kind == 'u' && dt.itemsize() == 1))
                                              : (kind == want_kind && dt.itemsize() == sizeof(T)));
    const bool convertible =
        is_mask ? (kind == 'b' || kind == 'u' || kind == 'i') : (kind == 'f' || kind == 'u' || kind == 'i');
    if (!same_type && !convertible) {
        throw py::type_error(std::string(function) + ": " + argument + " must be " +
                             (is_mask ? "a bool or integer (0/1) array" : "a real or integer array") + " (got dtype " +
                             std::string(py::str(static_cast<const py::handle&>(dt))) + ")");
    }
    const auto item = static_cast<py::ssize_t>(sizeof(T));
    const py::ssize_t rows = held_.shape(0), cols = held_.shape(1);
    const bool in_place = same_type && (cols <= 1 || held_.strides(1) == item) && held_.strides(0) >= 0 &&
                          held_.strides(0) % item == 0 && (rows <= 1 || held_.strides(0) / item >= cols);
    if (in_place) {
        const std::ptrdiff_t stride = rows <= 1 ? cols : held_.strides(0) / item;
        view_ = raster_view<const T>(static_cast<const T*>(held_.data()), rows, cols,
                                     std::max<std::ptrdiff_t>(stride, cols));
        return;
    }
    if (is_mask && kind != 'b') {  // integer masks: any non-zero is 1, as the library reads them
        copy_ = py::array(py::module_::import("numpy").attr("not_equal")(held_, 0));
        copy_ = py::array_t<std::uint8_t, py::array::c_style | py::array::forcecast>::ensure(*copy_);
    } else {
        copy_ = py::array_t<T, py::array::c_style | py::array::forcecast>::ensure(held_);
    }
    if (!copy_->ptr()) throw py::error_already_set();
    view_ = raster_view<const T>(static_cast<const T*>(copy_->data()), rows, cols);
}

template <class T>
py::array_t<T, py::array::c_style | py::array::forcecast> vector_input(const py::handle& array, const char* function,
                                                                       const char* argument)
{
    auto out = py::array_t<T, py::array::c_style | py::array::forcecast>::ensure(array);
    if (!out) {
        PyErr_Clear();
        throw py::type_error(std::string(function) + ": " + argument + " must be a 1-D numeric array");
    }
    if (out.ndim() != 1) {
        value_error(function, std::string(argument) + " must be 1-D (got " + std::to_string(out.ndim()) + "-D)");
    }
    return out;
}

template <class T>
py::array to_numpy(raster<T>&& cells, bool as_bool)
{
    auto* owned = new raster<T>(std::move(cells));
    py::capsule owner(owned, [](void* p) { delete static_cast<raster<T>*>(p); });
    const std::vector<py::ssize_t> shape{owned->rows(), owned->cols()};
    const std::vector<py::ssize_t> strides{static_cast<py::ssize_t>(owned->cols() * sizeof(T)), sizeof(T)};
    static T empty{};
    void* data = owned->size() == 0 ? static_cast<void*>(&empty) : static_cast<void*>(owned->data());
    if constexpr (sizeof(T) == 1) {
        if (as_bool) return py::array(py::dtype("bool"), shape, strides, data, owner);
    }
    return py::array(py::dtype::of<T>(), shape, strides, data, owner);
}

}  // namespace lidarfx::python
