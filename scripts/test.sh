#!/usr/bin/env bash
# Builds lidarfx with its tests and examples (Release) and runs every test; ends with ctest's summary.
# Usage: scripts/test.sh [preset]   (default preset: release; asan = AddressSanitizer + UBSan)
set -euo pipefail
cd "$(dirname "$0")/.."
preset="${1:-release}"
bash scripts/install-deps.sh --mpi --gdal   # the MPI driver and its test; GeoTIFF in and out (GDAL, PROJ)
cmake --preset "$preset" >/dev/null
cmake --build --preset "$preset"
ctest --preset "$preset"
