#!/usr/bin/env bash
# Builds lidarfx with its tests and examples (Release) and runs every test; ends with ctest's summary.
# Usage: scripts/test.sh [preset]   (default preset: release; asan = AddressSanitizer + UBSan)
set -euo pipefail
cd "$(dirname "$0")/.."
preset="${1:-release}"
bash scripts/install-deps.sh --mpi   # the MPI driver and its test (mpi_tiled_water)
cmake --preset "$preset" >/dev/null
cmake --build --preset "$preset"
ctest --preset "$preset"
