// SPDX-License-Identifier: Apache-2.0
// The extension module lidarfx._lidarfx: errors, run settings and the areas' bindings.
#include "binding.hpp"

namespace lidarfx::python {

namespace {
py::object& cancelled_type()
{
    static py::object type;  // set once at import, lives as long as the module
    return type;
}
}  // namespace

py::object cancelled_exception()
{
    return cancelled_type();
}

void value_error(const char* function, const std::string& message)
{
    throw py::value_error(std::string(function) + ": " + message);
}

py::object make_result(const char* type, const py::dict& fields)
{
    return py::module_::import("lidarfx._types").attr(type)(**fields);
}

run_settings::run_settings(int threads, py::object progress) : threads_(threads), progress_(std::move(progress))
{
    if (threads < 0)
        value_error("lidarfx", "threads must be >= 0 (0 = all cores; got " + std::to_string(threads) + ")");
    if (!progress_.is_none() && !PyCallable_Check(progress_.ptr())) {
        throw py::type_error("lidarfx: progress must be a callable taking the fraction done, or None");
    }
}

execution run_settings::run() const
{
    // Called from the thread that released the GIL, between blocks of rows: take the GIL back, check for
    // Ctrl-C, then ask the user's callable. Any reason to stop is recorded and returned as false (cancel).
    // The library may copy this callback while the GIL is released, so it holds plain pointers (no Python
    // reference counts change without the GIL); this object outlives the call.
    state* st = state_.get();
    PyObject* progress = progress_.ptr();
    return execution{
        .threads = threads_,
        .progress =
            [st, progress](double fraction) {
                py::gil_scoped_acquire gil;
                if (st->interrupted || st->error) return false;
                if (PyErr_CheckSignals() != 0) {
                    PyErr_Clear();
                    st->interrupted = true;
                    return false;
                }
                if (progress == Py_None) return true;
                try {
                    const py::object answer = py::reinterpret_borrow<py::object>(progress)(fraction);
                    return answer.is_none() || PyObject_IsTrue(answer.ptr()) == 1;
                } catch (py::error_already_set& e) {
                    st->error_type = e.type();
                    st->error = e.value();
                    st->error_traceback = e.trace();
                    return false;
                }
            },
    };
}

void run_settings::rethrow_cancellation() const
{
    if (state_->error) {
        PyErr_Restore(state_->error_type.release().ptr(), state_->error.release().ptr(),
                      state_->error_traceback.release().ptr());
        throw py::error_already_set();
    }
    if (state_->interrupted) {
        PyErr_SetNone(PyExc_KeyboardInterrupt);
        throw py::error_already_set();
    }
}

void register_errors(py::module_& m)
{
    cancelled_type() = py::reinterpret_steal<py::object>(PyErr_NewExceptionWithDoc(
        "lidarfx.Cancelled", "A long call stopped because its progress callable returned False.", PyExc_RuntimeError,
        nullptr));
    m.attr("Cancelled") = cancelled_type();
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const invalid_input& e) {
            PyErr_SetString(PyExc_ValueError, e.what());
        } catch (const cancelled& e) {
            PyErr_SetString(cancelled_type().ptr(), e.what());
        }
    });
}

}  // namespace lidarfx::python

PYBIND11_MODULE(_lidarfx, m)
{
    using namespace lidarfx::python;
    m.doc() = "lidarfx: algorithms for airborne LiDAR on NumPy arrays (the C++ library lidarfx, bound with pybind11).";
    register_errors(m);
    bind_kernels(m);
    bind_solar(m);
    bind_water(m);
    bind_buildings(m);
    bind_io(m);
    // For the tests: whether an argument would be copied ("heights": float32, "mask": uint8 / bool).
    m.def("_input_is_copied", [](const py::handle& a, const std::string& kind) {
        return kind == "mask" ? array_input<std::uint8_t>(a, "_input_is_copied", "a").copied()
                              : array_input<float>(a, "_input_is_copied", "a").copied();
    });
}
