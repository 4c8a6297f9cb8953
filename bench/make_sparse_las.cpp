// SPDX-License-Identifier: Apache-2.0
// Writes a sparse survey for bench/sparse_survey.sh: N points (default 1,000) scattered uniformly over a
// square of SIDE metres (default 5,000), heights 100-150 m, EPSG:32633.
// Usage: make_sparse_las OUT.las [N] [SIDE]
#include <cstdlib>
#include <iostream>
#include <random>

#include "io/las_writer.hpp"

int main(int argc, char** argv)
{
    if (argc < 2) {
        std::cerr << "usage: make_sparse_las OUT.las [N] [SIDE]\n";
        return 2;
    }
    const long n = argc > 2 ? std::atol(argv[2]) : 1000;
    const double side = argc > 3 ? std::atof(argv[3]) : 5000.0;
    std::mt19937_64 rng(20261201);
    std::uniform_real_distribution<double> u(0.0, side);
    lidarfx::io::las_points p;
    for (long i = 0; i < n; ++i) {
        p.x.push_back(500000.0 + u(rng));
        p.y.push_back(4000000.0 + u(rng));
        p.z.push_back(100.0 + u(rng) / side * 50.0);
        p.intensity.push_back(static_cast<std::uint16_t>(i % 250));
    }
    lidarfx::io::write_las(argv[1], p, {.epsg_projected = 32633});
    return 0;
}
