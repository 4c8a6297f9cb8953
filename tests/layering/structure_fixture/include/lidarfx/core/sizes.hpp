#pragma once
#include <cstddef>
namespace lidarfx {
inline std::vector<std::size_t> sizes() { return {}; }  // <vector> not included: reported
// std::map in a comment is not a use
inline auto pair_of() { return std::pair<int, int>{}; }  // <utility> not included: reported once
inline auto another_pair() { return std::pair<int, int>{}; }
inline int unknown() { return std::some_new_name; }  // not in the table: reported
}  // namespace lidarfx
