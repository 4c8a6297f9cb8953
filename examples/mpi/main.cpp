// SPDX-License-Identifier: Apache-2.0
// lidarfx-mpi: `lidarfx water --tile M` spread over MPI ranks. Rank r reads the tiles i with i % ranks == r
// (stage A, --threads tiles at a time) and sends each tile's rasters to rank 0 as one packed message; rank 0
// assembles the survey, runs stage B (the untiled waterbody extraction) and writes the outputs. The files
// equal those of `lidarfx water` (tiled or not) byte for byte. No resume (a killed MPI run starts over).
//     mpirun -np 4 lidarfx-mpi water DIR_OR_FILES... --cell 2 --tile 500 --threads 2 --out OUT/
#include <mpi.h>

#include <algorithm>
#include <exception>
#include <functional>
#include <iostream>
#include <limits>
#include <mutex>
#include <stdexcept>
#include <string>
#include <vector>

#include "cli/tiled_survey.hpp"
#include "cli/water_run.hpp"

namespace {

using namespace lidarfx;
using namespace lidarfx::cli;

constexpr int tile_tag = 15;

/// What every rank derives alike from the command line: the files, the layout and the tile plan.
struct run_plan {
    std::vector<std::string> files;
    survey_options opt;
    survey_layout layout;
    tile_plan plan;
    std::vector<file_readers> readers;  // every listing tile reads its files (ranks hand nothing on)
};

run_plan plan_run(const std::vector<std::string>& files, const survey_options& opt, double tile_edge_m)
{
    if (!(tile_edge_m > 0)) throw usage_error("lidarfx-mpi needs --tile M (metres > 0): ranks share the tiles");
    run_plan p{files, opt, survey_layout_of(files, opt), {}, {}};
    p.plan = plan_survey_tiles(p.layout, tile_edge_m, opt, std::max(1, opt.threads));
    p.readers = survey_file_readers(p.layout, p.plan, false);
    return p;
}

/// Reads this rank's tiles on opt.threads threads, handing each to `done` (called under a lock).
template <class Done>
void read_my_tiles(const run_plan& p, int rank, int ranks, Done&& done)
{
    std::mutex mutex;
    std::vector<std::function<void()>> jobs;
    for (const auto& tile : p.plan.tiles) {
        if (static_cast<int>(tile.index % static_cast<std::size_t>(ranks)) != rank) continue;
        jobs.push_back([&, index = tile.index] {
            tile_rasters t = read_tile(p.layout, p.files, p.plan, p.readers, index, p.opt.crop.has_value());
            const std::lock_guard lock(mutex);
            done(std::move(t));
        });
    }
    run_jobs(jobs, p.opt.threads);
}

/// Rank 0's survey: its own tiles and every other rank's, received as packed tiles.
survey gather_survey(const run_plan& p, int ranks)
{
    tiled_survey_assembly assembly(p.layout, p.plan, p.readers);
    const std::size_t tiles = p.plan.tiles.size();
    auto bar = p.opt.show_progress ? progress_bar("tiles    ") : progress_callback{};
    std::size_t finished = 0;
    const auto placed = [&] {
        ++finished;
        if (bar) bar(static_cast<double>(finished) / static_cast<double>(tiles));
    };
    std::vector<std::uint8_t> bytes;
    // Receives one tile from another rank: waiting for it, or only when one has arrived (false if none).
    const auto receive = [&](bool wait) {
        MPI_Status status;
        int arrived = 1;
        if (wait)
            MPI_Probe(MPI_ANY_SOURCE, tile_tag, MPI_COMM_WORLD, &status);
        else
            MPI_Iprobe(MPI_ANY_SOURCE, tile_tag, MPI_COMM_WORLD, &arrived, &status);
        if (!arrived) return false;
        int count = 0;
        MPI_Get_count(&status, MPI_BYTE, &count);
        bytes.resize(static_cast<std::size_t>(count));
        MPI_Recv(bytes.data(), count, MPI_BYTE, status.MPI_SOURCE, tile_tag, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
        assembly.place(unpack_tile(bytes, p.plan, "a tile from rank " + std::to_string(status.MPI_SOURCE)));
        placed();
        return true;
    };
    // After each own tile, the tiles that other ranks have sent meanwhile (so that they do not wait).
    read_my_tiles(p, 0, ranks, [&](tile_rasters&& t) {
        assembly.place(t);
        placed();
        while (receive(false)) {
        }
    });
    while (finished < tiles) receive(true);
    return assembly.finish();
}

/// A rank other than 0: waits for rank 0's go (it has checked the command line and the inputs), then reads
/// its tiles and sends each to rank 0.
void work(const std::vector<std::string>& args, int rank, int ranks)
{
    int go = 0;
    MPI_Bcast(&go, 1, MPI_INT, 0, MPI_COMM_WORLD);
    if (!go) return;
    const arguments a(args, water_value_options(), water_flag_options());
    auto opt = survey_options_from(a, water_bytes_per_cell);
    opt.show_progress = false;
    const run_plan p = plan_run(survey_files(a.positional()), opt, a.number("tile", 0));
    read_my_tiles(p, rank, ranks, [&](tile_rasters&& t) {
        auto bytes = pack_tile(t);
        if (bytes.size() > static_cast<std::size_t>(std::numeric_limits<int>::max()))
            throw std::runtime_error("tile " + std::to_string(t.index) +
                                     " is over 2 GiB as a message: use a smaller --tile");
        MPI_Send(bytes.data(), static_cast<int>(bytes.size()), MPI_BYTE, 0, tile_tag, MPI_COMM_WORLD);
    });
}

}  // namespace

int main(int argc, char** argv)
{
    lidarfx::cli::keep_freed_memory();
    int provided = 0;
    MPI_Init_thread(&argc, &argv, MPI_THREAD_SERIALIZED, &provided);
    int rank = 0, ranks = 1;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &ranks);
    if (argc < 2 || std::string(argv[1]) != "water") {
        if (rank == 0)
            std::cerr
                << "usage: mpirun -np N lidarfx-mpi water ...   (the options of lidarfx water, --tile M needed)\n";
        MPI_Finalize();
        return 2;
    }
    const std::vector<std::string> args(argv + 2, argv + argc);
    int code = 0;
    try {
        if (rank == 0) {
            bool announced = false;
            const auto source = [&](const std::vector<std::string>& files, const survey_options& opt,
                                    double tile_edge_m, const std::filesystem::path&) {
                run_plan p;
                try {
                    p = plan_run(files, opt, tile_edge_m);
                } catch (...) {
                    int go = 0;
                    announced = true;
                    MPI_Bcast(&go, 1, MPI_INT, 0, MPI_COMM_WORLD);
                    throw;
                }
                int go = 1;
                announced = true;
                MPI_Bcast(&go, 1, MPI_INT, 0, MPI_COMM_WORLD);
                return gather_survey(p, ranks);
            };
            try {
                code = run_water(args, source);
            } catch (...) {
                if (!announced) {
                    int go = 0;
                    MPI_Bcast(&go, 1, MPI_INT, 0, MPI_COMM_WORLD);
                }
                throw;
            }
            if (!announced) {  // --help or a usage error before any reading
                int go = 0;
                MPI_Bcast(&go, 1, MPI_INT, 0, MPI_COMM_WORLD);
            }
        } else {
            work(args, rank, ranks);
        }
    } catch (const usage_error& e) {
        std::cerr << "lidarfx-mpi water (rank " << rank << "): " << e.what() << '\n';
        if (rank != 0) MPI_Abort(MPI_COMM_WORLD, 2);  // rank 0 waits for this rank's tiles
        code = 2;
    } catch (const std::exception& e) {
        std::cerr << "lidarfx-mpi water (rank " << rank << "): error: " << e.what() << '\n';
        MPI_Abort(MPI_COMM_WORLD, 1);
    }
    MPI_Finalize();
    return code;
}
