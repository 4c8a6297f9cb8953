// SPDX-License-Identifier: Apache-2.0
// tile_store: the finished tiles of a tiled run, kept in the output folder so that a killed run resumes.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace lidarfx::cli {

/// Writes `bytes` to `path` so that the file is either absent, as before, or complete: a temporary file
/// next to it (PATH.tmpPID) is written, flushed to disk (fsync) and renamed over `path`, then (sync_folder)
/// the folder is flushed so that the rename itself survives a power cut. A failed write removes its
/// temporary. @throws std::runtime_error naming the file and the system's reason ("No space left on device").
void write_file_atomically(const std::filesystem::path& path, const std::vector<std::uint8_t>& bytes,
                           bool sync_folder = true);

/// 64-bit FNV-1a of `n` bytes, continuing from `h` (any single changed byte changes it).
std::uint64_t fnv1a64(const void* data, std::size_t n, std::uint64_t h = 0xcbf29ce484222325ull);

/// The finished tiles of a tiled run in a folder (OUT/.lidarfx-tiles/). The folder is lidarfx's only when it
/// holds the marker file .lidarfx-tile-store; it then holds only these names: the marker, manifest.txt (the
/// run's fingerprint: inputs and settings, see tiled_fingerprint), tile_N.bin (finished tile N) and
/// temporaries NAME.tmpPID. A tile file records its index, a hash of the fingerprint, its payload's size and
/// FNV-1a 64 checksum; it is written atomically (write_file_atomically). Nothing is ever removed through a
/// link or by pattern: only regular files (lstat) of those exact names. Thread-safe.
class tile_store {
public:
    /// Opens (creating) `dir`. Refused (usage_error, nothing touched) when `dir` is a symlink or not a folder,
    /// a folder without the marker that is not empty, or a folder holding a name that is not the store's.
    /// When the manifest holds another fingerprint, the run starts over (its tiles and temporaries are
    /// removed, said on stderr); with the same fingerprint each tile file is checked (a regular file, opened
    /// without following links or blocking, whose index, fingerprint and checksum match) and kept; one that
    /// fails is named on stderr with the reason and recomputed.
    tile_store(std::filesystem::path dir, std::string fingerprint);

    bool done(std::size_t tile) const;
    std::size_t done_count() const;
    /// The payload saved for `tile`, checked again. @throws std::runtime_error naming the file and the reason.
    std::vector<std::uint8_t> load(std::size_t tile) const;
    /// Saves the payload of `tile` (its file is the record that it is finished). A tile whose name holds
    /// something that is not the store's (a link, a FIFO) is not saved: that entry is left as it is.
    void save(std::size_t tile, const std::vector<std::uint8_t>& payload);
    /// Removes the store's own files by name, then the folder when that leaves it empty (after a complete run);
    /// anything else is left, said on stderr.
    void remove();

private:
    std::filesystem::path tile_path(std::size_t tile) const;
    /// The checked payload of the file at `path` for `tile`, or the reason it is refused.
    std::optional<std::vector<std::uint8_t>> read_checked(std::size_t tile, std::string& why) const;

    std::filesystem::path dir_;
    std::string fingerprint_;
    std::uint64_t fingerprint_hash_ = 0;
    std::set<std::size_t> done_;
    std::set<std::size_t> foreign_;  // tiles whose name holds an entry that is not a regular file
    mutable std::mutex mutex_;
};

/// Removes a tile folder after a complete run: only when `dir` is a real folder holding the marker, only the
/// store's own regular files by name, then the folder when that leaves it empty (else said on stderr).
void remove_tile_folder(const std::filesystem::path& dir);

}  // namespace lidarfx::cli
