#!/usr/bin/env bash
# Fuzzes the readers with libFuzzer + AddressSanitizer + UBSan for a bounded time: the LAS and LAZ reader
# (tests/fuzz/las_fuzz.cpp) for half of it, then the GeoJSON footprint reader (footprints_fuzz.cpp), the TMY3
# reader (tmy3_fuzz.cpp) and the ESRI ASCII grid reader (ascii_grid_fuzz.cpp) for a third of the rest each.
# Usage: scripts/fuzz.sh [seconds]   (default 60, in all). Exits non-zero when a fuzzer finds a crash, a
# sanitizer report, a timeout (10 s) or memory over its limit; the input is then left in build/fuzz/
# (<target>-crash-*, -oom-*, -timeout-*), replay it with: build/fuzz/<target> <file>.
# Seeds: writer outputs for every point format, the head of ../shared/data/Haystack_Rock.las and the LAZ
# fixtures of tests/data (formats 3 and 7); make_text_seeds' footprint collections, TMY3 years and ASCII
# grids, and the head of ../shared/data/723170TYA.CSV.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-60}"
out=build/fuzz
data="${LIDARFX_DATA_DIR:-../shared/data}"

cxx=""
for c in clang++ clang++-16 clang++-15 clang++-14; do
    if command -v "$c" >/dev/null; then cxx="$c"; break; fi
done
fuzzer_works() {
    echo 'extern "C" int LLVMFuzzerTestOneInput(const unsigned char*, unsigned long) { return 0; }' |
        "$cxx" -x c++ -fsanitize=fuzzer - -o "$out/probe" 2>/dev/null
}
mkdir -p "$out/corpus" "$out/seeds"
if [[ -z "$cxx" ]] || ! fuzzer_works; then
    echo "fuzz.sh: installing clang and libclang-rt-14-dev (libFuzzer)" >&2
    sudo=""; [[ $(id -u) -ne 0 ]] && sudo="sudo"
    $sudo apt-get update -qq && $sudo apt-get install -y -qq clang libclang-rt-14-dev >/dev/null
    cxx=clang++
    fuzzer_works || { echo "fuzz.sh: $cxx cannot link -fsanitize=fuzzer" >&2; exit 1; }
fi

flags=(-std=c++20 -g -O1 -Iinclude -Iexamples -fno-omit-frame-pointer)
fuzz_flags=(-fsanitize=fuzzer,address,undefined -fno-sanitize-recover=undefined)
io_sources=(examples/io/las.cpp examples/io/laz.cpp examples/io/las_writer.cpp)
"$cxx" "${flags[@]}" -fsanitize=address,undefined "${io_sources[@]}" tests/fuzz/make_seeds.cpp -o "$out/make_seeds"
"$cxx" "${flags[@]}" "${fuzz_flags[@]}" "${io_sources[@]}" tests/fuzz/las_fuzz.cpp -o "$out/las_fuzz"
"$cxx" "${flags[@]}" tests/fuzz/make_text_seeds.cpp -o "$out/make_text_seeds"
"$cxx" "${flags[@]}" "${fuzz_flags[@]}" examples/io/footprints.cpp examples/io/vectors.cpp tests/fuzz/footprints_fuzz.cpp -o "$out/footprints_fuzz"
"$cxx" "${flags[@]}" "${fuzz_flags[@]}" examples/io/tmy3.cpp tests/fuzz/tmy3_fuzz.cpp -o "$out/tmy3_fuzz"
"$cxx" "${flags[@]}" "${fuzz_flags[@]}" examples/io/ascii_grid.cpp tests/fuzz/ascii_grid_fuzz.cpp -o "$out/ascii_grid_fuzz"

real=()
[[ -f "$data/Haystack_Rock.las" ]] && real=("$data/Haystack_Rock.las")
"$out/make_seeds" "$out/seeds" "${real[@]}"
cp tests/data/*.laz "$out/seeds/"
rm -rf "$out/text_seeds"
"$out/make_text_seeds" "$out/text_seeds"
[[ -f "$data/723170TYA.CSV" ]] && head -n 200 "$data/723170TYA.CSV" > "$out/text_seeds/tmy3/723170TYA_head.csv"

las_seconds=$(( seconds / 2 > 0 ? seconds / 2 : 1 ))
text_seconds=$(( (seconds - las_seconds) / 3 > 0 ? (seconds - las_seconds) / 3 : 1 ))
export UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1 ASAN_OPTIONS=detect_leaks=1

echo "fuzz.sh: running las_fuzz for ${las_seconds}s on $(ls "$out/seeds" | wc -l) seeds" >&2
"$out/las_fuzz" -max_total_time="$las_seconds" -max_len=40000 -timeout=10 -rss_limit_mb=2048 \
    -print_final_stats=1 -artifact_prefix="$out/las_fuzz-" "$out/corpus" "$out/seeds"

# name, longest input (a whole TMY3 year in 13 columns is about 420 kB), memory limit in MB
for target in "footprints 65536 1024" "tmy3 500000 1024" "ascii_grid 65536 1024"; do
    read -r name max_len rss <<< "$target"
    mkdir -p "$out/corpus_$name"
    echo "fuzz.sh: running ${name}_fuzz for ${text_seconds}s on $(ls "$out/text_seeds/$name" | wc -l) seeds" >&2
    "$out/${name}_fuzz" -max_total_time="$text_seconds" -max_len="$max_len" -timeout=10 -rss_limit_mb="$rss" \
        -print_final_stats=1 -artifact_prefix="$out/${name}_fuzz-" "$out/corpus_$name" "$out/text_seeds/$name"
done
