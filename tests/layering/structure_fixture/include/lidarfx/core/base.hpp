#pragma once
namespace lidarfx::detail {
inline int shared_helper() { return 1; }
}  // namespace lidarfx::detail
