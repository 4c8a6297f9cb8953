// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include <lidarfx/core/parallel.hpp>

#include <atomic>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <thread>
#include <vector>

using namespace lidarfx;

TEST_CASE("core/parallel_for_rows: every row once, same result for any thread count")
{
    for (std::ptrdiff_t rows : {0, 1, 7, 100, 1001}) {
        std::vector<double> reference;
        for (int threads : {1, 2, 3, 8, 0}) {
            std::vector<double> out(static_cast<std::size_t>(rows), -1.0);
            std::vector<int> hits(static_cast<std::size_t>(rows), 0);
            parallel_for_rows(rows, 16, threads, [&](std::ptrdiff_t r0, std::ptrdiff_t r1) {
                for (auto r = r0; r < r1; ++r) {
                    out[r] = std::sin(static_cast<double>(r));
                    ++hits[r];
                }
            });
            for (int h : hits) REQUIRE(h == 1);
            if (reference.empty()) reference = out;
            CHECK(out == reference);
        }
    }
}

TEST_CASE("core/parallel_for_rows: exceptions propagate; progress reports and cancels")
{
    CHECK_THROWS_WITH_AS(parallel_for_rows(100, 10, 2,
                                           [](std::ptrdiff_t r0, std::ptrdiff_t) {
                                               if (r0 == 50) throw std::runtime_error("boom");
                                           }),
                         "boom", std::runtime_error);

    for (int threads : {1, 2}) {
        std::vector<double> seen;
        parallel_for_rows(
            40, 10, threads, [](std::ptrdiff_t, std::ptrdiff_t) {},
            [&](double f) {
                seen.push_back(f);
                return true;
            });
        REQUIRE_FALSE(seen.empty());
        CHECK(seen.back() == 1.0);
        for (std::size_t i = 1; i < seen.size(); ++i) CHECK(seen[i] >= seen[i - 1]);

        std::atomic<int> blocks_run{0};
        CHECK_THROWS_AS(parallel_for_rows(
                            1000, 1, threads,
                            [&](std::ptrdiff_t, std::ptrdiff_t) {
                                ++blocks_run;
                                std::this_thread::sleep_for(std::chrono::microseconds(200));
                            },
                            [](double f) { return f < 0.01; }, "slow_job"),
                        cancelled);
        CHECK(blocks_run.load() < 1000);
    }
    CHECK_THROWS_WITH_AS(parallel_for_rows(10, 0, 1, [](std::ptrdiff_t, std::ptrdiff_t) {}),
                         "parallel_for_rows: block_rows must be >= 1 (got 0)", invalid_input);
    CHECK_THROWS_AS(parallel_for_rows(10, 1, -2, [](std::ptrdiff_t, std::ptrdiff_t) {}), invalid_input);
}

TEST_CASE("core/execution: phases keep progress monotone and end at exactly 1; run.threads is checked")
{
    std::vector<double> seen;
    const progress_callback progress = [&](double f) {
        seen.push_back(f);
        return true;
    };
    const auto nothing = [](std::ptrdiff_t, std::ptrdiff_t) {};
    parallel_for_rows(30, 10, 1, nothing, detail::progress_phase(progress, 0.0, 0.05));
    parallel_for_rows(0, 10, 1, nothing, detail::progress_phase(progress, 0.05, 0.3));  // empty: reports 1 too
    parallel_for_rows(30, 7, 2, nothing, detail::progress_phase(progress, 0.3, 1.0));
    REQUIRE(seen.size() >= 5);
    for (std::size_t i = 1; i < seen.size(); ++i) CHECK(seen[i] >= seen[i - 1]);
    CHECK(seen[2] == 0.05);  // the end of each phase is exact
    CHECK(seen[3] == 0.3);
    CHECK(seen.back() == 1.0);
    CHECK_FALSE(detail::progress_phase({}, 0.0, 1.0));  // no callback, no reports

    const progress_callback stop = [](double) { return false; };
    CHECK_THROWS_WITH_AS(parallel_for_rows(30, 10, 1, nothing, detail::progress_phase(stop, 0.5, 1.0), "job"),
                         "job: cancelled", cancelled);
    CHECK_NOTHROW(detail::check_execution(execution{}, "job"));
    CHECK_THROWS_WITH_AS(detail::check_execution({.threads = -1}, "job"), "job: run.threads must be >= 0 (got -1)",
                         invalid_input);
}
