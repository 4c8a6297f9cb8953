// SPDX-License-Identifier: Apache-2.0
// grow_waterbodies on several threads: floods grown ahead of their seed's turn on the cells as they were before the
// first turn, taken at their turn when no body accepted since touched a cell they read, grown again otherwise. The
// bodies, labels and records are those of the turns one after another, bit for bit.
#pragma once
// Included by detail/grow_waterbodies_impl.hpp, which defines the turn's steps used here.

#include <algorithm>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <mutex>
#include <span>
#include <thread>
#include <utility>
#include <vector>

#include "lidarfx/core/parallel.hpp"
#include "lidarfx/core/raster.hpp"

namespace lidarfx::detail {

/// Thrown inside a flood grown ahead that reached an earlier seed's cell.
struct flood_overtaken {};

/// A seed's flood grown before its turn, on the eligible cells and labels as they were before the first turn.
struct flood_ahead {
    bool grows = false;                   ///< the seed was not skipped (by the labels before the first turn)
    bool overtaken = false;               ///< the flood stopped at a cell of an earlier seed
    grow_waterbody_result region;         ///< its flood
    std::vector<std::ptrdiff_t> visited;  ///< the cells the flood queued (with the seed's, all it read)
    std::exception_ptr error;             ///< what the flood threw (then it is grown again at its turn)
    /// Whether it holds a flood for its turn (not skipped, not stopped, not failed): it counts against the floods
    /// the threads may hold.
    bool holds_flood() const noexcept { return grows && !overtaken && !error; }
};

/// Which seeds grow, and from which cells, given the labels before the first turn (seed_cells_to_grow).
struct seed_starts {
    std::vector<std::uint8_t> starts;                      ///< per seed: 1 = it grows
    std::vector<std::vector<std::ptrdiff_t>> start_cells;  ///< per seed: its free cells; empty: all of them
    seed_starts(const seed_cell_runs& seed_lists, std::size_t n, const std::int32_t* labels, double min_free_share)
        : starts(n + 1, 0), start_cells(n + 1)
    {
        for (std::size_t s = 1; s <= n; ++s) {
            std::span<const std::ptrdiff_t> cells;
            std::vector<std::ptrdiff_t> free_cells;
            starts[s] = seed_cells_to_grow(seed_lists.of(s), labels, min_free_share, free_cells, cells);
            if (starts[s] && cells.data() == free_cells.data()) start_cells[s] = std::move(free_cells);
        }
    }
};

/// Seed s's flood grown ahead into `a`, on the eligible cells before the first turn (`eligible`). It marks the
/// cells it queues with 1 in `marks` (its thread's; allocated at first use) and clears them after: they are the
/// cells it visited. A flood that reaches a cell of an earlier seed is most likely overtaken by that seed's body (a
/// seed inside a lake whose first seed floods it): it stops there and is grown again at its turn, if at all. What
/// the flood throws is kept in `a` (then it is grown again at its turn).
inline void grow_flood_ahead(const water_field& field, const std::uint8_t* eligible, const std::int32_t* seed_labels,
                             const seed_cell_runs& seed_lists, const seed_starts& before,
                             const grow_waterbody_options& grow, std::size_t s, raster<std::uint8_t>& marks,
                             flood_ahead& a)
{
    try {
        a.grows = before.starts[s] != 0;
        if (!a.grows) return;
        if (marks.empty()) marks = raster<std::uint8_t>(field.eligible.rows(), field.eligible.cols(), 0);
        const std::span<const std::ptrdiff_t> cells =
            before.start_cells[s].empty() ? seed_lists.of(s) : std::span<const std::ptrdiff_t>(before.start_cells[s]);
        std::uint8_t* seen = marks.data();
        const auto on_queued = [&](std::ptrdiff_t i) {
            try {
                a.visited.push_back(i);
            } catch (...) {
                seen[i] = 0;  // the one marked cell the list does not hold
                throw;
            }
            if (const std::int32_t l = seed_labels[i]; l > 0 && static_cast<std::size_t>(l) < s && before.starts[l])
                throw flood_overtaken{};
        };
        const auto clear_marks = [&] {
            for (const auto i : a.visited) seen[i] = 0;
        };
        try {
            a.region = grow_waterbody_flood(field, eligible, cells, grow, seen, std::uint8_t{1}, on_queued);
        } catch (const flood_overtaken&) {
            a.overtaken = true;
        } catch (...) {
            clear_marks();
            throw;
        }
        clear_marks();
        if (a.overtaken) a.visited = {};  // its turn grows it again, if at all: nothing of it is read
    } catch (...) {
        a.error = std::current_exception();
        a.visited = {};  // grown again at its turn: nothing of it is read
    }
}

/// grow_waterbodies with run.threads > 1 (its checks done). A flood reads only the eligibility of the cells it
/// queues (a cell never queued has no effect on it) and the labels of its seed's cells; turns change both only in
/// the cells of the bodies they accept (labels the run gives). So a flood grown ahead is the flood of its turn when
/// no body accepted before its turn holds one of those cells; else it is grown again at its turn, as the sequential
/// run grows it. Floods are not grown ahead, or stop, where they would most likely be overtaken: a seed with a cell
/// in a body accepted so far, and a flood reaching a cell of an earlier seed. Turns are taken in seed order by the
/// calling thread, which grows floods ahead while it waits; the other threads grow floods ahead. At most 2 floods
/// per thread are held (growing, or grown and waiting for their turn); floods that stopped or did not grow hold
/// nothing, so the threads run past the seeds a lake still being flooded holds. Memory beyond the sequential run: a
/// copy of the eligible cells and a mark raster per thread (1 byte a cell each), and each held flood's region and
/// the cells it queued (16 bytes a cell reached).
inline void grow_waterbodies_ahead(water_field& field, const std::int32_t* seed_labels,
                                   const seed_cell_runs& seed_lists, std::size_t n, raster_view<const float> min_z,
                                   raster_view<const float> max_z, grow_waterbodies_result& out,
                                   const grow_waterbody_options& grow, const join_level_cells_options& level,
                                   const grow_waterbodies_options& opt, std::int32_t seed_offset, const execution& run)
{
    constexpr const char* fn = "grow_waterbodies";
    const auto threads = static_cast<std::size_t>(resolve_threads(run.threads, fn));
    const std::ptrdiff_t rows = field.eligible.rows(), cols = field.eligible.cols();
    // What floods ahead read: the eligible cells before the first turn, and where each seed starts from then.
    const raster<std::uint8_t> eligible_before = field.eligible;
    const seed_starts before(seed_lists, n, out.labels.data(), opt.min_free_seed_share);
    std::vector<flood_ahead> ahead(n + 1);
    const auto grow_ahead = [&](std::size_t s, raster<std::uint8_t>& marks) {
        grow_flood_ahead(field, eligible_before.data(), seed_labels, seed_lists, before, grow, s, marks, ahead[s]);
    };

    std::mutex mutex;
    std::condition_variable changed_state;
    std::size_t next = 1;  // the next seed to grow ahead
    std::vector<std::uint8_t> ready(n + 1, 0);
    bool stop = false;
    const std::size_t max_held = 2 * threads;
    std::size_t floods_held = 0;
    const auto can_claim = [&] { return next <= n && floods_held < max_held; };
    // Claims the next seed, grows its flood with the lock released, and marks it ready.
    std::vector<std::uint8_t> overtaken(n + 1, 0);  // a body accepted so far holds a cell of the seed
    const auto grow_next = [&](std::unique_lock<std::mutex>& lock, raster<std::uint8_t>& marks) {
        const std::size_t s = next++;
        const bool known_overtaken = overtaken[s] != 0;
        ++floods_held;
        lock.unlock();
        if (known_overtaken) {
            ahead[s].overtaken = true;  // its turn decides (most often: skipped)
        } else {
            grow_ahead(s, marks);
        }
        lock.lock();
        if (!ahead[s].holds_flood()) --floods_held;
        ready[s] = 1;
        changed_state.notify_all();
    };
    std::vector<std::thread> helpers;
    const auto stop_helpers = [&] {
        {
            const std::lock_guard lock(mutex);
            stop = true;
        }
        changed_state.notify_all();
        for (auto& h : helpers) h.join();
    };
    struct joiner {
        const decltype(stop_helpers)& stop;
        ~joiner() { stop(); }
    } join_at_exit{stop_helpers};
    for (std::size_t t = 1; t < threads; ++t) {
        helpers.emplace_back([&] {
            raster<std::uint8_t> marks;
            std::unique_lock lock(mutex);
            for (;;) {
                changed_state.wait(lock, [&] { return stop || can_claim(); });
                if (stop) return;
                grow_next(lock, marks);
            }
        });
    }

    raster<std::uint8_t> ahead_marks;                        // the calling thread's floods ahead
    grow_waterbody_workspace turn_marks(out.labels.view());  // floods grown again at their turn
    bool grown_again = false;

    // The cells of the bodies accepted by this run's turns: labels above those it started with.
    const auto first_label = static_cast<std::int32_t>(out.bodies.size() + 1);
    std::vector<std::ptrdiff_t> free_cells;
    std::vector<std::int32_t> later_seeds;  // seeds after the turn's with a cell in its body
    for (std::size_t s = 1; s <= n; ++s) {
        report(run.progress, static_cast<double>(s - 1) / static_cast<double>(n), fn);
        {
            std::unique_lock lock(mutex);
            while (!ready[s]) {
                if (can_claim()) {
                    grow_next(lock, ahead_marks);
                } else {
                    changed_state.wait(lock);
                }
            }
            if (ahead[s].holds_flood()) {
                --floods_held;  // its turn takes it: another flood may be grown ahead
                changed_state.notify_all();
            }
        }
        flood_ahead a = std::move(ahead[s]);  // no other thread touches ahead[s] once it is ready
        const std::int32_t* labels = out.labels.data();
        const auto touched = [&](std::ptrdiff_t i) { return labels[i] >= first_label; };
        const auto seed = seed_lists.of(s);
        // A flood ahead that threw is grown again: a cell that throws is read before it is queued, and a body
        // accepted since may have taken it.
        const bool stands = !a.overtaken && !a.error && std::none_of(seed.begin(), seed.end(), touched) &&
                            std::none_of(a.visited.begin(), a.visited.end(), touched);
        grow_waterbody_result region;
        if (stands) {
            if (!a.grows) continue;
            region = std::move(a.region);
        } else {
            std::span<const std::ptrdiff_t> cells;
            if (!seed_cells_to_grow(seed, out.labels.data(), opt.min_free_seed_share, free_cells, cells)) continue;
            const auto [marks, stamp] = turn_marks.next_flood(rows, cols);
            region = grow_waterbody_flood(field, field.eligible.data(), cells, grow, marks.data(), stamp,
                                          [](std::ptrdiff_t) {});
            grown_again = true;
        }
        accept_body(region, s, seed_offset, min_z, max_z, field.eligible.data(), out, level);
        later_seeds.clear();
        for (const auto i : region.cells) {
            if (const std::int32_t l = seed_labels[i]; static_cast<std::size_t>(l) > s) later_seeds.push_back(l);
        }
        if (!later_seeds.empty()) {
            const std::lock_guard lock(mutex);
            for (const auto l : later_seeds) overtaken[static_cast<std::size_t>(l)] = 1;
        }
    }
    if (grown_again) turn_marks.clear_marks();
    report(run.progress, 1.0, fn);
}

}  // namespace lidarfx::detail
