// SPDX-License-Identifier: Apache-2.0
// tile_store: the finished tiles of a tiled run, kept in the output folder so that a killed run resumes.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <mutex>
#include <set>
#include <string>
#include <vector>

namespace lidarfx::cli {

/// Writes `bytes` to `path` so that the file is either absent, as before, or complete: a temporary file
/// next to it is written, flushed to disk (fsync) and renamed over `path`, then (sync_folder) the folder is
/// flushed so that the rename itself survives a power cut. @throws std::runtime_error naming the file.
void write_file_atomically(const std::filesystem::path& path, const std::vector<std::uint8_t>& bytes,
                           bool sync_folder = true);

/// The finished tiles of a tiled run in a folder (OUT/.lidarfx-tiles/): manifest.txt holds the run's
/// fingerprint (its inputs and settings, see tiled_fingerprint), written once; tile_N.bin holds the rasters
/// of finished tile N. Each file is written atomically (write_file_atomically), so a tile file exists only
/// complete and a killed run leaves only finished tiles. Thread-safe: tiles may be saved from several threads.
class tile_store {
public:
    /// Opens (creating) `dir`. When its manifest holds another fingerprint, the tiles there are of another
    /// run: they are removed and the run starts over (said on stderr); with the same fingerprint the
    /// finished tiles are kept (resume, said on stderr).
    tile_store(std::filesystem::path dir, std::string fingerprint);

    bool done(std::size_t tile) const;
    std::size_t done_count() const;
    /// The bytes saved for `tile`. @throws std::runtime_error naming the file.
    std::vector<std::uint8_t> load(std::size_t tile) const;
    /// Saves the bytes of `tile` (its file is the record that it is finished).
    void save(std::size_t tile, const std::vector<std::uint8_t>& bytes);
    /// Removes the folder (after a complete run).
    void remove();

private:
    std::filesystem::path tile_path(std::size_t tile) const;

    std::filesystem::path dir_;
    std::string fingerprint_;
    std::set<std::size_t> done_;
    mutable std::mutex mutex_;
};

}  // namespace lidarfx::cli
