// SPDX-License-Identifier: Apache-2.0
// Subcommand registry of the lidarfx program: each cli/*.cpp registers one command at start-up.
#pragma once

#include <functional>
#include <map>
#include <string>
#include <vector>

namespace lidarfx::cli {

/// A subcommand: runs with its own arguments (argv after the subcommand name), returns the exit code.
struct command {
    std::string summary;
    std::function<int(const std::vector<std::string>& args)> run;
};

inline std::map<std::string, command>& registry()
{
    static std::map<std::string, command> commands;
    return commands;
}

/// Registers a subcommand; use as `static const cli::registration reg{"water", "...", run_water};`.
struct registration {
    registration(const std::string& name, std::string summary, std::function<int(const std::vector<std::string>&)> run)
    {
        registry()[name] = command{std::move(summary), std::move(run)};
    }
};

}  // namespace lidarfx::cli
