// SPDX-License-Identifier: Apache-2.0
#include "cli_common.hpp"

#if defined(__GLIBC__)
#include <malloc.h>
#endif

#include <algorithm>
#include <array>
#include <atomic>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstring>
#include <exception>
#include <future>
#include <iomanip>
#include <iostream>
#include <limits>
#include <memory>
#include <optional>
#include <sstream>
#include <thread>
#include <utility>

#include <sys/stat.h>
#include <unistd.h>
#include <stdexcept>

#include <lidarfx/kernels/filter/survey_footprint.hpp>
#include <lidarfx/kernels/points/count_points_above.hpp>
#include <lidarfx/kernels/points/scan_coverage.hpp>
#include <lidarfx/pipelines/buildings/morphological_ground.hpp>

#include "io/ascii_grid.hpp"
#include "io/crs_cache.hpp"
#include "io/file_output.hpp"
#include "io/geotiff.hpp"
#include "io/las.hpp"

namespace lidarfx::cli {

arguments::arguments(const std::vector<std::string>& args, const std::vector<std::string>& valued,
                     const std::vector<std::string>& flags)
{
    const auto is = [](const std::vector<std::string>& names, const std::string& n) {
        return std::find(names.begin(), names.end(), n) != names.end();
    };
    bool options_ended = false;
    for (std::size_t i = 0; i < args.size(); ++i) {
        const auto& a = args[i];
        if (options_ended) {
            positional_.push_back(a);
            continue;
        }
        if (a == "--") {  // everything after it is a file name, even when it starts with '-'
            options_ended = true;
            continue;
        }
        if (a.rfind("--", 0) != 0) {
            if (a.size() > 1 && a[0] == '-')
                throw std::invalid_argument("unknown option " + a + " (options are --name)");
            positional_.push_back(a);
            continue;
        }
        std::string name = a.substr(2), value;
        if (const auto eq = name.find('='); eq != std::string::npos) {
            value = name.substr(eq + 1);
            name = name.substr(0, eq);
            if (!is(valued, name)) throw std::invalid_argument("option --" + name + " takes no value or is unknown");
        } else if (is(valued, name)) {
            if (i + 1 >= args.size()) throw std::invalid_argument("option --" + name + " needs a value");
            value = args[++i];
        } else if (!is(flags, name)) {
            throw std::invalid_argument("unknown option --" + name);
        }
        if (values_.count(name)) throw std::invalid_argument("option --" + name + " is given more than once");
        values_[name] = value;
    }
}

std::string arguments::text(const std::string& name, const std::string& fallback) const
{
    const auto it = values_.find(name);
    return it == values_.end() ? fallback : it->second;
}

double arguments::number(const std::string& name, double fallback) const
{
    const auto it = values_.find(name);
    if (it == values_.end()) return fallback;
    try {
        std::size_t used = 0;
        const double v = std::stod(it->second, &used);
        if (used != it->second.size()) throw std::invalid_argument("trailing characters");
        return v;
    } catch (const std::exception&) {
        throw std::invalid_argument("option --" + name + " expects a number (got '" + it->second + "')");
    }
}

int arguments::integer(const std::string& name, int fallback) const
{
    const double v = number(name, fallback);
    if (v != std::floor(v) || std::abs(v) > 1e9) {
        throw std::invalid_argument("option --" + name + " expects a whole number (got '" + text(name, "") + "')");
    }
    return static_cast<int>(v);
}

std::optional<int> stop_for_usage(const arguments& a, const char* usage, bool needs_inputs_and_out)
{
    if (a.has("help")) {
        std::cout << usage;
        return 0;
    }
    if (needs_inputs_and_out && (a.positional().empty() || !a.has("out"))) {
        std::cerr << usage;
        return 2;
    }
    return std::nullopt;
}

progress_callback progress_bar(const std::string& label)
{
    auto last = std::make_shared<int>(-1);
    if (::isatty(STDERR_FILENO) == 0) {
        // Into a log or pipe: a plain line at most every 10 % and at most every 10 s, and the final 100 %.
        using clock = std::chrono::steady_clock;
        auto last_line = std::make_shared<clock::time_point>(clock::now());
        return [label, last, last_line](double f) {
            const int percent = static_cast<int>(std::floor(100.0 * f));
            const bool done = percent >= 100 && *last < 100;
            const bool due = percent / 10 > *last / 10 && clock::now() - *last_line >= std::chrono::seconds(10);
            if (!done && !due) return true;
            *last = percent;
            *last_line = clock::now();
            std::cerr << label << ' ' << percent << " %\n";
            std::cerr.flush();
            return true;
        };
    }
    return [label, last](double f) {
        const int percent = static_cast<int>(std::floor(100.0 * f));
        if (percent == *last) return true;
        *last = percent;
        const int filled = percent / 5;
        std::cerr << '\r' << label << " [" << std::string(static_cast<std::size_t>(filled), '#')
                  << std::string(static_cast<std::size_t>(20 - filled), '.') << "] " << percent << " %";
        if (percent >= 100) std::cerr << '\n';
        std::cerr.flush();
        return true;
    };
}

std::uint64_t parse_bytes(const std::string& text, const std::string& option)
{
    std::size_t used = 0;
    double value = 0;
    try {
        value = std::stod(text, &used);
    } catch (const std::exception&) {
        throw usage_error(option + " expects a size such as 4GiB or 512MiB (got '" + text + "')");
    }
    std::string unit = text.substr(used);
    unit.erase(std::remove(unit.begin(), unit.end(), ' '), unit.end());
    static const std::map<std::string, double> units{{"", 1.0},
                                                     {"B", 1.0},
                                                     {"K", 1024.0},
                                                     {"KB", 1e3},
                                                     {"KiB", 1024.0},
                                                     {"M", 1048576.0},
                                                     {"MB", 1e6},
                                                     {"MiB", 1048576.0},
                                                     {"G", 1073741824.0},
                                                     {"GB", 1e9},
                                                     {"GiB", 1073741824.0},
                                                     {"T", 1099511627776.0},
                                                     {"TB", 1e12},
                                                     {"TiB", 1099511627776.0}};
    const auto it = units.find(unit);
    const double bytes = it == units.end() ? -1 : value * it->second;
    if (!(bytes >= 1) || !(bytes < 1.8e19)) {
        throw usage_error(option + " expects a positive size such as 4GiB or 512MiB (got '" + text + "')");
    }
    return static_cast<std::uint64_t>(bytes);
}

output_formats output_formats_from(const arguments& a)
{
    if (!a.has("formats")) return {};
    output_formats f{false, false, false, false, false, false};
    const std::string text = a.text("formats", "");
    std::istringstream in(text);
    for (std::string name; std::getline(in, name, ',');) {
        if (name == "asc")
            f.asc = true;
        else if (name == "tif")
            f.tif = true;
        else if (name == "png")
            f.png = true;
        else if (name == "csv")
            f.csv = true;
        else if (name == "geojson")
            f.geojson = true;
        else if (name == "gpkg")
            f.gpkg = true;
        else
            throw usage_error("--formats takes a comma-separated list of asc, tif, png, csv, geojson and gpkg (got '" +
                              text + "')");
    }
    const bool rasters = f.asc || f.tif || f.png, vectors = f.csv || f.geojson || f.gpkg;
    if (!rasters && !vectors) throw usage_error("--formats names no format (got '" + text + "')");
    const output_formats defaults;
    if (!rasters) {
        f.asc = defaults.asc;
        f.tif = defaults.tif;
        f.png = defaults.png;
    }
    if (!vectors) {
        f.csv = defaults.csv;
        f.geojson = defaults.geojson;
        f.gpkg = defaults.gpkg;
    }
    if (f.tif && rasters && !io::geotiff_available())
        throw usage_error("--formats tif needs GeoTIFF support, and this lidarfx was built without GDAL; use asc");
    if (f.gpkg && vectors && !io::vectors_available())
        throw usage_error(std::string("--formats gpkg needs GeoPackage support (OGR), and ") +
                          io::vectors_rebuild_hint + "; or use csv,geojson");
    return f;
}

void run_jobs(const std::vector<std::function<void()>>& jobs, int threads)
{
    const auto n = static_cast<std::size_t>(detail::resolve_threads(threads, "run_jobs"));
    std::vector<std::exception_ptr> errors(jobs.size());
    std::atomic<std::size_t> next{0};
    const auto worker = [&] {
        for (std::size_t i; (i = next.fetch_add(1)) < jobs.size();) {
            try {
                jobs[i]();
            } catch (...) {
                errors[i] = std::current_exception();
            }
        }
    };
    std::vector<std::thread> helpers;
    for (std::size_t t = 1; t < std::min(n, jobs.size()); ++t) helpers.emplace_back(worker);
    worker();
    for (auto& h : helpers) h.join();
    for (const auto& e : errors)
        if (e) std::rethrow_exception(e);
}

survey_options survey_options_from(const arguments& a, double bytes_per_cell)
{
    survey_options o;
    o.formats = output_formats_from(a);
    o.bytes_per_cell = bytes_per_cell;
    o.cell_m = a.number("cell", o.cell_m);
    if (!(o.cell_m > 0) || !std::isfinite(o.cell_m)) {
        throw usage_error("--cell must be a positive number of metres (got " + a.text("cell", "") + ")");
    }
    o.threads = a.integer("threads", o.threads);
    if (o.threads < 0) throw usage_error("--threads must be >= 0 (got " + std::to_string(o.threads) + ")");
    o.memory_budget_bytes = memory_option(a);
    if (a.has("crop")) {
        const std::string text = a.text("crop", "");
        bounds b{};
        char c1 = 0, c2 = 0, c3 = 0;
        std::istringstream in(text);
        if (!(in >> b.xmin >> c1 >> b.ymin >> c2 >> b.xmax >> c3 >> b.ymax) || c1 != ',' || c2 != ',' || c3 != ',' ||
            !(in >> std::ws).eof() || !std::isfinite(b.xmin) || !std::isfinite(b.ymin) || !std::isfinite(b.xmax) ||
            !std::isfinite(b.ymax) || !(b.xmin < b.xmax) || !(b.ymin < b.ymax)) {
            throw usage_error("--crop expects xmin,ymin,xmax,ymax with min < max (got '" + text + "')");
        }
        o.crop = b;
    }
    o.force = a.has("force");
    return o;
}

namespace {

std::uint64_t physical_memory_bytes()
{
    const long pages = ::sysconf(_SC_PHYS_PAGES), page = ::sysconf(_SC_PAGESIZE);
    return pages > 0 && page > 0 ? static_cast<std::uint64_t>(pages) * static_cast<std::uint64_t>(page) : 0;
}

std::string gib(double bytes)
{
    std::ostringstream s;
    s << std::setprecision(3) << bytes / 1073741824.0 << " GiB";
    return s.str();
}

/// Smallest "round" cell size (1, 2 or 5 times a power of ten) that is at least `cell_m`.
double round_cell_up(double cell_m)
{
    const double decade = std::pow(10.0, std::floor(std::log10(cell_m)));
    for (const double m : {1.0, 2.0, 5.0, 10.0}) {
        if (m * decade >= cell_m * (1 - 1e-12)) return m * decade;
    }
    return 10 * decade;
}

}  // namespace

std::uint64_t memory_option(const arguments& a)
{
    return a.has("memory") ? parse_bytes(a.text("memory", ""), "--memory") : 0;
}

io::tmy3_data read_weather_year(const std::string& path)
{
    io::tmy3_data tmy;
    try {
        tmy = io::read_tmy3(path);
    } catch (const invalid_input& e) {
        throw usage_error(e.what());  // the file breaks the rules of a weather year: exit code 2
    }
    std::cerr << io::coverage_line(tmy, path) << "\n";
    return tmy;
}

std::uint64_t memory_budget_of(std::uint64_t memory_budget_bytes)
{
    return memory_budget_bytes ? memory_budget_bytes : physical_memory_bytes() / 2;
}

void report_non_finite_heights(const std::string& path, std::size_t cells)
{
    if (cells > 0) std::cerr << "lidarfx: " << path << ": " << cells << " cells hold inf, -inf or nan: no data (NaN)\n";
}

void refuse_grid_over_budget(const std::string& path, const grid& g, double bytes_per_cell,
                             std::uint64_t memory_budget_bytes)
{
    const std::uint64_t budget = memory_budget_of(memory_budget_bytes);
    const double cells = static_cast<double>(g.rows) * static_cast<double>(g.cols);
    const double need = cells * bytes_per_cell;
    if (budget == 0 || need <= static_cast<double>(budget)) return;
    std::ostringstream why;
    why << path << ": a grid of " << g.rows << " x " << g.cols << " cells needs about " << gib(need) << " ("
        << bytes_per_cell << " bytes a cell), over the memory budget of " << gib(static_cast<double>(budget))
        << "; cut it into smaller pieces (gdal_translate -srcwin), resample it to larger cells (gdalwarp -tr), "
        << "or give a larger --memory";
    throw usage_error(why.str());
}

outlier_bins::outlier_bins(const bounds& b)
    : box(b),
      bw(std::max(b.xmax - b.xmin, 1e-9) / bins),
      bh(std::max(b.ymax - b.ymin, 1e-9) / bins),
      count(static_cast<std::size_t>(bins) * bins, 0)
{
}

void outlier_bins::add(std::span<const double> x, std::span<const double> y)
{
    // Bins per metre: a product per point instead of a division (every count goes through here alike).
    const double per_x = 1.0 / bw, per_y = 1.0 / bh;
    const auto bin = [](double v, double lo, double per) {
        const double b = (v - lo) * per;  // >= 0 and < bins + 1 for points inside the box
        return b < 0 ? 0 : b >= bins - 1 ? bins - 1 : static_cast<int>(b);
    };
    for (std::size_t i = 0; i < x.size(); ++i) {
        if (!std::isfinite(x[i]) || !std::isfinite(y[i])) continue;
        ++count[static_cast<std::size_t>(bin(y[i], box.ymin, per_y)) * bins + bin(x[i], box.xmin, per_x)];
    }
}

void outlier_bins::merge(const outlier_bins& other)
{
    for (std::size_t i = 0; i < count.size(); ++i) count[i] += other.count[i];
}

outlier_bins count_outlier_bins(const std::vector<std::string>& paths, const bounds& box, double unit_m, int threads,
                                std::uint64_t memory_budget_bytes)
{
    // One histogram per group of files, read on its own thread; counts are integers, so the sum does not
    // depend on the grouping. A LAZ reader holds up to two chunks (one decoding, one kept): as many groups as
    // hold two of the largest chunk within --memory.
    std::size_t groups = std::min<std::size_t>(
        paths.size(), static_cast<std::size_t>(lidarfx::detail::resolve_threads(threads, "refuse_outliers")));
    if (groups > 1) {
        std::uint64_t largest = 0, budget = memory_budget_bytes;
        for (const auto& p : paths) {
            io::las_reader r(p);
            r.set_memory_budget(memory_budget_bytes);
            largest = std::max(largest, r.largest_chunk_bytes());
            budget = r.memory_budget();  // 0 resolved
        }
        if (largest > 0) groups = std::clamp<std::size_t>(static_cast<std::size_t>(budget / (2 * largest)), 1, groups);
    }
    std::vector<outlier_bins> counts(groups, outlier_bins(box));
    std::vector<std::function<void()>> jobs;
    for (std::size_t g = 0; g < groups; ++g) {
        jobs.push_back([&, g] {
            io::las_points chunk;
            std::vector<double> x, y;
            for (std::size_t f = g; f < paths.size(); f += groups) {
                io::las_reader r(paths[f]);
                r.set_memory_budget(memory_budget_bytes);  // LAZ chunks within --memory
                while (r.position() < r.point_count()) {   // an empty read would shrink the chunk's buffers
                    const std::size_t n = r.read(chunk, std::size_t{1} << 20);
                    x.resize(n), y.resize(n);
                    for (std::size_t i = 0; i < n; ++i) x[i] = chunk.x[i] * unit_m, y[i] = chunk.y[i] * unit_m;
                    counts[g].add(x, y);
                }
            }
        });
    }
    run_jobs(jobs, threads);
    for (std::size_t g = 1; g < groups; ++g) counts[0].merge(counts[g]);
    return std::move(counts[0]);
}

void refuse_outliers(const outlier_bins& bins_of_points, std::uint64_t total, double unit_m)
{
    constexpr int bins = outlier_bins::bins;
    const bounds& box = bins_of_points.box;
    const double bw = bins_of_points.bw, bh = bins_of_points.bh;
    const auto& count = bins_of_points.count;
    std::vector<std::uint64_t> column(bins, 0), row(bins, 0);
    for (int j = 0; j < bins; ++j)
        for (int i = 0; i < bins; ++i)
            column[i] += count[static_cast<std::size_t>(j) * bins + i],
                row[j] += count[static_cast<std::size_t>(j) * bins + i];
    const auto core = [&](const std::vector<std::uint64_t>& h) {
        const double tail = 1e-4 * static_cast<double>(total);
        int lo = 0, hi = bins - 1;
        for (double seen = 0; lo < bins - 1 && seen + static_cast<double>(h[lo]) <= tail; ++lo)
            seen += static_cast<double>(h[lo]);
        for (double seen = 0; hi > lo && seen + static_cast<double>(h[hi]) <= tail; --hi)
            seen += static_cast<double>(h[hi]);
        return std::pair{lo, hi};
    };
    const auto [c0, c1] = core(column);
    const auto [r0, r1] = core(row);
    bounds kept{box.xmin + c0 * bw, box.ymin + r0 * bh, box.xmin + (c1 + 1) * bw, box.ymin + (r1 + 1) * bh};
    const double mx = 0.05 * (kept.xmax - kept.xmin), my = 0.05 * (kept.ymax - kept.ymin);
    kept = {std::max(box.xmin, kept.xmin - mx), std::max(box.ymin, kept.ymin - my), std::min(box.xmax, kept.xmax + mx),
            std::min(box.ymax, kept.ymax + my)};
    const double full = std::max(box.xmax - box.xmin, bw) * std::max(box.ymax - box.ymin, bh);
    const double inner = std::max(kept.xmax - kept.xmin, bw) * std::max(kept.ymax - kept.ymin, bh);
    if (full <= 2 * inner) return;
    std::uint64_t outside = 0;
    std::array<double, 2> where{};
    std::uint64_t most = 0;
    for (int j = 0; j < bins; ++j) {
        for (int i = 0; i < bins; ++i) {
            const auto n = count[static_cast<std::size_t>(j) * bins + i];
            const double x = box.xmin + (i + 0.5) * bw, y = box.ymin + (j + 0.5) * bh;
            if (n == 0 || (x >= kept.xmin && x <= kept.xmax && y >= kept.ymin && y <= kept.ymax)) continue;
            outside += n;
            if (n > most) most = n, where = {x, y};
        }
    }
    if (outside == 0) return;
    // Places are given in the CRS's units (as --crop takes them), sizes in metres.
    const double u = unit_m;
    std::ostringstream why;
    why << std::fixed << std::setprecision(0) << outside << " of " << total
        << " points lie far from the rest (the most near x " << where[0] / u << ", y " << where[1] / u
        << ") and would stretch the grid from " << kept.xmax - kept.xmin << " m x " << kept.ymax - kept.ymin << " m to "
        << box.xmax - box.xmin << " m x " << box.ymax - box.ymin << " m. Use --crop " << kept.xmin / u << ','
        << kept.ymin / u << ',' << kept.xmax / u << ',' << kept.ymax / u
        << " to keep the rest, or --force to keep them";
    throw usage_error(why.str());
}

survey_layout survey_layout_of(const std::vector<std::string>& paths, const survey_options& opt,
                               bool reader_checks_outliers)
{
    const double cell_m = opt.cell_m;
    const int threads = opt.threads;
    if (threads < 0) throw usage_error("--threads must be >= 0 (got " + std::to_string(threads) + ")");
    if (paths.empty()) throw usage_error("no input LAS file given");
    if (!(cell_m > 0) || !std::isfinite(cell_m)) {
        throw usage_error("--cell must be a positive number of metres (got " + std::to_string(cell_m) + ")");
    }
    // The same file twice (by another name or through a link) would count its points twice.
    std::vector<std::pair<std::uintmax_t, std::uintmax_t>> identities;
    for (const auto& p : paths) {
        struct stat st {};
        if (::stat(p.c_str(), &st) != 0) throw std::runtime_error(p + ": cannot open: " + std::strerror(errno));
        const std::pair<std::uintmax_t, std::uintmax_t> id{st.st_dev, st.st_ino};
        const auto same = std::find(identities.begin(), identities.end(), id);
        if (same != identities.end()) {
            throw std::invalid_argument(p + " is the same file as " +
                                        paths[static_cast<std::size_t>(same - identities.begin())] +
                                        "; give each file once");
        }
        identities.push_back(id);
    }
    survey_layout layout;
    survey& s = layout.head;
    bounds box{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
               -std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
    std::uint64_t total = 0;
    std::vector<std::string> warned;  // each warning once, however many files give it
    std::optional<io::las_header> previous;
    io::survey_crs crs;
    for (const auto& p : paths) {
        io::las_reader r(p);
        const auto& h = r.header();
        if (!previous || !io::same_crs_records(*previous, h)) crs = io::crs_of_remembered(h);  // tiles share their CRS
        previous = h;
        for (const auto& w : crs.warnings) {
            if (std::find(warned.begin(), warned.end(), w) != warned.end()) continue;
            warned.push_back(w);
            std::cerr << "lidarfx: warning: " << p << ": " << w << '\n';
        }
        if (crs.geographic) {
            throw usage_error(p + ": x and y are longitude and latitude in degrees (" + crs.describe() +
                              "), but cells, heights and areas are measured in metres. Reproject the file to a "
                              "projected CRS first, e.g. pdal translate IN.las OUT.las reprojection "
                              "--filters.reprojection.out_srs=EPSG:<the UTM zone's code>, or las2las -target_utm auto");
        }
        if (s.files == 0) {
            s.crs = crs;
            s.crs_wkt = crs.wkt;
            s.epsg = crs.epsg;
            if (!io::crs_understood(s.crs_wkt)) {  // an odd record must not fail the run after the work is done
                std::cerr << "lidarfx: warning: " << p << ": its coordinate system cannot be written; outputs "
                          << (s.epsg ? "use its EPSG code " + std::to_string(s.epsg) : std::string("carry no CRS"))
                          << '\n';
                s.crs_wkt.clear();
            }
        } else if (crs.horizontal_unit_m != s.crs.horizontal_unit_m || crs.vertical_unit_m != s.crs.vertical_unit_m) {
            throw usage_error(p + " is in " + crs.describe() + " with z in " + crs.vertical_unit + ", but " + paths[0] +
                              " in " + s.crs.describe() + " with z in " + s.crs.vertical_unit +
                              ": reproject the files to one CRS first (pdal translate with filters.reprojection, or "
                              "las2las)");
        } else if (crs.epsg != s.crs.epsg || crs.wkt != s.crs.wkt) {
            std::cerr << "lidarfx: warning: " << p << " is in " << crs.describe() << ", the first file in "
                      << s.crs.describe() << "; coordinates are used as they are and outputs carry the first CRS\n";
        }
        ++s.files;
        total += h.point_count;
        layout.points.push_back(h.point_count);
        layout.extents.push_back({h.min[0], h.min[1], h.max[0], h.max[1]});
        if (h.point_count == 0) continue;
        box.xmin = std::min(box.xmin, h.min[0]);
        box.ymin = std::min(box.ymin, h.min[1]);
        box.xmax = std::max(box.xmax, h.max[0]);
        box.ymax = std::max(box.ymax, h.max[1]);
    }
    if (total == 0) throw std::runtime_error("the input files hold no point");
    // From here on, everything is in metres (a product of doubles is monotone, so bounds still hold the points).
    const double unit_xy = s.crs.horizontal_unit_m, unit_z = s.crs.vertical_unit_m;
    box = {box.xmin * unit_xy, box.ymin * unit_xy, box.xmax * unit_xy, box.ymax * unit_xy};
    for (auto& e : layout.extents) e = {e.xmin * unit_xy, e.ymin * unit_xy, e.xmax * unit_xy, e.ymax * unit_xy};
    const bounds header_box = box;
    if (opt.crop) {
        const bounds c{opt.crop->xmin * unit_xy, opt.crop->ymin * unit_xy, opt.crop->xmax * unit_xy,
                       opt.crop->ymax * unit_xy};
        box = {std::max(box.xmin, c.xmin), std::max(box.ymin, c.ymin), std::min(box.xmax, c.xmax),
               std::min(box.ymax, c.ymax)};
        if (!(box.xmin <= box.xmax && box.ymin <= box.ymax)) throw usage_error("--crop does not overlap the survey");
    }
    // Refuse before allocating: the grid's memory against the budget, the cell against the density.
    const double width = box.xmax - box.xmin, height = box.ymax - box.ymin;
    const double cells = (std::floor(width / cell_m) + 1) * (std::floor(height / cell_m) + 1);
    const double area = std::max(width, cell_m) * std::max(height, cell_m);
    const std::uint64_t budget = memory_budget_of(opt.memory_budget_bytes);
    const double need = cells * opt.bytes_per_cell;
    const double points_per_cell = static_cast<double>(total) / area * cell_m * cell_m;
    const bool over_budget = budget > 0 && need > static_cast<double>(budget);
    const bool too_sparse = points_per_cell < 0.01;
    // Outliers are looked for before the checks below, whose refusals they would explain. When the grid
    // passes them, the reader may count the points as it reads them instead of in a pass of their own.
    if (!opt.crop && !opt.force) {
        if (over_budget || too_sparse || !reader_checks_outliers)
            refuse_outliers(count_outlier_bins(paths, header_box, unit_xy, opt.threads, opt.memory_budget_bytes), total,
                            unit_xy);
        else
            layout.outliers_unchecked = true;
    }
    std::ostringstream extent;
    extent << std::fixed << std::setprecision(0) << width << " m x " << height << " m";
    if (over_budget) {
        const double fits = round_cell_up(cell_m * std::sqrt(need / static_cast<double>(budget)));
        std::ostringstream why;
        why << "a grid of " << extent.str() << " at " << cell_m << " m cells (" << std::setprecision(4) << cells
            << " cells) needs about " << gib(need) << ", over the memory budget of " << gib(static_cast<double>(budget))
            << "; use --cell " << fits << " or more, --crop to a smaller extent, or a larger --memory";
        throw usage_error(why.str());
    }
    if (!opt.force && too_sparse) {
        const double fits = round_cell_up(std::sqrt(area / static_cast<double>(total)));
        std::ostringstream why;
        why << total << " points over " << extent.str() << " give " << std::setprecision(2) << points_per_cell
            << " points per " << std::setprecision(6) << cell_m
            << " m cell: over 99 % of the cells would be empty. Use --cell " << fits
            << " or more (about one point per cell), --crop to where the points are, or --force";
        throw usage_error(why.str());
    }
    layout.g = snapped_grid(box, cell_m);
    layout.header_box = header_box;
    layout.memory_budget_bytes = opt.memory_budget_bytes;
    layout.total = total;
    layout.unit_xy = unit_xy;
    layout.unit_z = unit_z;
    return layout;
}

void to_metres(io::las_points& points, const survey_layout& layout)
{
    if (layout.unit_xy != 1) {
        for (double& x : points.x) x *= layout.unit_xy;
        for (double& y : points.y) y *= layout.unit_xy;
    }
    if (layout.unit_z != 1) {
        for (double& z : points.z) z *= layout.unit_z;
    }
}

void check_ground_choice(const std::string& choice)
{
    if (choice != "auto" && choice != "class2" && choice != "filter" && choice != "model")
        throw usage_error("--ground must be auto, class2, filter or model (got " + choice + ")");
}

raster<float> chosen_ground(survey& s, const std::string& choice, int threads)
{
    check_ground_choice(choice);
    const std::size_t on_grid = s.rasters.points_used;  // --crop leaves points off the grid
    const double share = on_grid ? static_cast<double>(s.class_ground_points) / static_cast<double>(on_grid) : 0.0;
    if (choice == "class2" && s.class_ground_points == 0)
        throw usage_error("--ground class2: the survey has no point of class 2 (ground)");
    if (choice == "model") {
        std::cout << "terrain under buildings: found from the DSM (ground_model)\n";
        return {};
    }
    if (choice == "filter" || (choice == "auto" && share < 0.01)) {
        morphological_ground_result filtered =
            morphological_ground(s.rasters.min_z, s.rasters.g.cell, {}, {.threads = threads});
        std::cout << "terrain under buildings: ground filter (progressive morphological, windows up to 40 m), "
                  << filtered.ground_cells << " ground cells"
                  << (choice == "auto" ? ", the survey has under 1 % of class-2 points" : "") << "\n";
        return std::move(filtered.ground);
    }
    std::ostringstream line;
    line << "terrain under buildings: class 2 (ground), " << s.class_ground_points << " points (" << std::fixed
         << std::setprecision(1) << 100.0 * share << " %), gaps filled by IDW\n";
    std::cout << line.str();
    return std::move(s.class_ground);
}

namespace {

// Lowers survey::class_ground to the class-2 points of a chunk (metres) that fall on the grid.
void add_class_ground(survey& s, const grid& g, const io::las_points& points)
{
    for (std::size_t i = 0; i < points.size(); ++i) {
        if (points.classification[i] != 2) continue;
        const auto at = g.cell_of(points.x[i], points.y[i]);
        if (!at || !std::isfinite(points.z[i])) continue;
        float& cell = s.class_ground(at->row, at->col);
        const auto z = static_cast<float>(points.z[i]);
        if (!(cell <= z)) cell = z;  // NaN (no ground yet) or higher
        ++s.class_ground_points;
    }
}

// Counts the class-6 (building) points of a chunk (metres) in survey::class_buildings.
void add_class_buildings(survey& s, const grid& g, const io::las_points& points)
{
    for (std::size_t i = 0; i < points.size(); ++i) {
        if (points.classification[i] != 6) continue;
        const auto at = g.cell_of(points.x[i], points.y[i]);
        if (!at || !std::isfinite(points.z[i])) continue;
        ++s.class_buildings(at->row, at->col);
        ++s.class_building_points;
    }
}

/// The points of a survey's files in file order, a chunk at a time, in metres: what read_survey reads, and
/// count_raised_points again. Each file's reader decodes LAZ chunks on `threads` within the memory budget.
class survey_chunks {
public:
    survey_chunks(const std::vector<std::string>& paths, const survey_layout& units, int threads,
                  std::uint64_t memory_budget_bytes)
        : paths_(paths), units_(units), threads_(threads), memory_budget_bytes_(memory_budget_bytes)
    {
    }

    /// Fills `dst` with the next chunk and `file` with the index of its file; returns its size, 0 after the last.
    std::size_t next(io::las_points& dst, std::size_t& file)
    {
        for (;;) {
            if (!reader_) {
                if (file_ == paths_.size()) return 0;
                reader_ = std::make_unique<io::las_reader>(paths_[file_++]);
                reader_->set_threads(threads_);                    // LAZ chunks decode in parallel (no effect on LAS)
                reader_->set_memory_budget(memory_budget_bytes_);  // ... within --memory
            }
            file = file_ - 1;
            // Stopping at the last point, not at an empty read, keeps the chunk's buffers for the next file.
            if (reader_->position() < reader_->point_count()) {
                const std::size_t n = reader_->read(dst, std::size_t{1} << 20);
                to_metres(dst, units_);
                return n;
            }
            reader_.reset();
        }
    }

private:
    const std::vector<std::string>& paths_;
    const survey_layout& units_;
    int threads_;
    std::uint64_t memory_budget_bytes_;
    std::size_t file_ = 0;
    std::unique_ptr<io::las_reader> reader_;
};

}  // namespace

survey read_survey(const std::vector<std::string>& paths, const survey_options& opt)
{
    const int threads = opt.threads;
    survey_layout layout = survey_layout_of(paths, opt, true);
    survey s = std::move(layout.head);
    const grid g = layout.g;
    std::optional<outlier_bins> outliers;  // counted as the points are read, when the layout left it to us
    if (layout.outliers_unchecked) outliers.emplace(layout.header_box);
    const std::uint64_t total = layout.total;
    raster_accumulator acc(g);
    auto bar = opt.show_progress ? progress_bar("reading  ") : progress_callback{};
    // The files' chunks in order: next_chunk(dst) fills dst, records its file and returns its size, 0 after
    // the last one.
    struct chunk {
        io::las_points points;
        std::size_t file = 0;
    };
    survey_chunks source(paths, layout, threads, opt.memory_budget_bytes);
    const auto next_chunk = [&](chunk& dst) { return source.next(dst.points, dst.file); };
    std::uint64_t done = 0;
    // Scan lines in file order, when the files carry GPS times (a new file starts a new sweep).
    std::optional<scan_coverage> scans;
    std::size_t scan_file = paths.size();
    if (opt.class_ground) s.class_ground = raster<float>(g.rows, g.cols, std::numeric_limits<float>::quiet_NaN());
    if (opt.class_buildings) s.class_buildings = raster<std::uint32_t>(g.rows, g.cols);
    const auto add = [&](const chunk& c, std::size_t n) {
        const std::size_t outside_before = acc.points_outside();
        acc.add(c.points.cloud());
        if (opt.class_ground) add_class_ground(s, g, c.points);
        if (opt.class_buildings) add_class_buildings(s, g, c.points);
        if (outliers) outliers->add(c.points.x, c.points.y);
        if (!c.points.gps_time.empty()) {
            if (!scans) scans.emplace(g);
            if (c.file != scan_file) scans->end_sweep();
            scan_file = c.file;
            scans->add(c.points.x, c.points.y, c.points.gps_time);
        }
        if (const std::size_t outside = acc.points_outside() - outside_before; outside > 0 && !opt.crop) {
            throw std::runtime_error(paths[c.file] + ": " + std::to_string(outside) +
                                     " points lie outside the bounds its LAS header declares; fix the header "
                                     "(e.g. lasinfo -repair) before rasterizing");
        }
        done += n;
        if (bar) bar(static_cast<double>(done) / static_cast<double>(total));
    };
    chunk current, ahead;
    std::size_t n = next_chunk(current);
    if (threads == 1) {
        for (; n > 0; n = next_chunk(current)) add(current, n);
    } else {
        // Two threads: one decodes the next chunk while this one rasterizes the current chunk.
        while (n > 0) {
            auto reading = std::async(std::launch::async, [&] { return next_chunk(ahead); });
            add(current, n);
            n = reading.get();
            std::swap(current, ahead);
        }
    }
    if (outliers) refuse_outliers(*outliers, total, layout.unit_xy);
    s.rasters = acc.finish();
    if (scans) s.scan_covered = scans->take();
    s.points = done;
    s.unit_xy = layout.unit_xy;
    s.unit_z = layout.unit_z;
    if (s.rasters.points_used == 0) {
        throw std::runtime_error("no point of the input has finite coordinates (" +
                                 std::to_string(s.rasters.points_nan) +
                                 " points with NaN or infinite x, y or z): nothing to rasterize");
    }
    return s;
}

raised_points count_raised_points(const std::vector<std::string>& paths, const survey& s, const survey_options& opt,
                                  raster_view<const float> terrain, double height_m)
{
    const grid& g = s.rasters.g;
    raised_points raised{raster<std::uint32_t>(g.rows, g.cols), raster<float>(g.rows, g.cols, NAN)};
    survey_layout units;
    units.unit_xy = s.unit_xy;
    units.unit_z = s.unit_z;
    auto bar = opt.show_progress ? progress_bar("rim points") : progress_callback{};
    survey_chunks source(paths, units, opt.threads, opt.memory_budget_bytes);
    io::las_points chunk;
    std::size_t file = 0;
    std::uint64_t done = 0;
    while (const std::size_t n = source.next(chunk, file)) {
        count_points_above(chunk.cloud(), g, terrain, height_m, raised.counts.view(), raised.lowest.view());
        done += n;
        if (bar && s.points > 0) bar(std::min(1.0, static_cast<double>(done) / static_cast<double>(s.points)));
    }
    return raised;
}

raster<std::uint8_t> class_building_cells(const survey& s)
{
    if (s.class_building_points == 0)
        throw usage_error(
            "--buildings class6: no point on the grid (inside --crop, when given) is of class 6 (building); use "
            "--buildings points to find the buildings from the surface");
    const raster<std::uint32_t>& all = s.rasters.count;
    raster<std::uint8_t> cells(all.rows(), all.cols());
    std::size_t n = 0;
    for (std::ptrdiff_t r = 0; r < all.rows(); ++r) {
        for (std::ptrdiff_t c = 0; c < all.cols(); ++c) {
            const bool building = all(r, c) > 0 && 2 * static_cast<std::uint64_t>(s.class_buildings(r, c)) >= all(r, c);
            cells(r, c) = building ? 1 : 0;
            n += building;
        }
    }
    std::cout << "buildings: class 6 (building), " << s.class_building_points << " points, " << n
              << " cells where they are at least half of the points\n";
    return cells;
}

raster<std::uint8_t> footprint_of(const survey& s, double hull_radius_m, int threads)
{
    const auto& pr = s.rasters;
    if (hull_radius_m <= 0) return raster<std::uint8_t>(pr.g.rows, pr.g.cols, 1);
    raster<std::uint8_t> covered(pr.g.rows, pr.g.cols, uninitialized);
    const bool scans = !s.scan_covered.empty();
    for (std::ptrdiff_t i = 0; i < covered.size(); ++i)
        covered.data()[i] = !pr.dropout.data()[i] || (scans && s.scan_covered.data()[i]);
    return survey_footprint(covered, pr.g.cell, {.hull_radius_m = hull_radius_m, .run = {.threads = threads}});
}

void keep_freed_memory()
{
#if defined(__GLIBC__)
    // A survey's rasters are tens to hundreds of MiB each (4096² floats: 64 MiB and the allocator's 2 MiB
    // of alignment); from mmap, each one's pages are new and zeroed by the kernel on first touch (~40 ms per
    // 64 MiB on some virtual machines), from the heap they are the pages the steps before it freed.
    mallopt(M_MMAP_THRESHOLD, 512 << 20);  // blocks below 512 MiB come from the heap and are reused
    mallopt(M_TRIM_THRESHOLD, 1 << 30);    // the heap keeps up to 1 GiB of free space at its top
#endif
}

bool has_extension(const std::string& path, const std::string& extension)
{
    return path.size() >= extension.size() &&
           std::equal(extension.rbegin(), extension.rend(), path.rbegin(), [](char a, char b) {
               return std::tolower(static_cast<unsigned char>(a)) == std::tolower(static_cast<unsigned char>(b));
           });
}

grid to_crs_units(const grid& g, const survey& s)
{
    grid out = g;
    const double u = s.crs.horizontal_unit_m;
    out.x0 = g.x0 / u;
    out.y0 = g.y0 / u;
    out.cell = g.cell / u;
    return out;
}

void write_raster(io::output_folder& out, const std::string& name, raster_view<const float> values, const grid& g,
                  const std::string& crs_wkt, int epsg, const output_formats& formats)
{
    const std::string crs = !crs_wkt.empty() ? crs_wkt : (epsg ? "EPSG:" + std::to_string(epsg) : "");
    if (formats.asc) {
        out.write(name + ".asc", [&](const std::string& path) { io::write_ascii_grid(path, values, g); });
        // The CRS beside the grid, as GDAL reads it (the .asc format itself has no place for it).
        if (const std::string prj = io::esri_prj_text(crs); !prj.empty())
            out.write(name + ".prj", [&](const std::string& path) { io::write_file(path, prj); });
    }
    if (formats.tif && io::geotiff_available()) {
        out.write(name + ".tif", [&](const std::string& path) { io::write_geotiff(path, values, g, crs); });
    }
}

std::vector<std::string> raster_file_names(const std::string& name, const output_formats& formats)
{
    std::vector<std::string> names;
    if (formats.asc) {
        names.push_back(name + ".asc");
        names.push_back(name + ".prj");  // written when the CRS is known
    }
    if (formats.tif && io::geotiff_available()) names.push_back(name + ".tif");
    return names;
}

void write_polygons(io::output_folder& out, const std::string& name, const std::vector<io::geojson_feature>& features,
                    const std::string& crs_wkt, int epsg, const output_formats& formats)
{
    if (formats.geojson) {
        const int code = epsg > 0 ? epsg : io::epsg_of_crs(crs_wkt);
        out.write(name + ".geojson", [&](const std::string& path) { io::write_geojson(path, features, code); });
    }
    if (formats.gpkg && io::vectors_available()) {
        out.write(name + ".gpkg",
                  [&](const std::string& path) { io::write_geopackage(path, name, features, crs_wkt, epsg); });
    }
}

std::vector<std::string> polygon_file_names(const std::string& name, const output_formats& formats)
{
    std::vector<std::string> names;
    if (formats.geojson) names.push_back(name + ".geojson");
    if (formats.gpkg && io::vectors_available()) names.push_back(name + ".gpkg");
    return names;
}

std::string command_line(const std::string& command, const std::vector<std::string>& args)
{
    std::string line = "lidarfx " + command;
    for (const auto& a : args) line += " " + a;
    return line;
}

void commit_and_report(io::output_folder& out, const std::string& command)
{
    out.commit(command);
    for (const auto& path : out.files()) std::cout << "  wrote " << path.string() << '\n';
    std::cout << "  wrote " << (out.path() / "manifest.json").string() << '\n';
    for (const auto& name : out.removed_stale()) {
        std::cout << "  removed " << (out.path() / name).string() << " (an earlier run's, not made by this one)\n";
    }
}

}  // namespace lidarfx::cli
