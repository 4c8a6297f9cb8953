// SPDX-License-Identifier: Apache-2.0
// lidarfx: command-line front end; dispatches to the registered subcommands.
#include <exception>
#include <iostream>
#include <string>
#include <vector>

#include <lidarfx/core/error.hpp>

#include "cli_common.hpp"
#include "command.hpp"

namespace {

void usage(std::ostream& os)
{
    os << "usage: lidarfx <command> [arguments]   (lidarfx <command> --help for details)\n"
          "       lidarfx --version   (the version and the optional parts built in)\n\ncommands:\n";
    for (const auto& [name, cmd] : lidarfx::cli::registry()) os << "  " << name << "  " << cmd.summary << '\n';
    os << "\nexit codes:\n"
          "  0  done\n"
          "  1  an error while running (a file that cannot be read or written, ...)\n"
          "  2  refused before any work: a bad option, an input over --memory or breaking the input rules\n"
          "  3  water, hydroflatten: the data cannot support the waterbody method (nothing written; --force runs "
          "anyway)\n";
}

// "yes"/"no" for an optional part, from the compile definitions the build sets.
const char* built(bool present)
{
    return present ? "yes" : "no";
}

void version(std::ostream& os)
{
#ifndef LIDARFX_VERSION
#define LIDARFX_VERSION "unknown"
#endif
#if defined(LIDARFX_HAVE_GDAL)
    constexpr bool gdal = true;
#else
    constexpr bool gdal = false;
#endif
#if defined(LIDARFX_HAVE_PROJ)
    constexpr bool proj = true;
#else
    constexpr bool proj = false;
#endif
#if defined(LIDARFX_HAVE_MPI_DRIVER)
    constexpr bool mpi = true;
#else
    constexpr bool mpi = false;
#endif
#if defined(LIDARFX_HAVE_ZLIB)
    constexpr bool zlib = true;
#else
    constexpr bool zlib = false;
#endif
    os << "lidarfx " << LIDARFX_VERSION << "\n"
       << "GDAL (GeoTIFF, GeoPackage, OGR footprints): " << built(gdal) << "\n"
       << "PROJ (latitude and longitude for solar): " << built(proj) << "\n"
       << "MPI driver (lidarfx-mpi): " << built(mpi) << "\n"
       << "zlib (compressed PNG): " << built(zlib) << "\n";
}

}  // namespace

int main(int argc, char** argv)
{
    lidarfx::cli::keep_freed_memory();
    if (argc < 2 || std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h") {
        usage(argc < 2 ? std::cerr : std::cout);
        return argc < 2 ? 2 : 0;
    }
    if (std::string(argv[1]) == "--version") {
        version(std::cout);
        return 0;
    }
    const auto& commands = lidarfx::cli::registry();
    const auto it = commands.find(argv[1]);
    if (it == commands.end()) {
        std::cerr << "lidarfx: unknown command '" << argv[1] << "'\n";
        usage(std::cerr);
        return 2;
    }
    try {
        return it->second.run(std::vector<std::string>(argv + 2, argv + argc));
    } catch (const lidarfx::cli::usage_error& e) {
        std::cerr << "lidarfx " << it->first << ": " << e.what() << '\n';
        return 2;
    } catch (const lidarfx::invalid_input& e) {  // input refused before it is read (a LAZ chunk over --memory)
        std::cerr << "lidarfx " << it->first << ": " << e.what() << '\n';
        return 2;
    } catch (const std::exception& e) {
        std::cerr << "lidarfx " << it->first << ": error: " << e.what() << '\n';
        return 1;
    }
}
