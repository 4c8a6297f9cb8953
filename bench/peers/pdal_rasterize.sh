#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Issue 11's end-to-end peer: `lidarfx rasterize` against PDAL's readers.las -> writers.gdal (binmode; min,
# max, count, mean; float32; DEFLATE tiled GeoTIFF) on the same LAS file, grid and thread count. Prints the
# best wall and CPU time of each (hyperfine if installed, else GNU time; best of $REPEAT), the ratio
# PDAL / lidarfx (> 1: lidarfx is faster) and the CPU's vector extensions, and compares lidarfx's min_z,
# max_z and count GeoTIFFs with PDAL's bands cell for cell (bench/peers/pdal_compare.py: differing cells,
# how many the documented edge rule explains, largest difference; exit 1 when a difference is not the edge
# rule's). PDAL writes with lidarfx's GeoTIFF creation options (compression, level, predictor, tile size, read
# from examples/io/geotiff.cpp by pdal_compare.py gdalopts; printed below) and, for a file in feet, gets lidarfx's
# conversion to metres first (filters.assign). Skips with a message when pdal is absent.
#
# Usage: bash bench/peers/pdal_rasterize.sh [IN.las] [CELL]    (after `cmake --preset bench &&
#        cmake --build --preset bench --target lidarfx_cli make_sparse_las`)
#   IN.las    a path, or a name under $LIDARFX_PDAL_DATA or $LIDARFX_PDAL_DATA/las (PDAL's test/data, e.g.
#             autzen_trim.las); default: a generated survey of $POINTS points (13.2 M) uniform over
#             $SIDE x $SIDE metres (7,800 m: 3,900 x 3,900 cells at 2 m) by bench/make_sparse_las
#   CELL      cell size in metres (lidarfx --cell), default 2
# Environment: BUILD (default build/bench), THREADS (default all cores: lidarfx --threads, readers.las
#   threads), REPEAT (default 3), PDAL (the pdal program; default from PATH, else /opt/pdal/bin/pdal),
#   PYTHON (default /usr/bin/python3, which has python3-gdal and numpy), LIDARFX_ARGS (more lidarfx options,
#   e.g. --force; not --crop, which PDAL would not get).
# PDAL's pipeline runs on one thread whatever THREADS says (readers.las uses threads only for LAZ).
set -euo pipefail
cd "$(dirname "$0")/../.."
build="${BUILD:-build/bench}"
threads="${THREADS:-$(nproc)}"
repeat="${REPEAT:-3}"
python="${PYTHON:-/usr/bin/python3}"
cell="${2:-2}"
compare_py="bench/peers/pdal_compare.py"

pdal="${PDAL:-$(command -v pdal || true)}"
[[ -z "$pdal" && -x /opt/pdal/bin/pdal ]] && pdal=/opt/pdal/bin/pdal
if [[ -z "$pdal" ]]; then
    echo "pdal_rasterize: skipped: no pdal program (not on PATH, not /opt/pdal/bin/pdal; set PDAL=...)"
    exit 0
fi
pdal_lib="$(dirname "$(dirname "$pdal")")/lib"  # an install prefix without an rpath, as /opt/pdal
[[ -d "$pdal_lib" ]] && export LD_LIBRARY_PATH="$pdal_lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
if ! pdal_says="$("$pdal" --version 2>&1)"; then
    echo "pdal_rasterize: skipped: $pdal does not run: $(echo "$pdal_says" | head -n 1)"
    exit 0
fi
pdal_version="$(echo "$pdal_says" | grep -o -E 'pdal [0-9][^ ]*' | head -n 1 || true)"
if ! "$python" -c 'import numpy; from osgeo import gdal' 2>/dev/null; then
    echo "pdal_rasterize: skipped: $python lacks numpy or GDAL's bindings (apt-get install python3-gdal)"
    exit 0
fi
lidarfx="$build/lidarfx"
[[ -x "$lidarfx" ]] || { echo "$lidarfx not found: build with cmake --preset bench &&" \
                              "cmake --build --preset bench --target lidarfx_cli make_sparse_las" >&2; exit 2; }

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
input="${1:-}"
if [[ -z "$input" ]]; then
    input="$work/survey.las"
    "$build/bench/make_sparse_las" "$input" "${POINTS:-13200000}" "${SIDE:-7800}"
elif [[ ! -f "$input" && -n "${LIDARFX_PDAL_DATA:-}" ]]; then
    for candidate in "$LIDARFX_PDAL_DATA/$input" "$LIDARFX_PDAL_DATA/las/$input"; do
        [[ -f "$candidate" ]] && { input="$candidate"; break; }
    done
fi
[[ -f "$input" ]] || { echo "pdal_rasterize: $input: no such file (give a path, or set LIDARFX_PDAL_DATA)" >&2; exit 2; }
input="$(realpath "$input")"

formats=()
lidarfx_help="$("$lidarfx" rasterize --help 2>&1 || true)"
[[ "$lidarfx_help" == *--formats* ]] && formats=(--formats tif)
read -r -a extra <<<"${LIDARFX_ARGS:-}"
lidarfx_cmd=("$lidarfx" rasterize "$input" --cell "$cell" --threads "$threads" "${formats[@]}" "${extra[@]}"
             --out "$work/lidarfx")
pdal_cmd=("$pdal" pipeline "$work/pipeline.json")

# "WALL CPU": the best wall time and the best CPU time (user + system) in seconds of "$@" over $repeat runs
# ($prepare runs untimed before each). CPU time is the fairer figure on a loaded machine for one thread.
best_of() {
    if command -v hyperfine >/dev/null; then
        hyperfine --runs "$repeat" --prepare "$prepare" --export-json "$work/hf.json" --style none \
            "$(printf '%q ' "$@")" >/dev/null
        "$python" -c 'import json,sys; r = json.load(open(sys.argv[1]))["results"][0]
print(min(r["times"]), r["user"] + r["system"])' "$work/hf.json"
        return
    fi
    for _ in $(seq "$repeat"); do
        bash -c "$prepare"
        /usr/bin/time -f "%e %U %S" -o "$work/time" "$@" >"$work/log" 2>&1 || { cat "$work/log" >&2; return 1; }
        tail -n 1 "$work/time"
    done | awk '{ w = $1; c = $2 + $3; if (NR == 1 || w < bw) bw = w; if (NR == 1 || c < bc) bc = c }
                END { print bw, bc }'
}

echo "CPU: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs), $(nproc) cores; vector extensions:" \
     "$(grep -m1 -o -w -E 'avx512f|avx2|sse4_2' /proc/cpuinfo | sort -u | xargs)"
echo "file: $input ($(du -h "$input" | cut -f1)), cell $cell, threads $threads; $pdal ($pdal_version)"
echo "GeoTIFF creation options of both: $("$python" "$compare_py" gdalopts) (lidarfx also writes overviews)"
# An untimed run of each first: it warms the page cache, lidarfx's grid and log set PDAL's grid and unit
# conversion (pdal_compare.py), and lidarfx remembers the file's CRS answer (in $work, not the user's cache), as
# every run after the first on a survey's CRS does; one more row times lidarfx with remembering off.
export LIDARFX_CACHE_DIR="$work/cache"
"${lidarfx_cmd[@]}" >"$work/lidarfx.log" 2>&1 || { cat "$work/lidarfx.log" >&2; exit 1; }
"$python" "$compare_py" pipeline "$work/lidarfx" "$work/lidarfx.log" "$cell" "$input" "$work/pdal.tif" "$threads" \
    >"$work/pipeline.json"
"${pdal_cmd[@]}" >"$work/pdal.log" 2>&1 || { cat "$work/pdal.log" >&2; exit 1; }

prepare="rm -rf '$work/lidarfx'"
t_lidarfx="$(best_of "${lidarfx_cmd[@]}")"
t_lidarfx_cold="$(LIDARFX_CACHE_DIR='' best_of "${lidarfx_cmd[@]}")"
prepare="rm -f '$work/pdal.tif'"
t_pdal="$(best_of "${pdal_cmd[@]}")"

echo "lidarfx rasterize ${formats[*]:-(default formats)}: $(ls "$work/lidarfx" | grep -c -v manifest) files," \
     "$(du -sh "$work/lidarfx" | cut -f1)"
echo "pdal writers.gdal: 1 file, $(du -h "$work/pdal.tif" | cut -f1)"
read -r wall_lidarfx cpu_lidarfx <<<"$t_lidarfx"
read -r wall_pdal cpu_pdal <<<"$t_pdal"
read -r wall_cold cpu_cold <<<"$t_lidarfx_cold"
awk -v a="$wall_lidarfx" -v ca="$cpu_lidarfx" -v b="$wall_pdal" -v cb="$cpu_pdal" -v n="$repeat" \
    -v d="$wall_cold" -v cd="$cpu_cold" 'BEGIN {
    printf "%-44s %8s %8s   (best of %d)\n", "", "wall s", "CPU s", n
    printf "%-44s %8.2f %8.2f\n%-44s %8.2f %8.2f\n", "lidarfx rasterize", a, ca, "pdal readers.las->writers.gdal", b, cb
    printf "ratio PDAL / lidarfx: wall %.2f, CPU %.2f (> 1: lidarfx is faster)\n", b / a, cb / ca
    printf "%-44s %8.2f %8.2f   ratio wall %.2f\n", "lidarfx, CRS answer not remembered (1st run)", d, cd, b / d }'
grep -m1 '^survey:' "$work/lidarfx.log" || true
grep -q filters.assign "$work/pipeline.json" && echo "PDAL converts to metres as lidarfx does (filters.assign)"
"$python" "$compare_py" compare "$work/lidarfx" "$work/lidarfx.log" "$cell" "$input" "$work/pdal.tif"
