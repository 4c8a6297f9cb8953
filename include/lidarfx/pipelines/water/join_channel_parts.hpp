// SPDX-License-Identifier: Apache-2.0
// join_channel_parts: the pieces of one river that waterbody extraction cut apart at a weir or a bridge deck
// become one body again, with the cells under the deck.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "lidarfx/core/grid.hpp"
#include "lidarfx/core/raster_view.hpp"

namespace lidarfx {

/// Options of join_channel_parts.
struct channel_join_options {
    double max_gap_m = 30.0;         ///< widest land between two parts that is bridged (a deck, a culvert's road),
                                     ///< metres, >= 0. Default 30 m
    double min_part_width_m = 15.0;  ///< parts of a smaller nominal width (area / length) are never joined
                                     ///< (ditches, ponds), metres, >= 0. Default 15 m, half the
                                     ///< specification's narrowest river
    double min_contact_share = 0.5;  ///< the parts face each other along at least this share of the narrower
                                     ///< one's width, in (0, 1]. Default 0.5
    double max_width_ratio = 2.5;    ///< the wider part is at most this many times as wide as the narrower
                                     ///< (a river's pool, not a lake it flows into), >= 1. Default 2.5
    double max_level_step_m = 2.0;   ///< the water either side of where they meet (the median lowest return of
                                     ///< the facing cells) differs by at most this: a weir, not a dam between a
                                     ///< reservoir and the river below it, nor a pond beside a stream, metres,
                                     ///< >= 0 (+inf: any). Default 2 m
    double min_elongation = 6.0;     ///< the two parts as one body are at least this many widths long (a river,
                                     ///< not two ponds beside a dam), >= 1. Default 6, hydro_flatten's
                                     ///< min_river_elongation
};

/// One pair of parts found to be one channel; both now carry the label `kept`.
struct channel_join {
    std::int32_t kept = 0;      ///< the smallest label of the channel the pair belongs to
    std::int32_t part_a = 0;    ///< the pair's smaller label, as given
    std::int32_t part_b = 0;    ///< the pair's larger label, as given
    double gap_m = 0;           ///< land crossed between the parts at their closest, metres (0: they touch); up to
                                ///< max_gap_m plus a diagonal step's 0.41 cell
    double contact_m = 0;       ///< how far the parts face each other across the gap, metres
    std::size_t gap_cells = 0;  ///< land cells between them (under the deck) that took the label `kept`
};

/// Joins the parts of one channel in `labels` (0 land, 1..n bodies; `box[l]` the bounding box of label l,
/// `box[0]` unused; both updated in place). Two parts are one channel when, measured on the labels as given:
///  - each is at least min_part_width_m wide (hydro_body_shape: area / longest path) and the wider is at most
///    max_width_ratio times the narrower;
///  - they touch (8-adjacent cells), or the shortest path between them over land (chamfer steps of one cell and
///    √2 cells, through no third body) crosses at most max_gap_m of it;
///  - they face each other along at least min_contact_share of the narrower width: the cells of each part within
///    3 cells of the other's closest approach span that far (their two farthest cell centres, plus a cell);
///    across a gap also at most twice the wider width (parallel channels beside each other are not one; pieces
///    that touch may face each other further: a strip of one pool taken into the other's piece);
///  - the median of `heights` (the water's heights, e.g. the lowest return per cell, metres, NaN where none) over
///    each part's facing cells differ by at most max_level_step_m (not checked when a side has none);
///  - together, with the land between them that a join adds, they are one 8-connected body and a river: its
///    hydro_body_shape's elongation is at least min_elongation.
/// Pairs are decided independently, then joined transitively, every part taking the smallest label of its
/// channel (empty boxes are left for the labels that went). Across a gap, the land cells inside the convex hull
/// of both sides' facing cells (a cell whose centre lies within half a cell outside an edge counts) take the
/// label: the water under the deck, not the banks beside it. Where the hulls of two pairs overlap the first pair
/// (in that order) gets the land.
/// O(cells + sum over parts wider than min_part_width_m of the cells of their box grown by max_gap_m, times the
/// log of the land reached, + the union boxes of the pairs that pass the other tests).
/// Returns one record per pair found, ordered by (kept, part_a, part_b).
/// @throws invalid_input on rasters of different shapes, cell_m not finite and > 0, options out of range, a
/// negative label or a label without its box.
inline std::vector<channel_join> join_channel_parts(raster_view<std::int32_t> labels, std::vector<cell_box>& box,
                                                    raster_view<const float> heights, double cell_m,
                                                    const channel_join_options& opt = {});

}  // namespace lidarfx

#include "lidarfx/pipelines/water/detail/join_channel_parts_impl.hpp"
