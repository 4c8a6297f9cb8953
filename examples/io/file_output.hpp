// SPDX-License-Identifier: Apache-2.0
// Whole-file output with errors that name the file (internal to the I/O examples).
#pragma once

#include <cerrno>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace lidarfx::io {

/// Writes `size` bytes to `path` (created or truncated). @throws std::runtime_error naming the file.
inline void write_file(const std::string& path, const void* data, std::size_t size)
{
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    if (!out) throw std::runtime_error(path + ": cannot open for writing");
    out.write(static_cast<const char*>(data), static_cast<std::streamsize>(size));
    out.close();
    if (!out) throw std::runtime_error(path + ": write failed (" + std::strerror(errno) + ")");
}

inline void write_file(const std::string& path, const std::vector<std::uint8_t>& bytes)
{
    write_file(path, bytes.data(), bytes.size());
}

inline void write_file(const std::string& path, std::string_view text)
{
    write_file(path, text.data(), text.size());
}

}  // namespace lidarfx::io
