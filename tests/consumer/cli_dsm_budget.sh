#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# DSM and DTM grids count against --memory from their header, before any cell is allocated: grids that declare
# far more cells than the budget holds (a 100-byte ESRI ASCII header of 20000 x 20000 cells, ncols 2147483648,
# a sparse 30000 x 30000 GeoTIFF when GDAL and gdal_create are here, a complete 8000 x 8000 DSM with
# --memory 64MiB) are refused by `lidarfx solar` and `lidarfx roofs` with exit code 2 and the budget's message,
# each in under 1 s with a peak resident memory under 200 MB (GNU time's %M); a header promising more values
# than its file holds fails before the grid exists; inf and nan heights are no data and counted.
#   Usage: cli_dsm_budget.sh LIDARFX WORK_DIR
set -euo pipefail
lidarfx="$1"
work="$2"
rm -rf "$work"
mkdir -p "$work"
failures=0
fail() { echo "FAILED: $*" >&2; failures=$((failures + 1)); }

# run EXPECTED_CODE PATTERN ARGS...: the program's exit code, message, time and peak memory.
run() {
    local expected="$1" pattern="$2" log="$work/log" start ms code kb
    shift 2
    start=$(date +%s%N)
    set +e
    /usr/bin/time -f "%M" -o "$work/peak_kb" "$lidarfx" "$@" >"$log" 2>&1
    code=$?
    set -e
    ms=$(( ($(date +%s%N) - start) / 1000000 ))
    kb=$(tail -1 "$work/peak_kb")
    echo "lidarfx $* -> exit $code in ${ms} ms, peak ${kb} KiB: $(grep -v '^ *$' "$log" | tail -1)"
    [[ "$code" == "$expected" ]] || fail "expected exit code $expected, got $code"
    grep -q -- "$pattern" "$log" || fail "the message does not say '$pattern': $(cat "$log")"
    ((ms < 1000)) || fail "took ${ms} ms (at most 1000)"
    ((kb < 200 * 1024)) || fail "peak resident memory ${kb} KiB (at most 200 MiB)"
}

header() {  # ncols nrows: an ESRI ASCII header of 1 m cells
    printf 'ncols %s\nnrows %s\nxllcorner 500000\nyllcorner 4000000\ncellsize 1\nNODATA_value -9999\n' "$1" "$2"
}

# A 100-byte header declaring 20000 x 20000 cells, with three values.
{ header 20000 20000; echo "1 2 3"; } >"$work/huge.asc"
run 2 "over the memory budget of 0.0625 GiB" solar "$work/huge.asc" --xy-unit m --z-unit m --lat 35 --lon -80 --memory 64MiB --out "$work/o1"
run 2 "over the memory budget" solar "$work/huge.asc" --xy-unit m --z-unit m --lat 35 --lon -80 --out "$work/o2"   # the default budget
cp "$work/huge.asc" "$work/huge_dtm.asc"
cat >"$work/footprints.geojson" <<'JSON'
{"type": "FeatureCollection", "features": [{"type": "Feature", "properties": {"building_id": 1},
 "geometry": {"type": "Polygon", "coordinates": [[[500010, 4000010], [500020, 4000010], [500020, 4000020],
 [500010, 4000020], [500010, 4000010]]]}}]}
JSON
run 2 "huge_dtm.asc: a grid of 20000 x 20000 cells needs about 25.3 GiB" roofs "$work/huge.asc" "$work/huge_dtm.asc" --xy-unit m --z-unit m \
    "$work/footprints.geojson" --memory 64MiB --out "$work/o3"
# ncols 2147483648: over any budget; with a budget that would hold it, the file is too short for its header.
{ header 2147483648 1; echo "1 2 3"; } >"$work/wide.asc"
run 2 "over the memory budget" solar "$work/wide.asc" --xy-unit m --z-unit m --lat 35 --lon -80 --memory 64MiB --out "$work/o4"
run 1 "truncated data: expected 2147483648 values, but the 7 bytes after the header hold at most 4" \
    solar "$work/wide.asc" --xy-unit m --z-unit m --lat 35 --lon -80 --memory 1TiB --out "$work/o5"
# A complete 8000 x 8000 DSM (128 MB of text) with --memory 64MiB.
{ header 8000 8000; yes 0 | head -n 64000000 || true; } >"$work/valid.asc"  # yes ends on SIGPIPE
run 2 "a grid of 8000 x 8000 cells needs about 9.18 GiB" solar "$work/valid.asc" --xy-unit m --z-unit m --lat 35 --lon -80 --memory 64MiB \
    --out "$work/o6"
rm -f "$work/valid.asc"
# A sparse 30000 x 30000 GeoTIFF (a few hundred KB on disk).
if command -v gdal_create >/dev/null && [[ "${HAVE_GDAL:-OFF}" == ON ]]; then
    gdal_create -q -of GTiff -outsize 30000 30000 -ot Float32 -a_srs EPSG:32617 -a_ullr 500000 4030000 530000 4000000 \
        -co SPARSE_OK=TRUE -co TILED=YES "$work/sparse.tif"
    run 2 "a grid of 30000 x 30000 cells needs about 129 GiB" solar "$work/sparse.tif" --memory 64MiB \
        --lat 35 --lon -80 --out "$work/o7"
else
    echo "GDAL or gdal_create not here: the sparse GeoTIFF case is not run"
fi
# inf and nan heights are no data, and the run says how many there were.
{ header 4 3; printf '10 10 inf 10\n10 -inf 10 10\nnan 10 10 10\n'; } >"$work/inf.asc"
"$lidarfx" solar "$work/inf.asc" --xy-unit m --z-unit m --lat 35 --lon -80 --out "$work/o8" >"$work/log" 2>&1 || fail "inf.asc: $(cat "$work/log")"
grep -q "inf.asc: 3 cells hold inf, -inf or nan: no data (NaN)" "$work/log" || fail "inf cells not reported: $(cat "$work/log")"
# No output folder is left by a refused run.
for o in o1 o2 o3 o4 o5 o6 o7; do [[ ! -e "$work/$o" ]] || fail "a refused run left $work/$o"; done
if ((failures)); then
    echo "$failures check(s) failed" >&2
    exit 1
fi
echo "every DSM over its budget was refused"
