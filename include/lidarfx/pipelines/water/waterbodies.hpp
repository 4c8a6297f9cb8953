// SPDX-License-Identifier: Apache-2.0
// extract_waterbodies: waterbody maps from the rasters of an airborne LiDAR survey (dissertation ch. 2).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <numeric>
#include <sstream>
#include <string>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/grid.hpp"
#include "lidarfx/core/parallel.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/kernels/filter/angular_filter.hpp"
#include "lidarfx/kernels/filter/morphology.hpp"
#include "lidarfx/kernels/label/connected_components.hpp"
#include "lidarfx/kernels/interpolate/idw_fill.hpp"
#include "lidarfx/kernels/points/rasterize.hpp"
#include "lidarfx/kernels/filter/vegetation_mask.hpp"
#include "lidarfx/pipelines/water/grow_waterbody.hpp"

namespace lidarfx {

/// The rasters of a survey that the method reads, all of one shape on one grid (see rasterize()).
struct water_rasters {
    raster_view<const float> min_z;                          ///< lowest return, metres; NaN = no return
    raster_view<const float> max_z;                          ///< highest return, metres; NaN = no return
    raster_view<const float> mean_intensity;                 ///< mean return intensity; ignored where dropout
    raster_view<const std::uint8_t> dropout;                 ///< 1 = no return in the cell
    raster_view<const std::uint8_t> multiple_returns = {};   ///< optional: 1 = a pulse with several returns
    raster_view<const std::uint32_t> count = {};             ///< optional: points per cell (density checks)
};

/// Which elevation the angular filter reads.
enum class angular_input {
    returns_only,  ///< minimum elevation of cells with returns; dropouts are skipped as neighbours and
                   ///< join the region at any threshold (their height is unknown, not steep)
    idw_filled,    ///< minimum elevation with dropouts filled by IDW, as in the dissertation
};

/// Options of extract_waterbodies; defaults follow the dissertation where it gives a value.
struct waterbody_options {
    double vegetation_height_m = 2.0;      ///< h: max_z - min_z above this is vegetation, metres
    int vegetation_closing_size = 5;       ///< closing of the vegetation mask, cells (odd)
    bool vegetation_from_multiple_returns = true;  ///< cells with multiple-return pulses are vegetation too
    int angular_radius = 2;                ///< angular filter window radius, cells ("two tiers")
    angular_input angular_on = angular_input::returns_only;  ///< elevation read by the angular filter
    bool dropouts_join_any_threshold = true;  ///< dropout cells join a region at any θ (their angle is
                                              ///< unknown); false = the dissertation's literal behaviour
    int seed_opening_size = 5;             ///< opening of the dropout mask before seeding, cells (odd)
    std::size_t min_seed_cells = 100;      ///< smallest seed component, cells
    grow_options grow = {};                ///< θ schedule, KS test, min_ks_samples
    double intensity_resolution = 1.0;     ///< intensity quantum of the KS samples (rounded to nearest, ties to
                                           ///< even), > 0
    double level_tolerance_m = 0.15;       ///< refinement: land cells next to a body whose min z is within this
                                           ///< of the adjacent water level join it; 0 disables
    double level_max_rise_m = 0.5;         ///< ... and whose highest return is at most this above that level
                                           ///< (a cell mostly on the bank is not water), metres
    int level_join_depth_cells = 2;        ///< how far (cells) from the grown region the refinement reaches
    double island_min_area_m2 = 200.0;     ///< holes in a body at least this large stay land; smaller are water
    double bridge_max_span_m = 30.0;       ///< gaps up to this long between two bodies at one water level are
                                           ///< bridged (decks become water, bodies merge); 0 disables
    double bridge_level_tolerance_m = 1.0; ///< water levels on both sides of a bridge differ by at most this
    double bridge_min_clearance_m = 2.0;   ///< a deck cell's lowest return stands at least this high above the
                                           ///< water on both sides (low banks beside a bridge stay land), metres
    double min_points_per_cell = 2.0;      ///< below this mean density the inputs are refused (check_inputs)
    bool check_inputs = true;              ///< refuse inputs that cannot support the method (see diagnostics)
    int threads = 1;                       ///< threads for the raster kernels (0 = all cores); same result
    progress_callback progress = {};       ///< progress over seeds; returning false cancels
};

/// One extracted waterbody.
struct waterbody {
    std::int32_t label = 0;                ///< 1..n by decreasing area
    std::size_t cells = 0;
    double area_m2 = 0;
    cell_box box;                          ///< bounding box, cells (inclusive)
    std::int32_t seed = 0;                 ///< rank of the seed it grew from (1 = largest seed)
    double theta_deg = NAN;                ///< angular threshold reached when growth stopped
    bool stopped_by_ks = false;            ///< false: θ_max reached without a KS rejection
    double mean_intensity = NAN;           ///< mean intensity of its cells with returns (NaN if none)
    double water_level_m = NAN;            ///< median min z of its cells with returns, metres (NaN if none)
    double dropout_fraction = 0;           ///< share of its cells without returns
};

/// What the inputs can support. `problems` block the method (check_inputs), `warnings` do not.
struct water_diagnostics {
    double points_per_cell = NAN;          ///< mean points per cell over the grid (needs the count raster)
    double dropout_fraction = NAN;         ///< share of cells without returns
    bool has_intensity = false;            ///< intensity varies between cells with returns
    bool has_multiple_returns = false;     ///< some cell has a multiple-return pulse
    double suggested_cell_m = NAN;         ///< smallest cell (0.5 m steps) reaching min_points_per_cell
    std::vector<std::string> problems;
    std::vector<std::string> warnings;
    bool usable() const noexcept { return problems.empty(); }
};

/// Result of extract_waterbodies, with the intermediate rasters for inspection.
struct waterbody_result {
    raster<std::int32_t> labels;           ///< 0 land, 1..n waterbodies by decreasing area
    raster<std::uint8_t> water;            ///< 1 water, 0 land
    std::vector<waterbody> bodies;         ///< bodies[i].label == i + 1
    water_diagnostics diagnostics;
    raster<std::uint8_t> vegetation;       ///< vegetation mask used
    raster<float> angle_deg;               ///< angular filter output as growing saw it (NaN: joins at any θ)
    raster<std::int32_t> seeds;            ///< seed components, 1 = largest
    std::size_t seeds_found = 0, seeds_grown = 0;
    bool ran = false;                      ///< false when check_inputs refused the data
};

namespace detail {

inline void validate(const waterbody_options& o, double cell_m, const char* fn)
{
    require_positive(cell_m, fn, "cell_m");
    require(o.vegetation_height_m > 0, fn, "vegetation_height_m", "> 0", o.vegetation_height_m);
    require(o.vegetation_closing_size >= 1 && o.vegetation_closing_size % 2 == 1, fn, "vegetation_closing_size",
            "odd and >= 1", o.vegetation_closing_size);
    require(o.angular_radius >= 1, fn, "angular_radius", ">= 1", o.angular_radius);
    require(o.seed_opening_size >= 1 && o.seed_opening_size % 2 == 1, fn, "seed_opening_size", "odd and >= 1",
            o.seed_opening_size);
    require(o.min_seed_cells >= 1, fn, "min_seed_cells", ">= 1", o.min_seed_cells);
    require_positive(o.intensity_resolution, fn, "intensity_resolution");
    require(o.level_tolerance_m >= 0, fn, "level_tolerance_m", ">= 0", o.level_tolerance_m);
    require(o.level_max_rise_m >= 0, fn, "level_max_rise_m", ">= 0", o.level_max_rise_m);
    require(o.level_join_depth_cells >= 0, fn, "level_join_depth_cells", ">= 0", o.level_join_depth_cells);
    require(o.island_min_area_m2 >= 0, fn, "island_min_area_m2", ">= 0", o.island_min_area_m2);
    require(o.bridge_max_span_m >= 0, fn, "bridge_max_span_m", ">= 0", o.bridge_max_span_m);
    require(o.bridge_min_clearance_m >= 0, fn, "bridge_min_clearance_m", ">= 0", o.bridge_min_clearance_m);
    require(o.bridge_level_tolerance_m >= 0, fn, "bridge_level_tolerance_m", ">= 0", o.bridge_level_tolerance_m);
    require(o.min_points_per_cell >= 0, fn, "min_points_per_cell", ">= 0", o.min_points_per_cell);
    validate(o.grow, fn);
}

inline void validate(const water_rasters& in, const char* fn)
{
    require_same_shape(in.min_z, in.max_z, fn, "min_z", "max_z");
    require_same_shape(in.min_z, in.mean_intensity, fn, "min_z", "mean_intensity");
    require_same_shape(in.min_z, in.dropout, fn, "min_z", "dropout");
    if (!in.multiple_returns.empty())
        require_same_shape(in.min_z, in.multiple_returns, fn, "min_z", "multiple_returns");
    if (!in.count.empty()) require_same_shape(in.min_z, in.count, fn, "min_z", "count");
    require(!in.min_z.empty(), fn, "the rasters are empty (0 cells)");
}

inline std::string fixed(double v, int digits = 2)
{
    std::ostringstream os;
    os.setf(std::ios::fixed);
    os.precision(digits);
    os << v;
    return os.str();
}

}  // namespace detail

/// Checks whether the rasters can support the method: point density per cell (needs `count`), intensity
/// that varies (the KS stop compares intensity distributions), multiple returns (vegetation). Fills
/// `problems` (the method's result would be meaningless) and `warnings`. O(cells).
inline water_diagnostics assess_water_inputs(const water_rasters& in, double cell_m, const waterbody_options& opt = {})
{
    constexpr const char* fn = "assess_water_inputs";
    detail::validate(in, fn);
    detail::validate(opt, cell_m, fn);
    water_diagnostics d;
    const std::ptrdiff_t rows = in.min_z.rows(), cols = in.min_z.cols();
    std::uint64_t points = 0, dropouts = 0;
    float lo = std::numeric_limits<float>::infinity(), hi = -lo;
    for (std::ptrdiff_t r = 0; r < rows; ++r) {
        const std::uint8_t* dropout = in.dropout.row(r);
        const float* mean = in.mean_intensity.row(r);
        if (!in.count.empty()) {
            const std::uint32_t* count = in.count.row(r);
            for (std::ptrdiff_t c = 0; c < cols; ++c) points += count[c];
        }
        for (std::ptrdiff_t c = 0; c < cols; ++c) {
            dropouts += dropout[c] != 0;
            // NaN compares false, so it changes neither bound.
            const float v = dropout[c] ? lo : mean[c];
            lo = std::min(lo, v);
            hi = std::max(hi, dropout[c] ? hi : v);
        }
        if (!in.multiple_returns.empty() && !d.has_multiple_returns) {
            const std::uint8_t* multiple = in.multiple_returns.row(r);
            for (std::ptrdiff_t c = 0; c < cols; ++c) d.has_multiple_returns |= multiple[c] && !dropout[c];
        }
    }
    const double cells = static_cast<double>(rows * cols);
    d.dropout_fraction = static_cast<double>(dropouts) / cells;
    d.has_intensity = hi > lo;
    if (!d.has_intensity) {
        d.problems.push_back(lo <= hi ? "intensity is the same (" + detail::fixed(lo, 0) +
                                            ") in every cell with returns: the KS test that stops region growing "
                                            "compares intensity distributions and cannot work"
                                      : "no cell has a return: nothing to analyse");
    }
    if (!in.count.empty()) {
        d.points_per_cell = static_cast<double>(points) / cells;
        const double density = static_cast<double>(points) / (cells * cell_m * cell_m);
        if (density > 0) {
            d.suggested_cell_m = std::max(cell_m, std::ceil(2.0 * std::sqrt(opt.min_points_per_cell / density)) / 2.0);
        }
        if (d.points_per_cell < opt.min_points_per_cell) {
            d.problems.push_back("point density " + detail::fixed(density) + " points/m² gives " +
                                 detail::fixed(d.points_per_cell) + " points per " + detail::fixed(cell_m, 1) +
                                 " m cell (below " + detail::fixed(opt.min_points_per_cell, 1) + "): " +
                                 detail::fixed(100 * d.dropout_fraction, 0) +
                                 " % of cells are empty by sparse sampling, so dropouts no longer mark water; use "
                                 "a cell of at least " + detail::fixed(d.suggested_cell_m, 1) + " m");
        }
    } else {
        d.warnings.push_back("no count raster: point density was not checked");
    }
    if (!in.multiple_returns.empty() && !d.has_multiple_returns) {
        d.warnings.push_back("no pulse has multiple returns: vegetation comes from max z - min z alone");
    }
    return d;
}

/// Seeds: the dropout mask opened by a size x size square (removes sparse dropouts), its 8-connected
/// components with at least min_cells cells, ranked by size (label 1 = largest; ties by scan order).
template <raster_input Mask>
components water_seeds(const Mask& dropout, int opening_size = 5, std::size_t min_cells = 100, int threads = 1)
{
    const auto opened =
        morph_open(dropout, morphology_options{.size_cells = opening_size, .run = {.threads = threads}});
    auto seeds = connected_components(
        opened, connected_components_options{.conn = connectivity::eight, .run = {.threads = threads}});
    rank_by_size(seeds);
    // Ranked by size: the seeds to keep are the labels 1..kept.
    std::size_t kept = 0;
    while (kept + 1 < seeds.sizes.size() && seeds.sizes[kept + 1] >= min_cells) ++kept;
    for (auto& l : seeds.labels) {
        if (static_cast<std::size_t>(l) > kept) {
            seeds.sizes[0] += 1;
            l = 0;
        }
    }
    seeds.sizes.resize(kept + 1);
    return seeds;
}

namespace detail {

/// Cells of each label of `labels` (1..n) as linear indices in scan order.
inline std::vector<std::vector<std::ptrdiff_t>> cells_by_label(const raster<std::int32_t>& labels, std::size_t n)
{
    std::vector<std::vector<std::ptrdiff_t>> out(n + 1);
    for (std::ptrdiff_t i = 0; i < labels.size(); ++i) {
        const auto l = labels.data()[i];
        if (l > 0) out[static_cast<std::size_t>(l)].push_back(i);
    }
    return out;
}

/// Rounds intensities of cells with returns to multiples of `resolution` and ranks the distinct values,
/// so KS histograms have one bin per distinct value (the KS statistic only depends on the order).
/// O(cells + range of the rounded values) when that range is small (LAS intensities), else a sort.
inline raster<std::int32_t> intensity_bins(const water_rasters& in, double resolution, int& bins)
{
    const std::ptrdiff_t rows = in.min_z.rows(), cols = in.min_z.cols();
    constexpr std::int32_t none = std::numeric_limits<std::int32_t>::min();
    raster<std::int32_t> out(rows, cols);
    // Pass 1: rounded values as integers (none = no sample), while they fit in +-1e9 (LAS intensities do).
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    const double inverse = 1.0 / resolution;
    // Presence of the values 0..65535 (16-bit LAS intensities), marked on the way.
    constexpr std::int32_t small = 65536;
    std::vector<std::uint8_t> seen_small(small, 0);
    for (std::ptrdiff_t r = 0; r < rows; ++r) {
        std::int32_t* o = out.row(r);
        const std::uint8_t* dropout = in.dropout.row(r);
        const float* mean = in.mean_intensity.row(r);
        for (std::ptrdiff_t c = 0; c < cols; ++c) {
            if (dropout[c] || !std::isfinite(mean[c])) {
                o[c] = none;
                continue;
            }
            const double q = std::nearbyint(static_cast<double>(mean[c]) * inverse);
            lo = std::min(lo, q);
            hi = std::max(hi, q);
            o[c] = static_cast<std::int32_t>(std::clamp(q, -1.0e9, 1.0e9));
            if (o[c] >= 0 && o[c] < small) seen_small[static_cast<std::size_t>(o[c])] = 1;
        }
    }
    bins = 1;
    if (lo > hi) {
        out.fill(-1);
        return out;
    }
    std::int32_t* cell = out.data();
    const std::ptrdiff_t n = out.size();
    if (hi - lo < double(1 << 24) && lo >= -1.0e9 && hi <= 1.0e9) {
        // Ranks from a presence table over the range of values.
        const auto base = static_cast<std::int64_t>(lo);
        std::vector<std::int32_t> rank(static_cast<std::size_t>(hi - lo) + 1, 0);
        if (lo >= 0 && hi < small) {
            for (std::size_t k = 0; k < rank.size(); ++k) rank[k] = seen_small[k + static_cast<std::size_t>(base)];
        } else {
            for (std::ptrdiff_t i = 0; i < n; ++i)
                if (cell[i] != none) rank[static_cast<std::size_t>(cell[i] - base)] = 1;
        }
        std::int32_t next = 0;
        for (auto& k : rank) k = k ? next++ : -1;
        bins = std::max(1, static_cast<int>(next));
        for (std::ptrdiff_t i = 0; i < n; ++i) cell[i] = cell[i] == none ? -1 : rank[static_cast<std::size_t>(cell[i] - base)];
        return out;
    }
    // Wide ranges: ranks from the sorted distinct values, recomputed exactly.
    std::vector<double> distinct;
    const auto value = [&](std::ptrdiff_t i) {
        return std::nearbyint(static_cast<double>(in.mean_intensity(i / cols, i % cols)) * inverse);
    };
    for (std::ptrdiff_t i = 0; i < n; ++i)
        if (cell[i] != none) distinct.push_back(value(i));
    std::sort(distinct.begin(), distinct.end());
    distinct.erase(std::unique(distinct.begin(), distinct.end()), distinct.end());
    bins = std::max(1, static_cast<int>(distinct.size()));
    for (std::ptrdiff_t i = 0; i < n; ++i)
        cell[i] = cell[i] == none ? -1
                                  : static_cast<std::int32_t>(std::lower_bound(distinct.begin(), distinct.end(), value(i)) -
                                                              distinct.begin());
    return out;
}

/// Refinement for narrow water: eligible cells within `depth` steps (8-neighbourhood) of the region whose
/// returns (min z and max z) all lie within `tolerance` of the level of the region cell they are reached
/// from join the region.
inline void join_level_cells(std::vector<std::ptrdiff_t>& region, const water_rasters& in,
                             const raster<std::uint8_t>& eligible, raster<std::int32_t>& seen, std::int32_t stamp,
                             double tolerance, double max_rise, int depth)
{
    if (tolerance <= 0 || depth <= 0) return;
    const std::ptrdiff_t rows = eligible.rows(), cols = eligible.cols();
    struct entry { std::ptrdiff_t cell; float level; int depth; };
    std::vector<entry> frontier;
    for (const auto i : region) {
        seen.data()[i] = stamp;
    }
    // Only region cells on the region's edge can reach a new cell: interior ones start nothing.
    const auto on_edge = [&](std::ptrdiff_t r, std::ptrdiff_t c) {
        for (std::ptrdiff_t rr = std::max<std::ptrdiff_t>(0, r - 1); rr <= std::min(rows - 1, r + 1); ++rr)
            for (std::ptrdiff_t cc = std::max<std::ptrdiff_t>(0, c - 1); cc <= std::min(cols - 1, c + 1); ++cc)
                if (seen.data()[rr * cols + cc] != stamp) return true;
        return false;
    };
    for (const auto i : region) {
        const std::ptrdiff_t r = i / cols, c = i % cols;
        const float z = in.min_z(r, c);
        if (std::isfinite(z) && on_edge(r, c)) frontier.push_back({i, z, 0});
    }
    for (std::size_t q = 0; q < frontier.size(); ++q) {
        const entry e = frontier[q];
        if (e.depth >= depth) continue;
        const std::ptrdiff_t r = e.cell / cols, c = e.cell % cols;
        for (std::ptrdiff_t dr = -1; dr <= 1; ++dr) {
            for (std::ptrdiff_t dc = -1; dc <= 1; ++dc) {
                const std::ptrdiff_t rr = r + dr, cc = c + dc;
                if ((dr == 0 && dc == 0) || rr < 0 || cc < 0 || rr >= rows || cc >= cols) continue;
                const std::ptrdiff_t j = rr * cols + cc;
                if (seen.data()[j] == stamp || !eligible.data()[j]) continue;
                // The whole cell must lie at the water level: a shore cell holding water and bank returns
                // has its lowest return on the water but its highest on the bank.
                const float lo = in.min_z(rr, cc), hi = in.max_z(rr, cc);
                if (!std::isfinite(lo) || std::abs(static_cast<double>(lo) - e.level) > tolerance ||
                    !(static_cast<double>(hi) - e.level <= max_rise)) {
                    continue;
                }
                seen.data()[j] = stamp;
                region.push_back(j);
                frontier.push_back({j, e.level, e.depth + 1});
            }
        }
    }
}

/// Holes of the water mask (4-connected land components not touching the border) smaller than
/// `max_hole_cells` and surrounded by a single body become part of that body. A hole lies inside its body's
/// bounding box, so each body is examined in that box grown by one cell: O(sum of the boxes' areas).
inline void fill_small_islands(raster<std::int32_t>& labels, std::size_t max_hole_cells)
{
    if (max_hole_cells == 0) return;
    const std::ptrdiff_t rows = labels.rows(), cols = labels.cols();
    std::int32_t bodies = 0;
    for (const auto l : labels) bodies = std::max(bodies, l);
    std::vector<std::array<std::ptrdiff_t, 4>> box(static_cast<std::size_t>(bodies) + 1,
                                                   {rows, cols, -1, -1});  // r0, c0, r1, c1 inclusive
    for (std::ptrdiff_t r = 0; r < rows; ++r) {
        const std::int32_t* row = labels.row(r);
        for (std::ptrdiff_t c = 0; c < cols; ++c) {
            if (row[c] <= 0) continue;
            auto& b = box[static_cast<std::size_t>(row[c])];
            b = {std::min(b[0], r), std::min(b[1], c), std::max(b[2], r), std::max(b[3], c)};
        }
    }
    raster<std::uint8_t> other;
    for (std::int32_t body = 1; body <= bodies; ++body) {
        const auto& b = box[static_cast<std::size_t>(body)];
        if (b[2] < 0) continue;
        const std::ptrdiff_t r0 = std::max<std::ptrdiff_t>(0, b[0] - 1), c0 = std::max<std::ptrdiff_t>(0, b[1] - 1);
        const std::ptrdiff_t r1 = std::min(rows - 1, b[2] + 1), c1 = std::min(cols - 1, b[3] + 1);
        const std::ptrdiff_t nr = r1 - r0 + 1, nc = c1 - c0 + 1;
        if (nr < 3 || nc < 3) continue;
        other = raster<std::uint8_t>(nr, nc);
        for (std::ptrdiff_t r = 0; r < nr; ++r)
            for (std::ptrdiff_t c = 0; c < nc; ++c) other(r, c) = labels(r0 + r, c0 + c) != body;
        const auto parts = connected_components(other, connectivity::four);
        // A part is a hole to fill when it touches no edge of the box (nor so the raster's border), holds
        // only land and is small enough.
        std::vector<std::uint8_t> fill(parts.sizes.size(), 1);
        fill[0] = 0;
        for (std::size_t k = 1; k < parts.sizes.size(); ++k)
            if (parts.sizes[k] >= max_hole_cells) fill[k] = 0;
        for (std::ptrdiff_t r = 0; r < nr; ++r)
            for (std::ptrdiff_t c = 0; c < nc; ++c) {
                const auto k = static_cast<std::size_t>(parts.labels(r, c));
                if (k == 0 || !fill[k]) continue;
                if (r == 0 || c == 0 || r == nr - 1 || c == nc - 1 || labels(r0 + r, c0 + c) != 0) fill[k] = 0;
            }
        for (std::ptrdiff_t r = 0; r < nr; ++r)
            for (std::ptrdiff_t c = 0; c < nc; ++c)
                if (fill[static_cast<std::size_t>(parts.labels(r, c))]) labels(r0 + r, c0 + c) = body;
    }
}

/// Median of `values` (reordered; NaN when empty).
inline double median(std::vector<float>& values)
{
    if (values.empty()) return NAN;
    const auto mid = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
    std::nth_element(values.begin(), mid, values.end());
    return *mid;
}

/// Median min z of the cells (linear indices) that have a return; NaN when none has.
inline double median_level(const std::vector<std::ptrdiff_t>& cells, const water_rasters& in)
{
    std::vector<float> z;
    z.reserve(cells.size());
    const auto cols = in.min_z.cols();
    const bool contiguous = in.min_z.is_contiguous();
    for (const auto i : cells) {
        const float v = contiguous ? in.min_z.data()[i] : in.min_z(i / cols, i % cols);
        if (std::isfinite(v)) z.push_back(v);
    }
    return median(z);
}

/// Bridges: a land cell lying on a straight run (row, column or diagonal) of at most `span_cells` land
/// cells whose two ends touch two different bodies at water levels within `level_tolerance`, and whose
/// lowest return is NaN (none), at least `clearance` above both levels (the deck) or within
/// `water_tolerance` of them (water seen past the deck's edge), becomes water; the two bodies merge.
/// One row-major pass keeps, for each line of the 4 directions, the last water cell seen on it; a run is
/// examined when a water cell of another body closes it. O(cells + cells of examined runs).
/// Returns the number of bridged cells.
inline std::size_t join_across_bridges(raster<std::int32_t>& labels, raster_view<const float> min_z,
                                       const std::vector<double>& level, int span_cells, double level_tolerance,
                                       double clearance, double water_tolerance)
{
    if (span_cells <= 0) return 0;
    const std::ptrdiff_t rows = labels.rows(), cols = labels.cols();
    std::vector<std::int32_t> parent(level.size());
    std::iota(parent.begin(), parent.end(), 0);
    const auto find = [&](std::int32_t x) {
        while (parent[static_cast<std::size_t>(x)] != x) x = parent[static_cast<std::size_t>(x)];
        return x;
    };
    const auto bridge_ok = [&](std::ptrdiff_t r, std::ptrdiff_t c, std::int32_t a, std::int32_t b) {
        const double la = level[static_cast<std::size_t>(a)], lb = level[static_cast<std::size_t>(b)];
        if (!(std::abs(la - lb) <= level_tolerance)) return false;
        const float z = min_z(r, c);
        if (!std::isfinite(z)) return true;
        const double above = static_cast<double>(z) - std::max(la, lb);
        const double below = std::min(la, lb) - static_cast<double>(z);
        return above >= clearance || (above <= water_tolerance && below <= water_tolerance);
    };
    // Last water cell on each line: its row (for rows: its column) and label; -1 = none yet.
    struct last_water { std::ptrdiff_t at = -1; std::int32_t label = 0; };
    std::vector<last_water> down(static_cast<std::size_t>(cols)), diag(static_cast<std::size_t>(rows + cols)),
        anti(static_cast<std::size_t>(rows + cols));
    // Bridged cells are recorded and written after the pass, so every decision reads the original labels;
    // a cell bridged in several directions takes the label of the first direction (row, column, diagonal,
    // anti-diagonal).
    struct bridged_cell { std::ptrdiff_t cell; int direction; std::int32_t label; };
    std::vector<bridged_cell> bridged;
    const auto close_run = [&](last_water& lw, std::ptrdiff_t at, std::int32_t l, std::ptrdiff_t r,
                               std::ptrdiff_t c, int dr, int dc, int direction) {
        const std::ptrdiff_t gap = at - lw.at - 1;
        if (lw.at >= 0 && lw.label != l && gap >= 1 && gap <= span_cells) {
            bool any = false;
            for (std::ptrdiff_t k = 1; k <= gap; ++k) {  // walk back from (r, c) over the land run
                const std::ptrdiff_t rr = r - k * dr, cc = c - k * dc;
                if (!bridge_ok(rr, cc, lw.label, l)) continue;
                bridged.push_back({rr * cols + cc, direction, std::min(lw.label, l)});
                any = true;
            }
            const auto ra = find(lw.label), rb = find(l);
            if (any && ra != rb) parent[static_cast<std::size_t>(std::max(ra, rb))] = std::min(ra, rb);
        }
        lw = {at, l};
    };
    for (std::ptrdiff_t r = 0; r < rows; ++r) {
        last_water across;
        const std::int32_t* row = labels.row(r);
        for (std::ptrdiff_t c = 0; c < cols; ++c) {
            const std::int32_t l = row[c];
            if (l == 0) continue;
            close_run(across, c, l, r, c, 0, 1, 0);
            close_run(down[static_cast<std::size_t>(c)], r, l, r, c, 1, 0, 1);
            close_run(diag[static_cast<std::size_t>(c - r + rows)], r, l, r, c, 1, 1, 2);
            close_run(anti[static_cast<std::size_t>(c + r)], r, l, r, c, 1, -1, 3);
        }
    }
    std::sort(bridged.begin(), bridged.end(), [](const bridged_cell& a, const bridged_cell& b) {
        return a.cell != b.cell ? a.cell < b.cell : a.direction < b.direction;
    });
    std::size_t count = 0;
    for (std::size_t k = 0; k < bridged.size(); ++k) {
        if (k > 0 && bridged[k].cell == bridged[k - 1].cell) continue;
        labels.data()[bridged[k].cell] = bridged[k].label;
        ++count;
    }
    bool merged = false;
    for (std::size_t b = 0; b < parent.size(); ++b) merged |= parent[b] != static_cast<std::int32_t>(b);
    if (merged)
        for (auto& l : labels)
            if (l > 0) l = find(l);
    return count;
}

}  // namespace detail

/// Extracts waterbodies from the rasters of a survey (dissertation ch. 2, with DESIGN.md §5's refinements):
/// vegetation mask (max z - min z > h, closed; plus multiple returns), angular filter of min z, seeds from
/// opened dropouts (>= min_seed_cells, largest first), one KS-stopped bucket-queue flood per seed not yet
/// inside a body, the level refinement for narrow water, bridges joined, holes below island_min_area_m2
/// filled. Labels are numbered by decreasing area. When check_inputs is set and assess_water_inputs()
/// reports problems, nothing is extracted (ran = false) and the diagnostics say why.
/// O(cells · (kernel radius) + sum over seeds of cells reached). Progress is reported per seed.
/// @throws invalid_input on rasters of different shapes, cell_m <= 0 or options out of range; cancelled.
inline waterbody_result extract_waterbodies(const water_rasters& in, double cell_m, const waterbody_options& opt = {})
{
    constexpr const char* fn = "extract_waterbodies";
    detail::validate(in, fn);
    detail::validate(opt, cell_m, fn);
    const std::ptrdiff_t rows = in.min_z.rows(), cols = in.min_z.cols();

    waterbody_result res;
    res.diagnostics = assess_water_inputs(in, cell_m, opt);
    res.labels = raster<std::int32_t>(rows, cols, 0);
    res.water = raster<std::uint8_t>(rows, cols, 0);
    if (opt.check_inputs && !res.diagnostics.usable()) return res;
    res.ran = true;
    detail::report(opt.progress, 0.0, fn);

    // 1. Vegetation.
    res.vegetation = vegetation_mask(in.min_z, in.max_z,
                                     vegetation_mask_options{.height_m = opt.vegetation_height_m,
                                                             .closing_size_cells = opt.vegetation_closing_size,
                                                             .run = {.threads = opt.threads}});
    if (opt.vegetation_from_multiple_returns && !in.multiple_returns.empty()) {
        for (std::ptrdiff_t r = 0; r < rows; ++r) {
            const std::uint8_t* multiple = in.multiple_returns.row(r);
            const std::uint8_t* dropout = in.dropout.row(r);
            std::uint8_t* vegetation = res.vegetation.row(r);
            for (std::ptrdiff_t c = 0; c < cols; ++c)
                vegetation[c] = static_cast<std::uint8_t>(vegetation[c] | ((multiple[c] != 0) & (dropout[c] == 0)));
        }
    }

    // 2. Angular filter of the minimum elevation (into the growing field; moved to the result at the end).
    water_field field;
    const angular_filter_options af{.radius_cells = opt.angular_radius, .run = {.threads = opt.threads}};
    if (opt.angular_on == angular_input::idw_filled) {
        const auto filled = idw_fill(in.min_z, cell_m, idw_fill_options{.run = {.threads = opt.threads}});
        field.angle_deg = angular_filter(filled.filled, cell_m, af);
    } else {
        field.angle_deg = angular_filter(in.min_z, cell_m, af);
    }

    // 3. Seeds.
    auto seeds = water_seeds(in.dropout, opt.seed_opening_size, opt.min_seed_cells, opt.threads);
    res.seeds_found = seeds.sizes.empty() ? 0 : seeds.sizes.size() - 1;
    const auto seed_cells = detail::cells_by_label(seeds.labels, res.seeds_found);
    res.seeds = std::move(seeds.labels);

    // 4. Growing, largest seed first; cells of accepted bodies are no longer eligible.
    // NaN in the field means "joins at any threshold"; without that option a dropout is as steep as can be
    // unless the filter saw an (interpolated) height for it.
    field.eligible = raster<std::uint8_t>(rows, cols);
    for (std::ptrdiff_t r = 0; r < rows; ++r) {
        float* angle = field.angle_deg.row(r);
        const std::uint8_t* dropout = in.dropout.row(r);
        const std::uint8_t* vegetation = res.vegetation.row(r);
        std::uint8_t* eligible = field.eligible.row(r);
        for (std::ptrdiff_t c = 0; c < cols; ++c) eligible[c] = !vegetation[c];
        if (opt.dropouts_join_any_threshold) {
            for (std::ptrdiff_t c = 0; c < cols; ++c) angle[c] = dropout[c] ? NAN : angle[c];
        } else {
            for (std::ptrdiff_t c = 0; c < cols; ++c) angle[c] = dropout[c] && std::isnan(angle[c]) ? 90.0f : angle[c];
        }
    }
    field.intensity_bin = detail::intensity_bins(in, opt.intensity_resolution, field.bins);

    // The label raster doubles as the flood's scratch: bodies are > 0, a flood marks the cells it visits
    // with its own negative stamp, and the marks are cleared once every seed has grown.
    raster<std::int32_t>& visited = res.labels;
    std::int32_t stamp = 0;
    struct grown { std::vector<std::ptrdiff_t> cells; std::int32_t seed; double theta; bool ks; };
    std::vector<grown> bodies;
    for (std::size_t s = 1; s <= res.seeds_found; ++s) {
        detail::report(opt.progress, 0.9 * static_cast<double>(s - 1) / static_cast<double>(res.seeds_found), fn);
        const auto& cells = seed_cells[s];
        const bool taken = std::any_of(cells.begin(), cells.end(), [&](std::ptrdiff_t i) { return res.labels.data()[i] > 0; });
        if (taken) continue;
        auto region = grow_waterbody(field, cells, opt.grow, visited, --stamp);
        if (region.cells.empty()) continue;
        detail::join_level_cells(region.cells, in, field.eligible, visited, --stamp, opt.level_tolerance_m,
                                 opt.level_max_rise_m, opt.level_join_depth_cells);
        const auto label = static_cast<std::int32_t>(bodies.size() + 1);
        for (const auto i : region.cells) {
            res.labels.data()[i] = label;
            field.eligible.data()[i] = 0;
        }
        bodies.push_back({std::move(region.cells), static_cast<std::int32_t>(s), region.theta_deg, region.stopped_by_ks});
        ++res.seeds_grown;
    }
    for (auto& l : res.labels) l = std::max(l, 0);

    // 5. Bridges between bodies at one water level, then small islands.
    if (opt.bridge_max_span_m > 0 && bodies.size() > 1) {
        std::vector<double> level(bodies.size() + 1, NAN);
        for (std::size_t b = 0; b < bodies.size(); ++b) level[b + 1] = detail::median_level(bodies[b].cells, in);
        detail::join_across_bridges(res.labels, in.min_z, level,
                                    static_cast<int>(std::floor(opt.bridge_max_span_m / cell_m)),
                                    opt.bridge_level_tolerance_m, opt.bridge_min_clearance_m, opt.level_tolerance_m);
    }
    detail::fill_small_islands(res.labels,
                               static_cast<std::size_t>(std::ceil(opt.island_min_area_m2 / (cell_m * cell_m))));

    // 6. Number bodies by decreasing area and describe them.
    std::vector<std::size_t> size(bodies.size() + 1, 0);
    for (const auto l : res.labels) ++size[static_cast<std::size_t>(l)];
    std::vector<std::int32_t> order;
    for (std::size_t b = 1; b < size.size(); ++b)
        if (size[b] > 0) order.push_back(static_cast<std::int32_t>(b));
    std::stable_sort(order.begin(), order.end(), [&](auto a, auto b) { return size[static_cast<std::size_t>(a)] > size[static_cast<std::size_t>(b)]; });
    std::vector<std::int32_t> relabel(size.size(), 0);
    for (std::size_t k = 0; k < order.size(); ++k) relabel[static_cast<std::size_t>(order[k])] = static_cast<std::int32_t>(k + 1);

    // One row-major pass gathers every body's extent, intensity and the heights for its water level.
    res.bodies.resize(order.size());
    std::vector<double> intensity(order.size(), 0.0);
    std::vector<std::size_t> with_returns(order.size(), 0);
    std::vector<std::vector<float>> heights(order.size());
    for (std::size_t k = 0; k < order.size(); ++k) {
        auto& b = res.bodies[k];
        b.label = static_cast<std::int32_t>(k + 1);
        b.box.row_min = rows;
        b.box.col_min = cols;
    }
    for (std::ptrdiff_t r = 0; r < rows; ++r) {
        std::int32_t* label = res.labels.row(r);
        std::uint8_t* water = res.water.row(r);
        for (std::ptrdiff_t c = 0; c < cols; ++c) {
            const auto l = label[c] = relabel[static_cast<std::size_t>(label[c])];
            water[c] = l > 0;
            if (l <= 0) continue;
            const auto k = static_cast<std::size_t>(l - 1);
            auto& b = res.bodies[k];
            ++b.cells;
            b.box.row_min = std::min(b.box.row_min, r);
            b.box.row_max = r;
            b.box.col_min = std::min(b.box.col_min, c);
            b.box.col_max = std::max(b.box.col_max, c);
            if (in.dropout(r, c)) continue;
            intensity[k] += in.mean_intensity(r, c);
            ++with_returns[k];
            if (const float z = in.min_z(r, c); std::isfinite(z)) heights[k].push_back(z);
        }
    }
    for (std::size_t k = 0; k < order.size(); ++k) {
        const auto& src = bodies[static_cast<std::size_t>(order[k] - 1)];
        auto& b = res.bodies[k];
        b.area_m2 = static_cast<double>(b.cells) * cell_m * cell_m;
        b.seed = src.seed;
        b.theta_deg = src.theta;
        b.stopped_by_ks = src.ks;
        b.mean_intensity = with_returns[k] ? intensity[k] / static_cast<double>(with_returns[k]) : NAN;
        b.dropout_fraction = b.cells ? 1.0 - static_cast<double>(with_returns[k]) / static_cast<double>(b.cells) : 0.0;
        b.water_level_m = detail::median(heights[k]);
    }
    res.angle_deg = std::move(field.angle_deg);
    detail::report(opt.progress, 1.0, fn);
    return res;
}

/// Convenience overload on the output of rasterize().
inline waterbody_result extract_waterbodies(const rasterize_result& pr, const waterbody_options& opt = {})
{
    return extract_waterbodies(water_rasters{pr.min_z, pr.max_z, pr.mean_intensity, pr.dropout,
                                             pr.multiple_returns, pr.count},
                               pr.g.cell, opt);
}

}  // namespace lidarfx
