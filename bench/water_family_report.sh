#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# The water-family tables of docs/waterbodies.md, on the reporting seeds (5001-5050 per kind, never used to
# choose anything): the classic family at 0.5-8 pulses/m², the level-land scenes at 1-2.5 pulses/m² (QL2 is
# 2), narrow rivers (5-15 m) on 2 m and 3 m cells, and the classic rivers on 3 m cells. Each table compares
# the method before the family, the library's defaults and flat_seed_water_method() (what `lidarfx water`
# runs). Takes a few minutes on one core.
# Usage: bash bench/water_family_report.sh   (after `cmake --preset bench && cmake --build --preset bench`)
set -euo pipefail
cd "$(dirname "$0")/.."
family="${BUILD:-build/bench}/bench/water_family"
seeds=(--first 5001 --count 50)
report() {
    echo "### $1"
    shift
    "$family" "${seeds[@]}" "$@" 2>/dev/null | grep '^|'
    echo
}
report "classic family, 0.5-8 pulses/m², cells >= 2 m"
report "level land, 1-2.5 pulses/m², 2 m cells" --variant level-land --density 1 2.5
report "narrow rivers, 1-8 pulses/m², 2 m cells" --variant narrow-river --density 1 8 --cell 2
report "narrow rivers, 1-8 pulses/m², 3 m cells" --variant narrow-river --density 1 8 --cell 3
report "classic family, 1-8 pulses/m², 3 m cells" --density 1 8 --cell 3
