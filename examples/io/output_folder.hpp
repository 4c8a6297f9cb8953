// SPDX-License-Identifier: Apache-2.0
// output_folder: the folder a run writes into, written so that no run loses user data (internal to the examples).
#pragma once

#include <filesystem>
#include <functional>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

namespace lidarfx::io {

/// The folder a run writes its outputs into. What it guarantees:
/// - a file appears under its final name only complete: each is written to a temporary name in the folder and
///   renamed into place in commit(), after every file of the run is written (a killed or failed run leaves the
///   earlier outputs as they were, and its own temporary files, which the next run into the folder removes);
/// - manifest.json (name, size and SHA-256 of every file of the run) is removed when commit() starts and written
///   last, so a folder whose manifest is missing holds an incomplete run;
/// - a symlink at an output name is never followed or replaced, and no output replaces an input of the run;
/// - one run at a time: the folder is locked (flock on .lidarfx.lock, released by the kernel even after kill -9),
///   and a second run into it fails at once with a message, touching nothing; the run removes .lidarfx.lock
///   when it ends (a killed run leaves it, harmless: the next run takes and removes it);
/// - no stale companion: a name the run declared but did not write (a .prj when this survey has no CRS) is
///   removed in commit() only when an earlier lidarfx run wrote it and it is unchanged since (manifest.json lists
///   it with the same size and SHA-256); a file the manifest does not list, or that changed since, stays.
/// Errors are std::runtime_error naming the file.
class output_folder {
public:
    /// Creates `dir` when missing (with its parents), locks it and removes temporary files left by killed runs.
    /// `inputs` are the files the run reads (compared by device and inode). A run that ends without commit()
    /// removes its temporary files, and the folder too when this run created it and left it empty.
    explicit output_folder(std::filesystem::path dir, std::vector<std::filesystem::path> inputs = {});
    ~output_folder();
    output_folder(const output_folder&) = delete;
    output_folder& operator=(const output_folder&) = delete;

    const std::filesystem::path& path() const noexcept { return dir_; }

    /// Throws if an output named `name` could not be written safely: the name is not a plain file name, a
    /// symlink or a folder stands there, or it is one of the inputs. Call it before long work.
    void check_name(const std::string& name) const;

    /// check_name(name), and records `name` as an output this run may write (see "no stale companion" above).
    void declare(const std::string& name);

    /// Names commit() removed as stale companions of an earlier run (sorted).
    const std::vector<std::string>& removed_stale() const noexcept { return removed_; }

    /// Writes the output `name` by calling `writer` with a temporary path in the folder; the file takes its
    /// final name in commit(). Writing a name twice in one run is an error. Several threads may write
    /// different names at once (the writers run concurrently; the bookkeeping is serialised).
    void write(const std::string& name, const std::function<void(const std::string& temporary_path)>& writer);

    /// A sentence on the units of the outputs, recorded in manifest.json as "units" (the last one set).
    void set_units_note(std::string note) { units_ = std::move(note); }

    /// Moves every written file to its final name and writes manifest.json. `command` is recorded in it.
    void commit(const std::string& command = "");

    /// Final paths of the files written so far (in the order written).
    std::vector<std::filesystem::path> files() const;

private:
    std::vector<std::string> stale_companions() const;  // declared, not written, unchanged since the last manifest
    struct pending {
        std::string name;
        std::filesystem::path temporary;
    };
    std::filesystem::path dir_;
    std::vector<std::filesystem::path> inputs_;
    std::vector<pending> pending_;
    std::vector<std::string> declared_, removed_;
    mutable std::mutex mutex_;  // guards pending_ while writers run on several threads
    int lock_fd_ = -1;
    bool created_ = false;  // the folder did not exist before this run
    bool committed_ = false;
    std::string units_;
};

/// SHA-256 of a file's bytes as 64 lower-case hex digits. @throws std::runtime_error naming the file.
std::string sha256_of_file(const std::filesystem::path& path);

}  // namespace lidarfx::io
