// SPDX-License-Identifier: Apache-2.0
// The manifest's SHA-256: FIPS 180-4's test vectors, and the SHA-extension engine against the portable one on every
// length around the block size and on streams cut anywhere.
#include <doctest/doctest.h>

#include <random>
#include <string>

#include "io/sha256.hpp"

using lidarfx::io::sha256;
using lidarfx::io::sha256_engine;
using lidarfx::io::sha256_hex;

TEST_CASE("io/sha256: the FIPS 180-4 test vectors, with either engine")
{
    for (const auto engine : {sha256_engine::fastest, sha256_engine::portable}) {
        CHECK(sha256_hex("", engine) == "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
        CHECK(sha256_hex("abc", engine) == "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
        CHECK(sha256_hex("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq", engine) ==
              "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
        CHECK(sha256_hex(std::string(1000000, 'a'), engine) ==
              "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
    }
}

TEST_CASE("io/sha256: the fastest engine equals the portable one on every length and every way of streaming")
{
    INFO("SHA extensions on this CPU: ", lidarfx::io::sha256_extensions_available());
    std::mt19937 rng(256);
    std::string data(70000, '\0');
    for (char& c : data) c = static_cast<char>(rng());
    const std::string_view all(data);
    for (std::size_t n = 0; n <= 300; ++n) {
        INFO("length ", n);
        CHECK(sha256_hex(all.substr(0, n)) == sha256_hex(all.substr(0, n), sha256_engine::portable));
    }
    const std::string whole = sha256_hex(all, sha256_engine::portable);
    for (int trial = 0; trial < 20; ++trial) {
        sha256 hash;
        std::size_t at = 0;
        while (at < data.size()) {
            const std::size_t take = std::min<std::size_t>(data.size() - at, rng() % (trial < 10 ? 100 : 5000));
            hash.add(reinterpret_cast<const unsigned char*>(data.data()) + at, take);
            at += take;
        }
        CHECK(hash.hex() == whole);
    }
}
