// SPDX-License-Identifier: Apache-2.0
// SHA-256 (FIPS 180-4) of bytes, streamed: the checksums of the manifest. On CPUs with the SHA extensions (most
// x86-64 CPUs since 2017) the blocks go through them, several times faster than the portable code; both give the
// same digest.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace lidarfx::io {

/// Which code compresses the blocks: the fastest the CPU has, or the portable one (for tests and comparisons).
enum class sha256_engine { fastest, portable };

/// True if this CPU has the x86 SHA extensions (and SSE4.1) that sha256_engine::fastest uses.
bool sha256_extensions_available();

/// SHA-256, streaming: add() any number of times, then hex() once.
class sha256 {
public:
    explicit sha256(sha256_engine engine = sha256_engine::fastest);
    void add(const unsigned char* data, std::size_t n);
    /// The digest as 64 lowercase hex digits; the stream is finished (add() no more).
    std::string hex();

private:
    void compress(const unsigned char* blocks, std::size_t count);

    std::array<std::uint32_t, 8> h_{0x6a09e667, 0xbb67ae85, 0x3c6ef372, 0xa54ff53a,
                                    0x510e527f, 0x9b05688c, 0x1f83d9ab, 0x5be0cd19};
    std::array<unsigned char, 64> block_{};
    std::size_t used_ = 0;
    std::uint64_t bytes_ = 0;
    bool extensions_ = false;
};

/// SHA-256 of `data` as 64 lowercase hex digits.
std::string sha256_hex(std::string_view data, sha256_engine engine = sha256_engine::fastest);

}  // namespace lidarfx::io
