#!/usr/bin/env bash
# Builds the lidarfx program and runs `lidarfx demo` on its embedded data; outputs go to ./lidarfx-demo/.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh --gdal
cmake --preset release >/dev/null
cmake --build --preset release --target lidarfx_cli
./build/release/lidarfx demo --out lidarfx-demo "$@"
