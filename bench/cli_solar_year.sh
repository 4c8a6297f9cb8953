#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Times `lidarfx solar` on a year of TMY3 weather over a synthetic 1520 x 1520 DSM (2.3 M cells of 1 m, 1,400 box
# buildings 8-24 m a side and 6-30 m tall on flat ground), as a user runs it: read, outlier step, sky view, a
# year of shadows, every map written.
# usage: bash bench/cli_solar_year.sh LIDARFX_BINARY TMY3.csv [THREADS]
set -euo pipefail
lidarfx=${1:?usage: cli_solar_year.sh LIDARFX_BINARY TMY3.csv [THREADS]}
tmy=${2:?usage: cli_solar_year.sh LIDARFX_BINARY TMY3.csv [THREADS]}
threads=${3:-2}
if [ ! -f "$tmy" ]; then
    echo "cli_solar_year: skipped: no TMY3 file at $tmy (NREL's 723170TYA.CSV, for example)"
    exit 0
fi
work=$(mktemp -d)
[ -n "${KEEP:-}" ] && echo "work: $work" || trap 'rm -rf "$work"' EXIT
/usr/bin/python3 - "$work/dsm.asc" <<'PY'
import sys
import numpy as np
rng = np.random.default_rng(7)
n = 1520
z = 100 + rng.uniform(0, 0.2, (n, n)).astype(np.float32)
for _ in range(1400):
    r, c = rng.integers(0, n - 30, 2)
    h, w = rng.integers(8, 25, 2)
    z[r:r + h, c:c + w] = 100 + rng.uniform(6, 30)
with open(sys.argv[1], "w") as f:
    f.write(f"ncols {n}\nnrows {n}\nxllcorner 500000\nyllcorner 4000000\ncellsize 1\nNODATA_value -9999\n")
    np.savetxt(f, z, fmt="%.2f")
PY
grep -o -m1 -E 'avx512[a-z]*|avx2' /proc/cpuinfo | sort -u | tr '\n' ' ' | sed 's/^/cpu vector extensions: /'; echo
/usr/bin/time -o "$work/time.txt" -f "lidarfx solar, 2.3 M cells, a TMY3 year, $threads threads: wall %e s, CPU %U s user + %S s system, peak %M KiB" \
    "$lidarfx" solar "$work/dsm.asc" --out "$work/out/" --tmy "$tmy" --xy-unit m --z-unit m --threads "$threads" \
    > "$work/log.txt" 2>&1 || { cat "$work/log.txt"; exit 1; }
cat "$work/time.txt"
