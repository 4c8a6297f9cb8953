// SPDX-License-Identifier: Apache-2.0
// The entropy decoder of LASzip (internal): a 32-bit range decoder with adaptive bit and symbol models
// and the integer "corrector" decompressor built on them, as described by Isenburg, "LASzip: lossless
// compression of LiDAR data" (2013), after Said's FastAC coder. Written from the format description.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace lidarfx::io::laz {

/// Adaptive binary model: P(0) estimated from counts, re-estimated every `update_cycle` bits (a cycle that
/// grows by 5/4 up to 64); counts are halved past 2^13.
struct bit_model {
    static constexpr std::uint32_t length_shift = 13, max_count = 1u << length_shift;
    std::uint32_t bit_0_count = 1, bit_count = 2, bit_0_prob = 1u << (length_shift - 1);
    std::uint32_t update_cycle = 4, bits_until_update = 4;

    void update() noexcept
    {
        if ((bit_count += update_cycle) > max_count) {
            bit_count = (bit_count + 1) >> 1;
            bit_0_count = (bit_0_count + 1) >> 1;
            if (bit_0_count == bit_count) ++bit_count;
        }
        const std::uint32_t scale = 0x80000000u / bit_count;
        bit_0_prob = (bit_0_count * scale) >> (31 - length_shift);
        update_cycle = (5 * update_cycle) >> 2;
        if (update_cycle > 64) update_cycle = 64;
        bits_until_update = update_cycle;
    }
};

/// Adaptive model over `symbols` symbols (2..2048): a cumulative distribution in units of 2^-15,
/// re-estimated every `update_cycle` symbols; models of more than 16 symbols keep a lookup table that
/// narrows the search for the decoded symbol.
class symbol_model {
public:
    static constexpr std::uint32_t length_shift = 15, max_count = 1u << length_shift;

    symbol_model() { init(2); }
    explicit symbol_model(std::uint32_t symbols) { init(symbols); }

    void init(std::uint32_t symbols)
    {
        symbols_ = symbols;
        last_symbol_ = symbols - 1;
        if (symbols > 16) {
            std::uint32_t table_bits = 3;
            while (symbols > (1u << (table_bits + 2))) ++table_bits;
            table_size_ = 1u << table_bits;
            table_shift_ = length_shift - table_bits;
            decoder_table_.assign(table_size_ + 2, 0);
        } else {
            table_size_ = table_shift_ = 0;
            decoder_table_.clear();
        }
        distribution_.assign(symbols, 0);
        symbol_count_.assign(symbols, 1);
        total_count_ = 0;
        update_cycle_ = symbols;
        update();
        symbols_until_update_ = update_cycle_ = (symbols + 6) >> 1;
    }

    void update() noexcept
    {
        if ((total_count_ += update_cycle_) > max_count) {
            total_count_ = 0;
            for (auto& c : symbol_count_) total_count_ += (c = (c + 1) >> 1);
        }
        const std::uint32_t scale = 0x80000000u / total_count_;
        std::uint32_t sum = 0;
        if (table_size_ == 0) {
            for (std::uint32_t k = 0; k < symbols_; ++k) {
                distribution_[k] = (scale * sum) >> (31 - length_shift);
                sum += symbol_count_[k];
            }
        } else {
            std::uint32_t s = 0;
            for (std::uint32_t k = 0; k < symbols_; ++k) {
                distribution_[k] = (scale * sum) >> (31 - length_shift);
                sum += symbol_count_[k];
                const std::uint32_t w = distribution_[k] >> table_shift_;
                while (s < w) decoder_table_[++s] = k - 1;
            }
            decoder_table_[0] = 0;
            while (s <= table_size_) decoder_table_[++s] = symbols_ - 1;
        }
        update_cycle_ = (5 * update_cycle_) >> 2;
        const std::uint32_t max_cycle = (symbols_ + 6) << 3;
        if (update_cycle_ > max_cycle) update_cycle_ = max_cycle;
        symbols_until_update_ = update_cycle_;
    }

private:
    friend class decoder;
    std::vector<std::uint32_t> distribution_, symbol_count_, decoder_table_;
    std::uint32_t symbols_ = 0, last_symbol_ = 0, total_count_ = 0, update_cycle_ = 0, symbols_until_update_ = 0;
    std::uint32_t table_size_ = 0, table_shift_ = 0;
};

/// Range decoder over one span of bytes. Reading past the end yields zero bytes and counts them in
/// overrun(), so a truncated or corrupt stream decodes to garbage (checked by the caller), never out of
/// bounds.
class decoder {
public:
    static constexpr std::uint32_t min_length = 0x01000000u;

    decoder() = default;
    decoder(const std::uint8_t* begin, const std::uint8_t* end) { init(begin, end); }

    /// Starts decoding at `begin`: the first four bytes (big-endian) are the initial value.
    void init(const std::uint8_t* begin, const std::uint8_t* end) noexcept
    {
        p_ = begin;
        end_ = end;
        overrun_ = 0;
        length_ = 0xFFFFFFFFu;
        value_ = 0;
        for (int i = 0; i < 4; ++i) value_ = (value_ << 8) | next_byte();
    }

    /// Bytes consumed so far (including the four read by init), and bytes asked for past the end.
    const std::uint8_t* position() const noexcept { return p_; }
    std::size_t overrun() const noexcept { return overrun_; }

    std::uint32_t decode_bit(bit_model& m) noexcept
    {
        const std::uint32_t x = m.bit_0_prob * (length_ >> bit_model::length_shift);
        std::uint32_t sym;
        if (value_ < x) {
            sym = 0;
            length_ = x;
            ++m.bit_0_count;
        } else {
            sym = 1;
            value_ -= x;
            length_ -= x;
        }
        if (length_ < min_length) renormalize();
        if (--m.bits_until_update == 0) m.update();
        return sym;
    }

    std::uint32_t decode_symbol(symbol_model& m) noexcept
    {
        std::uint32_t n, sym, x, y = length_;
        if (!m.decoder_table_.empty()) {
            length_ >>= symbol_model::length_shift;
            // A corrupt stream can leave value >= length; clamp so the table lookup stays in range.
            std::uint32_t dv = value_ / length_;
            std::uint32_t t = dv >> m.table_shift_;
            if (t > m.table_size_) t = m.table_size_;
            sym = m.decoder_table_[t];
            n = m.decoder_table_[t + 1] + 1;
            while (n > sym + 1) {
                const std::uint32_t k = (sym + n) >> 1;
                if (m.distribution_[k] > dv)
                    n = k;
                else
                    sym = k;
            }
            x = m.distribution_[sym] * length_;
            if (sym != m.last_symbol_) y = m.distribution_[sym + 1] * length_;
        } else {
            x = sym = 0;
            length_ >>= symbol_model::length_shift;
            n = m.symbols_;
            std::uint32_t k = n >> 1;
            do {
                const std::uint32_t z = length_ * m.distribution_[k];
                if (z > value_) {
                    n = k;
                    y = z;
                } else {
                    sym = k;
                    x = z;
                }
            } while ((k = (sym + n) >> 1) != sym);
        }
        value_ -= x;
        length_ = y - x;
        if (length_ < min_length) renormalize();
        ++m.symbol_count_[sym];
        if (--m.symbols_until_update_ == 0) m.update();
        return sym;
    }

    /// `bits` raw bits (1..32), uniform.
    std::uint32_t read_bits(std::uint32_t bits) noexcept
    {
        if (bits > 19) {
            const std::uint32_t low = read_short();
            return (read_bits(bits - 16) << 16) | low;
        }
        const std::uint32_t sym = value_ / (length_ >>= bits);
        value_ -= length_ * sym;
        if (length_ < min_length) renormalize();
        return sym;
    }

    std::uint32_t read_short() noexcept
    {
        const std::uint32_t sym = value_ / (length_ >>= 16);
        value_ -= length_ * sym;
        if (length_ < min_length) renormalize();
        return sym & 0xFFFFu;
    }

    std::uint32_t read_int() noexcept
    {
        const std::uint32_t low = read_short();
        return (read_short() << 16) | low;
    }

private:
    std::uint32_t next_byte() noexcept
    {
        if (p_ < end_) return *p_++;
        ++overrun_;
        return 0;
    }
    void renormalize() noexcept
    {
        do {
            value_ = (value_ << 8) | next_byte();
        } while ((length_ <<= 8) < min_length);
    }

    const std::uint8_t* p_ = nullptr;
    const std::uint8_t* end_ = nullptr;
    std::size_t overrun_ = 0;
    std::uint32_t value_ = 0, length_ = 0;
};

/// Integers coded as a correction to a prediction: the number k of bits of the correction with a symbol
/// model per context, then the correction inside its k-bit interval (an adaptive model for the top
/// `bits_high` bits, raw bits below). Results wrap into the `bits`-bit range.
class integer_decoder {
public:
    integer_decoder(std::uint32_t bits = 16, std::uint32_t contexts = 1, std::uint32_t bits_high = 8)
    {
        init(bits, contexts, bits_high);
    }

    void init(std::uint32_t bits, std::uint32_t contexts, std::uint32_t bits_high = 8)
    {
        bits_high_ = bits_high;
        if (bits > 0 && bits < 32) {
            corr_bits_ = bits;
            corr_range_ = 1u << bits;
            corr_min_ = -static_cast<std::int32_t>(corr_range_ / 2);
        } else {
            corr_bits_ = 32;
            corr_range_ = 0;
            corr_min_ = INT32_MIN;
        }
        k_ = 0;
        // Models are made on first use (as fresh ones), so restarting a chunk costs little.
        bits_.resize(contexts);
        bits_ready_.assign(contexts, 0);
        corrector_0_ = bit_model{};
        corrector_.resize(corr_bits_ + 1);
        corrector_ready_.assign(corr_bits_ + 1, 0);
    }

    /// Decodes pred + correction in context `context` (< contexts), wrapped into the coder's range.
    std::int32_t decompress(decoder& dec, std::int32_t pred, std::uint32_t context = 0) noexcept
    {
        if (!bits_ready_[context]) {
            bits_[context].init(corr_bits_ + 1);
            bits_ready_[context] = 1;
        }
        const std::uint32_t real =
            static_cast<std::uint32_t>(pred) + static_cast<std::uint32_t>(corrector(dec, bits_[context]));
        if (corr_range_ == 0) return static_cast<std::int32_t>(real);
        // Fold into [0, range) as the encoder did (pred and correction lie within one range of it).
        std::int32_t r = static_cast<std::int32_t>(real);
        if (r < 0)
            r += static_cast<std::int32_t>(corr_range_);
        else if (static_cast<std::uint32_t>(r) >= corr_range_)
            r -= static_cast<std::int32_t>(corr_range_);
        return r;
    }

    /// The bit count k of the last correction (predicts the contexts of neighbouring values).
    std::uint32_t k() const noexcept { return k_; }

private:
    std::int32_t corrector(decoder& dec, symbol_model& m) noexcept
    {
        k_ = dec.decode_symbol(m);
        if (k_ != 0 && k_ < 32 && !corrector_ready_[k_]) {
            corrector_[k_].init(1u << (k_ <= bits_high_ ? k_ : bits_high_));
            corrector_ready_[k_] = 1;
        }
        if (k_ == 0) return static_cast<std::int32_t>(dec.decode_bit(corrector_0_));
        if (k_ >= 32) return corr_min_;
        std::uint32_t c;
        if (k_ <= bits_high_) {
            c = dec.decode_symbol(corrector_[k_]);
        } else {
            const std::uint32_t low_bits = k_ - bits_high_;
            c = (dec.decode_symbol(corrector_[k_]) << low_bits) | dec.read_bits(low_bits);
        }
        // c in [0, 2^k): the upper half maps to [2^(k-1), 2^k), the lower half to [-(2^k - 1), -2^(k-1)].
        const std::int64_t v =
            c >= (1u << (k_ - 1)) ? std::int64_t{c} + 1 : std::int64_t{c} - ((std::int64_t{1} << k_) - 1);
        return static_cast<std::int32_t>(v);
    }

    std::uint32_t bits_high_ = 8, corr_bits_ = 16, corr_range_ = 0, k_ = 0;
    std::int32_t corr_min_ = 0;
    std::vector<symbol_model> bits_;
    bit_model corrector_0_;
    std::vector<symbol_model> corrector_;
    std::vector<std::uint8_t> bits_ready_, corrector_ready_;
};

}  // namespace lidarfx::io::laz
