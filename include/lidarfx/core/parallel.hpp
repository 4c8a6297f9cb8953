// SPDX-License-Identifier: Apache-2.0
// How algorithms run: the execution settings (threads, progress, cancellation) and a deterministic
// parallel-for over blocks of rows.
//
// Running: threads, progress, cancellation. Every algorithm that may run long takes, in its options
// struct, the member `execution run = {};`, and nothing else about running; a pipeline step whose options
// are nested in a pipeline's options takes it as its last argument instead, `const execution& run = {}`
// (the pipeline passes its own run):
//   - run.threads: worker threads, 1 by default (the caller's thread only), 0 = all cores. Work is cut into
//     blocks fixed by the input alone and every output cell is computed the same way in any block, so
//     results never depend on the thread count, bit for bit.
//   - run.progress: called from the caller's thread with the fraction done, monotone in [0, 1] and ending
//     with exactly 1 on success, reported between blocks of rows or chunks of points. Returning false
//     cancels: the algorithm stops after the block at hand and throws lidarfx::cancelled("<function>:
//     cancelled"); its outputs are then unspecified. The callback need not be thread-safe.
// Example: rasterize(cloud, g, {.run = {.threads = 0, .progress = show}}).
#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

#include "lidarfx/core/error.hpp"

namespace lidarfx {

/// Progress callback for long algorithms: called with the fraction done in [0, 1] (monotone, ends with 1
/// on success). Return false to cancel: the algorithm then throws lidarfx::cancelled. Called only from
/// the caller's thread, so it need not be thread-safe. An empty function means "no progress reports".
using progress_callback = std::function<bool(double fraction_done)>;

/// How an algorithm runs (see the header comment): thread count, and progress with cancellation.
/// Default: the caller's thread only, no reports. Never changes a result.
struct execution {
    int threads = 1;                  ///< worker threads; 0 = std::thread::hardware_concurrency(); >= 0
    progress_callback progress = {};  ///< optional progress / cancellation callback (empty = no reports)
};

namespace detail {

/// Reports `fraction` to the callback, throwing cancelled("<function>: cancelled") when it returns false.
inline void report(const progress_callback& progress, double fraction, const char* function)
{
    if (progress && !progress(std::clamp(fraction, 0.0, 1.0))) throw cancelled(concat(function, ": cancelled"));
}

/// The thread count to use: `threads`, or all cores for 0. @throws invalid_input naming `argument` if < 0.
inline int resolve_threads(int threads, const char* function, const char* argument = "threads")
{
    require(threads >= 0, function, argument, ">= 0", threads);
    if (threads == 0) threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    return threads;
}

/// Validates an algorithm's `run` member: "<function>: run.threads must be >= 0 (got -1)".
inline void check_execution(const execution& run, const char* function)
{
    resolve_threads(run.threads, function, "run.threads");
}

/// One phase of a longer algorithm, spanning [from, to] of its progress: the phase's own fraction f is
/// reported as from + (to - from) * f (exactly `to` when f = 1), so phases run one after the other stay
/// monotone and the last one, ending at to = 1, ends the algorithm's progress at exactly 1. Empty when
/// `progress` is; `progress` must outlive the result.
inline progress_callback progress_phase(const progress_callback& progress, double from, double to)
{
    if (!progress) return {};
    return [&progress, from, to](double f) { return progress(f >= 1.0 ? to : from + (to - from) * f); };
}

}  // namespace detail

/// Runs body(r0, r1) over [0, rows) split into blocks of `block_rows` rows, on `threads` threads
/// (0 = all cores). Blocks are fixed by `rows` and `block_rows` alone, never by the thread count, so a body
/// that writes only its own rows gives identical results for any thread count. Blocks are handed out in
/// order; the first exception thrown by a body is rethrown after all threads have stopped. If `progress`
/// is set it is called from this thread between blocks (fraction of blocks done, ending with 1, also for
/// rows = 0) and may cancel: cancelled("<function>: cancelled") is thrown once running blocks finish.
template <class Body>
void parallel_for_rows(std::ptrdiff_t rows, std::ptrdiff_t block_rows, int threads, Body&& body,
                       const progress_callback& progress = {}, const char* function = "parallel_for_rows")
{
    detail::require(block_rows >= 1, function, "block_rows", ">= 1", block_rows);
    threads = detail::resolve_threads(threads, function);
    if (rows <= 0) {
        detail::report(progress, 1.0, function);  // nothing to do is done
        return;
    }
    const std::ptrdiff_t blocks = (rows + block_rows - 1) / block_rows;
    const auto run_block = [&](std::ptrdiff_t b) { body(b * block_rows, std::min(rows, (b + 1) * block_rows)); };
    if (threads == 1 || blocks == 1) {
        for (std::ptrdiff_t b = 0; b < blocks; ++b) {
            run_block(b);
            detail::report(progress, static_cast<double>(b + 1) / static_cast<double>(blocks), function);
        }
        return;
    }
    std::atomic<std::ptrdiff_t> next{0}, done{0};
    std::atomic<bool> stop{false};
    std::exception_ptr error;
    std::mutex error_mutex;
    const auto fail = [&] {
        std::lock_guard lock(error_mutex);
        if (!error) error = std::current_exception();
        stop = true;
    };
    // Every thread takes the next block in order; the calling thread also reports progress (and so may
    // cancel) after each of its own blocks.
    const auto worker = [&](bool reporter) {
        while (!stop.load(std::memory_order_relaxed)) {
            const std::ptrdiff_t b = next.fetch_add(1);
            if (b >= blocks) return;
            try {
                run_block(b);
                const auto finished = done.fetch_add(1) + 1;
                if (reporter) {
                    detail::report(progress, static_cast<double>(finished) / static_cast<double>(blocks), function);
                }
            } catch (...) {
                fail();
            }
        }
    };
    const int helpers = static_cast<int>(std::min<std::ptrdiff_t>(threads, blocks)) - 1;
    std::vector<std::thread> pool;
    pool.reserve(static_cast<std::size_t>(helpers));
    for (int t = 0; t < helpers; ++t) pool.emplace_back(worker, false);
    worker(true);
    for (auto& t : pool) t.join();
    if (error) std::rethrow_exception(error);
    detail::report(progress, 1.0, function);
}

}  // namespace lidarfx
