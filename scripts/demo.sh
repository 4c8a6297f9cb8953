#!/usr/bin/env bash
# Builds the lidarfx program and runs `lidarfx demo` on its embedded scenes (plus ../shared/data/Haystack_Rock.las
# when present); outputs go to ./lidarfx-demo/.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh --gdal --python   # the release preset also configures the Python module
cmake --preset release >/dev/null
cmake --build --preset release --target lidarfx_cli
# The demo runs on its embedded scenes; the sample survey next to the repository is added when present.
sample=../shared/data/Haystack_Rock.las
extra=()
[[ -f "$sample" ]] && extra=(--las "$sample")
./build/release/lidarfx demo --out lidarfx-demo "${extra[@]}" "$@"
