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

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <lidarfx/kernels/points/scan_coverage.hpp>

#include "io/las.hpp"
#include "tile_store.hpp"

namespace lidarfx::cli {

namespace {

/// Points a tile reads at a time (the memory model of plan_survey_tiles counts this chunk per tile in flight).
/// 64 Ki points (2.7 MiB as read): larger chunks fall out of the caches, and two threads then share less well.
constexpr std::size_t tile_chunk_points = std::size_t{1} << 16;

/// The largest share of a file a home hands to one neighbour (survey_file_readers), points.
constexpr std::uint64_t max_handed_points = std::uint64_t{1} << 16;

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
    f(&rasterize_result::multiple_return_count);
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

std::vector<survey_file_extent> survey_file_extents(const survey_layout& layout)
{
    std::vector<survey_file_extent> files;
    for (std::size_t f = 0; f < layout.extents.size(); ++f) {
        const bounds& e = layout.extents[f];
        const double grow =
            1e-6 + 1e-12 * std::max({std::abs(e.xmin), std::abs(e.xmax), std::abs(e.ymin), std::abs(e.ymax)});
        if (layout.points[f] > 0)
            files.push_back({{e.xmin - grow, e.ymin - grow, e.xmax + grow, e.ymax + grow}, layout.points[f]});
        else
            files.push_back({bounds{layout.g.x0 - 1e9, layout.g.y0 + 1e9, layout.g.x0 - 1e9, layout.g.y0 + 1e9}, 0});
    }
    return files;
}

tile_plan plan_survey_tiles(const survey_layout& layout, double tile_edge_m, const survey_options& opt,
                            int tiles_in_flight)
{
    if (!(tile_edge_m > 0) || !std::isfinite(tile_edge_m))
        throw usage_error("--tile must be a positive number of metres (got " + std::to_string(tile_edge_m) + ")");
    tile_plan_options o;
    o.tile_edge_m = tile_edge_m;
    o.halo_cells = 0;  // stage A bins each point in its own cell: no step reaches beyond the core
    o.memory_budget_bytes = opt.memory_budget_bytes;
    o.bytes_per_cell = opt.bytes_per_cell;
    o.bytes_per_tile_cell = 64;  // accumulator (24 B), finished rasters (18 B), scan lines (1 B), packed copy (19 B)
    o.bytes_per_point = 72;      // a chunk as read (42 B) and its points in the core (30 B)
    o.chunk_points = tile_chunk_points;
    o.tiles_in_flight = std::max(1, tiles_in_flight);
    try {
        return make_tile_plan(layout.g, survey_file_extents(layout), o);
    } catch (const invalid_input& e) {
        std::ostringstream why;
        why << "--tile " << tile_edge_m
            << " does not fit --memory (lower --tile or --threads, or raise --memory): " << e.what();
        throw usage_error(why.str());
    }
}

std::vector<file_readers> survey_file_readers(const survey_layout& layout, const tile_plan& plan, bool hand,
                                              std::uint64_t memory_budget_bytes, int tiles_in_flight)
{
    const auto files = survey_file_extents(layout);
    if (!hand) return assign_file_readers(plan, files, 0);
    // Handed points (30 B each) are held until their tile is finished, and tiles started in index order wait
    // for at most tile_cols + 1 later ones: at most tile_cols + 2 + tiles_in_flight consecutive tiles hold
    // handed points and open accumulators (24 B a cell) at once.
    std::vector<double> handed;
    auto readers = assign_file_readers(plan, files, max_handed_points, &handed);
    const auto open = std::min(
        handed.size(), static_cast<std::size_t>(plan.tile_cols) + 2 + static_cast<std::size_t>(tiles_in_flight));
    double most = 0, sum = 0;  // the largest sum of handed points over `open` consecutive tiles
    for (std::size_t t = 0; t < handed.size(); ++t) {
        sum += handed[t] - (t >= open ? handed[t - open] : 0.0);
        most = std::max(most, sum);
    }
    const double waiting =
        static_cast<double>(open) * static_cast<double>(plan.tile_cells) * static_cast<double>(plan.tile_cells) * 24.0;
    const bool fits = memory_budget_bytes == 0 ||
                      plan.peak_bytes_estimate + most * 30.0 + waiting <= static_cast<double>(memory_budget_bytes);
    return fits ? readers : assign_file_readers(plan, files, 0);
}

namespace {

/// Points of one tile's core as its accumulator takes them: each at the centre of its cell on the tile's
/// window grid (so that the window cannot place it elsewhere), with z and the attributes the rasters use.
struct core_points {
    std::vector<double> x, y, z;
    std::vector<std::uint16_t> intensity;
    std::vector<std::uint8_t> return_number, number_of_returns, classification;

    void clear()
    {
        x.clear(), y.clear(), z.clear(), intensity.clear();
        return_number.clear(), number_of_returns.clear(), classification.clear();
    }
    /// Adds point i of `chunk`, in cell `at` of the survey grid, to the core `core` whose window grid is `window`.
    void push(const io::las_points& chunk, std::size_t i, const cell_index& at, const cell_box& core,
              const grid& window)
    {
        const auto centre = window.center(at.row - core.row_min, at.col - core.col_min);
        x.push_back(centre[0]);
        y.push_back(centre[1]);
        z.push_back(chunk.z[i]);
        intensity.push_back(chunk.intensity[i]);
        return_number.push_back(chunk.return_number[i]);
        number_of_returns.push_back(chunk.number_of_returns[i]);
        classification.push_back(chunk.classification[i]);
    }
    void append(const core_points& p)
    {
        const auto cat = [](auto& to, const auto& from) { to.insert(to.end(), from.begin(), from.end()); };
        cat(x, p.x), cat(y, p.y), cat(z, p.z), cat(intensity, p.intensity);
        cat(return_number, p.return_number), cat(number_of_returns, p.number_of_returns);
        cat(classification, p.classification);
    }
    soa_cloud<> cloud() const
    {
        return soa_cloud<>(x, y, z, intensity, return_number, number_of_returns, classification);
    }
};

bool holds(const cell_box& b, const cell_index& at)
{
    return at.row >= b.row_min && at.row <= b.row_max && at.col >= b.col_min && at.col <= b.col_max;
}

/// ORs the cells of `from` (box `from_box` of the survey grid) that fall in `core` into `to` (core-sized;
/// allocated zero when empty).
void or_scan_lines(raster<std::uint8_t>& to, const cell_box& core, raster_view<const std::uint8_t> from,
                   const cell_box& from_box)
{
    if (to.empty()) to = raster<std::uint8_t>(core.rows(), core.cols(), 0);
    const std::ptrdiff_t r0 = std::max(core.row_min, from_box.row_min), r1 = std::min(core.row_max, from_box.row_max);
    const std::ptrdiff_t c0 = std::max(core.col_min, from_box.col_min), c1 = std::min(core.col_max, from_box.col_max);
    auto out = to.view();
    for (std::ptrdiff_t r = r0; r <= r1; ++r) {
        const std::uint8_t* in = from.row(r - from_box.row_min);
        std::uint8_t* o = out.row(r - core.row_min);
        for (std::ptrdiff_t c = c0; c <= c1; ++c) o[c - core.col_min] |= in[c - from_box.col_min];
    }
}

/// What reading one file counted (only for the file's home tile).
struct file_counts {
    std::size_t nan = 0, outside = 0;
    std::uint64_t points = 0;
};

/// Reads one file for the tiles whose cores are `cores` (cores[0] the reading tile): the points in cores[k]
/// go to add(k, points) chunk by chunk, the others are skipped; scan lines (when the file has GPS times) are
/// walked on the box holding every core and ORed into scans[k]. Counts NaN, outside and all points when
/// `home`, and throws for points outside the grid unless `crop`, as read_survey does; the home also counts
/// every point in `outliers` (when not null). `chunk` and `kept` are buffers reused across files.
template <class Add>
file_counts read_file_into(const survey_layout& layout, const std::string& path, const grid& g,
                           std::span<const cell_box> cores, bool home, bool crop, Add&& add,
                           std::span<raster<std::uint8_t>> scans, io::las_points& chunk, std::vector<core_points>& kept,
                           outlier_bins* outliers = nullptr)
{
    file_counts counts;
    io::las_reader reader(path);
    reader.set_memory_budget(layout.memory_budget_bytes);  // LAZ chunks within --memory
    cell_box all = cores[0];
    std::vector<grid> windows;
    for (const cell_box& c : cores) {
        all = {std::min(all.row_min, c.row_min), std::min(all.col_min, c.col_min), std::max(all.row_max, c.row_max),
               std::max(all.col_max, c.col_max)};
        windows.push_back(g.window(c.row_min, c.col_min, c.rows(), c.cols()));
    }
    kept.resize(cores.size());
    std::optional<scan_coverage> lines;
    // Reading stops at the last point rather than at an empty read, which would shrink the chunk's buffers
    // (and make the next file's first read fill them anew).
    while (reader.position() < reader.point_count()) {
        const std::size_t n = reader.read(chunk, tile_chunk_points);
        to_metres(chunk, layout);
        if (home && outliers) outliers->add(chunk.x, chunk.y);
        for (auto& k : kept) k.clear();
        for (std::size_t i = 0; i < n; ++i) {
            const double x = chunk.x[i], y = chunk.y[i], z = chunk.z[i];
            if (!(std::isfinite(x) && std::isfinite(y) && std::isfinite(z))) {
                counts.nan += home;
                continue;
            }
            const auto at = g.cell_of(x, y);
            if (!at) {
                counts.outside += home;
                continue;
            }
            for (std::size_t k = 0; k < cores.size(); ++k) {
                if (holds(cores[k], *at)) {
                    kept[k].push(chunk, i, *at, cores[k], windows[k]);
                    break;
                }
            }
        }
        for (std::size_t k = 0; k < cores.size(); ++k) add(k, kept[k]);
        if (!chunk.gps_time.empty()) {
            if (!lines) lines.emplace(g, all);
            lines->add(chunk.x, chunk.y, chunk.gps_time);
        }
        if (home) counts.points += n;
    }
    if (counts.outside > 0 && !crop) {
        throw std::runtime_error(path + ": " + std::to_string(counts.outside) +
                                 " points lie outside the bounds its LAS header declares; fix the header "
                                 "(e.g. lasinfo -repair) before rasterizing");
    }
    if (lines)
        for (std::size_t k = 0; k < cores.size(); ++k) or_scan_lines(scans[k], cores[k], lines->covered(), all);
    return counts;
}

}  // namespace

tile_rasters read_tile(const survey_layout& layout, const std::vector<std::string>& paths, const tile_plan& plan,
                       const std::vector<file_readers>& readers, std::size_t index, bool crop)
{
    const survey_tile& tile = plan.tiles.at(index);
    const cell_box& core = tile.core;
    raster_accumulator acc(plan.g.window(core.row_min, core.col_min, core.rows(), core.cols()));
    tile_rasters out;
    out.index = index;
    io::las_points chunk;
    std::vector<core_points> kept;
    file_counts counts;
    for (const std::size_t f : tile.files) {
        const file_counts c = read_file_into(
            layout, paths[f], plan.g, std::span(&core, 1), readers.at(f).home == index, crop,
            [&](std::size_t, const core_points& p) { acc.add(p.cloud()); }, std::span(&out.scan_covered, 1), chunk,
            kept);
        counts.nan += c.nan, counts.outside += c.outside, counts.points += c.points;
    }
    out.rasters = acc.finish();
    out.rasters.points_nan = counts.nan;
    out.rasters.points_outside = counts.outside;
    out.points_read = counts.points;
    return out;
}

namespace {

// '2': tiles hold rasterize_result::multiple_return_count since; a tile of '1' is recomputed, not misread.
constexpr char tile_magic[8] = {'L', 'F', 'X', 'T', 'I', 'L', 'E', '2'};

struct byte_writer {
    std::vector<std::uint8_t> bytes;
    void put(const void* p, std::size_t n)
    {
        const auto* b = static_cast<const std::uint8_t*>(p);
        bytes.insert(bytes.end(), b, b + n);
    }
    void u64(std::uint64_t v) { put(&v, sizeof v); }
    template <class T>
    void cells(const raster<T>& r)
    {
        put(r.data(), static_cast<std::size_t>(r.size()) * sizeof(T));
    }
};

struct byte_reader {
    std::span<const std::uint8_t> bytes;
    const std::string& where;
    std::size_t at = 0;
    void get(void* p, std::size_t n)
    {
        if (bytes.size() - at < n)
            throw std::runtime_error(where + ": a saved tile is cut short; remove it to start over");
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
    void cells(raster<T>& r)
    {
        get(r.data(), static_cast<std::size_t>(r.size()) * sizeof(T));
    }
};

}  // namespace

std::vector<std::uint8_t> pack_tile(const tile_rasters& t)
{
    byte_writer w;
    w.put(tile_magic, sizeof tile_magic);
    const auto& r = t.rasters;
    for (const std::uint64_t v :
         {std::uint64_t{t.index}, std::uint64_t(r.g.rows), std::uint64_t(r.g.cols), std::uint64_t{r.points_used},
          std::uint64_t{r.points_outside}, std::uint64_t{r.points_nan}, std::uint64_t{t.points_read},
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
    if (t.index >= plan.tiles.size() || plan.tiles[t.index].core.rows() != rows ||
        plan.tiles[t.index].core.cols() != cols)
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

tiled_survey_assembly::tiled_survey_assembly(survey_layout layout, const tile_plan& plan,
                                             const std::vector<file_readers>& readers)
    : s_(std::move(layout.head)), plan_(plan)
{
    const grid& g = plan.g;
    auto& r = s_.rasters;
    r.g = g;
    allocate_cell_rasters(r, g.rows, g.cols);
    for (std::size_t f = 0; f < readers.size(); ++f)
        if (readers[f].home == plan.tiles.size()) unread_points_ += layout.points[f];
}

void tiled_survey_assembly::place(const tile_rasters& t)
{
    const std::lock_guard lock(mutex_);
    const cell_box& core = plan_.tiles.at(t.index).core;
    auto& r = s_.rasters;
    const auto copy = [&](auto& to, const auto& from) {
        for (std::ptrdiff_t i = 0; i < core.rows(); ++i)
            std::copy(from.view().row(i), from.view().row(i) + core.cols(),
                      to.view().row(core.row_min + i) + core.col_min);
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

namespace {

/// FNV-1a 64 of a file's header and sampled blocks: its first and last 64 KiB and 16 evenly spaced 4 KiB blocks
/// (the whole file when it is smaller than that), so that an input edited in place is noticed even when its
/// size and modification time were kept.
std::uint64_t sampled_hash(const std::string& path, std::uint64_t size)
{
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) throw std::runtime_error(path + ": cannot open: " + std::strerror(errno));
    constexpr std::uint64_t edge = 64 * 1024, block = 4 * 1024, blocks = 16;
    std::vector<std::pair<std::uint64_t, std::uint64_t>> spans;  // offset, length
    if (size <= 2 * edge + blocks * block)
        spans.push_back({0, size});
    else {
        spans.push_back({0, edge});
        for (std::uint64_t k = 0; k < blocks; ++k)
            spans.push_back({edge + (size - 2 * edge - block) * k / (blocks - 1), block});
        spans.push_back({size - edge, edge});
    }
    std::uint64_t h = fnv1a64(nullptr, 0);
    std::vector<std::uint8_t> buffer;
    for (const auto& [offset, length] : spans) {
        buffer.resize(length);
        std::size_t got = 0;
        while (got < length) {
            const ssize_t n = ::pread(fd, buffer.data() + got, length - got, static_cast<off_t>(offset + got));
            if (n < 0 && errno == EINTR) continue;
            if (n <= 0) break;
            got += static_cast<std::size_t>(n);
        }
        h = fnv1a64(buffer.data(), got, h);
    }
    ::close(fd);
    return h;
}

}  // namespace

std::string tiled_fingerprint(const std::vector<std::string>& paths, const survey_options& opt, double tile_edge_m)
{
    std::ostringstream f;
    f.precision(17);
    f << "cell_m " << opt.cell_m << "\ntile_edge_m " << tile_edge_m << "\n";
    if (opt.crop)
        f << "crop " << opt.crop->xmin << ' ' << opt.crop->ymin << ' ' << opt.crop->xmax << ' ' << opt.crop->ymax
          << "\n";
    for (const auto& p : paths) {
        struct stat st {};
        if (::stat(p.c_str(), &st) != 0) throw std::runtime_error(p + ": cannot open: " + std::strerror(errno));
        f << "file " << std::filesystem::absolute(p).string() << " size " << st.st_size << " mtime "
          << st.st_mtim.tv_sec << '.' << st.st_mtim.tv_nsec << " sampled_fnv1a64 " << std::hex
          << sampled_hash(p, static_cast<std::uint64_t>(st.st_size)) << std::dec << "\n";
    }
    return f.str();
}

namespace {

/// A tile of a tiled run while its parts come in: its own reading and the files handed to it.
struct open_tile {
    std::mutex mutex;
    int pending = 1;                          // parts still to come: its own reading + files handed to it
    std::unique_ptr<raster_accumulator> acc;  // from its own reading on
    std::vector<core_points> handed;          // points handed by the homes of its thin files
    tile_rasters out;                         // counts and scan lines so far
};

/// A reading thread's buffers: the chunk as read and its points sorted by core.
struct reading_buffers {
    io::las_points chunk;
    std::vector<core_points> kept;
    std::optional<outlier_bins> outliers;  // the points of the files this thread read as their home
};

}  // namespace

survey read_survey_tiled(const std::vector<std::string>& paths, const survey_options& opt, double tile_edge_m,
                         const std::filesystem::path& resume_dir)
{
    survey_layout layout = survey_layout_of(paths, opt, true);
    const int threads = detail::resolve_threads(opt.threads, "--threads");
    const auto check_outliers_now = [&] {
        refuse_outliers(
            count_outlier_bins(paths, layout.header_box, layout.unit_xy, opt.threads, opt.memory_budget_bytes),
            layout.total, layout.unit_xy);
    };
    const tile_plan plan = [&] {
        try {
            return plan_survey_tiles(layout, tile_edge_m, opt, threads);
        } catch (const usage_error&) {
            if (layout.outliers_unchecked) check_outliers_now();  // far points would explain the refusal
            throw;
        }
    }();
    const auto readers = survey_file_readers(layout, plan, true, opt.memory_budget_bytes, threads);
    std::optional<tile_store> store;
    if (!resume_dir.empty()) store.emplace(resume_dir, tiled_fingerprint(paths, opt, tile_edge_m));
    const auto done = [&](std::size_t tile) { return store && store->done(tile); };
    // The outlier check counts the points as their home tiles read them; a resumed run, whose finished tiles
    // are not read again, counts them in a pass of their own first.
    bool count_outliers = layout.outliers_unchecked;
    if (count_outliers && store && store->done_count() > 0) {
        check_outliers_now();
        count_outliers = false;
    }
    const char* kill_hook = std::getenv("LIDARFX_TEST_KILL_AFTER_TILES");  // test hook, see the header
    const long kill_after = kill_hook ? std::atol(kill_hook) : 0;
    const survey_layout& L = layout;
    const bool crop = opt.crop.has_value();
    tiled_survey_assembly assembly(layout, plan, readers);
    auto bar = opt.show_progress ? progress_bar("tiles    ") : progress_callback{};
    std::mutex bar_mutex;
    std::size_t finished = 0;
    std::atomic<long> recorded{0};
    std::atomic<bool> stop{false};           // set by the first failure: no tile starts after it
    std::atomic<std::size_t> file_reads{0};  // files read by this run's tiles (not those taken from the store)
    const auto placed = [&](const tile_rasters& t) {
        assembly.place(t);
        const std::lock_guard lock(bar_mutex);
        ++finished;
        if (bar) bar(static_cast<double>(finished) / static_cast<double>(plan.tiles.size()));
    };

    // Files a home hands on in this run: not to finished tiles, and none from a finished home (its tile came
    // from the store, so the tiles it would hand to read the file themselves).
    const std::size_t tiles = plan.tiles.size();
    std::vector<std::vector<std::size_t>> hands(paths.size());
    std::vector<open_tile> open(tiles);
    for (std::size_t f = 0; f < paths.size(); ++f) {
        if (readers[f].home == tiles || done(readers[f].home)) continue;
        for (const std::size_t t : readers[f].handed_to) {
            if (done(t)) continue;
            hands[f].push_back(t);
            ++open[t].pending;
        }
    }
    // Whether tile t reads file f itself: the file's home does, and so does every listing tile it is not handed to.
    const auto reads_itself = [&](std::size_t f, std::size_t t) {
        const auto& to = hands[f];
        return readers[f].home == t || std::find(to.begin(), to.end(), t) == to.end();
    };
    // Finishes tile t once its last part is in (called by whichever thread brought that part).
    const auto finish = [&](std::size_t t) {
        open_tile& o = open[t];
        for (const core_points& p : o.handed) o.acc->add(p.cloud());
        tile_rasters r = std::move(o.out);
        const std::size_t nan = r.rasters.points_nan, outside = r.rasters.points_outside;
        r.rasters = o.acc->finish();
        r.rasters.points_nan = nan;
        r.rasters.points_outside = outside;
        o.acc.reset();
        o.handed = {};
        if (store) {
            store->save(t, pack_tile(r));  // a failure stops the run (below), keeping the tiles saved before
            if (recorded.fetch_add(1) + 1 == kill_after) std::raise(SIGKILL);
        }
        placed(r);
    };
    // One part of tile t is in: `bring` runs under the tile's lock, then the tile is finished if it was the last.
    const auto part_in = [&](std::size_t t, const auto& bring) {
        bool last = false;
        {
            const std::lock_guard lock(open[t].mutex);
            bring(open[t]);
            last = --open[t].pending == 0;
        }
        if (last) finish(t);
    };

    // Chunk buffers pass from tile to tile (fresh ones would be zeroed again for every file).
    std::mutex pool_mutex;
    std::vector<std::unique_ptr<reading_buffers>> pool;
    const auto take_buffers = [&] {
        const std::lock_guard lock(pool_mutex);
        if (pool.empty()) {
            auto fresh = std::make_unique<reading_buffers>();
            if (count_outliers) fresh->outliers.emplace(L.header_box);
            return fresh;
        }
        auto b = std::move(pool.back());
        pool.pop_back();
        return b;
    };
    const auto give_back = [&](std::unique_ptr<reading_buffers> b) {
        const std::lock_guard lock(pool_mutex);
        pool.push_back(std::move(b));
    };

    std::vector<std::function<void()>> jobs;
    for (const auto& tile : plan.tiles) {
        jobs.push_back([&, index = tile.index] {
            if (done(index)) {
                const std::string where = (resume_dir / ("tile_" + std::to_string(index) + ".bin")).string();
                tile_rasters saved = unpack_tile(store->load(index), plan, where);
                if (saved.index != index)
                    throw std::runtime_error(where + ": holds tile " + std::to_string(saved.index) + ", not tile " +
                                             std::to_string(index));
                placed(saved);
                return;
            }
            const cell_box& core = tile.core;
            auto acc = std::make_unique<raster_accumulator>(
                plan.g.window(core.row_min, core.col_min, core.rows(), core.cols()));
            tile_rasters own;
            own.index = index;
            std::unique_ptr<reading_buffers> buffers = take_buffers();
            io::las_points& chunk = buffers->chunk;
            std::vector<core_points>& kept = buffers->kept;
            for (const std::size_t f : tile.files) {
                if (!reads_itself(f, index)) continue;  // handed to this tile
                ++file_reads;
                const bool home = readers[f].home == index;
                const auto& to = hands[f];
                // The reading tile first, then the tiles this home hands the file to.
                std::vector<cell_box> cores{core};
                if (home)
                    for (const std::size_t t : to) cores.push_back(plan.tiles[t].core);
                std::vector<raster<std::uint8_t>> scans(cores.size());
                scans[0] = std::move(own.scan_covered);
                std::vector<core_points> handing(cores.size());
                const file_counts c = read_file_into(
                    L, paths[f], plan.g, cores, home, crop,
                    [&](std::size_t k, const core_points& p) {
                        if (k == 0) {
                            acc->add(p.cloud());
                            return;
                        }
                        handing[k].append(p);
                    },
                    scans, chunk, kept, buffers->outliers ? &*buffers->outliers : nullptr);
                own.scan_covered = std::move(scans[0]);
                own.rasters.points_nan += c.nan, own.rasters.points_outside += c.outside, own.points_read += c.points;
                for (std::size_t k = 1; k < cores.size(); ++k) {
                    part_in(to[k - 1], [&](open_tile& o) {
                        o.handed.push_back(std::move(handing[k]));
                        if (!scans[k].empty()) {
                            const cell_box& r = cores[k];
                            or_scan_lines(o.out.scan_covered, r, scans[k], r);
                        }
                    });
                }
            }
            give_back(std::move(buffers));
            part_in(index, [&](open_tile& o) {
                o.acc = std::move(acc);
                o.out.index = index;
                o.out.points_read += own.points_read;
                o.out.rasters.points_nan += own.rasters.points_nan;
                o.out.rasters.points_outside += own.rasters.points_outside;
                if (!own.scan_covered.empty()) or_scan_lines(o.out.scan_covered, core, own.scan_covered, core);
            });
        });
    }
    const auto start = std::chrono::steady_clock::now();
    const std::clock_t cpu_start = std::clock();
    for (auto& job : jobs) {  // the first failure (a write on a full disk, a bad file) ends the run
        job = [&stop, body = std::move(job)] {
            if (stop) return;
            try {
                body();
            } catch (...) {
                stop = true;
                throw;
            }
        };
    }
    run_jobs(jobs, threads);
    if (count_outliers) {
        outlier_bins all(L.header_box);
        for (const auto& b : pool) all.merge(*b->outliers);
        refuse_outliers(all, L.total, L.unit_xy);
    }
    if (opt.show_progress) {
        const std::chrono::duration<double> took = std::chrono::steady_clock::now() - start;
        const double cpu = static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
        const std::size_t reads = file_reads;
        std::cerr << "tiles: " << plan.tiles.size() << " tiles of " << plan.tile_cells << " x " << plan.tile_cells
                  << " cells read in " << took.count() << " s (CPU " << cpu << " s); " << reads << " file reads for "
                  << paths.size() << " files"
                  << (reads > paths.size() ? " (a file is read by each tile it reaches unless its home hands that "
                                             "tile its points: only small shares are handed, and none when "
                                             "--memory leaves no room)"
                                           : "")
                  << "\n";
    }
    return assembly.finish();  // the tiles stay in resume_dir until the caller's outputs are committed
}

}  // namespace lidarfx::cli
