// SPDX-License-Identifier: Apache-2.0
#include "tile_store.hpp"

#include <cerrno>
#include <cstring>
#include <iostream>
#include <stdexcept>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cli_common.hpp"

namespace lidarfx::cli {

namespace {

constexpr const char* manifest_header = "lidarfx tiles 2";
constexpr const char* marker_name = ".lidarfx-tile-store";
constexpr const char* manifest_name = "manifest.txt";
constexpr char tile_file_magic[8] = {'L', 'F', 'X', 'S', 'T', 'O', 'R', '1'};
constexpr std::size_t tile_header_bytes = 8 + 4 * 8;  // magic, index, fingerprint hash, payload size, checksum

[[noreturn]] void fail(const std::filesystem::path& path, const std::string& what, int error)
{
    throw std::runtime_error(path.string() + ": " + what + " (" + std::strerror(error) + ")");
}

/// True for a decimal number as std::to_string writes it (no sign, no leading zero).
bool canonical_number(const std::string& s)
{
    if (s.empty() || s.size() > 19 || (s.size() > 1 && s[0] == '0')) return false;
    for (const char c : s)
        if (c < '0' || c > '9') return false;
    return true;
}

/// The tile of a name "tile_N.bin", if it is one.
std::optional<std::size_t> tile_of_name(const std::string& name)
{
    if (name.size() < 10 || name.rfind("tile_", 0) != 0 || name.compare(name.size() - 4, 4, ".bin") != 0) return {};
    const std::string digits = name.substr(5, name.size() - 9);
    if (!canonical_number(digits)) return {};
    return static_cast<std::size_t>(std::stoull(digits));
}

/// True for a temporary write_file_atomically makes for one of the store's files: "NAME.tmpPID".
bool temporary_name(const std::string& name)
{
    const auto at = name.rfind(".tmp");
    if (at == std::string::npos || !canonical_number(name.substr(at + 4))) return false;
    const std::string of = name.substr(0, at);
    return of == manifest_name || of == marker_name || tile_of_name(of).has_value();
}

void put_u64(std::vector<std::uint8_t>& to, std::uint64_t v)
{
    const auto* b = reinterpret_cast<const std::uint8_t*>(&v);
    to.insert(to.end(), b, b + sizeof v);
}

std::uint64_t get_u64(const std::uint8_t* p)
{
    std::uint64_t v = 0;
    std::memcpy(&v, p, sizeof v);
    return v;
}

/// Reads a regular file without following a link or blocking on a FIFO; nullopt with `why` otherwise.
std::optional<std::vector<std::uint8_t>> read_regular(const std::filesystem::path& path, std::string& why)
{
    const int fd = ::open(path.c_str(), O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) {
        why = errno == ELOOP ? "is a symbolic link" : std::string("cannot be opened: ") + std::strerror(errno);
        return std::nullopt;
    }
    struct stat st {};
    if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
        ::close(fd);
        why = "is not a regular file";
        return std::nullopt;
    }
    std::vector<std::uint8_t> bytes(static_cast<std::size_t>(st.st_size));
    std::size_t got = 0;
    while (got < bytes.size()) {
        const ssize_t n = ::read(fd, bytes.data() + got, bytes.size() - got);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) break;
        got += static_cast<std::size_t>(n);
    }
    ::close(fd);
    if (got != bytes.size()) {
        why = "could not be read whole";
        return std::nullopt;
    }
    return bytes;
}

/// Removes `path` only when it is a regular file (never through or of a link). True when removed.
bool remove_regular(const std::filesystem::path& path)
{
    struct stat st {};
    return ::lstat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode) && ::unlink(path.c_str()) == 0;
}

}  // namespace

std::uint64_t fnv1a64(const void* data, std::size_t n, std::uint64_t h)
{
    const auto* b = static_cast<const std::uint8_t*>(data);
    for (std::size_t i = 0; i < n; ++i) h = (h ^ b[i]) * 0x100000001b3ull;
    return h;
}

void write_file_atomically(const std::filesystem::path& path, const std::vector<std::uint8_t>& bytes, bool sync_folder)
{
    auto temporary = path;
    temporary += ".tmp" + std::to_string(::getpid());
    remove_regular(temporary);  // a leftover of this process id; anything else there makes open fail
    const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644);
    if (fd < 0) fail(temporary, "cannot open for writing", errno);
    const auto give_up = [&](const char* what) {
        const int error = errno;
        ::close(fd);
        ::unlink(temporary.c_str());  // this run's temporary: never left behind a failed write
        fail(temporary, what, error);
    };
    std::size_t done = 0;
    while (done < bytes.size()) {
        const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) {
            if (n == 0) errno = ENOSPC;
            give_up("write failed");
        }
        done += static_cast<std::size_t>(n);
    }
    if (::fsync(fd) != 0 && errno != EINVAL) give_up("flushing to disk failed");  // EINVAL: cannot sync
    if (::close(fd) != 0) {
        const int error = errno;
        ::unlink(temporary.c_str());
        fail(temporary, "write failed", error);
    }
    if (std::rename(temporary.c_str(), path.c_str()) != 0) {
        const int error = errno;
        ::unlink(temporary.c_str());
        fail(path, "cannot rename the temporary file into place", error);
    }
    if (sync_folder) {
        const auto folder = path.parent_path();
        const int dfd = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
        if (dfd < 0) fail(folder, "cannot open to flush", errno);
        const bool ok = ::fsync(dfd) == 0 || errno == EINVAL;
        const int error = errno;
        ::close(dfd);
        if (!ok) fail(folder, "flushing to disk failed", error);
    }
}

tile_store::tile_store(std::filesystem::path dir, std::string fingerprint)
    : dir_(std::move(dir)),
      fingerprint_(std::move(fingerprint)),
      fingerprint_hash_(fnv1a64(fingerprint_.data(), fingerprint_.size()))
{
    const std::string what_to_do =
        "; lidarfx keeps its tiles only in a folder it made there and touched nothing: "
        "move it away, or choose another --out";
    struct stat st {};
    if (::lstat(dir_.c_str(), &st) != 0) {
        if (errno != ENOENT) fail(dir_, "cannot inspect", errno);
        if (::mkdir(dir_.c_str(), 0755) != 0) fail(dir_, "cannot create the tile folder", errno);
        st.st_mode = S_IFDIR;
    }
    if (S_ISLNK(st.st_mode)) throw usage_error(dir_.string() + " is a symbolic link" + what_to_do);
    if (!S_ISDIR(st.st_mode)) throw usage_error(dir_.string() + " exists and is not a folder" + what_to_do);

    // Every entry is looked at (lstat) before anything is removed: a folder that is not all ours is refused whole.
    bool marked = false, any = false;
    std::vector<std::size_t> tiles;
    std::vector<std::string> warnings;
    std::string stranger;  // the first entry that is not the store's
    for (const auto& entry : std::filesystem::directory_iterator(dir_)) {
        any = true;
        const std::string name = entry.path().filename().string();
        struct stat e {};
        if (::lstat(entry.path().c_str(), &e) != 0) fail(entry.path(), "cannot inspect", errno);
        const auto tile = tile_of_name(name);
        if (tile && !S_ISREG(e.st_mode)) {
            foreign_.insert(*tile);  // not ours: recomputed, and left as it is
            warnings.push_back(entry.path().string() +
                               (S_ISLNK(e.st_mode)    ? " is a symbolic link, not a regular file"
                                : S_ISFIFO(e.st_mode) ? " is a FIFO, not a regular file"
                                                      : " is not a regular file") +
                               "; recomputing the tile and leaving that entry as it is");
            continue;
        }
        if (tile) tiles.push_back(*tile);
        const bool ours = tile || name == manifest_name || name == marker_name || temporary_name(name);
        if ((!ours || !S_ISREG(e.st_mode)) && stranger.empty()) stranger = name;
        marked = marked || name == marker_name;
    }
    if (any && !marked)
        throw usage_error(dir_.string() + " is not a lidarfx tile folder (no " + marker_name + ")" + what_to_do);
    if (!stranger.empty())
        throw usage_error(dir_.string() + " holds " + stranger + ", which lidarfx did not write" + what_to_do);
    if (!any) {
        const std::string marker = "lidarfx tile store\n";
        write_file_atomically(dir_ / marker_name, std::vector<std::uint8_t>(marker.begin(), marker.end()));
    }

    const std::string manifest = std::string(manifest_header) + "\n" + fingerprint_ + "end of fingerprint\n";
    std::string why;
    const auto found = read_regular(dir_ / manifest_name, why);
    const bool same = found && std::string(found->begin(), found->end()) == manifest;
    if (same) {
        for (const std::size_t t : tiles) {
            if (read_checked(t, why)) {
                done_.insert(t);
                continue;
            }
            std::cerr << "lidarfx: warning: " << tile_path(t).string() << " " << why << "; recomputing the tile\n";
            remove_regular(tile_path(t));
        }
        std::cerr << "lidarfx: resuming the run in " << dir_.string() << ": " << done_.size()
                  << " tile(s) already done\n";
    } else {
        if (found) {
            std::cerr << "lidarfx: " << dir_.string() << " holds tiles of a run with other inputs or settings; "
                      << "starting over\n";
        }
        for (const std::size_t t : tiles) remove_regular(tile_path(t));
    }
    for (const auto& w : warnings) std::cerr << "lidarfx: warning: " << w << "\n";
    for (const auto& entry : std::filesystem::directory_iterator(dir_))  // temporaries of killed runs
        if (temporary_name(entry.path().filename().string())) remove_regular(entry.path());
    if (done_.empty())
        write_file_atomically(dir_ / manifest_name, std::vector<std::uint8_t>(manifest.begin(), manifest.end()));
}

std::optional<std::vector<std::uint8_t>> tile_store::read_checked(std::size_t tile, std::string& why) const
{
    auto bytes = read_regular(tile_path(tile), why);
    if (!bytes) return std::nullopt;
    if (bytes->size() < tile_header_bytes || std::memcmp(bytes->data(), tile_file_magic, 8) != 0) {
        why = "is not a saved lidarfx tile";
        return std::nullopt;
    }
    const std::uint8_t* h = bytes->data() + 8;
    if (get_u64(h) != tile) {
        why = "holds tile " + std::to_string(get_u64(h)) + ", not tile " + std::to_string(tile);
        return std::nullopt;
    }
    if (get_u64(h + 8) != fingerprint_hash_) {
        why = "was saved by a run with other inputs or settings";
        return std::nullopt;
    }
    const std::size_t size = bytes->size() - tile_header_bytes;
    if (get_u64(h + 16) != size) {
        why = "is cut short or too long";
        return std::nullopt;
    }
    if (get_u64(h + 24) != fnv1a64(bytes->data() + tile_header_bytes, size)) {
        why = "fails its checksum (its contents changed after it was saved)";
        return std::nullopt;
    }
    bytes->erase(bytes->begin(), bytes->begin() + static_cast<std::ptrdiff_t>(tile_header_bytes));
    return bytes;
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
    std::string why;
    auto payload = read_checked(tile, why);
    if (!payload) throw std::runtime_error(tile_path(tile).string() + " " + why + " (changed during the run)");
    return std::move(*payload);
}

void tile_store::save(std::size_t tile, const std::vector<std::uint8_t>& payload)
{
    {
        const std::lock_guard lock(mutex_);
        if (foreign_.count(tile)) return;
    }
    std::vector<std::uint8_t> bytes(tile_file_magic, tile_file_magic + 8);
    bytes.reserve(tile_header_bytes + payload.size());
    for (const std::uint64_t v : {std::uint64_t{tile}, fingerprint_hash_, std::uint64_t{payload.size()},
                                  fnv1a64(payload.data(), payload.size())})
        put_u64(bytes, v);
    bytes.insert(bytes.end(), payload.begin(), payload.end());
    // The folder is not flushed: a rename lost to a power cut only means the tile is read again.
    write_file_atomically(tile_path(tile), bytes, false);
    const std::lock_guard lock(mutex_);
    done_.insert(tile);
}

void tile_store::remove()
{
    const std::lock_guard lock(mutex_);
    remove_tile_folder(dir_);
    done_.clear();
}

void remove_tile_folder(const std::filesystem::path& dir)
{
    struct stat st {
    }, marker_st{};
    // Only a real folder holding the marker is the store: a link, a file or a foreign folder is not touched.
    if (::lstat(dir.c_str(), &st) != 0 || !S_ISDIR(st.st_mode)) return;
    if (::lstat((dir / marker_name).c_str(), &marker_st) != 0 || !S_ISREG(marker_st.st_mode)) return;
    std::error_code ec;
    for (const auto& entry : std::filesystem::directory_iterator(dir, ec)) {
        const std::string name = entry.path().filename().string();
        if (tile_of_name(name) || name == manifest_name || temporary_name(name)) remove_regular(entry.path());
    }
    remove_regular(dir / marker_name);  // last: until the folder is empty it stays recognisably ours
    if (::rmdir(dir.c_str()) != 0 && errno != ENOENT) {
        const std::string marker = "lidarfx tile store\n";
        write_file_atomically(dir / marker_name, std::vector<std::uint8_t>(marker.begin(), marker.end()), false);
        std::cerr << "lidarfx: left " << dir.string() << ": it holds entries lidarfx did not write\n";
    }
}

std::filesystem::path tile_store::tile_path(std::size_t tile) const
{
    return dir_ / ("tile_" + std::to_string(tile) + ".bin");
}

}  // namespace lidarfx::cli
