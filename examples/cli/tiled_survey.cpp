// SPDX-License-Identifier: Apache-2.0
#include "tiled_survey.hpp"

#include <algorithm>
#include <atomic>
#include <cctype>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <iostream>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <type_traits>

#include <sys/stat.h>

#include <lidarfx/kernels/points/scan_coverage.hpp>

#include "io/las.hpp"
#include "tile_store.hpp"

namespace lidarfx::cli {

namespace {

/// Points a tile reads at a time (the memory model of plan_survey_tiles counts this chunk per tile in flight).
constexpr std::size_t tile_chunk_points = std::size_t{1} << 19;

/// Calls f(member) for each per-cell raster of rasterize_result (a pointer to member), always in this order:
/// the tile file's layout follows it.
template <class F>
void each_cell_raster(F f)
{
    f(&rasterize_result::min_z);
    f(&rasterize_result::max_z);
    f(&rasterize_result::mean_intensity);
    f(&rasterize_result::count);
    f(&rasterize_result::dropout);
    f(&rasterize_result::multiple_returns);
}

/// Sets each per-cell raster of r to rows x cols uninitialized cells.
void allocate_cell_rasters(rasterize_result& r, std::ptrdiff_t rows, std::ptrdiff_t cols)
{
    each_cell_raster([&](auto member) {
        auto& cells = r.*member;
        cells = std::remove_cvref_t<decltype(cells)>(rows, cols, uninitialized);
    });
}

}  // namespace

std::vector<std::string> survey_files(const std::vector<std::string>& arguments)
{
    std::vector<std::string> files;
    for (const auto& a : arguments) {
        std::error_code ec;
        if (!std::filesystem::is_directory(a, ec)) {
            files.push_back(a);
            continue;
        }
        std::vector<std::string> found;
        for (const auto& entry : std::filesystem::directory_iterator(a)) {
            const auto name = entry.path().string();
            if (entry.is_regular_file() && (has_extension(name, ".las") || has_extension(name, ".laz")))
                found.push_back(name);
        }
        if (found.empty()) throw usage_error(a + " is a folder without *.las or *.laz files");
        std::sort(found.begin(), found.end());
        files.insert(files.end(), found.begin(), found.end());
    }
    return files;
}

tile_plan plan_survey_tiles(const survey_layout& layout, double tile_edge_m, const survey_options& opt,
                            int tiles_in_flight)
{
    if (!(tile_edge_m > 0) || !std::isfinite(tile_edge_m))
        throw usage_error("--tile must be a positive number of metres (got " + std::to_string(tile_edge_m) + ")");
    std::vector<survey_file_extent> files;
    for (std::size_t f = 0; f < layout.extents.size(); ++f) {
        // Grown by a micrometre (and 1e-12 of the coordinates): a header box rounded a hair inside its points,
        // or a scan segment's cell coordinates a rounding step beyond its ends, still reach the tile.
        const bounds& e = layout.extents[f];
        const double grow = 1e-6 + 1e-12 * std::max({std::abs(e.xmin), std::abs(e.xmax), std::abs(e.ymin), std::abs(e.ymax)});
        // A file without points has no meaningful box: it is read by no tile.
        if (layout.points[f] > 0) files.push_back({{e.xmin - grow, e.ymin - grow, e.xmax + grow, e.ymax + grow}, layout.points[f]});
        else files.push_back({bounds{layout.g.x0 - 1e9, layout.g.y0 + 1e9, layout.g.x0 - 1e9, layout.g.y0 + 1e9}, 0});
    }
    tile_plan_options o;
    o.tile_edge_m = tile_edge_m;
    o.halo_cells = 0;   // stage A bins each point in its own cell: no step reaches beyond the core
    o.memory_budget_bytes = opt.memory_budget_bytes;
    o.bytes_per_cell = opt.bytes_per_cell;
    o.bytes_per_tile_cell = 64;   // accumulator (24 B), finished rasters (18 B), scan lines (1 B), packed copy (19 B)
    o.bytes_per_point = 72;       // a chunk as read (42 B) and its points in the core (30 B)
    o.chunk_points = tile_chunk_points;
    o.tiles_in_flight = std::max(1, tiles_in_flight);
    try {
        return make_tile_plan(layout.g, files, o);
    } catch (const invalid_input& e) {
        std::ostringstream why;
        why << "--tile " << tile_edge_m << " does not fit --memory (lower --tile or --threads, or raise --memory): "
            << e.what();
        throw usage_error(why.str());
    }
}

namespace {

/// The tile that reads each file first (lowest index); tiles.size() for files no tile lists.
std::vector<std::size_t> file_owners(const tile_plan& plan, std::size_t files)
{
    std::vector<std::size_t> owner(files, plan.tiles.size());
    for (const auto& t : plan.tiles)
        for (const std::size_t f : t.files) owner[f] = std::min(owner[f], t.index);
    return owner;
}

}  // namespace

tile_rasters read_tile(const survey_layout& layout, const std::vector<std::string>& paths, const tile_plan& plan,
                       std::size_t index, bool crop)
{
    const survey_tile& tile = plan.tiles.at(index);
    const grid& g = plan.g;
    const cell_box& core = tile.core;
    const grid window = g.window(core.row_min, core.col_min, core.rows(), core.cols());
    const auto owner = file_owners(plan, paths.size());
    raster_accumulator acc(window);
    std::optional<scan_coverage> scans;
    tile_rasters out;
    out.index = index;
    std::size_t nan = 0, outside = 0;
    io::las_points chunk;
    std::vector<double> kx, ky, kz;   // the chunk's points in the core, at the centres of their cells
    std::vector<std::uint16_t> ki;
    std::vector<std::uint8_t> kr, kn, kc;
    for (const std::size_t f : tile.files) {
        const bool owns = owner[f] == index;
        io::las_reader reader(paths[f]);
        if (scans) scans->end_sweep();   // a new file starts a new sweep, as in read_survey
        std::size_t file_outside = 0;
        while (const std::size_t n = reader.read(chunk, tile_chunk_points)) {
            to_metres(chunk, layout);
            kx.clear(), ky.clear(), kz.clear(), ki.clear(), kr.clear(), kn.clear(), kc.clear();
            for (std::size_t i = 0; i < n; ++i) {
                const double x = chunk.x[i], y = chunk.y[i], z = chunk.z[i];
                if (!(std::isfinite(x) && std::isfinite(y) && std::isfinite(z))) {
                    nan += owns;
                    continue;
                }
                const auto at = g.cell_of(x, y);
                if (!at) {
                    file_outside += owns;
                    continue;
                }
                if (at->row < core.row_min || at->row > core.row_max || at->col < core.col_min || at->col > core.col_max)
                    continue;
                const auto centre = window.center(at->row - core.row_min, at->col - core.col_min);
                kx.push_back(centre[0]);
                ky.push_back(centre[1]);
                kz.push_back(z);
                ki.push_back(chunk.intensity[i]);
                kr.push_back(chunk.return_number[i]);
                kn.push_back(chunk.number_of_returns[i]);
                kc.push_back(chunk.classification[i]);
            }
            acc.add(soa_cloud<>(kx, ky, kz, ki, kr, kn, kc));
            if (!chunk.gps_time.empty()) {
                if (!scans) scans.emplace(g, core);
                scans->add(chunk.x, chunk.y, chunk.gps_time);
            }
            if (owns) out.points_read += n;
        }
        if (file_outside > 0 && !crop) {
            throw std::runtime_error(paths[f] + ": " + std::to_string(file_outside) +
                                     " points lie outside the bounds its LAS header declares; fix the header "
                                     "(e.g. lasinfo -repair) before rasterizing");
        }
        outside += file_outside;
    }
    out.rasters = acc.finish();
    out.rasters.points_nan = nan;
    out.rasters.points_outside = outside;
    if (scans) out.scan_covered = scans->take();
    return out;
}

namespace {

constexpr char tile_magic[8] = {'L', 'F', 'X', 'T', 'I', 'L', 'E', '1'};

struct byte_writer {
    std::vector<std::uint8_t> bytes;
    void put(const void* p, std::size_t n)
    {
        const auto* b = static_cast<const std::uint8_t*>(p);
        bytes.insert(bytes.end(), b, b + n);
    }
    void u64(std::uint64_t v) { put(&v, sizeof v); }
    template <class T>
    void cells(const raster<T>& r) { put(r.data(), static_cast<std::size_t>(r.size()) * sizeof(T)); }
};

struct byte_reader {
    std::span<const std::uint8_t> bytes;
    const std::string& where;
    std::size_t at = 0;
    void get(void* p, std::size_t n)
    {
        if (bytes.size() - at < n) throw std::runtime_error(where + ": a saved tile is cut short; remove it to start over");
        std::memcpy(p, bytes.data() + at, n);
        at += n;
    }
    std::uint64_t u64()
    {
        std::uint64_t v = 0;
        get(&v, sizeof v);
        return v;
    }
    template <class T>
    void cells(raster<T>& r) { get(r.data(), static_cast<std::size_t>(r.size()) * sizeof(T)); }
};

}  // namespace

std::vector<std::uint8_t> pack_tile(const tile_rasters& t)
{
    byte_writer w;
    w.put(tile_magic, sizeof tile_magic);
    const auto& r = t.rasters;
    for (const std::uint64_t v : {std::uint64_t{t.index}, std::uint64_t(r.g.rows), std::uint64_t(r.g.cols),
                                  std::uint64_t{r.points_used}, std::uint64_t{r.points_outside},
                                  std::uint64_t{r.points_nan}, std::uint64_t{t.points_read},
                                  std::uint64_t{!t.scan_covered.empty()}})
        w.u64(v);
    each_cell_raster([&](auto member) { w.cells(r.*member); });
    if (!t.scan_covered.empty()) w.cells(t.scan_covered);
    return std::move(w.bytes);
}

tile_rasters unpack_tile(std::span<const std::uint8_t> bytes, const tile_plan& plan, const std::string& where)
{
    byte_reader in{bytes, where};
    char magic[sizeof tile_magic] = {};
    in.get(magic, sizeof magic);
    if (std::memcmp(magic, tile_magic, sizeof magic) != 0)
        throw std::runtime_error(where + ": not a saved lidarfx tile; remove it to start over");
    tile_rasters t;
    t.index = in.u64();
    const auto rows = static_cast<std::ptrdiff_t>(in.u64()), cols = static_cast<std::ptrdiff_t>(in.u64());
    if (t.index >= plan.tiles.size() || plan.tiles[t.index].core.rows() != rows || plan.tiles[t.index].core.cols() != cols)
        throw std::runtime_error(where + ": a saved tile does not fit this run's tiles; remove it to start over");
    const auto& core = plan.tiles[t.index].core;
    auto& r = t.rasters;
    r.g = plan.g.window(core.row_min, core.col_min, rows, cols);
    r.points_used = in.u64();
    r.points_outside = in.u64();
    r.points_nan = in.u64();
    t.points_read = in.u64();
    const bool scans = in.u64() != 0;
    allocate_cell_rasters(r, rows, cols);
    each_cell_raster([&](auto member) { in.cells(r.*member); });
    if (scans) {
        t.scan_covered = raster<std::uint8_t>(rows, cols, uninitialized);
        in.cells(t.scan_covered);
    }
    if (in.at != bytes.size()) throw std::runtime_error(where + ": a saved tile is too long; remove it to start over");
    return t;
}

tiled_survey_assembly::tiled_survey_assembly(survey_layout layout, const tile_plan& plan)
    : s_(std::move(layout.head)), plan_(plan)
{
    const grid& g = plan.g;
    auto& r = s_.rasters;
    r.g = g;
    allocate_cell_rasters(r, g.rows, g.cols);
    const auto owner = file_owners(plan, layout.points.size());
    for (std::size_t f = 0; f < owner.size(); ++f)
        if (owner[f] == plan.tiles.size()) unread_points_ += layout.points[f];
}

void tiled_survey_assembly::place(const tile_rasters& t)
{
    const std::lock_guard lock(mutex_);
    const cell_box& core = plan_.tiles.at(t.index).core;
    auto& r = s_.rasters;
    const auto copy = [&](auto& to, const auto& from) {
        for (std::ptrdiff_t i = 0; i < core.rows(); ++i)
            std::copy(from.view().row(i), from.view().row(i) + core.cols(), to.view().row(core.row_min + i) + core.col_min);
    };
    each_cell_raster([&](auto member) { copy(r.*member, t.rasters.*member); });
    if (!t.scan_covered.empty()) {
        if (s_.scan_covered.empty()) s_.scan_covered = raster<std::uint8_t>(r.g.rows, r.g.cols, 0);
        copy(s_.scan_covered, t.scan_covered);
    }
    r.points_used += t.rasters.points_used;
    r.points_outside += t.rasters.points_outside;
    r.points_nan += t.rasters.points_nan;
    s_.points += t.points_read;
}

survey tiled_survey_assembly::finish()
{
    s_.rasters.points_outside += unread_points_;
    s_.points += unread_points_;
    if (s_.rasters.points_used == 0) {
        throw std::runtime_error("no point of the input has finite coordinates (" +
                                 std::to_string(s_.rasters.points_nan) +
                                 " points with NaN or infinite x, y or z): nothing to rasterize");
    }
    return std::move(s_);
}

std::string tiled_fingerprint(const std::vector<std::string>& paths, const survey_options& opt, double tile_edge_m)
{
    std::ostringstream f;
    f.precision(17);
    f << "cell_m " << opt.cell_m << "\ntile_edge_m " << tile_edge_m << "\n";
    if (opt.crop) f << "crop " << opt.crop->xmin << ' ' << opt.crop->ymin << ' ' << opt.crop->xmax << ' ' << opt.crop->ymax << "\n";
    for (const auto& p : paths) {
        struct stat st {};
        if (::stat(p.c_str(), &st) != 0) throw std::runtime_error(p + ": cannot open: " + std::strerror(errno));
        f << "file " << std::filesystem::absolute(p).string() << " size " << st.st_size << " mtime "
          << st.st_mtim.tv_sec << '.' << st.st_mtim.tv_nsec << "\n";
    }
    return f.str();
}

survey read_survey_tiled(const std::vector<std::string>& paths, const survey_options& opt, double tile_edge_m,
                         const std::filesystem::path& resume_dir)
{
    survey_layout layout = survey_layout_of(paths, opt);
    const int threads = detail::resolve_threads(opt.threads, "--threads");
    const tile_plan plan = plan_survey_tiles(layout, tile_edge_m, opt, threads);
    std::optional<tile_store> store;
    if (!resume_dir.empty()) store.emplace(resume_dir, tiled_fingerprint(paths, opt, tile_edge_m));
    const char* kill_hook = std::getenv("LIDARFX_TEST_KILL_AFTER_TILES");   // test hook, see the header
    const long kill_after = kill_hook ? std::atol(kill_hook) : 0;
    const survey_layout& L = layout;
    tiled_survey_assembly assembly(layout, plan);
    auto bar = opt.show_progress ? progress_bar("tiles    ") : progress_callback{};
    std::mutex bar_mutex;
    std::size_t finished = 0;
    std::atomic<long> recorded{0};
    std::vector<std::function<void()>> jobs;
    for (const auto& tile : plan.tiles) {
        jobs.push_back([&, index = tile.index] {
            const std::string where = resume_dir.empty() ? std::string("tile ") + std::to_string(index)
                                                         : (resume_dir / ("tile_" + std::to_string(index))).string();
            if (store && store->done(index)) {
                assembly.place(unpack_tile(store->load(index), plan, where));
            } else {
                const tile_rasters t = read_tile(L, paths, plan, index, opt.crop.has_value());
                if (store) {
                    store->save(index, pack_tile(t));
                    if (recorded.fetch_add(1) + 1 == kill_after) std::raise(SIGKILL);
                }
                assembly.place(t);
            }
            const std::lock_guard lock(bar_mutex);
            ++finished;
            if (bar) bar(static_cast<double>(finished) / static_cast<double>(plan.tiles.size()));
        });
    }
    const auto start = std::chrono::steady_clock::now();
    const std::clock_t cpu_start = std::clock();
    run_jobs(jobs, threads);
    if (opt.show_progress) {
        const std::chrono::duration<double> took = std::chrono::steady_clock::now() - start;
        const double cpu = static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
        std::cerr << "tiles: " << plan.tiles.size() << " tiles of " << plan.tile_cells << " x " << plan.tile_cells
                  << " cells read in " << took.count() << " s (CPU " << cpu << " s)\n";
    }
    return assembly.finish();   // the tiles stay in resume_dir until the caller's outputs are committed
}

}  // namespace lidarfx::cli
