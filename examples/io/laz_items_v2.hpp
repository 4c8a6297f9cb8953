// SPDX-License-Identifier: Apache-2.0
// LASzip item decoders, version 2 (internal): POINT10 (the 20 bytes of point formats 0–5), GPSTIME11,
// RGB12 and BYTE (extra bytes), all sharing one range decoder in point-wise chunks (compressor 2).
// Each decoder predicts a field from the previous point and decodes the correction (Isenburg 2013).
#pragma once

#include <array>
#include <cstdint>
#include <cstring>
#include <memory>
#include <vector>

#include "io/laz_arithmetic.hpp"

namespace lidarfx::io::laz {

/// Folds an int into a byte the way the encoder's byte arithmetic wrapped it.
inline std::uint8_t fold_u8(std::int32_t n) noexcept
{
    return static_cast<std::uint8_t>(n);
}
inline std::int32_t clamp_u8(std::int32_t n) noexcept
{
    return n < 0 ? 0 : n > 255 ? 255 : n;
}

/// The streaming median of the last five values (the predictor of x and y differences).
class median5 {
public:
    std::int32_t get() const noexcept { return v_[2]; }
    void add(std::int32_t v) noexcept
    {
        if (high_) {
            if (v < v_[2]) {
                v_[4] = v_[3];
                v_[3] = v_[2];
                if (v < v_[0]) {
                    v_[2] = v_[1];
                    v_[1] = v_[0];
                    v_[0] = v;
                } else if (v < v_[1]) {
                    v_[2] = v_[1];
                    v_[1] = v;
                } else {
                    v_[2] = v;
                }
            } else {
                if (v < v_[3]) {
                    v_[4] = v_[3];
                    v_[3] = v;
                } else {
                    v_[4] = v;
                }
                high_ = false;
            }
        } else {
            if (v_[2] < v) {
                v_[0] = v_[1];
                v_[1] = v_[2];
                if (v_[4] < v) {
                    v_[2] = v_[3];
                    v_[3] = v_[4];
                    v_[4] = v;
                } else if (v_[3] < v) {
                    v_[2] = v_[3];
                    v_[3] = v;
                } else {
                    v_[2] = v;
                }
            } else {
                if (v_[1] < v) {
                    v_[0] = v_[1];
                    v_[1] = v;
                } else {
                    v_[0] = v;
                }
                high_ = true;
            }
        }
    }

private:
    std::array<std::int32_t, 5> v_{};
    bool high_ = true;
};

/// Which of 16 predictor sets a point uses, from (number of returns, return number), and the level
/// (distance from the last return) that picks the height predictor.
inline constexpr std::uint8_t return_map[8][8] = {{15, 14, 13, 12, 11, 10, 9, 8},  {14, 0, 1, 3, 6, 10, 10, 9},
                                                  {13, 1, 2, 4, 7, 11, 11, 10},    {12, 3, 4, 5, 8, 12, 12, 11},
                                                  {11, 6, 7, 8, 9, 13, 13, 12},    {10, 10, 11, 12, 13, 14, 14, 13},
                                                  {9, 10, 11, 12, 13, 14, 15, 14}, {8, 9, 10, 11, 12, 13, 14, 15}};
inline constexpr std::uint8_t return_level[8][8] = {
    {0, 1, 2, 3, 4, 5, 6, 7}, {1, 0, 1, 2, 3, 4, 5, 6}, {2, 1, 0, 1, 2, 3, 4, 5}, {3, 2, 1, 0, 1, 2, 3, 4},
    {4, 3, 2, 1, 0, 1, 2, 3}, {5, 4, 3, 2, 1, 0, 1, 2}, {6, 5, 4, 3, 2, 1, 0, 1}, {7, 6, 5, 4, 3, 2, 1, 0}};

/// A field-by-field item decoder of the point-wise scheme: init() takes the chunk's first (raw) item,
/// decode() writes the next one.
class item_decoder {
public:
    virtual ~item_decoder() = default;
    virtual void init(const std::uint8_t* first) = 0;
    virtual void decode(std::uint8_t* item) = 0;
};

/// POINT10 v2: x, y (median-predicted differences per return class), z (last height per level),
/// intensity, the returns byte, classification, scan angle, user data and point source id.
class point10_v2 final : public item_decoder {
public:
    explicit point10_v2(decoder& dec) : dec_(dec) {}

    void init(const std::uint8_t* first) override
    {
        changed_ = symbol_model(64);
        scan_angle_[0] = symbol_model(256);
        scan_angle_[1] = symbol_model(256);
        for (auto& m : bit_byte_) m.reset();
        for (auto& m : classification_) m.reset();
        for (auto& m : user_data_) m.reset();
        intensity_.init(16, 4);
        point_source_.init(16, 1);
        dx_.init(32, 2);
        dy_.init(32, 22);
        z_.init(32, 20);
        last_intensity_.fill(0);
        last_height_.fill(0);
        dx_median_.fill(median5{});
        dy_median_.fill(median5{});
        std::memcpy(last_, first, 20);
        last_[12] = last_[13] = 0;  // the intensity predictor starts from 0, not the first point's value
    }

    void decode(std::uint8_t* item) override
    {
        std::uint8_t* p = last_;
        const std::uint32_t changed = dec_.decode_symbol(changed_);
        std::uint32_t r, n;
        if (changed != 0) {
            if (changed & 32) p[14] = static_cast<std::uint8_t>(dec_.decode_symbol(model(bit_byte_, p[14])));
            r = p[14] & 7;
            n = (p[14] >> 3) & 7;
            const std::uint32_t m = return_map[n][r];
            if (changed & 16) {
                const auto v =
                    static_cast<std::uint16_t>(intensity_.decompress(dec_, last_intensity_[m], m < 3 ? m : 3));
                last_intensity_[m] = v;
                store16(p + 12, v);
            } else {
                store16(p + 12, last_intensity_[m]);
            }
            if (changed & 8) p[15] = static_cast<std::uint8_t>(dec_.decode_symbol(model(classification_, p[15])));
            if (changed & 4) {
                const auto v = static_cast<std::int32_t>(dec_.decode_symbol(scan_angle_[(p[14] >> 6) & 1]));
                p[16] = fold_u8(v + p[16]);
            }
            if (changed & 2) p[17] = static_cast<std::uint8_t>(dec_.decode_symbol(model(user_data_, p[17])));
            if (changed & 1)
                store16(p + 18, static_cast<std::uint16_t>(point_source_.decompress(dec_, load16(p + 18))));
        } else {
            r = p[14] & 7;
            n = (p[14] >> 3) & 7;
        }
        const std::uint32_t m = return_map[n][r], l = return_level[n][r];
        const std::uint32_t single = n == 1 ? 1 : 0;

        const std::int32_t diff_x = dx_.decompress(dec_, dx_median_[m].get(), single);
        store32(p, load32(p) + static_cast<std::uint32_t>(diff_x));
        dx_median_[m].add(diff_x);

        std::uint32_t k = dx_.k();
        const std::int32_t diff_y = dy_.decompress(dec_, dy_median_[m].get(), single + (k < 20 ? (k & ~1u) : 20));
        store32(p + 4, load32(p + 4) + static_cast<std::uint32_t>(diff_y));
        dy_median_[m].add(diff_y);

        k = (dx_.k() + dy_.k()) / 2;
        const std::int32_t z = z_.decompress(dec_, last_height_[l], single + (k < 18 ? (k & ~1u) : 18));
        store32(p + 8, static_cast<std::uint32_t>(z));
        last_height_[l] = z;
        std::memcpy(item, p, 20);
    }

private:
    static std::uint16_t load16(const std::uint8_t* p) noexcept
    {
        std::uint16_t v;
        std::memcpy(&v, p, 2);
        return v;
    }
    static std::uint32_t load32(const std::uint8_t* p) noexcept
    {
        std::uint32_t v;
        std::memcpy(&v, p, 4);
        return v;
    }
    static void store16(std::uint8_t* p, std::uint16_t v) noexcept { std::memcpy(p, &v, 2); }
    static void store32(std::uint8_t* p, std::uint32_t v) noexcept { std::memcpy(p, &v, 4); }
    /// The model for a byte field given its previous value, made on first use (as the encoder does).
    static symbol_model& model(std::array<std::unique_ptr<symbol_model>, 256>& models, std::uint8_t previous)
    {
        auto& m = models[previous];
        if (!m) m = std::make_unique<symbol_model>(256);
        return *m;
    }

    decoder& dec_;
    std::uint8_t last_[20]{};
    symbol_model changed_{64};
    std::array<symbol_model, 2> scan_angle_{symbol_model(256), symbol_model(256)};
    std::array<std::unique_ptr<symbol_model>, 256> bit_byte_, classification_, user_data_;
    integer_decoder intensity_{16, 4}, point_source_{16, 1}, dx_{32, 2}, dy_{32, 22}, z_{32, 20};
    std::array<std::uint16_t, 16> last_intensity_{};
    std::array<std::int32_t, 8> last_height_{};
    std::array<median5, 16> dx_median_, dy_median_;
};

/// GPSTIME11 v2: the time as a difference from one of four recent time sequences, coded as a multiple of
/// that sequence's last difference, a new difference, or a full 64-bit value.
class gpstime11_v2 final : public item_decoder {
public:
    static constexpr std::int32_t multi_max = 500, multi_minus = -10;
    static constexpr std::uint32_t multi_unchanged = multi_max - multi_minus + 1;  // 511
    static constexpr std::uint32_t multi_code_full = multi_max - multi_minus + 2;  // 512
    static constexpr std::uint32_t multi_total = multi_max - multi_minus + 6;      // 516

    explicit gpstime11_v2(decoder& dec) : dec_(dec) {}

    void init(const std::uint8_t* first) override
    {
        multi_ = symbol_model(multi_total);
        zero_diff_ = symbol_model(6);
        ic_.init(32, 9);
        last_ = next_ = 0;
        diff_.fill(0);
        extreme_.fill(0);
        time_.fill(0);
        std::memcpy(&time_[0], first, 8);
    }

    void decode(std::uint8_t* item) override
    {
        // A valid stream switches sequence at most once before a value; more means corruption.
        for (int switches = 0; switches < 4; ++switches) {
            if (diff_[last_] == 0) {
                const std::uint32_t multi = dec_.decode_symbol(zero_diff_);
                if (multi == 1) {
                    diff_[last_] = ic_.decompress(dec_, 0, 0);
                    time_[last_] += static_cast<std::uint64_t>(static_cast<std::int64_t>(diff_[last_]));
                    extreme_[last_] = 0;
                } else if (multi == 2) {
                    read_full();
                } else if (multi > 2) {
                    last_ = (last_ + multi - 2) & 3;
                    continue;
                }
            } else {
                const std::uint32_t multi = dec_.decode_symbol(multi_);
                if (multi == 1) {
                    time_[last_] +=
                        static_cast<std::uint64_t>(static_cast<std::int64_t>(ic_.decompress(dec_, diff_[last_], 1)));
                    extreme_[last_] = 0;
                } else if (multi < multi_unchanged) {
                    std::int32_t d;
                    if (multi == 0) {
                        d = ic_.decompress(dec_, 0, 7);
                        count_extreme(d);
                    } else if (multi < static_cast<std::uint32_t>(multi_max)) {
                        d = ic_.decompress(dec_, times(multi, diff_[last_]), multi < 10 ? 2 : 3);
                    } else if (multi == static_cast<std::uint32_t>(multi_max)) {
                        d = ic_.decompress(dec_, times(multi_max, diff_[last_]), 4);
                        count_extreme(d);
                    } else {
                        const std::int32_t back = multi_max - static_cast<std::int32_t>(multi);
                        if (back > multi_minus) {
                            d = ic_.decompress(dec_, times(back, diff_[last_]), 5);
                        } else {
                            d = ic_.decompress(dec_, times(multi_minus, diff_[last_]), 6);
                            count_extreme(d);
                        }
                    }
                    time_[last_] += static_cast<std::uint64_t>(static_cast<std::int64_t>(d));
                } else if (multi == multi_code_full) {
                    read_full();
                } else if (multi > multi_code_full) {
                    last_ = (last_ + multi - multi_code_full) & 3;
                    continue;
                }
            }
            break;
        }
        std::memcpy(item, &time_[last_], 8);
    }

private:
    static std::int32_t times(std::int64_t m, std::int32_t d) noexcept
    {
        return static_cast<std::int32_t>(static_cast<std::uint32_t>(static_cast<std::uint64_t>(m * d)));
    }
    void count_extreme(std::int32_t d) noexcept
    {
        if (++extreme_[last_] > 3) {
            diff_[last_] = d;
            extreme_[last_] = 0;
        }
    }
    void read_full() noexcept
    {
        next_ = (next_ + 1) & 3;
        const auto high =
            static_cast<std::uint32_t>(ic_.decompress(dec_, static_cast<std::int32_t>(time_[last_] >> 32), 8));
        time_[next_] = (std::uint64_t{high} << 32) | dec_.read_int();
        last_ = next_;
        diff_[last_] = 0;
        extreme_[last_] = 0;
    }

    decoder& dec_;
    symbol_model multi_{multi_total}, zero_diff_{6};
    integer_decoder ic_{32, 9};
    std::uint32_t last_ = 0, next_ = 0;
    std::array<std::int32_t, 4> diff_{};
    std::array<std::int32_t, 4> extreme_{};
    std::array<std::uint64_t, 4> time_{};  // the bits of the double, as integers
};

/// The RGB prediction shared by RGB12 v2 and RGB14 v3: which bytes changed (one symbol), then each
/// changed byte as a correction to the previous colour, green and blue predicted from red's change.
inline void decode_rgb(decoder& dec, symbol_model& byte_used, std::array<symbol_model, 6>& diff,
                       const std::uint16_t* last, std::uint16_t* rgb) noexcept
{
    const std::uint32_t sym = dec.decode_symbol(byte_used);
    const auto corr = [&](int k) {
        return static_cast<std::int32_t>(dec.decode_symbol(diff[static_cast<std::size_t>(k)]));
    };
    std::uint32_t r, g, b;
    r = (sym & 1) ? fold_u8(corr(0) + (last[0] & 0xFF)) : (last[0] & 0xFF);
    r |= (sym & 2) ? std::uint32_t{fold_u8(corr(1) + (last[0] >> 8))} << 8 : (last[0] & 0xFF00);
    if (sym & 64) {
        std::int32_t d = static_cast<std::int32_t>(r & 0xFF) - (last[0] & 0xFF);
        g = (sym & 4) ? fold_u8(corr(2) + clamp_u8(d + (last[1] & 0xFF))) : (last[1] & 0xFF);
        if (sym & 16) {
            d = (d + (static_cast<std::int32_t>(g & 0xFF) - (last[1] & 0xFF))) / 2;
            b = fold_u8(corr(4) + clamp_u8(d + (last[2] & 0xFF)));
        } else {
            b = last[2] & 0xFF;
        }
        d = static_cast<std::int32_t>(r >> 8) - (last[0] >> 8);
        g |= (sym & 8) ? std::uint32_t{fold_u8(corr(3) + clamp_u8(d + (last[1] >> 8)))} << 8 : (last[1] & 0xFF00);
        if (sym & 32) {
            d = (d + (static_cast<std::int32_t>(g >> 8) - (last[1] >> 8))) / 2;
            b |= std::uint32_t{fold_u8(corr(5) + clamp_u8(d + (last[2] >> 8)))} << 8;
        } else {
            b |= last[2] & 0xFF00;
        }
    } else {
        g = b = r;
    }
    rgb[0] = static_cast<std::uint16_t>(r);
    rgb[1] = static_cast<std::uint16_t>(g);
    rgb[2] = static_cast<std::uint16_t>(b);
}

/// RGB12 v2: red, green, blue (16 bits each).
class rgb12_v2 final : public item_decoder {
public:
    explicit rgb12_v2(decoder& dec) : dec_(dec) {}
    void init(const std::uint8_t* first) override
    {
        byte_used_ = symbol_model(128);
        for (auto& m : diff_) m = symbol_model(256);
        std::memcpy(last_, first, 6);
    }
    void decode(std::uint8_t* item) override
    {
        std::uint16_t rgb[3];
        decode_rgb(dec_, byte_used_, diff_, last_, rgb);
        std::memcpy(last_, rgb, 6);
        std::memcpy(item, rgb, 6);
    }

private:
    decoder& dec_;
    symbol_model byte_used_{128};
    std::array<symbol_model, 6> diff_{symbol_model(256), symbol_model(256), symbol_model(256),
                                      symbol_model(256), symbol_model(256), symbol_model(256)};
    std::uint16_t last_[3]{};
};

/// BYTE v2: `n` extra bytes, each a correction to its previous value.
class bytes_v2 final : public item_decoder {
public:
    bytes_v2(decoder& dec, std::size_t n) : dec_(dec), models_(n, symbol_model(256)), last_(n) {}
    void init(const std::uint8_t* first) override
    {
        for (auto& m : models_) m = symbol_model(256);
        std::memcpy(last_.data(), first, last_.size());
    }
    void decode(std::uint8_t* item) override
    {
        for (std::size_t i = 0; i < last_.size(); ++i) {
            last_[i] = fold_u8(static_cast<std::int32_t>(last_[i] + dec_.decode_symbol(models_[i])));
        }
        std::memcpy(item, last_.data(), last_.size());
    }

private:
    decoder& dec_;
    std::vector<symbol_model> models_;
    std::vector<std::uint8_t> last_;
};

}  // namespace lidarfx::io::laz
