// SPDX-License-Identifier: Apache-2.0
// LASzip item decoders, version 3 (internal): POINT14, RGB14, RGBNIR14 and BYTE14 of the layered chunks
// (compressor 3, point formats 6–10). Each field group lives in its own layer with its own decoder.
#pragma once

#include <cstdint>
#include <cstring>

#include "io/laz_arithmetic.hpp"

namespace lidarfx::io::laz {

/// A layered item decoder: read_sizes() reads its layer sizes from the chunk header, init() takes the
/// chunk's first (raw) item and its layers' bytes (advancing p), decode() writes the next item in the
/// given scanner-channel context (set by POINT14, read by the items after it).
class layered_item_decoder {
public:
    virtual ~layered_item_decoder() = default;
    virtual bool read_sizes(const std::uint8_t*& p, const std::uint8_t* end) = 0;
    virtual bool init(const std::uint8_t* first, const std::uint8_t*& p, const std::uint8_t* end) = 0;
    virtual void decode(std::uint8_t* item, std::uint32_t& context) = 0;
    virtual std::size_t overrun() const = 0;
};

}  // namespace lidarfx::io::laz
