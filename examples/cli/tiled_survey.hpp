// SPDX-License-Identifier: Apache-2.0
// Reading a survey tile by tile (stage A of a tiled run, docs/scale.md): the same survey as read_survey,
// bit for bit, with the points of one tile at a time per thread, resumable, and spread over MPI ranks.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <mutex>
#include <span>
#include <string>
#include <vector>

#include <lidarfx/tiling/tile_plan.hpp>

#include "cli_common.hpp"

namespace lidarfx::cli {

/// The input files of a command: each argument a file, or a folder whose *.las and *.laz files (any case,
/// sorted by name) are taken. @throws usage_error for a folder with no LAS file.
std::vector<std::string> survey_files(const std::vector<std::string>& arguments);

/// The tiling of a survey's grid for a tiled run: cores of tile_edge_m metres (rounded to whole cells), no
/// halo (stage A bins each point in its own cell), each file listed for the tiles its header box (grown by
/// a micrometre, so that a rounding step beyond it is still read) reaches, `tiles_in_flight` tiles at once
/// within opt.memory_budget_bytes (0 = no limit).
/// @throws usage_error naming what fits when the plan exceeds the budget.
tile_plan plan_survey_tiles(const survey_layout& layout, double tile_edge_m, const survey_options& opt,
                            int tiles_in_flight);

/// The files of a survey as make_tile_plan takes them: each header box, grown by a micrometre (and 1e-12 of
/// the coordinates) so that a box rounded a hair inside its points, or a scan segment's cell coordinates a
/// rounding step beyond its ends, still reach their tiles; a file without points gets a box off the grid.
std::vector<survey_file_extent> survey_file_extents(const survey_layout& layout);

/// Who reads each file of a tiled run (assign_file_readers on survey_file_extents): its home tile, which
/// counts its points, and the neighbours the home hands their few points to. hand = false, or a plan whose
/// handed points and waiting tiles (with tiles_in_flight tiles read at once) would not fit memory_budget_bytes
/// (0 = no limit) besides its own peak: nothing is handed, every listing tile reads the file (as MPI ranks do:
/// they share no memory).
std::vector<file_readers> survey_file_readers(const survey_layout& layout, const tile_plan& plan, bool hand,
                                              std::uint64_t memory_budget_bytes = 0, int tiles_in_flight = 1);

/// The survey rasters of one tile's core cells.
struct tile_rasters {
    std::size_t index = 0;              ///< the tile (tile_plan::tiles)
    rasterize_result rasters;           ///< on the core's window of the survey grid
    raster<std::uint8_t> scan_covered;  ///< core-sized; empty when no file the tile read has GPS times
    std::uint64_t points_read = 0;      ///< points of the files this tile owns (each file has one owner tile)
};

/// Reads the files of tile `index` and bins the points that fall (grid::cell_of on the survey grid) in its
/// core, on the core's window, each point moved to the centre of its survey cell so that the window cannot
/// place it elsewhere: the rasters equal the untiled survey's core cells bit for bit. Scan lines are walked
/// on the survey grid and clipped to the core. Every file the tile lists is read (nothing is handed); the
/// file's home tile (`readers`) counts its NaN and outside points, and refuses points outside the grid unless
/// `crop`, as read_survey does.
tile_rasters read_tile(const survey_layout& layout, const std::vector<std::string>& paths, const tile_plan& plan,
                       const std::vector<file_readers>& readers, std::size_t index, bool crop);

/// tile_rasters as bytes (for a resume file or an MPI message), and back. unpack checks the size against
/// the plan. @throws std::runtime_error naming `where` on bytes that are not a tile of this plan.
std::vector<std::uint8_t> pack_tile(const tile_rasters& t);
tile_rasters unpack_tile(std::span<const std::uint8_t> bytes, const tile_plan& plan, const std::string& where);

/// Assembles the survey of a tiled run: start_tiled_survey allocates the survey-wide rasters, place_tile
/// copies one tile's core in (tiles write disjoint cells: several threads may place at once, provided
/// the first tile with scan lines is placed by one; see tiled_survey_assembly), finish_tiled_survey adds
/// what no tile read and checks the result as read_survey does.
class tiled_survey_assembly {
public:
    tiled_survey_assembly(survey_layout layout, const tile_plan& plan, const std::vector<file_readers>& readers);
    void place(const tile_rasters& t);
    survey finish();

private:
    survey s_;
    tile_plan plan_;
    std::uint64_t unread_points_ = 0;  // points of files no tile lists (outside the grid)
    std::mutex mutex_;
};

/// A fingerprint of a tiled run's inputs and settings: each file's path, size, modification time and an FNV-1a 64
/// hash of its first and last 64 KiB and 16 evenly spaced 4 KiB blocks (the whole file up to 192 KiB), the cell,
/// tile edge and crop. Two runs with the same fingerprint produce the same tiles.
std::string tiled_fingerprint(const std::vector<std::string>& paths, const survey_options& opt, double tile_edge_m);

/// read_survey, tile by tile: stage A of a tiled run on opt.threads threads (one tile, one accumulator per
/// thread; tiles start in index order), with a progress bar over tiles. Each file is read by its home tile,
/// which hands the points of thin neighbours to them (survey_file_readers): a survey cut into files along
/// the tile lines is read once, not up to four times. A tile is finished by whichever thread brings its last
/// part (its own reading or a handed file). With a non-empty `resume_dir`, finished tiles are kept there
/// (tile_store) and a rerun with the same inputs and settings skips them; the caller removes the folder once its
/// outputs are committed. Test hook: LIDARFX_TEST_KILL_AFTER_TILES=N in the environment makes the program kill
/// itself (SIGKILL) right after the N-th tile of this run is recorded. Same survey as read_survey.
survey read_survey_tiled(const std::vector<std::string>& paths, const survey_options& opt, double tile_edge_m,
                         const std::filesystem::path& resume_dir);

}  // namespace lidarfx::cli
