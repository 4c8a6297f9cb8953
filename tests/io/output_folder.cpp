// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include "io/file_output.hpp"
#include "io/output_folder.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <stdexcept>
#include <string>

#include "io_test_util.hpp"

using namespace lidarfx::io;
using io_test::contains;
using io_test::temp_dir;

namespace {

std::string text_of(const std::filesystem::path& p)
{
    const auto bytes = io_test::read_bytes(p.string());
    return {bytes.begin(), bytes.end()};
}

void write_text(output_folder& out, const std::string& name, const std::string& text)
{
    out.write(name, [&](const std::string& path) { write_file(path, text); });
}

/// Names in `dir`, hidden ones included.
std::vector<std::string> entries(const std::filesystem::path& dir)
{
    std::vector<std::string> names;
    for (const auto& e : std::filesystem::directory_iterator(dir)) names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
}

}  // namespace

TEST_CASE("io/output_folder: files appear under their names only at commit, with a manifest written last")
{
    temp_dir tmp;
    const std::filesystem::path dir = tmp.file("out");
    {
        output_folder out(dir);
        write_text(out, "a.txt", "abc");
        write_text(out, "b.txt", "");
        CHECK_FALSE(std::filesystem::exists(dir / "a.txt"));
        CHECK_FALSE(std::filesystem::exists(dir / "manifest.json"));
        out.commit("lidarfx test \"quoted\"");
    }
    CHECK(text_of(dir / "a.txt") == "abc");
    CHECK(text_of(dir / "b.txt").empty());
    const auto manifest = text_of(dir / "manifest.json");
    // SHA-256 of "abc" and of the empty string (FIPS 180-4 examples).
    CHECK(contains(
        manifest,
        R"({"name": "a.txt", "bytes": 3, "sha256": "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad"})"));
    CHECK(contains(
        manifest,
        R"({"name": "b.txt", "bytes": 0, "sha256": "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855"})"));
    CHECK(contains(manifest, R"("command": "lidarfx test \"quoted\"")"));
    CHECK(entries(dir) == std::vector<std::string>{"a.txt", "b.txt", "manifest.json"});  // no .lidarfx.lock left
    CHECK(sha256_of_file(dir / "a.txt") == "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
}

TEST_CASE("io/output_folder: a run that fails before commit leaves the earlier outputs untouched")
{
    temp_dir tmp;
    const std::filesystem::path dir = tmp.file("out");
    {
        output_folder first(dir);
        write_text(first, "a.txt", "first run");
        first.commit();
    }
    const auto manifest = text_of(dir / "manifest.json");
    CHECK_THROWS_AS(([&] {
                        output_folder second(dir);
                        write_text(second, "a.txt", "second run");
                        write_text(second, "c.txt", "second run");
                        throw std::runtime_error("the computation failed");
                    }()),
                    std::runtime_error);
    CHECK(text_of(dir / "a.txt") == "first run");
    CHECK(text_of(dir / "manifest.json") == manifest);
    CHECK(entries(dir) == std::vector<std::string>{"a.txt", "manifest.json"});  // no temporaries, no lock file
}

TEST_CASE("io/output_folder: a folder created by a run that fails is removed again")
{
    temp_dir tmp;
    const std::filesystem::path dir = tmp.file("new/deeper");
    {
        output_folder out(dir);
        CHECK(std::filesystem::is_directory(dir));
    }
    CHECK_FALSE(std::filesystem::exists(dir));
}

TEST_CASE("io/output_folder: a symlink at an output name is neither followed nor replaced")
{
    temp_dir tmp;
    const std::filesystem::path dir = tmp.file("out");
    std::filesystem::create_directories(dir);
    const auto victim = tmp.file("victim.las");
    write_file(victim, std::string("precious survey"));
    std::filesystem::create_symlink(victim, dir / "waterbodies.csv");
    output_folder out(dir);
    const auto why = io_test::runtime_error_of([&] { out.check_name("waterbodies.csv"); });
    CHECK(contains(why, "waterbodies.csv: is a symbolic link; refusing to write through or replace it"));
    CHECK_THROWS_AS(write_text(out, "waterbodies.csv", "label,area"), std::runtime_error);
    CHECK(text_of(victim) == "precious survey");
    CHECK(std::filesystem::is_symlink(dir / "waterbodies.csv"));
}

TEST_CASE("io/output_folder: an output never replaces an input of the run, whatever its name")
{
    temp_dir tmp;
    const std::filesystem::path dir = tmp.file("out");
    std::filesystem::create_directories(dir);
    write_file((dir / "water.asc").string(), std::string("an input that happens to be called water.asc"));
    std::filesystem::create_hard_link(dir / "water.asc", tmp.file("input.las"));
    output_folder out(dir, {tmp.file("input.las")});
    const auto why = io_test::runtime_error_of([&] { out.check_name("water.asc"); });
    CHECK(contains(why, "water.asc: is an input of this run"));
    CHECK_THROWS_AS(write_text(out, "water.asc", "1 0 1"), std::runtime_error);
    CHECK(text_of(dir / "water.asc") == "an input that happens to be called water.asc");
}

TEST_CASE("io/output_folder: a second run into a locked folder fails at once and touches nothing")
{
    temp_dir tmp;
    const std::filesystem::path dir = tmp.file("out");
    {
        output_folder first(dir);
        write_text(first, "a.txt", "first");
        const auto why = io_test::runtime_error_of([&] { output_folder second(dir); });
        CHECK(contains(why, "another lidarfx run is writing into this folder"));
        CHECK(std::filesystem::exists(dir / ".lidarfx.lock"));  // held while the run is active
        first.commit();
    }
    CHECK(text_of(dir / "a.txt") == "first");
    output_folder third(dir);  // the lock is free again once the first run is over
    write_text(third, "a.txt", "third");
    third.commit();
    CHECK(text_of(dir / "a.txt") == "third");
}

TEST_CASE("io/output_folder: leftovers of killed runs are removed; bad names are refused")
{
    temp_dir tmp;
    const std::filesystem::path dir = tmp.file("out");
    std::filesystem::create_directories(dir);
    write_file((dir / ".min_z.asc.4242.lidarfx-tmp").string(), std::string("half a raster"));
    output_folder out(dir);
    CHECK_FALSE(std::filesystem::exists(dir / ".min_z.asc.4242.lidarfx-tmp"));
    CHECK_THROWS_AS(write_text(out, "../escape.txt", "x"), std::runtime_error);
    CHECK_THROWS_AS(write_text(out, "", "x"), std::runtime_error);
    write_text(out, "once.txt", "x");
    CHECK(contains(io_test::runtime_error_of([&] { write_text(out, "once.txt", "y"); }), "written twice"));
    std::filesystem::create_directories(dir / "sub");
    CHECK(contains(io_test::runtime_error_of([&] { out.check_name("sub"); }), "not a regular file"));
    write_file((dir / "plain.txt").string(), std::string("a file"));
    CHECK(contains(io_test::runtime_error_of([&] { output_folder bad(dir / "plain.txt"); }),
                   "plain.txt: exists and is not a folder"));
}

TEST_CASE("io/output_folder: only regular files named as this program names its temporaries are removed as leftovers")
{
    temp_dir tmp;
    const std::filesystem::path dir = tmp.file("out");
    const std::filesystem::path theirs = tmp.file("theirs.lidarfx-tmp");
    std::filesystem::create_directories(dir);
    write_file(theirs.string(), std::string("someone's"));
    write_file((dir / ".a.txt.77.lidarfx-tmp").string(), std::string("ours"));  // a leftover
    for (const char* foreign : {"notes.lidarfx-tmp", ".a.txt.lidarfx-tmp", ".a.txt.7x.lidarfx-tmp", "..1.lidarfx-tmp"})
        write_file((dir / foreign).string(), std::string("theirs"));
    std::filesystem::create_symlink(theirs, dir / ".b.txt.78.lidarfx-tmp");  // a link at our form
    {
        output_folder out(dir);
    }
    CHECK_FALSE(std::filesystem::exists(dir / ".a.txt.77.lidarfx-tmp"));
    for (const char* foreign : {"notes.lidarfx-tmp", ".a.txt.lidarfx-tmp", ".a.txt.7x.lidarfx-tmp", "..1.lidarfx-tmp"})
        CHECK(text_of(dir / foreign) == "theirs");
    CHECK(std::filesystem::is_symlink(dir / ".b.txt.78.lidarfx-tmp"));
    CHECK(text_of(theirs) == "someone's");
}

TEST_CASE("io/output_folder: a lock file left by a killed run is taken and removed by the next run")
{
    temp_dir tmp;
    const std::filesystem::path dir = tmp.file("out");
    std::filesystem::create_directories(dir);
    std::ofstream(dir / ".lidarfx.lock").close();  // what kill -9 leaves (the kernel released its flock)
    {
        output_folder run(dir);
        write_text(run, "a.txt", "a");
        run.commit();
    }
    CHECK(entries(dir) == std::vector<std::string>{"a.txt", "manifest.json"});
}

TEST_CASE("io/output_folder: a declared name this run does not write goes only when it is an earlier run's, unchanged")
{
    temp_dir tmp;
    const std::filesystem::path dir = tmp.file("out");
    {  // the first run knows the CRS: each grid has its .prj
        output_folder out(dir);
        for (const char* name : {"dsm.asc", "dsm.prj", "dtm.asc", "dtm.prj"}) out.declare(name);
        for (const char* name : {"dsm.asc", "dsm.prj", "dtm.asc", "dtm.prj"}) write_text(out, name, name);
        out.commit("first");
        CHECK(out.removed_stale().empty());
    }
    write_file((dir / "dtm.prj").string(), std::string("edited by the user"));
    write_file((dir / "mine.prj").string(), std::string("never written by lidarfx"));
    {  // the second run has no CRS: it writes the grids only
        output_folder out(dir);
        for (const char* name : {"dsm.asc", "dsm.prj", "dtm.asc", "dtm.prj", "mine.prj"}) out.declare(name);
        for (const char* name : {"dsm.asc", "dtm.asc"}) write_text(out, name, std::string(name) + " again");
        out.commit("second");
        CHECK(out.removed_stale() == std::vector<std::string>{"dsm.prj"});
    }
    CHECK_FALSE(std::filesystem::exists(dir / "dsm.prj"));           // unchanged output of the first run
    CHECK(text_of(dir / "dtm.prj") == "edited by the user");         // changed since: the user's now
    CHECK(text_of(dir / "mine.prj") == "never written by lidarfx");  // in no manifest
    CHECK(text_of(dir / "dsm.asc") == "dsm.asc again");
    const std::string manifest = text_of(dir / "manifest.json");
    CHECK(contains(manifest, "\"dsm.asc\""));
    CHECK_FALSE(contains(manifest, "dsm.prj"));
}

TEST_CASE("io/output_folder: a name another command wrote is not removed when this run does not declare it")
{
    temp_dir tmp;
    const std::filesystem::path dir = tmp.file("out");
    {
        output_folder out(dir);
        out.declare("max_z.asc");
        write_text(out, "max_z.asc", "1");
        out.commit("rasterize");
    }
    output_folder out(dir);
    out.declare("water.asc");
    write_text(out, "water.asc", "0");
    out.commit("water");
    CHECK(out.removed_stale().empty());
    CHECK(text_of(dir / "max_z.asc") == "1");
}
