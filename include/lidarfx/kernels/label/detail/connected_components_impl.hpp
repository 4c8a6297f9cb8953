// SPDX-License-Identifier: Apache-2.0
// Implementation of kernels/label/connected_components.hpp (included at its end; not meant to be included alone).
#pragma once

#include <algorithm>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <numeric>
#include <type_traits>
#include <utility>
#include <vector>

#include "lidarfx/core/bit_mask.hpp"
#include "lidarfx/core/error.hpp"
#include "lidarfx/core/fast_math.hpp"
#include "lidarfx/core/grid.hpp"
#include "lidarfx/core/parallel.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/core/raster_view.hpp"

namespace lidarfx {

namespace detail {

/// A horizontal run of foreground cells [begin, end) of one row, and its union-find node.
struct label_run {
    std::int32_t begin, end, node;
};

/// Union-find forest: parent < node for non-roots, so the root of a set is its first node.
struct label_forest {
    std::vector<std::int32_t> parent;
    std::vector<std::size_t> cells;  // cells of the runs that the first pass gave each node
};

/// A band of rows labelled on its own: the rows packed to bits, and the band's forest.
struct label_band_state {
    std::vector<mask_word> bits;
    label_forest forest;
};

/// Root of `node`. Sets stay shallow (roots are only ever linked to roots), so two unconditional hops
/// (a root is its own parent) nearly always arrive, without a data-dependent branch; deeper paths are
/// walked on, halving them.
inline std::int32_t find_root(std::int32_t* parent, std::int32_t node) noexcept
{
    node = parent[parent[node]];
    while (parent[node] != node) {
        parent[node] = parent[parent[node]];
        node = parent[node];
    }
    return node;
}

/// Reads the runs of packed rows (bits past the last column are 0) into label_run lists, node -1.
class run_reader {
public:
    void read(const mask_word* bits, std::ptrdiff_t words, std::vector<label_run>& runs)
    {
        // A set bit of x ^ (x << 1 | carry) marks a change between a cell and its left neighbour; the
        // changes alternate run begin, run end. Positions are written 4 at a time without testing
        // whether each exists (simdjson's flatten_bits), so sparse words cost no mispredicted exits.
        edges_.resize(static_cast<std::size_t>(words * 64 + 5));
        std::int32_t* out = edges_.data();
        std::ptrdiff_t n = 0;
        mask_word carry = 0;
        for (std::ptrdiff_t w = 0; w < words; ++w) {
            const mask_word x = bits[w];
            mask_word e = x ^ ((x << 1) | carry);
            carry = x >> 63;
            const int count = std::popcount(e);
            const auto base = static_cast<std::int32_t>(w * 64);
            for (int k = 0; k < count; k += 4) {
                for (int j = 0; j < 4; ++j) {
                    out[n + k + j] = base + std::countr_zero(e);  // 64 past the last edge: overwritten later
                    e &= e - 1;
                }
            }
            n += count;
        }
        if (n % 2 != 0) out[n++] = static_cast<std::int32_t>(words * 64);  // a run reaching the last word's end
        runs.resize(static_cast<std::size_t>(n / 2));
        for (std::size_t i = 0; i < runs.size(); ++i) runs[i] = {out[2 * i], out[2 * i + 1], -1};
    }

private:
    std::vector<std::int32_t> edges_;
};

/// Number of runs in a packed row: half its edges, rounded up (a run may end at the last column).
inline std::size_t count_runs(const mask_word* bits, std::ptrdiff_t words) noexcept
{
    std::size_t edges = 0;
    mask_word carry = 0;
    for (std::ptrdiff_t w = 0; w < words; ++w) {
        edges += static_cast<std::size_t>(std::popcount(bits[w] ^ ((bits[w] << 1) | carry)));
        carry = bits[w] >> 63;
    }
    return (edges + 1) / 2;
}

/// Joins the sets of the previous-row runs [q, q_end) (all touching one current run) and returns the
/// root of the result, or -1 for an empty range; the smaller id stays the root.
inline std::int32_t join_touching(const label_run* q, const label_run* q_end, std::int32_t* parent) noexcept
{
    if (q == q_end) return -1;
    std::int32_t root = find_root(parent, q->node);
    for (++q; q != q_end; ++q) {
        const std::int32_t other = find_root(parent, q->node);
        const std::int32_t low = std::min(root, other);
        parent[std::max(root, other)] = low;  // a no-op when they already share the root
        root = low;
    }
    return root;
}

/// Gives a current run its set: the joined set of the previous-row runs it touches, or a new node.
inline void settle_run(label_run& run, std::int32_t root, label_forest& forest)
{
    if (root < 0) {
        root = static_cast<std::int32_t>(forest.parent.size());
        forest.parent.push_back(root);  // capacity reserved: pointers into `parent` stay valid
        forest.cells.push_back(0);
    }
    run.node = root;
    forest.cells[static_cast<std::size_t>(root)] += static_cast<std::size_t>(run.end - run.begin);
}

/// Links runs of two rows that already have nodes (rows on each side of a band edge): runs that touch
/// (overlap, or meet diagonally when reach = 1) share a set. A two-pointer merge.
inline void link_rows(const std::vector<label_run>& prev, const std::vector<label_run>& cur, std::int32_t reach,
                      label_forest& forest)
{
    const label_run* p = prev.data();
    const label_run* const prev_end = p + prev.size();
    for (const label_run& run : cur) {
        while (p != prev_end && p->end + reach <= run.begin) ++p;  // ends left of the run's reach
        const label_run* q = p;
        while (q != prev_end && q->begin < run.end + reach) ++q;
        if (p == q) continue;
        const std::int32_t root = join_touching(p, q, forest.parent.data());
        const std::int32_t own = find_root(forest.parent.data(), run.node);
        forest.parent[static_cast<std::size_t>(std::max(root, own))] = std::min(root, own);
        p = q - 1;  // the last touching run may touch the next run too
    }
}

/// Ranks of the first and last cells of the runs of a packed row: first_before(x) = number of runs
/// starting before column x, last_before(x) = number of runs ending (last cell) before x, in O(1)
/// without branches. With them, the previous-row runs that touch a current run [b, e) are exactly
/// those of index last_before(b - reach) .. first_before(e + reach) - 1.
class run_ranks {
public:
    void build(const mask_word* bits, std::ptrdiff_t words)
    {
        first_.assign(static_cast<std::size_t>(words) + 1, 0);
        last_.assign(static_cast<std::size_t>(words) + 1, 0);
        first_cum_.assign(static_cast<std::size_t>(words) + 1, 0);
        last_cum_.assign(static_cast<std::size_t>(words) + 1, 0);
        for (std::ptrdiff_t w = 0; w < words; ++w) {
            const mask_word x = bits[w];
            const mask_word left = w > 0 ? bits[w - 1] >> 63 : 0, right = w + 1 < words ? bits[w + 1] << 63 : 0;
            const auto i = static_cast<std::size_t>(w);
            first_[i] = x & ~((x << 1) | left);
            last_[i] = x & ~((x >> 1) | right);
            first_cum_[i + 1] = first_cum_[i] + static_cast<std::int32_t>(std::popcount(first_[i]));
            last_cum_[i + 1] = last_cum_[i] + static_cast<std::int32_t>(std::popcount(last_[i]));
        }
    }
    std::int32_t first_before(std::int32_t x) const noexcept { return rank(first_, first_cum_, x); }
    std::int32_t last_before(std::int32_t x) const noexcept { return rank(last_, last_cum_, std::max(x, 0)); }

private:
    // x in [0, 64 * words + 1]: reads at most word `words`, which holds no bits.
    static std::int32_t rank(const std::vector<mask_word>& bits, const std::vector<std::int32_t>& cum,
                             std::int32_t x) noexcept
    {
        const auto w = static_cast<std::size_t>(x >> 6);
        const mask_word below = (mask_word{1} << (x & 63)) - 1;
        return cum[w] + static_cast<std::int32_t>(std::popcount(bits[w] & below));
    }
    std::vector<mask_word> first_, last_;
    std::vector<std::int32_t> first_cum_, last_cum_;
};

/// Links the runs of the current row (new, without nodes) to those of the previous row, whose ranks
/// are `prev_ranks`: each current run joins the sets of the runs it touches, or gets a new node; its
/// cells count towards its node.
inline void link_new_row(const std::vector<label_run>& prev, const run_ranks& prev_ranks, std::vector<label_run>& cur,
                         std::int32_t reach, label_forest& forest)
{
    const label_run* p = prev.data();
    for (label_run& run : cur) {
        const std::int32_t lo = prev_ranks.last_before(run.begin - reach);
        const std::int32_t hi = prev_ranks.first_before(run.end + reach);
        settle_run(run, join_touching(p + lo, p + std::max(lo, hi), forest.parent.data()), forest);
    }
}

/// Writes a row of labels: value(run) on each run, 0 elsewhere. Blocks of 8 equal values are stored
/// unconditionally (each block's overshoot is rewritten by the next), avoiding a data-dependent branch
/// per cell on fragmented masks; the last 8 cells of the row are written one by one.
template <class Value>
void write_label_row(const std::vector<label_run>& runs, Value value, std::int32_t cols, std::int32_t* out) noexcept
{
    const auto fill = [out, safe = cols - 8](std::int32_t from, std::int32_t to, std::int32_t v) {
        for (; from < to && from <= safe; from += 8) {
            for (int j = 0; j < 8; ++j) out[from + j] = v;
        }
        for (; from < to; ++from) out[from] = v;
    };
    std::int32_t c = 0;
    for (const label_run& run : runs) {
        fill(c, run.begin, 0);
        fill(run.begin, run.end, value(run));
        c = run.end;
    }
    fill(c, cols, 0);
}

/// The runs of row r of a band, with their band-local nodes. Between the two passes, the nodes of a
/// row's runs are stored in order at the start of its own row of labels (a row of n cells has at most
/// (n + 1) / 2 runs): memory the output needs anyway, written and read sequentially.
inline void band_row_runs(const label_band_state& band, std::ptrdiff_t r0, std::ptrdiff_t r, std::ptrdiff_t words,
                          raster_view<std::int32_t> labels, run_reader& reader, std::vector<label_run>& runs)
{
    reader.read(band.bits.data() + (r - r0) * words, words, runs);
    const std::int32_t* node = labels.row(r);
    for (std::size_t i = 0; i < runs.size(); ++i) runs[i].node = node[i];
}

/// First pass over the band of rows [r0, r1): packs the rows, builds the band's forest and stores the
/// band-local node of each run (see band_row_runs).
template <class T>
void label_band(raster_view<const T> m, std::ptrdiff_t r0, std::ptrdiff_t r1, std::int32_t reach,
                label_band_state& band, raster_view<std::int32_t> labels)
{
    const std::ptrdiff_t cols = m.cols(), words = mask_words(cols);
    band.bits.resize(static_cast<std::size_t>((r1 - r0) * words));
    std::size_t runs = 0;
    for (std::ptrdiff_t r = r0; r < r1; ++r) {
        mask_word* row = band.bits.data() + (r - r0) * words;
        pack_mask_row(m.row(r), cols, row);
        runs += count_runs(row, words);
    }
    band.forest.parent.reserve(runs);  // nodes <= runs: no reallocation
    band.forest.cells.reserve(runs);
    std::vector<label_run> prev, cur;
    prev.reserve(static_cast<std::size_t>(cols / 2 + 1));
    cur.reserve(static_cast<std::size_t>(cols / 2 + 1));
    run_ranks prev_ranks, cur_ranks;
    run_reader reader;
    prev_ranks.build(std::vector<mask_word>(static_cast<std::size_t>(words), 0).data(), words);  // no row above
    for (std::ptrdiff_t r = r0; r < r1; ++r) {
        const mask_word* bits = band.bits.data() + (r - r0) * words;
        reader.read(bits, words, cur);
        link_new_row(prev, prev_ranks, cur, reach, band.forest);
        std::int32_t* node = labels.row(r);
        for (std::size_t i = 0; i < cur.size(); ++i) node[i] = cur[i].node;
        if (r + 1 < r1) cur_ranks.build(bits, words);
        std::swap(prev, cur);
        std::swap(prev_ranks, cur_ranks);
    }
}

/// Labels `m` into `labels` (same shape) and returns sizes (see components).
template <class T>
std::vector<std::size_t> label_components(raster_view<const T> m, raster_view<std::int32_t> labels,
                                          const connected_components_options& opt, const char* function)
{
    const std::ptrdiff_t rows = m.rows(), cols = m.cols(), words = mask_words(cols);
    std::vector<std::size_t> sizes(1, static_cast<std::size_t>(rows * cols));
    if (rows == 0 || cols == 0) {
        report(opt.run.progress, 1.0, function);
        return sizes;
    }
    const std::int32_t reach = opt.conn == connectivity::eight ? 1 : 0;

    // Bands of rows are labelled independently (in parallel), then joined along their shared edges.
    // Bands are fixed by the raster alone, so node ids, and thus labels, never depend on the threads.
    constexpr std::ptrdiff_t band_rows = 256;
    const std::ptrdiff_t band_count = (rows + band_rows - 1) / band_rows;
    std::vector<label_band_state> bands(static_cast<std::size_t>(band_count));
    // Progress: the first pass (packing and linking) costs about as much as the second (writing labels).
    parallel_for_rows(
        rows, band_rows, opt.run.threads,
        [&](std::ptrdiff_t r0, std::ptrdiff_t r1) {
            label_band(m, r0, r1, reach, bands[static_cast<std::size_t>(r0 / band_rows)], labels);
        },
        progress_phase(opt.run.progress, 0.0, 0.5), function);

    // One global forest: band b's node ids are offset by the nodes of the bands above it.
    std::vector<std::size_t> offset(bands.size() + 1, 0);
    for (std::size_t b = 0; b < bands.size(); ++b) offset[b + 1] = offset[b] + bands[b].forest.parent.size();
    require(offset.back() < static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max()), function,
            "m has more runs than int32 labels can number");
    label_forest all;
    all.parent.resize(offset.back());
    all.cells.resize(offset.back());
    for (std::size_t b = 0; b < bands.size(); ++b) {
        auto& forest = bands[b].forest;
        const auto shift = static_cast<std::int32_t>(offset[b]);
        std::transform(forest.parent.begin(), forest.parent.end(),
                       all.parent.begin() + static_cast<std::ptrdiff_t>(offset[b]),
                       [shift](std::int32_t p) { return p + shift; });
        std::copy(forest.cells.begin(), forest.cells.end(), all.cells.begin() + static_cast<std::ptrdiff_t>(offset[b]));
        forest = {};
    }
    std::vector<label_run> above, below;
    run_reader edge_reader;
    for (std::size_t b = 1; b < bands.size(); ++b) {
        const std::ptrdiff_t r = static_cast<std::ptrdiff_t>(b) * band_rows;
        band_row_runs(bands[b - 1], r - band_rows, r - 1, words, labels, edge_reader, above);
        band_row_runs(bands[b], r, r, words, labels, edge_reader, below);
        for (auto& run : above) run.node += static_cast<std::int32_t>(offset[b - 1]);
        for (auto& run : below) run.node += static_cast<std::int32_t>(offset[b]);
        link_rows(above, below, reach, all);
    }

    // Roots precede their members, so one increasing sweep numbers the sets in raster-scan order of
    // their first run (= of the component's first cell). final_label[1 + node] = label of node.
    std::vector<std::int32_t> final_label(all.parent.size() + 1, 0);
    std::int32_t count = 0;
    for (std::size_t i = 0; i < all.parent.size(); ++i) {
        const auto p = static_cast<std::size_t>(all.parent[i]);
        final_label[i + 1] = p == i ? ++count : final_label[p + 1];
    }
    sizes.resize(static_cast<std::size_t>(count) + 1, 0);
    for (std::size_t i = 0; i < all.parent.size(); ++i) {
        sizes[static_cast<std::size_t>(final_label[i + 1])] += all.cells[i];
        sizes[0] -= all.cells[i];
    }
    all = {};

    // Second pass: each run's band-local node becomes the final label final_label[offset[b] + node + 1].
    parallel_for_rows(
        rows, band_rows, opt.run.threads,
        [&](std::ptrdiff_t r0, std::ptrdiff_t r1) {
            const std::size_t b = static_cast<std::size_t>(r0 / band_rows);
            const std::int32_t* table = final_label.data() + offset[b] + 1;
            std::vector<label_run> runs;
            runs.reserve(static_cast<std::size_t>(cols / 2 + 1));
            run_reader reader;
            for (std::ptrdiff_t r = r0; r < r1; ++r) {
                band_row_runs(bands[b], r0, r, words, labels, reader, runs);
                write_label_row(
                    runs, [table](const label_run& run) { return table[run.node]; }, static_cast<std::int32_t>(cols),
                    labels.row(r));
            }
        },
        progress_phase(opt.run.progress, 0.5, 1.0), function);
    return sizes;
}

}  // namespace detail

template <raster_input In, class Out>
requires raster_output_of<Out, std::int32_t> std::vector<std::size_t> connected_components(
    const In& m, Out&& labels, const connected_components_options& opt)
{
    static_assert(std::is_arithmetic_v<typename In::value_type>, "a mask holds numbers (nonzero = foreground)");
    constexpr const char* function = "connected_components";
    detail::check_execution(opt.run, function);
    detail::require_same_shape(m, labels, function, "m", "labels");
    // Run nodes of a band of 256 rows are numbered in int32.
    detail::require(m.cols() <= (std::ptrdiff_t{1} << 24), function, "m", "at most 2^24 columns wide", m.cols());
    const detail::readable<In> in(m);
    std::vector<std::size_t> sizes;
    detail::write_through<std::int32_t>(std::forward<Out>(labels), [&](raster_view<std::int32_t> out) {
        sizes = detail::label_components(in.view(), out, opt, function);
    });
    return sizes;
}

template <raster_input In>
components connected_components(const In& m, const connected_components_options& opt)
{
    components result{raster<std::int32_t>(m.rows(), m.cols(), uninitialized), {}};  // every cell is written
    result.sizes = connected_components(m, result.labels, opt);
    return result;
}

template <raster_input In>
components connected_components(const In& m, connectivity c)
{
    return connected_components(m, connected_components_options{.conn = c});
}

inline std::vector<std::int32_t> rank_components_by_size(const std::vector<std::size_t>& sizes)
{
    const std::size_t n = sizes.empty() ? 0 : sizes.size() - 1;
    std::vector<std::int32_t> order(n);
    std::iota(order.begin(), order.end(), 1);
    std::stable_sort(order.begin(), order.end(), [&](std::int32_t a, std::int32_t b) {
        return sizes[static_cast<std::size_t>(a)] > sizes[static_cast<std::size_t>(b)];
    });
    std::vector<std::int32_t> rank(n + 1, 0);
    for (std::size_t k = 0; k < n; ++k) rank[static_cast<std::size_t>(order[k])] = static_cast<std::int32_t>(k + 1);
    return rank;
}

inline void relabel_components(raster_view<std::int32_t> labels, const std::vector<std::int32_t>& to)
{
    const std::ptrdiff_t cols = labels.cols();
    for (std::ptrdiff_t r = 0; r < labels.rows(); ++r) {
        std::int32_t* row = labels.row(r);
        detail::for_each_run(row, cols, [&](std::int32_t l, std::ptrdiff_t from, std::ptrdiff_t end) {
            std::fill(row + from, row + end, to[static_cast<std::size_t>(l)]);
        });
    }
}

inline void rank_by_size(components& comps)
{
    const std::size_t n = comps.count();
    const auto rank = rank_components_by_size(comps.sizes);
    std::vector<std::size_t> new_sizes(n + 1, comps.sizes.empty() ? 0 : comps.sizes[0]);
    for (std::size_t l = 1; l <= n; ++l) new_sizes[static_cast<std::size_t>(rank[l])] = comps.sizes[l];
    relabel_components(comps.labels, rank);
    comps.sizes = std::move(new_sizes);
}

inline std::vector<cell_box> component_bounds(const components& comps)
{
    std::vector<cell_box> boxes(comps.sizes.size());
    std::vector<bool> seen(comps.sizes.size(), false);
    const auto& labels = comps.labels;
    for (std::ptrdiff_t r = 0; r < labels.rows(); ++r) {
        const std::int32_t* row = labels.row(r);
        for (std::ptrdiff_t c = 0; c < labels.cols(); ++c) {
            const auto l = static_cast<std::size_t>(row[c]);
            cell_box& b = boxes[l];
            if (!seen[l]) {
                seen[l] = true;
                b = {r, c, r, c};
                continue;
            }
            b.row_max = r;  // rows are visited in increasing order
            b.col_min = std::min(b.col_min, c);
            b.col_max = std::max(b.col_max, c);
        }
    }
    return boxes;
}

template <raster_input In>
raster<std::uint8_t> remove_small_components(const In& m, std::size_t min_cells, connectivity c)
{
    const components comps = connected_components(m, c);
    raster<std::uint8_t> out(m.rows(), m.cols(), uninitialized);  // every cell is written below
    std::vector<std::uint8_t> keep(comps.sizes.size(), 0);
    for (std::size_t l = 1; l < keep.size(); ++l) keep[l] = comps.sizes[l] >= min_cells ? 1 : 0;
    std::uint8_t* cells = out.data();  // in locals: the byte stores would reload them
    const std::int32_t* labels = comps.labels.data();
    const std::uint8_t* kept = keep.data();
    for (std::ptrdiff_t i = 0, n = out.size(); i < n; ++i) cells[i] = kept[static_cast<std::size_t>(labels[i])];
    return out;
}

template <raster_input In>
raster<std::uint8_t> fill_holes(const In& m, std::size_t max_hole_cells, connectivity c)
{
    const detail::readable<In> in(m);
    const auto v = in.view();
    raster<std::uint8_t> out(m.rows(), m.cols(), uninitialized);  // both written in full by the first loop
    if (out.empty()) return out;
    raster<std::uint8_t> background(m.rows(), m.cols(), uninitialized);
    for (std::ptrdiff_t r = 0; r < v.rows(); ++r) {
        for (std::ptrdiff_t col = 0; col < v.cols(); ++col) {
            const bool fg = v(r, col) != typename In::value_type{};
            out(r, col) = fg ? 1 : 0;
            background(r, col) = fg ? 0 : 1;
        }
    }
    const components holes =
        connected_components(background, c == connectivity::eight ? connectivity::four : connectivity::eight);
    std::vector<std::uint8_t> fill(holes.sizes.size(), 0);
    for (std::size_t l = 1; l < fill.size(); ++l) fill[l] = holes.sizes[l] <= max_hole_cells ? 1 : 0;
    const auto unfill_edge = [&](std::ptrdiff_t r, std::ptrdiff_t col) {
        fill[static_cast<std::size_t>(holes.labels(r, col))] = 0;
    };
    for (std::ptrdiff_t col = 0; col < v.cols(); ++col) {
        unfill_edge(0, col);
        unfill_edge(v.rows() - 1, col);
    }
    for (std::ptrdiff_t r = 0; r < v.rows(); ++r) {
        unfill_edge(r, 0);
        unfill_edge(r, v.cols() - 1);
    }
    fill[0] = 0;
    for (std::ptrdiff_t i = 0; i < out.size(); ++i) {
        out.data()[i] =
            static_cast<std::uint8_t>(out.data()[i] | fill[static_cast<std::size_t>(holes.labels.data()[i])]);
    }
    return out;
}

}  // namespace lidarfx
