#!/usr/bin/env bash
# Builds lidarfx with its tests and examples (Release) and runs every test; ends with ctest's summary.
# Usage: scripts/test.sh [preset]   (default preset: release; asan = AddressSanitizer + UBSan)
# Each step is announced with the time it starts, so a slow machine is never silent for long.
set -euo pipefail
cd "$(dirname "$0")/.."
preset="${1:-release}"
step() { echo "test.sh [$(date +%H:%M:%S)] $*"; }
step "1/4 Debian packages (compiler, CMake, Eigen, Boost, doctest, MPI, GDAL/PROJ, pybind11, QGIS): installing those missing"
bash scripts/install-deps.sh --mpi --gdal --python --qgis  # MPI driver; GeoTIFF (GDAL, PROJ); Python module; QGIS provider
step "2/4 configuring build/$preset (cmake --preset $preset)"
cmake --preset "$preset" >/dev/null
step "2/4 configured; 3/4 building the library's tests, examples and the program"
cmake --build --preset "$preset"
step "4/4 running the tests, two at a time (ctest --preset $preset)"
ctest --preset "$preset"
step "done"
