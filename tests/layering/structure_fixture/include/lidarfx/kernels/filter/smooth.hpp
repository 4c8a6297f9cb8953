#pragma once
#include "lidarfx/core/base.hpp"
namespace lidarfx {
namespace detail {
inline int smooth_rows(int x) { return x + shared_helper(); }
}  // namespace detail
inline int smooth(int x) { return detail::smooth_rows(x) + detail::shared_helper(); }
}  // namespace lidarfx
