// SPDX-License-Identifier: Apache-2.0
// libFuzzer target for the LAS reader: any bytes must give valid points or a std::runtime_error, never a
// crash, a sanitizer report or an allocation beyond the input's size; accepted files must survive a round
// trip through the writer. Built and run by scripts/fuzz.sh.
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <span>
#include <stdexcept>

#include <lidarfx/core/error.hpp>

#include "io/las.hpp"
#include "io/las_writer.hpp"

namespace {

using lidarfx::io::las_points;

bool identical(const las_points& a, const las_points& b)
{
    return a.x == b.x && a.y == b.y && a.z == b.z && a.intensity == b.intensity &&
           a.return_number == b.return_number && a.number_of_returns == b.number_of_returns &&
           a.classification == b.classification && a.classification_flags == b.classification_flags &&
           a.scan_angle_deg == b.scan_angle_deg && a.gps_time.size() == b.gps_time.size();
}

/// True when integer * scale + offset round-trips through the writer's quantization exactly: scales of a
/// normal size and offsets small against 2^52 quanta (else the double sum loses the integer).
bool exact_lattice(const lidarfx::io::las_header& h)
{
    for (std::size_t k = 0; k < 3; ++k) {
        const double s = h.scale[k], o = h.offset[k];
        if (!(s > 1e-200 && s < 1e200) || !(std::abs(o) / s < 0x1p45)) return false;
    }
    return true;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    las_points all;
    lidarfx::io::las_header header;
    try {
        lidarfx::io::las_reader r(std::span<const std::uint8_t>(data, size), "fuzz");
        header = r.header();
        las_points chunk;
        std::uint64_t total = 0;
        const std::size_t step = 1 + size % 13;   // odd chunk sizes
        while (const std::size_t k = r.read(chunk, step)) total += k;
        if (total != r.point_count()) std::abort();
        all = r.read_all();
        if (all.size() != total || r.position() != total) std::abort();
        if (total * header.point_record_length + header.offset_to_point_data > size) std::abort();
        (void)all.cloud();
    } catch (const std::runtime_error&) {
        return 0;
    }

    // Round trip: what the reader accepted, the writer writes back to the same points (when it can hold them).
    if (!exact_lattice(header)) return 0;
    std::vector<std::uint8_t> bytes;
    try {
        bytes = lidarfx::io::encode_las(all, {.version_minor = 4, .point_format = header.point_format,
                                              .scale = header.scale, .offset = header.offset});
    } catch (const lidarfx::invalid_input&) {
        return 0;   // e.g. a legacy scan angle outside [-90, 90], which the reader reports as stored
    }
    lidarfx::io::las_reader again(bytes, "fuzz round trip");
    if (!identical(again.read_all(), all)) std::abort();
    return 0;
}
