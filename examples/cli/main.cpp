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
    os << "usage: lidarfx <command> [arguments]   (lidarfx <command> --help for details)\n\ncommands:\n";
    for (const auto& [name, cmd] : lidarfx::cli::registry()) os << "  " << name << "  " << cmd.summary << '\n';
}

}  // namespace

int main(int argc, char** argv)
{
    lidarfx::cli::keep_freed_memory();
    if (argc < 2 || std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h") {
        usage(argc < 2 ? std::cerr : std::cout);
        return argc < 2 ? 2 : 0;
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
