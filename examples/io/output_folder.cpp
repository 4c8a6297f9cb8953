// SPDX-License-Identifier: Apache-2.0
#include "io/output_folder.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <future>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <system_error>
#include <thread>

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include "io/file_output.hpp"
#include "io/sha256.hpp"
#include "io/tables.hpp"

namespace lidarfx::io {

namespace {

constexpr const char* temporary_suffix = ".lidarfx-tmp";
constexpr const char* lock_name = ".lidarfx.lock";
constexpr const char* manifest_name = "manifest.json";

std::runtime_error failure(const std::filesystem::path& path, const std::string& what)
{
    return std::runtime_error(path.string() + ": " + what);
}

std::string errno_text()
{
    return std::strerror(errno);
}

/// ".<name>.<pid>.lidarfx-tmp": hidden, unique to this process, recognisable as a leftover.
std::string temporary_name(const std::string& name)
{
    std::string t = ".";
    t += name;
    t += '.';
    t += std::to_string(::getpid());
    t += temporary_suffix;
    return t;
}

/// True for a name of the form temporary_name gives: ".<name>.<decimal pid>.lidarfx-tmp", <name> not empty.
bool is_temporary_name(const std::string& t)
{
    const std::size_t suffix = std::strlen(temporary_suffix);
    if (t.size() <= suffix + 3 || t[0] != '.' || t.compare(t.size() - suffix, suffix, temporary_suffix) != 0)
        return false;
    const std::string rest = t.substr(1, t.size() - suffix - 1);  // <name>.<pid>
    const auto dot = rest.rfind('.');
    if (dot == std::string::npos || dot == 0 || dot + 1 == rest.size()) return false;
    for (std::size_t i = dot + 1; i < rest.size(); ++i)
        if (rest[i] < '0' || rest[i] > '9') return false;
    return true;
}

/// lstat of `path`: nullopt-like false when nothing is there.
bool entry_at(const std::filesystem::path& path, struct stat& st)
{
    if (::lstat(path.c_str(), &st) == 0) return true;
    if (errno == ENOENT) return false;
    throw failure(path, "cannot inspect: " + errno_text());
}

/// Flushes a file's (or folder's) contents to the disk.
void sync_path(const std::filesystem::path& path, bool directory)
{
    const int fd = ::open(path.c_str(), (directory ? O_RDONLY | O_DIRECTORY : O_RDONLY) | O_CLOEXEC | O_NOFOLLOW);
    if (fd < 0) throw failure(path, "cannot open to flush: " + errno_text());
    const bool ok = ::fsync(fd) == 0 || errno == EINVAL;  // EINVAL: the file system cannot sync (e.g. some tmpfs)
    ::close(fd);
    if (!ok) throw failure(path, "flushing to disk failed: " + errno_text());
}

/// The files manifest.json lists (name, bytes, sha256), as commit() writes it; empty when there is no manifest
/// or it cannot be read (then nothing counts as an earlier run's unchanged output).
struct listed_file {
    std::string name;
    std::uintmax_t bytes = 0;
    std::string sha256;
};
std::vector<listed_file> files_in_manifest(const std::filesystem::path& manifest)
{
    std::ifstream in(manifest, std::ios::binary);
    std::vector<listed_file> files;
    // One line per file: {"name": "<name>", "bytes": <n>, "sha256": "<hex>"} (names are plain file names).
    static const std::regex line(
        R"re(\{"name": "((?:[^"\\]|\\.)*)", "bytes": ([0-9]+), "sha256": "([0-9a-f]{64})"\})re");
    for (std::string text; std::getline(in, text);) {
        std::smatch m;
        if (!std::regex_search(text, m, line)) continue;
        std::string name;
        for (std::size_t i = 0; i < m[1].str().size(); ++i) {
            const char c = m[1].str()[i];
            if (c == '\\' && i + 1 < m[1].str().size()) {
                const char e = m[1].str()[++i];
                if (e != '"' && e != '\\') return {};  // an escape plain file names never need: not ours
                name += e;
            } else {
                name += c;
            }
        }
        files.push_back({name, std::stoull(m[2].str()), m[3].str()});
    }
    return files;
}

}  // namespace

std::string sha256_of_file(const std::filesystem::path& path)
{
    std::ifstream in(path, std::ios::binary);
    if (!in) throw failure(path, "cannot open for reading");
    sha256 hash;
    std::vector<char> buffer(1 << 16);
    while (in) {
        in.read(buffer.data(), static_cast<std::streamsize>(buffer.size()));
        hash.add(reinterpret_cast<const unsigned char*>(buffer.data()), static_cast<std::size_t>(in.gcount()));
    }
    if (in.bad()) throw failure(path, "read failed");
    return hash.hex();
}

output_folder::output_folder(std::filesystem::path dir, std::vector<std::filesystem::path> inputs)
    : dir_(std::move(dir)), inputs_(std::move(inputs))
{
    if (dir_.empty()) throw std::runtime_error("no output folder given");
    struct stat st {};
    if (entry_at(dir_, st) && !S_ISDIR(st.st_mode)) {
        // A symlink to a folder is accepted (the user chose it); anything else is not a folder.
        if (!S_ISLNK(st.st_mode) || !std::filesystem::is_directory(dir_)) {
            throw failure(dir_, "exists and is not a folder");
        }
    }
    std::error_code ec;
    created_ = !std::filesystem::exists(dir_);
    std::filesystem::create_directories(dir_, ec);
    if (ec) throw failure(dir_, "cannot create the output folder: " + ec.message());
    // The lock file is removed when the run ends, so a lock taken on a file that a finishing run has just
    // removed is no lock: it is retaken until the locked file is the one at the lock's name.
    const auto lock = dir_ / lock_name;
    for (;;) {
        lock_fd_ = ::open(lock.c_str(), O_CREAT | O_RDWR | O_CLOEXEC | O_NOFOLLOW, 0644);
        if (lock_fd_ < 0) throw failure(dir_, "cannot write into the output folder: " + errno_text());
        if (::flock(lock_fd_, LOCK_EX | LOCK_NB) != 0) {
            ::close(lock_fd_);
            lock_fd_ = -1;
            throw failure(dir_, "another lidarfx run is writing into this folder; wait for it or choose another --out");
        }
        struct stat held {};
        struct stat named {};
        if (::fstat(lock_fd_, &held) == 0 && ::lstat(lock.c_str(), &named) == 0 && held.st_dev == named.st_dev &&
            held.st_ino == named.st_ino) {
            break;
        }
        ::close(lock_fd_);
        lock_fd_ = -1;
    }
    // Holding the lock, no other run is active: temporary files here are leftovers of killed runs.
    // Only names of the exact form temporary_name gives, and only regular files (a link is never removed).
    for (const auto& entry : std::filesystem::directory_iterator(dir_)) {
        struct stat e {};
        if (is_temporary_name(entry.path().filename().string()) && ::lstat(entry.path().c_str(), &e) == 0 &&
            S_ISREG(e.st_mode)) {
            std::filesystem::remove(entry.path(), ec);
        }
    }
}

output_folder::~output_folder()
{
    std::error_code ec;
    if (!committed_) {
        for (const auto& p : pending_) std::filesystem::remove(p.temporary, ec);
    }
    // The lock file goes while still locked (no run is left with a lock on it), so no run leaves it behind.
    if (lock_fd_ >= 0) std::filesystem::remove(dir_ / lock_name, ec);
    if (!committed_ && created_ && lock_fd_ >= 0) {
        std::filesystem::remove(dir_, ec);  // only succeeds when empty
    }
    if (lock_fd_ >= 0) ::close(lock_fd_);  // releases the lock
}

void output_folder::check_name(const std::string& name) const
{
    if (name.empty() || name == "." || name == ".." || name.find('/') != std::string::npos || name == lock_name) {
        throw std::runtime_error("output name '" + name + "' is not a plain file name");
    }
    const auto target = dir_ / name;
    struct stat st {};
    if (!entry_at(target, st)) return;
    if (S_ISLNK(st.st_mode)) throw failure(target, "is a symbolic link; refusing to write through or replace it");
    if (!S_ISREG(st.st_mode)) throw failure(target, "exists and is not a regular file; refusing to replace it");
    for (const auto& input : inputs_) {
        struct stat in {};
        if (::stat(input.c_str(), &in) == 0 && in.st_dev == st.st_dev && in.st_ino == st.st_ino) {
            throw failure(target, "is an input of this run (" + input.string() + "); refusing to overwrite it");
        }
    }
}

void output_folder::declare(const std::string& name)
{
    check_name(name);
    const std::lock_guard<std::mutex> guard(mutex_);
    if (std::find(declared_.begin(), declared_.end(), name) == declared_.end()) declared_.push_back(name);
}

void output_folder::write(const std::string& name, const std::function<void(const std::string& temporary_path)>& writer)
{
    const auto temporary = dir_ / temporary_name(name);
    {
        const std::lock_guard lock(mutex_);
        if (committed_) throw failure(dir_ / name, "written after the run was committed");
        check_name(name);
        if (std::any_of(pending_.begin(), pending_.end(), [&](const pending& p) { return p.name == name; })) {
            throw failure(dir_ / name, "written twice in one run");
        }
        std::error_code ec;
        std::filesystem::remove(temporary, ec);  // never write through whatever stands at the temporary name
        pending_.push_back({name, temporary});
    }
    writer(temporary.string());
    struct stat st {};
    if (!entry_at(temporary, st) || !S_ISREG(st.st_mode)) throw failure(dir_ / name, "the writer produced no file");
}

void output_folder::commit(const std::string& command)
{
    if (committed_) return;
    // Everything is checked before anything moves, so a refusal leaves the folder as it was. The manifest lists
    // the files by name, whatever order (or threads) they were written in.
    for (const auto& p : pending_) check_name(p.name);
    std::sort(pending_.begin(), pending_.end(), [](const pending& a, const pending& b) { return a.name < b.name; });
    // Each file flushed to disk and its checksum taken, on all cores (hashing reads back everything written).
    std::vector<std::string> digests(pending_.size());
    {
        std::atomic<std::size_t> next{0};
        const auto worker = [&] {
            for (std::size_t i; (i = next.fetch_add(1)) < pending_.size();) {
                sync_path(pending_[i].temporary, false);
                digests[i] = sha256_of_file(pending_[i].temporary);
            }
        };
        const std::size_t helpers =
            std::min<std::size_t>(std::max(1u, std::thread::hardware_concurrency()), pending_.size());
        std::vector<std::future<void>> running;
        for (std::size_t t = 1; t < helpers; ++t) running.push_back(std::async(std::launch::async, worker));
        worker();
        for (auto& r : running) r.get();  // rethrows a reader's error
    }
    std::ostringstream manifest;
    manifest << "{\n  \"program\": \"lidarfx\",\n  \"command\": " << json_string(command) << ",\n";
    if (!units_.empty()) manifest << "  \"units\": " << json_string(units_) << ",\n";
    manifest << "  \"files\": [";
    for (std::size_t i = 0; i < pending_.size(); ++i) {
        const auto& p = pending_[i];
        manifest << (i ? ",\n" : "\n") << "    {\"name\": " << json_string(p.name)
                 << ", \"bytes\": " << std::filesystem::file_size(p.temporary) << ", \"sha256\": \"" << digests[i]
                 << "\"}";
    }
    manifest << "\n  ]\n}\n";
    check_name(manifest_name);
    const std::vector<std::string> stale = stale_companions();
    std::error_code ec;
    std::filesystem::remove(dir_ / manifest_name, ec);  // from here until the new one exists, the folder is incomplete
    sync_path(dir_, true);
    for (const auto& p : pending_) {
        if (std::rename(p.temporary.c_str(), (dir_ / p.name).c_str()) != 0) {
            throw failure(dir_ / p.name, "cannot move into place: " + errno_text());
        }
    }
    for (const auto& name : stale) {
        if (::unlink((dir_ / name).c_str()) != 0 && errno != ENOENT) {
            throw failure(dir_ / name, "cannot remove this stale output of an earlier run: " + errno_text());
        }
        removed_.push_back(name);
    }
    const auto manifest_temporary = dir_ / temporary_name(manifest_name);
    write_file(manifest_temporary.string(), manifest.str());
    sync_path(manifest_temporary, false);
    if (std::rename(manifest_temporary.c_str(), (dir_ / manifest_name).c_str()) != 0) {
        throw failure(dir_ / manifest_name, "cannot move into place: " + errno_text());
    }
    sync_path(dir_, true);
    committed_ = true;
}

std::vector<std::string> output_folder::stale_companions() const
{
    std::vector<std::string> stale;
    const auto listed = files_in_manifest(dir_ / manifest_name);
    for (const auto& name : declared_) {
        if (std::any_of(pending_.begin(), pending_.end(), [&](const pending& p) { return p.name == name; })) continue;
        const auto entry =
            std::find_if(listed.begin(), listed.end(), [&](const listed_file& f) { return f.name == name; });
        struct stat st {};
        if (entry == listed.end() || !entry_at(dir_ / name, st) || !S_ISREG(st.st_mode)) continue;
        check_name(name);  // never an input of this run, never through a link
        if (static_cast<std::uintmax_t>(st.st_size) == entry->bytes && sha256_of_file(dir_ / name) == entry->sha256) {
            stale.push_back(name);
        }
    }
    std::sort(stale.begin(), stale.end());
    return stale;
}

std::vector<std::filesystem::path> output_folder::files() const
{
    std::vector<std::filesystem::path> out;
    for (const auto& p : pending_) out.push_back(dir_ / p.name);
    return out;
}

}  // namespace lidarfx::io
