// SPDX-License-Identifier: Apache-2.0
// Progress callbacks for the tests of core/parallel.hpp's contract: a recorder of the fractions reported,
// and a callback that cancels.
#pragma once

#include <cstddef>
#include <memory>
#include <vector>

#include <lidarfx/core/parallel.hpp>

namespace reference {

/// Records every fraction an algorithm reports. callback() may be copied into options; the copies share
/// one record.
class progress_log {
public:
    lidarfx::progress_callback callback() const
    {
        return [seen = seen_](double f) {
            seen->push_back(f);
            return true;
        };
    }
    const std::vector<double>& seen() const noexcept { return *seen_; }

    /// The contract of execution::progress on success: at least `reports` calls, every fraction in
    /// [0, 1], never decreasing, the last exactly 1.
    bool monotone_to_one(std::size_t reports = 1) const
    {
        const auto& s = *seen_;
        if (s.size() < reports || s.back() != 1.0) return false;
        for (std::size_t i = 0; i < s.size(); ++i) {
            if (!(s[i] >= 0.0 && s[i] <= 1.0)) return false;
            if (i > 0 && s[i] < s[i - 1]) return false;
        }
        return true;
    }

private:
    std::shared_ptr<std::vector<double>> seen_ = std::make_shared<std::vector<double>>();
};

/// A progress callback that asks to stop at its first call.
inline lidarfx::progress_callback cancel_at_once()
{
    return [](double) { return false; };
}

}  // namespace reference
