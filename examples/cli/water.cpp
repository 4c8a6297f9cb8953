// SPDX-License-Identifier: Apache-2.0
// lidarfx water: registers the command (its run is water_run.cpp, shared with the MPI driver).
#include "command.hpp"
#include "water_run.hpp"

namespace {

int run_water(const std::vector<std::string>& args)
{
    return lidarfx::cli::run_water(args);
}

const lidarfx::cli::registration reg{"water", "LAS files -> waterbody maps, tables and polygons", run_water};

}  // namespace
