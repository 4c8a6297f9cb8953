// SPDX-License-Identifier: Apache-2.0
// Helpers shared by the I/O tests: scratch folders, whole-file bytes, and catching error messages.
#pragma once

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <unistd.h>

#include <lidarfx/core/error.hpp>
#include <lidarfx/core/raster_view.hpp>

#include <doctest/doctest.h>

#include "io/las.hpp"
#include "io/png.hpp"

namespace io_test {

/// The message of the lidarfx::invalid_input that `f` throws, "<no error>" when it returns.
template <class F>
std::string invalid_input_of(F&& f)
{
    try {
        f();
    } catch (const lidarfx::invalid_input& e) {
        return e.what();
    }
    return "<no error>";
}

/// The colour of pixel (r, c) of a picture.
inline std::array<std::uint8_t, 3> pixel(const lidarfx::io::rgb_image& img, std::ptrdiff_t r, std::ptrdiff_t c)
{
    const auto* p = img.rgb.data() + (r * img.width + c) * 3;
    return {p[0], p[1], p[2]};
}

/// A fresh folder under the system temp dir, removed with everything in it when the object dies.
class temp_dir {
public:
    temp_dir()
    {
        std::random_device rd;
        path_ = std::filesystem::temp_directory_path() /
                ("lidarfx_io_" + std::to_string(::getpid()) + "_" + std::to_string(rd()));
        std::filesystem::create_directories(path_);
    }
    temp_dir(const temp_dir&) = delete;
    temp_dir& operator=(const temp_dir&) = delete;
    ~temp_dir()
    {
        std::error_code ec;
        std::filesystem::remove_all(path_, ec);
    }
    std::string file(const std::string& name) const { return (path_ / name).string(); }

private:
    std::filesystem::path path_;
};

inline std::vector<std::uint8_t> read_bytes(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error(path + ": cannot open");
    return std::vector<std::uint8_t>(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

inline void write_bytes(const std::string& path, const std::vector<std::uint8_t>& bytes)
{
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
    if (!out) throw std::runtime_error(path + ": cannot write");
}

/// The message of the std::runtime_error `f` throws, or "<no error>" when it returns normally.
/// Other exception types propagate (and fail the test).
template <class F>
std::string runtime_error_of(F&& f)
{
    try {
        f();
    } catch (const std::runtime_error& e) {
        return e.what();
    }
    return "<no error>";
}

/// The message of any std::exception `f` throws, or "<no error>" when it returns normally.
template <class F>
std::string error_of(F&& f)
{
    try {
        f();
    } catch (const std::exception& e) {
        return e.what();
    }
    return "<no error>";
}

/// True when a and b have the same shape and cells: NaN where the other is NaN, identical bits elsewhere.
inline bool same_cells(lidarfx::raster_view<const float> a, lidarfx::raster_view<const float> b)
{
    if (a.rows() != b.rows() || a.cols() != b.cols()) return false;
    for (std::ptrdiff_t r = 0; r < a.rows(); ++r) {
        for (std::ptrdiff_t c = 0; c < a.cols(); ++c) {
            const float x = a(r, c), y = b(r, c);
            if (std::isnan(x) != std::isnan(y)) return false;
            if (!std::isnan(x) && std::bit_cast<std::uint32_t>(x) != std::bit_cast<std::uint32_t>(y)) return false;
        }
    }
    return true;
}

/// Every attribute of a and b is equal.
inline bool identical(const lidarfx::io::las_points& a, const lidarfx::io::las_points& b)
{
    return a.x == b.x && a.y == b.y && a.z == b.z && a.intensity == b.intensity && a.return_number == b.return_number &&
           a.number_of_returns == b.number_of_returns && a.classification == b.classification &&
           a.classification_flags == b.classification_flags && a.scan_angle_deg == b.scan_angle_deg &&
           a.gps_time == b.gps_time;
}

/// All points of r read from the start in chunks of chunk_size (checking each chunk's size).
inline lidarfx::io::las_points read_in_chunks(lidarfx::io::las_reader& r, std::size_t chunk_size)
{
    r.seek(0);
    lidarfx::io::las_points all, chunk;
    while (r.read(chunk, chunk_size) > 0) {
        CHECK(chunk.size() <= chunk_size);
        all.append(chunk);
    }
    return all;
}

inline bool starts_with(const std::string& s, const std::string& prefix)
{
    return s.rfind(prefix, 0) == 0;
}
inline bool contains(const std::string& s, const std::string& part)
{
    return s.find(part) != std::string::npos;
}

}  // namespace io_test
