#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Outputs survive kill -9 and concurrent runs: `lidarfx demo` is killed at random moments of a run, again and
# again into the same folder; after each kill every file under its final name must equal the file of a
# complete run (a file is never incomplete under its final name, earlier outputs are never damaged). Then a
# second run started into a folder that a first run is writing must fail with a message while the first one
# completes untouched.   Usage: cli_safe_outputs.sh LIDARFX WORK_DIR
set -euo pipefail
lidarfx="$1"
work="$2"
rm -rf "$work"
mkdir -p "$work"
args=(demo --size 300 --seed 3 --threads 1)

start=$(date +%s%N)
"$lidarfx" "${args[@]}" --out "$work/reference" >/dev/null 2>&1
duration_ms=$(( ($(date +%s%N) - start) / 1000000 ))
echo "a complete run takes ${duration_ms} ms"
# The complete run holds the roof town's outputs: both modes' patches and one score row per mode.
for f in roof_scores.csv roofs_{planes,paper}/roof_patches.{csv,geojson,png} roofs_{planes,paper}/manifest.json; do
    [[ -f "$work/reference/$f" ]] || { echo "lidarfx demo did not write $f" >&2; exit 1; }
done
[[ "$(cut -d, -f1 "$work/reference/roof_scores.csv" | tr '\n' ' ')" == "mode planes paper " ]] ||
    { echo "roof_scores.csv should have a row per mode:" >&2; cat "$work/reference/roof_scores.csv" >&2; exit 1; }

# Every visible file under $1 equals its twin in the reference run (manifest.json aside: it names the folder).
check_complete() {
    local dir="$1" bad=0 f
    while IFS= read -r -d '' f; do
        local rel="${f#"$dir"/}"
        case "$(basename "$rel")" in
            manifest.json) continue ;;  # names the folder and checksums; its files are compared themselves
            scores.csv)  # its last column is the run time: compare the others
                if ! cmp -s <(cut -d, -f1-9 "$f") <(cut -d, -f1-9 "$work/reference/$rel"); then
                    echo "INCOMPLETE OR WRONG: $rel" >&2
                    bad=1
                fi
                continue ;;
        esac
        if ! cmp -s "$f" "$work/reference/$rel"; then
            echo "INCOMPLETE OR WRONG: $rel" >&2
            bad=1
        fi
    done < <(find "$dir" -type f ! -name '.*' -print0)
    return $bad
}

RANDOM=20261201
kills=0
for attempt in $(seq 1 12); do
    delay_ms=$(( RANDOM % (duration_ms + 1) ))
    "$lidarfx" "${args[@]}" --out "$work/killed" >/dev/null 2>&1 &
    pid=$!
    sleep "$(printf '0.%03d' "$delay_ms")" 2>/dev/null || sleep "$((delay_ms / 1000))"
    if kill -9 "$pid" 2>/dev/null; then kills=$((kills + 1)); fi
    wait "$pid" 2>/dev/null || true
    [[ -d "$work/killed" ]] && check_complete "$work/killed"
done
echo
echo "killed $kills of 12 runs at random moments: no file under its final name was incomplete"
((kills >= 6)) || { echo "too few runs were killed while running ($kills)" >&2; exit 1; }

# A run into the same folder after all this completes, and its result is whole.
"$lidarfx" "${args[@]}" --out "$work/killed" >/dev/null 2>&1
check_complete "$work/killed"
[[ -f "$work/killed/manifest.json" && -f "$work/killed/lake/manifest.json" ]]

# Concurrent runs: the second fails at once with a message, the first is unharmed.
"$lidarfx" "${args[@]}" --out "$work/shared" >/dev/null 2>&1 &
first=$!
for _ in $(seq 1 200); do [[ -e "$work/shared/.lidarfx.lock" ]] && break; sleep 0.01; done
if second_output=$("$lidarfx" "${args[@]}" --out "$work/shared" 2>&1); then
    echo "a second run into a folder in use succeeded" >&2
    exit 1
fi
grep -q "another lidarfx run is writing into this folder" <<<"$second_output" ||
    { echo "the second run did not say why it failed: $second_output" >&2; exit 1; }
wait "$first"
check_complete "$work/shared"
[[ -f "$work/shared/manifest.json" ]]
echo "a concurrent second run failed with a message; the first completed untouched"
