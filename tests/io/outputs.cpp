// SPDX-License-Identifier: Apache-2.0
// The program's output sets: --formats, files written side by side, pictures without interpolation.
#include <doctest/doctest.h>

#include "cli/cli_common.hpp"
#include "cli/outputs.hpp"
#include "io/geotiff.hpp"

#include <atomic>
#include <filesystem>
#include <set>
#include <stdexcept>
#include <string>

#include "io_test_survey.hpp"
#include "io_test_util.hpp"

using namespace lidarfx;
using io_test::contains;
using io_test::error_of;

namespace {

cli::output_formats formats_of(const std::string& list)
{
    return cli::output_formats_from(cli::arguments({"in.las", "--formats", list}, {"formats"}, {}));
}

std::set<std::string> files_in(const std::filesystem::path& dir)
{
    std::set<std::string> names;
    for (const auto& e : std::filesystem::directory_iterator(dir)) names.insert(e.path().filename().string());
    return names;
}

}  // namespace

TEST_CASE("cli/--formats: any subset of asc, tif and png; unknown names and empty lists are usage errors")
{
    const auto all = cli::output_formats_from(cli::arguments({"in.las"}, {"formats"}, {}));
    CHECK((all.asc && all.tif && all.png));
    const auto asc_png = formats_of("asc,png");
    CHECK((asc_png.asc && !asc_png.tif && asc_png.png));
    CHECK(contains(error_of([] { formats_of("asc,tiff"); }), "--formats takes a comma-separated list"));
    CHECK(contains(error_of([] { formats_of(""); }), "--formats names no format"));
    if (!io::geotiff_available()) CHECK(contains(error_of([] { formats_of("tif"); }), "built without GDAL"));
}

TEST_CASE("cli/write_point_rasters: exactly the files the formats name, the same on 1 and 4 threads")
{
    io_test::temp_dir dir;
    const auto s = io_test::small_survey();
    for (const int threads : {1, 4}) {
        const auto out = std::filesystem::path(dir.file("asc_" + std::to_string(threads)));
        {
            io::output_folder folder(out);
            cli::write_point_rasters(folder, s, formats_of("asc"), threads);
            folder.commit("test");
        }
        CHECK(files_in(out) == std::set<std::string>{"min_z.asc", "max_z.asc", "mean_intensity.asc", "count.asc",
                                                     "dropout.asc", "manifest.json"});
        CHECK(io_test::read_bytes((out / "count.asc").string()) ==
              io_test::read_bytes((std::filesystem::path(dir.file("asc_1")) / "count.asc").string()));
    }
    const auto pictures = std::filesystem::path(dir.file("png"));
    {
        io::output_folder folder(pictures);
        cli::write_point_rasters(folder, s, formats_of("png"), 2);
        folder.commit("test");
    }
    CHECK(files_in(pictures) ==
          std::set<std::string>{"min_z.png", "mean_intensity.png", "dropout.png", "manifest.json"});
    CHECK(cli::point_raster_file_names(formats_of("png")).size() == 3);
}

TEST_CASE("cli/run_jobs: every job runs once; the first failure in job order is rethrown after all stop")
{
    std::atomic<int> ran{0};
    std::vector<std::function<void()>> jobs;
    for (int i = 0; i < 9; ++i)
        jobs.emplace_back([&ran, i] {
            ++ran;
            if (i == 3 || i == 7) throw std::runtime_error("job " + std::to_string(i));
        });
    CHECK(error_of([&] { cli::run_jobs(jobs, 3); }) == "job 3");
    CHECK(ran == 9);
    cli::run_jobs({}, 0);  // nothing to do is fine
}
