// The primitive kinds a scene holds, as hits, AOVs and stats name them.
#pragma once

#include <cstdint>

namespace quiver {

// kNoKind stands for a miss.
enum class PrimitiveKind : std::int32_t { sphere = 0, plane = 1, triangle = 2, polygon = 3, cone = 4 };
inline constexpr std::int32_t kNoKind = -1;

}  // namespace quiver
