// SPDX-License-Identifier: Apache-2.0
// LASzip item decoders, version 3 (internal): POINT14, RGB14, RGBNIR14 and BYTE14 of the layered chunks
// (compressor 3, point formats 6–10). Each group of fields lives in its own layer with its own range
// decoder, and every item keeps one set of models and predictions per scanner channel (0–3).
#pragma once

#include <array>
#include <cstdint>
#include <cstring>
#include <vector>

#include "io/laz_arithmetic.hpp"
#include "io/laz_items_v2.hpp"

namespace lidarfx::io::laz {

/// A layered item decoder: read_sizes() reads its layer sizes from the chunk header, init() takes the
/// chunk's first (raw) item and its layers' bytes (advancing p), decode() writes the next item. POINT14
/// sets `context` (the scanner channel); the items after it read it.
class layered_item_decoder {
public:
    virtual ~layered_item_decoder() = default;
    virtual bool read_sizes(const std::uint8_t*& p, const std::uint8_t* end) = 0;
    virtual bool init(const std::uint8_t* first, const std::uint8_t*& p, const std::uint8_t* end,
                      std::uint32_t& context) = 0;
    virtual void decode(std::uint8_t* item, std::uint32_t& context) = 0;
    /// Bytes the layers' decoders asked for past their ends (0 for a valid chunk, up to a few at most).
    virtual std::size_t overrun() const = 0;
};

/// One layer of a chunk: its size, then its bytes and their decoder. An empty layer means the fields
/// it holds never change in the chunk.
struct layer {
    std::uint32_t size = 0;
    decoder dec;

    bool read_size(const std::uint8_t*& p, const std::uint8_t* end) noexcept
    {
        if (end - p < 4) return false;
        std::memcpy(&size, p, 4);
        p += 4;
        return true;
    }
    bool start(const std::uint8_t*& p, const std::uint8_t* end) noexcept
    {
        if (static_cast<std::uint64_t>(end - p) < size) return false;
        dec.init(p, p + size);
        p += size;
        return true;
    }
    bool used() const noexcept { return size > 0; }
    /// Bytes read past the layer's end beyond the four an empty layer's start asks for.
    std::size_t overrun() const noexcept
    {
        const std::size_t n = dec.overrun(), empty = size == 0 ? 4 : 0;
        return n > empty ? n - empty : 0;
    }
};

/// Reads the size of every layer in order; false when the chunk header is too short.
template <class Layers>
bool read_layer_sizes(Layers& layers, const std::uint8_t*& p, const std::uint8_t* end) noexcept
{
    for (auto& l : layers) {
        if (!l.read_size(p, end)) return false;
    }
    return true;
}

/// Starts every layer's decoder on its bytes, in order; false when the chunk is too short.
template <class Layers>
bool start_layers(Layers& layers, const std::uint8_t*& p, const std::uint8_t* end) noexcept
{
    for (auto& l : layers) {
        if (!l.start(p, end)) return false;
    }
    return true;
}

/// The largest overrun of the layers.
template <class Layers>
std::size_t layers_overrun(const Layers& layers) noexcept
{
    std::size_t n = 0;
    for (const auto& l : layers) n = std::max(n, l.overrun());
    return n;
}

/// Symbol models made on first use in a chunk (most of the 64 class or flag contexts never occur).
class lazy_models {
public:
    lazy_models(std::size_t count, std::uint32_t symbols) : models_(count), ready_(count, 0), symbols_(symbols) {}
    symbol_model& operator[](std::size_t i)
    {
        if (!ready_[i]) {
            models_[i].init(symbols_);
            ready_[i] = 1;
        }
        return models_[i];
    }
    void reset() { std::fill(ready_.begin(), ready_.end(), std::uint8_t{0}); }

private:
    std::vector<symbol_model> models_;
    std::vector<std::uint8_t> ready_;
    std::uint32_t symbols_;
};

/// POINT14 v3 predictor tables, indexed [number of returns][return number] (0–15).
inline constexpr std::uint8_t return_map_6ctx[16][16] = {
    {0, 1, 2, 3, 4, 5, 3, 4, 4, 5, 5, 5, 5, 5, 5, 5}, {1, 0, 1, 3, 3, 3, 3, 3, 3, 3, 3, 3, 3, 3, 3, 3},
    {2, 1, 2, 4, 4, 4, 4, 4, 4, 4, 4, 3, 3, 3, 3, 3}, {3, 3, 4, 5, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4},
    {4, 3, 4, 4, 5, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4}, {5, 3, 4, 4, 4, 5, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4},
    {3, 3, 4, 4, 4, 4, 5, 4, 4, 4, 4, 4, 4, 4, 4, 4}, {4, 3, 4, 4, 4, 4, 4, 5, 4, 4, 4, 4, 4, 4, 4, 4},
    {4, 3, 4, 4, 4, 4, 4, 4, 5, 4, 4, 4, 4, 4, 4, 4}, {5, 3, 4, 4, 4, 4, 4, 4, 4, 5, 4, 4, 4, 4, 4, 4},
    {5, 3, 4, 4, 4, 4, 4, 4, 4, 4, 5, 4, 4, 4, 4, 4}, {5, 3, 3, 4, 4, 4, 4, 4, 4, 4, 4, 5, 5, 4, 4, 4},
    {5, 3, 3, 4, 4, 4, 4, 4, 4, 4, 4, 5, 5, 5, 4, 4}, {5, 3, 3, 4, 4, 4, 4, 4, 4, 4, 4, 4, 5, 5, 5, 4},
    {5, 3, 3, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4, 5, 5, 5}, {5, 3, 3, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4, 5, 5}};
inline constexpr std::uint8_t return_level_8ctx[16][16] = {
    {0, 1, 2, 3, 4, 5, 6, 7, 7, 7, 7, 7, 7, 7, 7, 7}, {1, 0, 1, 2, 3, 4, 5, 6, 7, 7, 7, 7, 7, 7, 7, 7},
    {2, 1, 0, 1, 2, 3, 4, 5, 6, 7, 7, 7, 7, 7, 7, 7}, {3, 2, 1, 0, 1, 2, 3, 4, 5, 6, 7, 7, 7, 7, 7, 7},
    {4, 3, 2, 1, 0, 1, 2, 3, 4, 5, 6, 7, 7, 7, 7, 7}, {5, 4, 3, 2, 1, 0, 1, 2, 3, 4, 5, 6, 7, 7, 7, 7},
    {6, 5, 4, 3, 2, 1, 0, 1, 2, 3, 4, 5, 6, 7, 7, 7}, {7, 6, 5, 4, 3, 2, 1, 0, 1, 2, 3, 4, 5, 6, 7, 7},
    {7, 7, 6, 5, 4, 3, 2, 1, 0, 1, 2, 3, 4, 5, 6, 7}, {7, 7, 7, 6, 5, 4, 3, 2, 1, 0, 1, 2, 3, 4, 5, 6},
    {7, 7, 7, 7, 6, 5, 4, 3, 2, 1, 0, 1, 2, 3, 4, 5}, {7, 7, 7, 7, 7, 6, 5, 4, 3, 2, 1, 0, 1, 2, 3, 4},
    {7, 7, 7, 7, 7, 7, 6, 5, 4, 3, 2, 1, 0, 1, 2, 3}, {7, 7, 7, 7, 7, 7, 7, 6, 5, 4, 3, 2, 1, 0, 1, 2},
    {7, 7, 7, 7, 7, 7, 7, 7, 6, 5, 4, 3, 2, 1, 0, 1}, {7, 7, 7, 7, 7, 7, 7, 7, 7, 6, 5, 4, 3, 2, 1, 0}};

/// POINT14 v3: nine layers (channel, returns and x/y; z; classification; flags; intensity; scan angle;
/// user data; point source; GPS time), predicted per scanner channel.
class point14_v3 final : public layered_item_decoder {
public:
    bool read_sizes(const std::uint8_t*& p, const std::uint8_t* end) override
    {
        return read_layer_sizes(layers_, p, end);
    }

    bool init(const std::uint8_t* first, const std::uint8_t*& p, const std::uint8_t* end,
              std::uint32_t& context) override
    {
        if (!start_layers(layers_, p, end)) return false;
        for (auto& c : contexts_) c.used = false;
        current_ = channel(first);
        context = current_;
        start(contexts_[current_], first);
        return true;
    }

    void decode(std::uint8_t* item, std::uint32_t& context) override
    {
        channel_state& prev = contexts_[current_];
        const std::uint32_t prev_r = prev.last[14] & 15, prev_n = prev.last[14] >> 4;
        const std::uint32_t lpr = (prev_r == 1 ? 1u : 0u) | (prev_r >= prev_n ? 2u : 0u) | (prev.gps_changed ? 4u : 0u);
        decoder& xy = layers_[0].dec;
        const std::uint32_t changed = xy.decode_symbol(prev.changed[lpr]);

        std::uint32_t sc = current_;
        if (changed & 64) {
            sc = (sc + xy.decode_symbol(prev.scanner_channel) + 1) & 3;
            current_ = sc;
        }
        channel_state& c = contexts_[sc];
        if (!c.used) start(c, prev.last);
        std::uint8_t* last = c.last;
        last[15] = static_cast<std::uint8_t>((last[15] & 0xCF) | (sc << 4));
        context = sc;

        const bool gps_changed = (changed & 16) != 0;
        std::uint32_t n = last[14] >> 4, r = last[14] & 15;
        if (changed & 4) n = xy.decode_symbol(c.number_of_returns[n]);
        const bool rn_plus = changed & 1, rn_minus = changed & 2;
        if (rn_plus && !rn_minus) {
            r = (r + 1) & 15;
        } else if (rn_minus && !rn_plus) {
            r = (r + 15) & 15;
        } else if (rn_plus && rn_minus) {
            r = gps_changed ? xy.decode_symbol(c.return_number[r])
                            : (r + xy.decode_symbol(c.return_number_gps_same) + 2) & 15;
        }
        last[14] = static_cast<std::uint8_t>((n << 4) | r);

        const std::uint32_t m = (std::uint32_t{return_map_6ctx[n][r]} << 1) | (gps_changed ? 1u : 0u);
        const std::uint32_t single = n == 1 ? 1 : 0;
        const std::int32_t diff_x = c.dx.decompress(xy, c.dx_median[m].get(), single);
        add32(last, diff_x);
        c.dx_median[m].add(diff_x);
        const std::uint32_t kx = std::min(c.dx.k(), 20u) & ~1u;
        const std::int32_t diff_y = c.dy.decompress(xy, c.dy_median[m].get(), single | kx);
        add32(last + 4, diff_y);
        c.dy_median[m].add(diff_y);

        if (layers_[1].used()) {
            const std::uint32_t kz = std::min((c.dx.k() + c.dy.k()) / 2, 18u) & ~1u;
            const std::uint32_t level = return_level_8ctx[n][r];
            const std::int32_t z = c.z.decompress(layers_[1].dec, c.last_z[level], single | kz);
            std::memcpy(last + 8, &z, 4);
            c.last_z[level] = z;
        }
        if (layers_[2].used()) {
            const std::uint32_t k = ((last[16] & 0x1Fu) << 1) | (r == 1 && r >= n ? 1u : 0u);
            last[16] = static_cast<std::uint8_t>(layers_[2].dec.decode_symbol(c.classification[k]));
        }
        if (layers_[3].used()) {
            // Classification flags (4 bits), scan direction and edge of flight line; the channel bits stay.
            const std::uint32_t now = (last[15] & 0x0Fu) | ((last[15] >> 2) & 0x30u);
            const std::uint32_t f = layers_[3].dec.decode_symbol(c.flags[now]);
            last[15] = static_cast<std::uint8_t>((f & 0x0F) | ((f & 0x30) << 2) | (last[15] & 0x30));
        }
        if (layers_[4].used()) {
            const std::uint32_t k = (gps_changed ? 1u : 0u) | (r >= n ? 2u : 0u) | (r == 1 ? 4u : 0u);
            const auto v =
                static_cast<std::uint16_t>(c.intensity.decompress(layers_[4].dec, c.last_intensity[k], k >> 1));
            c.last_intensity[k] = v;
            std::memcpy(last + 12, &v, 2);
        }
        if (changed & 8) {
            std::int16_t angle;
            std::memcpy(&angle, last + 18, 2);
            const auto v =
                static_cast<std::uint16_t>(c.scan_angle.decompress(layers_[5].dec, angle, gps_changed ? 1 : 0));
            std::memcpy(last + 18, &v, 2);
        }
        if (layers_[6].used())
            last[17] = static_cast<std::uint8_t>(layers_[6].dec.decode_symbol(c.user_data[last[17] / 4]));
        if (changed & 32) {
            std::uint16_t source;
            std::memcpy(&source, last + 20, 2);
            const auto v = static_cast<std::uint16_t>(c.point_source.decompress(layers_[7].dec, source, 0));
            std::memcpy(last + 20, &v, 2);
        }
        if (gps_changed) {
            decode_time(c, layers_[8].dec);
            std::memcpy(last + 22, &c.time[c.seq], 8);
        }
        c.gps_changed = gps_changed;
        std::memcpy(item, last, 30);
    }

    std::size_t overrun() const override { return layers_overrun(layers_); }

private:
    struct channel_state {
        bool used = false;
        std::array<symbol_model, 8> changed{};
        symbol_model scanner_channel{3}, return_number_gps_same{13};
        lazy_models number_of_returns{16, 16}, return_number{16, 16};
        lazy_models classification{64, 256}, flags{64, 64}, user_data{64, 256};
        symbol_model time_multi{515}, time_zero_diff{5};
        integer_decoder dx{32, 2}, dy{32, 22}, z{32, 20}, intensity{16, 4}, scan_angle{16, 2}, point_source{16, 1},
            time_ic{32, 9};
        std::uint8_t last[30]{};
        std::array<std::uint16_t, 8> last_intensity{};
        std::array<std::int32_t, 8> last_z{};
        std::array<median5, 12> dx_median, dy_median;
        bool gps_changed = false;
        std::uint32_t seq = 0, next_seq = 0;
        std::array<std::uint64_t, 4> time{};  // bits of the doubles
        std::array<std::int32_t, 4> time_diff{}, extreme{};
    };

    static std::uint32_t channel(const std::uint8_t* point) noexcept { return (point[15] >> 4) & 3; }
    static void add32(std::uint8_t* p, std::int32_t d) noexcept
    {
        std::uint32_t v;
        std::memcpy(&v, p, 4);
        v += static_cast<std::uint32_t>(d);
        std::memcpy(p, &v, 4);
    }

    /// Fresh models for a channel first seen in this chunk, predictions from the point before it.
    static void start(channel_state& c, const std::uint8_t* from)
    {
        c.used = true;
        for (auto& m : c.changed) m.init(128);
        c.scanner_channel.init(3);
        c.return_number_gps_same.init(13);
        c.number_of_returns.reset();
        c.return_number.reset();
        c.classification.reset();
        c.flags.reset();
        c.user_data.reset();
        c.time_multi.init(515);
        c.time_zero_diff.init(5);
        c.dx.init(32, 2);
        c.dy.init(32, 22);
        c.z.init(32, 20);
        c.intensity.init(16, 4);
        c.scan_angle.init(16, 2);
        c.point_source.init(16, 1);
        c.time_ic.init(32, 9);
        std::memcpy(c.last, from, 30);
        std::int32_t z;
        std::memcpy(&z, from + 8, 4);
        c.last_z.fill(z);
        std::uint16_t intensity;
        std::memcpy(&intensity, from + 12, 2);
        c.last_intensity.fill(intensity);
        c.dx_median.fill(median5{});
        c.dy_median.fill(median5{});
        c.gps_changed = false;
        c.seq = c.next_seq = 0;
        c.time.fill(0);
        std::memcpy(&c.time[0], from + 22, 8);
        c.time_diff.fill(0);
        c.extreme.fill(0);
    }

    static std::int32_t times(std::int64_t m, std::int32_t d) noexcept
    {
        return static_cast<std::int32_t>(static_cast<std::uint32_t>(static_cast<std::uint64_t>(m * d)));
    }

    /// GPS time as in GPSTIME11 v2, without the "unchanged" code (a changed flag says so instead).
    static void decode_time(channel_state& c, decoder& dec) noexcept
    {
        constexpr std::int32_t multi_max = 500, multi_minus = -10;
        constexpr std::uint32_t code_full = 511;
        const auto extreme = [&c](std::int32_t d) {
            if (++c.extreme[c.seq] > 3) {
                c.time_diff[c.seq] = d;
                c.extreme[c.seq] = 0;
            }
        };
        const auto full = [&c, &dec] {
            c.next_seq = (c.next_seq + 1) & 3;
            const auto high = static_cast<std::uint32_t>(
                c.time_ic.decompress(dec, static_cast<std::int32_t>(c.time[c.seq] >> 32), 8));
            c.time[c.next_seq] = (std::uint64_t{high} << 32) | dec.read_int();
            c.seq = c.next_seq;
            c.time_diff[c.seq] = 0;
            c.extreme[c.seq] = 0;
        };
        const auto add = [&c](std::int32_t d) {
            c.time[c.seq] += static_cast<std::uint64_t>(static_cast<std::int64_t>(d));
        };
        for (int switches = 0; switches < 4; ++switches) {  // a valid stream switches at most once
            if (c.time_diff[c.seq] == 0) {
                const std::uint32_t multi = dec.decode_symbol(c.time_zero_diff);
                if (multi == 0) {
                    const std::int32_t d = c.time_ic.decompress(dec, 0, 0);
                    c.time_diff[c.seq] = d;
                    add(d);
                    c.extreme[c.seq] = 0;
                } else if (multi == 1) {
                    full();
                } else {
                    c.seq = (c.seq + multi - 1) & 3;
                    continue;
                }
            } else {
                const std::uint32_t multi = dec.decode_symbol(c.time_multi);
                if (multi == 1) {
                    add(c.time_ic.decompress(dec, c.time_diff[c.seq], 1));
                    c.extreme[c.seq] = 0;
                } else if (multi < code_full) {
                    std::int32_t d;
                    if (multi == 0) {
                        d = c.time_ic.decompress(dec, 0, 7);
                        extreme(d);
                    } else if (multi < static_cast<std::uint32_t>(multi_max)) {
                        d = c.time_ic.decompress(dec, times(multi, c.time_diff[c.seq]), multi < 10 ? 2 : 3);
                    } else if (multi == static_cast<std::uint32_t>(multi_max)) {
                        d = c.time_ic.decompress(dec, times(multi_max, c.time_diff[c.seq]), 4);
                        extreme(d);
                    } else {
                        const std::int32_t back = multi_max - static_cast<std::int32_t>(multi);
                        if (back > multi_minus) {
                            d = c.time_ic.decompress(dec, times(back, c.time_diff[c.seq]), 5);
                        } else {
                            d = c.time_ic.decompress(dec, times(multi_minus, c.time_diff[c.seq]), 6);
                            extreme(d);
                        }
                    }
                    add(d);
                } else if (multi == code_full) {
                    full();
                } else {
                    c.seq = (c.seq + multi - code_full) & 3;
                    continue;
                }
            }
            return;
        }
    }

    std::array<layer, 9> layers_;
    std::array<channel_state, 4> contexts_;
    std::uint32_t current_ = 0;
};

/// RGB14 v3 (and RGBNIR14 v3 with `nir`): the RGB prediction of RGB12 v2 in its own layer, and the
/// near-infrared word in a second one, with models per scanner channel.
class rgb14_v3 final : public layered_item_decoder {
public:
    explicit rgb14_v3(bool nir) : nir_(nir) {}

    bool read_sizes(const std::uint8_t*& p, const std::uint8_t* end) override
    {
        return rgb_.read_size(p, end) && (!nir_ || nir_layer_.read_size(p, end));
    }
    bool init(const std::uint8_t* first, const std::uint8_t*& p, const std::uint8_t* end,
              std::uint32_t& context) override
    {
        if (!rgb_.start(p, end) || (nir_ && !nir_layer_.start(p, end))) return false;
        for (auto& c : contexts_) c.used = false;
        current_ = context & 3;
        start(contexts_[current_], first);
        return true;
    }
    void decode(std::uint8_t* item, std::uint32_t& context) override
    {
        // Switching to a channel seen before keeps predicting from the previous channel's last value,
        // as LASzip does; a new channel starts from it.
        std::uint16_t* last = contexts_[current_].last;
        if (current_ != (context & 3)) {
            current_ = context & 3;
            if (!contexts_[current_].used) {
                start(contexts_[current_], reinterpret_cast<const std::uint8_t*>(last));
                last = contexts_[current_].last;
            }
        }
        channel_state& c = contexts_[current_];
        std::uint16_t now[4];
        if (rgb_.used()) {
            decode_rgb(rgb_.dec, c.byte_used, c.diff, last, now);
        } else {
            std::memcpy(now, last, 6);
        }
        if (nir_) {
            if (nir_layer_.used()) {
                const std::uint32_t sym = nir_layer_.dec.decode_symbol(c.nir_used);
                std::uint32_t v = (sym & 1)
                                      ? fold_u8(static_cast<std::int32_t>(nir_layer_.dec.decode_symbol(c.nir_diff[0])) +
                                                (last[3] & 0xFF))
                                      : (last[3] & 0xFFu);
                v |= (sym & 2)
                         ? std::uint32_t{fold_u8(
                               static_cast<std::int32_t>(nir_layer_.dec.decode_symbol(c.nir_diff[1])) + (last[3] >> 8))}
                               << 8
                         : (last[3] & 0xFF00u);
                now[3] = static_cast<std::uint16_t>(v);
            } else {
                now[3] = last[3];
            }
        }
        const std::size_t size = nir_ ? 8 : 6;
        std::memcpy(last, now, size);
        std::memcpy(item, now, size);
    }
    std::size_t overrun() const override { return std::max(rgb_.overrun(), nir_ ? nir_layer_.overrun() : 0); }

private:
    struct channel_state {
        bool used = false;
        symbol_model byte_used{128};
        std::array<symbol_model, 6> diff{};
        symbol_model nir_used{4};
        std::array<symbol_model, 2> nir_diff{};
        std::uint16_t last[4]{};
    };
    void start(channel_state& c, const std::uint8_t* from) const
    {
        c.used = true;
        c.byte_used.init(128);
        for (auto& m : c.diff) m.init(256);
        if (nir_) {
            c.nir_used.init(4);
            for (auto& m : c.nir_diff) m.init(256);
        }
        std::memcpy(c.last, from, nir_ ? 8 : 6);
    }

    bool nir_;
    layer rgb_, nir_layer_;
    std::array<channel_state, 4> contexts_;
    std::uint32_t current_ = 0;
};

/// BYTE14 v3: each extra byte in its own layer, a correction to its previous value per scanner channel.
class bytes14_v3 final : public layered_item_decoder {
public:
    explicit bytes14_v3(std::size_t n) : n_(n), layers_(n)
    {
        for (auto& c : contexts_) {
            c.models.assign(n, symbol_model(256));
            c.last.assign(n, 0);
        }
    }
    bool read_sizes(const std::uint8_t*& p, const std::uint8_t* end) override
    {
        return read_layer_sizes(layers_, p, end);
    }
    bool init(const std::uint8_t* first, const std::uint8_t*& p, const std::uint8_t* end,
              std::uint32_t& context) override
    {
        if (!start_layers(layers_, p, end)) return false;
        for (auto& c : contexts_) c.used = false;
        current_ = context & 3;
        start(contexts_[current_], first);
        return true;
    }
    void decode(std::uint8_t* item, std::uint32_t& context) override
    {
        std::uint8_t* last = contexts_[current_].last.data();
        if (current_ != (context & 3)) {
            current_ = context & 3;
            if (!contexts_[current_].used) {
                start(contexts_[current_], last);
                last = contexts_[current_].last.data();
            }
        }
        channel_state& c = contexts_[current_];
        for (std::size_t i = 0; i < n_; ++i) {
            if (layers_[i].used()) {
                last[i] = fold_u8(static_cast<std::int32_t>(last[i] + layers_[i].dec.decode_symbol(c.models[i])));
            }
            item[i] = last[i];
        }
    }
    std::size_t overrun() const override { return layers_overrun(layers_); }

private:
    struct channel_state {
        bool used = false;
        std::vector<symbol_model> models;
        std::vector<std::uint8_t> last;
    };
    void start(channel_state& c, const std::uint8_t* from)
    {
        c.used = true;
        for (auto& m : c.models) m.init(256);
        std::memcpy(c.last.data(), from, n_);
    }

    std::size_t n_;
    std::vector<layer> layers_;
    std::array<channel_state, 4> contexts_;
    std::uint32_t current_ = 0;
};

}  // namespace lidarfx::io::laz
