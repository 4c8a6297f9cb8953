// SPDX-License-Identifier: Apache-2.0
#include "tile_store.hpp"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <iostream>
#include <iterator>
#include <sstream>
#include <stdexcept>

#include <fcntl.h>
#include <unistd.h>

namespace lidarfx::cli {

namespace {

constexpr const char* manifest_header = "lidarfx tiles 1";

[[noreturn]] void fail(const std::filesystem::path& path, const std::string& what)
{
    throw std::runtime_error(path.string() + ": " + what + " (" + std::strerror(errno) + ")");
}

void sync_fd_of(const std::filesystem::path& path, int flags)
{
    const int fd = ::open(path.c_str(), flags | O_CLOEXEC);
    if (fd < 0) fail(path, "cannot open to flush");
    const bool ok = ::fsync(fd) == 0 || errno == EINVAL;   // EINVAL: the file system cannot sync
    ::close(fd);
    if (!ok) fail(path, "flushing to disk failed");
}

}  // namespace

void write_file_atomically(const std::filesystem::path& path, const std::vector<std::uint8_t>& bytes, bool sync_folder)
{
    auto temporary = path;
    temporary += ".tmp" + std::to_string(::getpid());
    {
        std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
        if (!out) fail(temporary, "cannot open for writing");
        out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
        out.close();
        if (!out) fail(temporary, "write failed");
    }
    sync_fd_of(temporary, O_RDONLY);
    if (std::rename(temporary.c_str(), path.c_str()) != 0) fail(path, "cannot rename the temporary file into place");
    if (sync_folder) sync_fd_of(path.parent_path(), O_RDONLY | O_DIRECTORY);
}

tile_store::tile_store(std::filesystem::path dir, std::string fingerprint)
    : dir_(std::move(dir)), fingerprint_(std::move(fingerprint))
{
    std::filesystem::create_directories(dir_);
    std::ifstream in(dir_ / "manifest.txt");
    const std::string manifest = std::string(manifest_header) + "\n" + fingerprint_ + "end of fingerprint\n";
    if (in) {
        const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
        if (text == manifest) {
            // A tile file exists only complete (renamed into place after it was flushed).
            for (const auto& entry : std::filesystem::directory_iterator(dir_)) {
                const std::string name = entry.path().filename().string();
                std::size_t tile = 0, used = 0;
                if (name.rfind("tile_", 0) != 0 || name.size() < 10 || name.compare(name.size() - 4, 4, ".bin") != 0) continue;
                try {
                    tile = std::stoul(name.substr(5, name.size() - 9), &used);
                } catch (const std::exception&) {
                    continue;
                }
                if (used == name.size() - 9 && entry.path() == tile_path(tile)) done_.insert(tile);
            }
            std::cerr << "lidarfx: resuming the run in " << dir_.string() << ": " << done_.size()
                      << " tile(s) already done\n";
        } else {
            std::cerr << "lidarfx: " << dir_.string() << " holds tiles of a run with other inputs or settings; "
                      << "starting over\n";
        }
    }
    // Everything else (another run's tiles, temporary files of a killed one) goes.
    for (const auto& entry : std::filesystem::directory_iterator(dir_)) {
        bool keep = entry.path().filename() == "manifest.txt" && !done_.empty();
        for (const std::size_t t : done_) keep = keep || entry.path() == tile_path(t);
        if (!keep) std::filesystem::remove(entry.path());
    }
    if (done_.empty()) write_file_atomically(dir_ / "manifest.txt", std::vector<std::uint8_t>(manifest.begin(), manifest.end()));
}

bool tile_store::done(std::size_t tile) const
{
    const std::lock_guard lock(mutex_);
    return done_.count(tile) > 0;
}

std::size_t tile_store::done_count() const
{
    const std::lock_guard lock(mutex_);
    return done_.size();
}

std::vector<std::uint8_t> tile_store::load(std::size_t tile) const
{
    const auto path = tile_path(tile);
    std::ifstream in(path, std::ios::binary);
    if (!in) fail(path, "cannot open the saved tile; remove the folder to start over");
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void tile_store::save(std::size_t tile, const std::vector<std::uint8_t>& bytes)
{
    // The folder is not flushed: a rename lost to a power cut only means the tile is read again.
    write_file_atomically(tile_path(tile), bytes, false);
    const std::lock_guard lock(mutex_);
    done_.insert(tile);
}

void tile_store::remove()
{
    const std::lock_guard lock(mutex_);
    std::filesystem::remove_all(dir_);
    done_.clear();
}

std::filesystem::path tile_store::tile_path(std::size_t tile) const
{
    return dir_ / ("tile_" + std::to_string(tile) + ".bin");
}

}  // namespace lidarfx::cli
