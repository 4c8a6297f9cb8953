#!/usr/bin/env bash
# Fuzzes the LAS and LAZ reader (tests/fuzz/las_fuzz.cpp) with libFuzzer + AddressSanitizer + UBSan for a bounded time.
# Usage: scripts/fuzz.sh [seconds]   (default 60). Exits non-zero when the fuzzer finds a crash; the
# crashing input is then left in build/fuzz/ (crash-*), replay it with: build/fuzz/las_fuzz <file>.
# Seeds: writer outputs for every point format, the head of ../shared/data/Haystack_Rock.las and the LAZ
# fixtures of tests/data (formats 3 and 7).
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
io_sources=(examples/io/las.cpp examples/io/laz.cpp examples/io/las_writer.cpp)
"$cxx" "${flags[@]}" -fsanitize=address,undefined "${io_sources[@]}" tests/fuzz/make_seeds.cpp -o "$out/make_seeds"
"$cxx" "${flags[@]}" -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=undefined \
    "${io_sources[@]}" tests/fuzz/las_fuzz.cpp -o "$out/las_fuzz"

real=()
[[ -f "$data/Haystack_Rock.las" ]] && real=("$data/Haystack_Rock.las")
"$out/make_seeds" "$out/seeds" "${real[@]}"
cp tests/data/*.laz "$out/seeds/"

echo "fuzz.sh: running las_fuzz for ${seconds}s on $(ls "$out/seeds" | wc -l) seeds" >&2
UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1 ASAN_OPTIONS=detect_leaks=1 \
    "$out/las_fuzz" -max_total_time="$seconds" -max_len=40000 -timeout=10 -rss_limit_mb=2048 \
    -print_final_stats=1 -artifact_prefix="$out/" "$out/corpus" "$out/seeds"
